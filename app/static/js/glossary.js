// Glossary tooltips that work on touch: a "?" button next to a parameter toggles its
// definition on click or tap (no hover-only information); Escape or a click elsewhere closes
// it. Also renders the server pages' formulas (span.tex[data-tex]) with the vendored KaTeX.
"use strict";

let cache = null;

export async function glossary() {
  if (!cache) {
    cache = fetch("/api/glossary", { headers: { Accept: "application/json" } })
      .then((r) => (r.ok ? r.json() : { entries: [] }))
      .then((g) => Object.fromEntries(g.entries.map((e) => [e.symbol, e])))
      .catch(() => ({}));
  }
  return cache;
}

const esc = (s) => String(s).replace(/[&<>"']/g, (c) => ({ "&": "&amp;", "<": "&lt;", ">": "&gt;", '"': "&quot;", "'": "&#39;" }[c]));

// the button a form field or a text puts next to a symbol
export function tipHtml(symbol) {
  return `<button type="button" class="tip" data-glossary="${esc(symbol)}" aria-expanded="false" ` +
    `aria-label="What is ${esc(symbol)}?">?</button>`;
}

function close(except) {
  for (const b of document.querySelectorAll('button.tip[aria-expanded="true"]')) {
    if (b === except) continue;
    b.setAttribute("aria-expanded", "false");
    b.nextElementSibling?.classList.contains("tipbox") && b.nextElementSibling.remove();
  }
}

async function toggle(btn) {
  const open = btn.getAttribute("aria-expanded") === "true";
  close(btn);
  if (open) {
    btn.setAttribute("aria-expanded", "false");
    btn.nextElementSibling?.classList.contains("tipbox") && btn.nextElementSibling.remove();
    return;
  }
  const e = (await glossary())[btn.dataset.glossary];
  const box = document.createElement("span");
  box.className = "tipbox";
  box.setAttribute("role", "tooltip");
  box.id = `tip-${btn.dataset.glossary}`;
  box.innerHTML = e
    ? `<strong>${esc(e.symbol)}</strong>: ${esc(e.meaning)} <em>Valid:</em> ${esc(e.range)}` +
      (e.paper_numbers.filter(Boolean).length ? ` <em>In the paper:</em> ${esc(e.paper_numbers.filter(Boolean).join(", "))}.` : "") +
      ` <a href="/glossary#g-${esc(e.symbol)}">Glossary</a>`
    : `No glossary entry for ${esc(btn.dataset.glossary)}.`;
  btn.setAttribute("aria-expanded", "true");
  btn.setAttribute("aria-describedby", box.id);
  btn.after(box);
}

document.addEventListener("click", (ev) => {
  const btn = ev.target.closest ? ev.target.closest("button.tip[data-glossary]") : null;
  if (btn) {
    ev.preventDefault();
    toggle(btn);
  } else if (!ev.target.closest || !ev.target.closest(".tipbox")) {
    close(null);
  }
});
document.addEventListener("keydown", (ev) => { if (ev.key === "Escape") close(null); });

function renderTex() {
  if (!window.katex) return;
  for (const el of document.querySelectorAll("span.tex[data-tex]")) {
    try {
      window.katex.render(el.dataset.tex, el, { throwOnError: false });
    } catch { /* the TeX stays as text */ }
  }
}
if (document.readyState === "complete") renderTex();
else window.addEventListener("load", renderTex);
