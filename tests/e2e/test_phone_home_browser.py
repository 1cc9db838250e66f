"""Browser, a phone (390 px): the home tables keep their column headings in view while the
page scrolls down through them (app/static/js/pinned_head.js), lined up with the columns
as the table scrolls sideways. The first screen of a phone shows a table, the search box and
the menu button that opens the site's links (app/services/site_shell.py, page.js); no word
of a navigation link or a table heading is split, no control is under 24 px; at 1280 px the
navigation is the full strip."""

from playwright.sync_api import expect

from app.services import site_shell

# the rows of the navigation: its links' distinct tops
NAV_ROWS = """() => { const n = document.querySelector('header.site nav');
  const tops = new Set([...n.querySelectorAll('a')].filter((e) => e.offsetParent !== null)
    .map((e) => Math.round(e.getBoundingClientRect().top)));
  return { rows: tops.size, height: n.getBoundingClientRect().height,
           line: Math.max(...[...n.querySelectorAll('a')]
             .map((e) => e.getBoundingClientRect().height)) }; }"""

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


# no word of a link is split over two lines: each word's boxes (Range.getClientRects) lie on
# one line, and the link's own box does not overflow sideways. Words are parted by spaces
# and dashes: "Borisov–Fedorov" may wrap after its dash, between the two names
BROKEN_WORDS = """(sel) => { const out = [];
  for (const a of document.querySelectorAll(sel)) {
    if (!a.getClientRects().length) continue;
    if (a.scrollWidth > a.clientWidth + 1 && getComputedStyle(a).display !== 'inline') {
      out.push(`${a.textContent.trim()}: overflows its box`); }
    const walk = document.createTreeWalker(a, NodeFilter.SHOW_TEXT);
    for (let t = walk.nextNode(); t; t = walk.nextNode()) {
      for (const m of t.data.matchAll(/[^\\s\u2013\u2014-]+/g)) {
        const r = document.createRange();
        r.setStart(t, m.index); r.setEnd(t, m.index + m[0].length);
        const tops = new Set([...r.getClientRects()].filter((b) => b.width > 0)
          .map((b) => Math.round(b.top)));
        if (tops.size > 1) out.push(`${a.textContent.trim()}: "${m[0]}" split`);
      }
    }
  }
  return out; }"""

# every control a finger must hit under 24 px in either dimension (WCAG 2.5.8); a link
# inside a sentence (inline, among other words of its block) is the rule's exception
SMALL_CONTROLS = """() => {
  const BLOCK = new Set(['block', 'flex', 'grid', 'table-cell', 'list-item', 'flow-root']);
  const inSentence = (a) => {
    if (a.tagName !== 'A' || getComputedStyle(a).display !== 'inline') return false;
    let p = a.parentElement;
    while (p && !BLOCK.has(getComputedStyle(p).display)) p = p.parentElement;
    const rest = p ? p.textContent.replace(a.textContent, '') : '';
    return rest.replace(/[^A-Za-z]/g, '').length >= 3;
  };
  const out = [];
  for (const el of document.querySelectorAll('a, button, input, select, summary')) {
    if (el.matches('.skip, .sr-only') || el.closest('.sr-only, .pinned-head')) continue;
    const r = el.getBoundingClientRect();
    if (!el.getClientRects().length || (r.width === 0 && r.height === 0)) continue;
    if (getComputedStyle(el).visibility === 'hidden' || inSentence(el)) continue;
    if (r.width < 24 || r.height < 24) {
      out.push(`${el.tagName} ${(el.textContent || el.name || '').trim().slice(0, 30)}: ` +
               `${Math.round(r.width)}x${Math.round(r.height)}`);
    }
  }
  return out; }"""


def test_phone_home_shows_a_table_first(browser, server, artifacts):
    """A phone (its own context: a clean profile at 390x844): the first screen shows Table 1,
    the search box is in view, the links are one tap away behind the menu button, no word
    of the navigation or the table headings is split, and no control is under 24 px."""
    ctx = browser.new_context(viewport={"width": 390, "height": 844}, bypass_csp=True,
                              is_mobile=True, has_touch=True)
    try:
        page = ctx.new_page()
        page.goto(server + "/")
        page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
        top = page.evaluate("document.querySelector('#tbl-plane').getBoundingClientRect().top")
        assert 0 < top < 844 - 100, top          # its headings, not only its top border
        assert not page.locator("details.legend-box").evaluate("d => d.open")
        assert page.evaluate("document.documentElement.scrollWidth") <= 390
        search = page.locator("#nav-q")
        expect(search).to_be_visible()
        assert search.bounding_box()["y"] + search.bounding_box()["height"] <= 844
        menu = page.locator("header.site button.navmenu")
        expect(menu).to_be_visible()
        expect(menu).to_have_attribute("aria-expanded", "false")
        expect(page.locator('header.site nav a[href="/errata"]')).to_be_hidden()
        assert not page.evaluate(BROKEN_WORDS, "table.paper thead th a, nav.pagenav a")
        assert not page.evaluate(SMALL_CONTROLS)
        page.screenshot(path=str(artifacts / "phone-home-390.png"))
        # one tap opens the links, each whole on its line(s)
        menu.tap()
        expect(menu).to_have_attribute("aria-expanded", "true")
        for href, _ in site_shell.NAV:
            expect(page.locator(f'header.site nav a[href="{href}"]')).to_be_visible()
        assert not page.evaluate(BROKEN_WORDS, "header.site nav a")
        assert not page.evaluate(SMALL_CONTROLS)
        page.screenshot(path=str(artifacts / "phone-home-menu-390.png"))
        # the keyboard: Escape folds them and gives the focus back to the button
        page.locator('header.site nav a[href="/errata"]').focus()
        page.keyboard.press("Escape")
        expect(menu).to_have_attribute("aria-expanded", "false")
        expect(menu).to_be_focused()
        page.keyboard.press("Enter")
        expect(menu).to_have_attribute("aria-expanded", "true")
    finally:
        ctx.close()


def test_case_page_on_a_phone_splits_no_word(browser, server, artifacts):
    ctx = browser.new_context(viewport={"width": 390, "height": 844}, bypass_csp=True)
    try:
        page = ctx.new_page()
        page.goto(server + "/case/plane/unbalanced-ball")
        page.wait_for_function("document.body?.dataset.ready === '1'", timeout=60_000)
        expect(page.locator("#nav-q")).to_be_visible()
        assert not page.evaluate(BROKEN_WORDS, "nav.pagenav a, nav.crumbs a")
        assert not page.evaluate(SMALL_CONTROLS)
        assert page.evaluate("document.documentElement.scrollWidth") <= 390
        page.screenshot(path=str(artifacts / "phone-case-390.png"))
    finally:
        ctx.close()


def test_navigation_is_a_full_strip_on_a_projector(page, server):
    page.set_viewport_size({"width": 1280, "height": 720})
    for path in ("/", "/poincare"):
        page.goto(server + path)
        expect(page.locator("header.site button.navmenu")).to_be_hidden()
        for href, _ in site_shell.NAV:
            expect(page.locator(f'header.site nav a[href="{href}"]')).to_be_visible()
        expect(page.locator("#nav-q")).to_be_visible()
        nav = page.evaluate(NAV_ROWS)
        assert nav["rows"] <= 2, (path, nav)
