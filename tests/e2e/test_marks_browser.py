"""Marks that read at a glance (issue 11, item 3) in chromium: text on the paper's gray
shading has AA contrast (measured here from the computed colours: axe-core cannot judge
the half-gray gradient of a partial cell and leaves it "incomplete"); why a cell is shaded
is visible text behind a disclosure that opens on a tap, never a hover title alone; the
marks are at least 24 px tall, a target a finger can hit (WCAG 2.5.8)."""

import pytest
from playwright.sync_api import expect

GRAY = "#d4d4d4"        # --gray, the paper's shading (app/static/css/app.css)

# every element that draws text inside a shaded cell: its colour, the background it is drawn
# on (the nearest opaque background; a partial cell's gradient is gray on one half and white
# on the other, so both are tried), and whether it is large text (3:1 suffices)
TEXT_ON_SHADING = """(gray) => {
  const rgb = (s) => (s.match(/[\\d.]+/g) || []).map(Number);
  const lum = ([r, g, b]) => [r, g, b].map((v) => v / 255)
    .map((c) => (c <= 0.03928 ? c / 12.92 : ((c + 0.055) / 1.055) ** 2.4))
    .reduce((s, c, i) => s + c * [0.2126, 0.7152, 0.0722][i], 0);
  const ratio = (a, b) => {
    const [x, y] = [lum(a), lum(b)].sort((p, q) => q - p);
    return (x + 0.05) / (y + 0.05);
  };
  const hex = (h) => [1, 3, 5].map((i) => parseInt(h.slice(i, i + 2), 16));
  const out = [];
  for (const td of document.querySelectorAll("td.shade-full, td.shade-partial")) {
    for (const el of td.querySelectorAll("*")) {
      const own = [...el.childNodes].some((n) => n.nodeType === 3 && n.textContent.trim());
      if (!own || !el.getClientRects().length || el.closest(".sr-only")) continue;
      const st = getComputedStyle(el);
      if (st.visibility === "hidden" || Number(st.opacity) === 0) continue;
      let bgs = null;
      for (let e = el; e; e = e.parentElement) {
        const b = rgb(getComputedStyle(e).backgroundColor);
        if (b.length === 3 || (b.length === 4 && b[3] > 0.9)) { bgs = [b.slice(0, 3)]; break; }
        if (e === td) {
          const half = td.classList.contains("shade-partial");
          bgs = half ? [hex(gray), [255, 255, 255]] : [hex(gray)];
          break;
        }
      }
      const size = parseFloat(st.fontSize), bold = Number(st.fontWeight) >= 700;
      const large = size >= 24 || (bold && size >= 18.66);
      const worst = Math.min(...bgs.map((b) => ratio(rgb(st.color).slice(0, 3), b)));
      out.push({ text: el.textContent.trim().slice(0, 30), ratio: worst, need: large ? 3 : 4.5 });
    }
  }
  return out;
}"""


def ready(page):
    page.locator("body[data-ready='1']").wait_for(state="attached")


@pytest.mark.parametrize("path", ["/", "/case/plane/chaplygin-ball", "/case/sphere/round-disk"])
def test_text_on_the_gray_shading_has_aa_contrast(page, server, path):
    page.goto(server + path)
    ready(page)
    page.evaluate("document.querySelectorAll('details').forEach(d => d.open = true)")
    found = page.evaluate(TEXT_ON_SHADING, GRAY)
    assert len(found) > 20, found        # the measurement saw the shaded cells' text
    low = [f for f in found if f["ratio"] < f["need"]]
    assert not low, f"{path}: text below AA on the shading: {low[:8]}"
    print(f"{path}: {len(found)} texts on the shading, lowest contrast "
          f"{min(f['ratio'] for f in found):.2f}:1")


def test_why_a_cell_is_shaded_opens_on_a_tap(browser, server):
    ctx = browser.new_context(viewport={"width": 390, "height": 844}, has_touch=True)
    page = ctx.new_page()
    try:
        page.goto(server + "/")
        ready(page)
        # nothing explains a cell in a hover title only
        assert page.locator("table.paper td[title]").count() == 0
        why = page.locator("#tbl-plane tr.row-integrals details.shade-why").first
        note = why.locator("p")
        expect(note).not_to_be_visible()
        why.locator("summary").tap()
        expect(note).to_be_visible()
        expect(note).to_contain_text("integrals")
        # the marks: at least 24 px tall, with the meaning in text for screen readers
        mark = page.locator("#tbl-plane a.cellmark").first
        box = mark.bounding_box()
        assert box["height"] >= 24 and box["width"] >= 24, box
        assert mark.locator(".sr-only").inner_text().strip()
        # the case page writes the shading out in words
        page.goto(server + "/case/plane/chaplygin-ball")
        ready(page)
        expect(page.locator("#row-integrals .shade-note")).to_contain_text(
            "shading: gray: the invariant exists — two additional integrals")
        assert page.locator("#cells td[title]").count() == 0
    finally:
        ctx.close()
