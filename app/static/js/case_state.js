// The case page's shared state: the case (GET /api/cases/{id}), which both halves of the
// page read (case_claims.js: the claims; case.js: the run form) and either replaces when it
// is fetched again; ES modules see the new value through the live binding.
"use strict";

export const $ = (id) => document.getElementById(id);

export let C = null;

export function setCase(c) {
  C = c;
}
