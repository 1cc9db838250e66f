// The symbols of a formula, each a link to its definition on /notation (like a knowl): the
// name on hover (title), and a click or tap opens the definition in place, with where the
// paper defines it and a link to the full entry; a second click, Escape or a click
// elsewhere closes it. A click with a modifier key (or without scripts) follows the link.
"use strict";

import { mathHtml } from "./latex.js";

let cache = null;

export function notation() {
  if (!cache) {
    cache = fetch("/api/notation", { headers: { Accept: "application/json" } })
      .then((r) => (r.ok ? r.json() : { entries: [] }))
      .then((n) => Object.fromEntries(n.entries.map((e) => [e.id, e])))
      .catch(() => ({}));
  }
  return cache;
}

const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" }[c]));

function texHtml(tex) {
  return window.katex ? mathHtml(tex) : esc(tex);
}

// one symbol (views.symbol_refs: id, tex, name, href); the same markup as ssr.symbol_link
export function symbolLink(s) {
  return `<a class="sym" href="${esc(s.href)}" data-sym="${esc(s.id)}" title="${esc(s.name)}">` +
    `${texHtml(s.tex)}<span class="sr-only"> ${esc(s.text)}: ${esc(s.name)}</span></a>`;
}

// "Symbols in this formula" under a formula
export function symbolsHtml(list) {
  if (!list || !list.length) return "";
  return `<p class="symbols"><span class="symlabel">Symbols:</span> ${list.map(symbolLink).join(" ")}</p>`;
}

function shut(a) {
  a.setAttribute("aria-expanded", "false");
  document.getElementById(a.getAttribute("aria-controls") || "")?.remove();
}

function close(except) {
  for (const a of document.querySelectorAll('a.sym[aria-expanded="true"]')) {
    if (a !== except) shut(a);
  }
}

function boxHtml(e) {
  const defs = e.defined.map((d) =>
    `<li><span class="where">${esc(d.numbers.filter(Boolean).join(", "))}, ${esc(d.section_title)}</span>: ${esc(d.text)}</li>`).join("");
  const conv = e.convention ? `<p><strong>In this project:</strong> ${esc(e.convention)}</p>` : "";
  return `<strong>${texHtml(e.tex)}</strong> ${esc(e.name)}<ul>${defs}</ul>${conv}` +
    `<a href="${esc(e.href)}">Notation: the full entry</a>`;
}

async function toggle(a) {
  const open = a.getAttribute("aria-expanded") === "true";
  close(a);
  if (open) {
    shut(a);
    return;
  }
  const e = (await notation())[a.dataset.sym];
  if (!e) {
    location.href = a.href;
    return;
  }
  const box = document.createElement("span");
  box.className = "symbox";
  box.setAttribute("role", "note");
  box.id = `symbox-${a.dataset.sym}`;
  box.innerHTML = boxHtml(e);
  a.setAttribute("aria-expanded", "true");
  a.setAttribute("aria-controls", box.id);
  // under the formula's whole list of symbols (or the page's list item), not inside it
  (a.closest("p.symbols, li") || a).after(box);
}

document.addEventListener("click", (ev) => {
  const a = ev.target.closest ? ev.target.closest("a.sym[data-sym]") : null;
  if (a && !(ev.ctrlKey || ev.metaKey || ev.shiftKey || ev.altKey || ev.button)) {
    ev.preventDefault();
    toggle(a);
  } else if (!ev.target.closest || !ev.target.closest(".symbox")) {
    close(null);
  }
});
document.addEventListener("keydown", (ev) => { if (ev.key === "Escape") close(null); });
