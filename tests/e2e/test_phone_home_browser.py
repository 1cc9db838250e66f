"""Browser, a phone (390 px): the home tables keep their column headings in view while the
page scrolls down through them (app/static/js/pinned_head.js), lined up with the columns
as the table scrolls sideways; the site's navigation takes at most two lines (reader.css).
Issue 20."""

# the rows of the navigation: its items' distinct tops
NAV_ROWS = """() => { const n = document.querySelector('header.site nav');
  const tops = new Set([...n.children].filter((e) => e.offsetParent !== null)
    .map((e) => Math.round(e.getBoundingClientRect().top)));
  return { rows: tops.size, height: n.getBoundingClientRect().height,
           line: Math.max(...[...n.children].map((e) => e.getBoundingClientRect().height)) }; }"""

# what is drawn at the middle of each column heading's place at the top of the screen:
# a heading cell (the original or its pinned copy) showing that column's title
HEADINGS_AT_TOP = """() => {
  const src = document.querySelector('#tbl-plane thead tr').cells;
  const wrap = document.querySelector('#table-plane .table-wrap').getBoundingClientRect();
  const out = [];
  for (const th of src) {
    const r = th.getBoundingClientRect();
    const x = r.left + r.width / 2;
    if (x < wrap.left + 2 || x > wrap.right - 2) continue;       // scrolled out sideways
    let y = 0;                                   // the first heading cell from the top down
    let hit = null;
    for (; y < 200; y += 4) {
      const e = document.elementFromPoint(x, y);
      hit = e && e.closest('thead th');
      if (hit) break;
    }
    out.push({ want: th.textContent.trim(), got: hit ? hit.textContent.trim() : null, y });
  }
  return out;
}"""


def test_home_table_headings_stay_in_view_on_a_phone(page, server):
    page.set_viewport_size({"width": 390, "height": 844})
    page.goto(server + "/")
    page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
    # half way down Table 1: its heading row has long left the top of the screen
    page.evaluate("""() => { const t = document.querySelector('#tbl-plane').getBoundingClientRect();
        window.scrollTo(0, scrollY + t.top + t.height / 2); }""")
    page.wait_for_timeout(200)
    assert page.evaluate(
        "document.querySelector('#tbl-plane thead').getBoundingClientRect().bottom") < 0
    for sideways in (0, 240):
        page.evaluate(f"document.querySelector('#table-plane .table-wrap').scrollLeft = {sideways}")
        page.wait_for_timeout(200)
        cols = page.evaluate(HEADINGS_AT_TOP)
        assert len(cols) >= 2, cols
        wrong = [c for c in cols if c["got"] != c["want"]]
        assert not wrong, (sideways, wrong)
        assert all(c["y"] <= 8 for c in cols), cols        # at the very top of the screen


def test_navigation_fits_in_two_lines_on_a_phone(page, server):
    page.set_viewport_size({"width": 390, "height": 844})
    for path in ("/", "/scenes", "/poincare"):
        page.goto(server + path)
        nav = page.evaluate(NAV_ROWS)
        assert nav["rows"] <= 2 and nav["height"] <= 2 * nav["line"] + 16, (path, nav)
        # every link can still be reached: the row scrolls sideways
        assert page.evaluate("""() => { const n = document.querySelector('header.site nav');
            n.scrollLeft = n.scrollWidth; const a = [...n.querySelectorAll('a')].pop();
            const r = a.getBoundingClientRect();
            return r.right <= innerWidth + 1 && r.left >= 0; }""")
