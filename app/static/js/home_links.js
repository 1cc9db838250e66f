// Home page: links to the teaching scenes (each opens /scenes#ID and plays) and to the
// 3D point maps. Kept apart from home.js, which draws the tables.
"use strict";

import { api, escapeHtml } from "./api.js";

async function main() {
  const ul = document.getElementById("scene-links");
  if (!ul) return;
  try {
    const scenes = await api("/api/scenes");
    ul.innerHTML = scenes.map((s) =>
      `<li><a href="/scenes#${encodeURIComponent(s.id)}">${escapeHtml(s.title)}</a></li>`).join("");
  } catch (e) {
    ul.innerHTML = `<li class="error">Could not load the scenes: ${escapeHtml(e.message)}</li>`;
  }
}

main();
