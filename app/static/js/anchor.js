// A claim's anchor on its case page: the rule of app/services/anchors.py (the server's
// pages), repeated once here for the pages the browser draws; tests/test_claim_anchor.py
// checks that both give the same anchors.
"use strict";

export const claimAnchor = (claimId) => "claim-" + claimId.replace(/[^A-Za-z0-9_-]+/g, "_");
