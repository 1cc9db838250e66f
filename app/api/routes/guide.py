"""/guide/: the user guide. Its sources are docs/ (Markdown) and mkdocs.yml; `mkdocs build`
writes it to site/ at the repository root (or to the directory ROLLING_GUIDE_DIR names), and
this route serves that directory as it is. Before it is built, /guide/ answers a page in the
site's shell that says how to build it.

The built pages are mkdocs-material's. They start from a few inline scripts (the theme's
settings), which the explorer's Content-Security-Policy (app.core.guards.CSP: this server
only, no inline script) would block; each HTML answer allows exactly its own inline scripts
by their SHA-256 hashes, nothing else.
"""

from __future__ import annotations

import base64
import hashlib
import re
from functools import lru_cache
from pathlib import Path

from fastapi import APIRouter
from fastapi.responses import FileResponse, HTMLResponse, RedirectResponse, Response

from app.api.deps import SettingsDep
from app.core.config import ROOT, Settings
from app.core.errors import not_found_page
from app.core.guards import CSP
from app.services.reader_pages import layout

router = APIRouter(include_in_schema=False)
_INLINE = re.compile(r"<script(?![^>]*\bsrc=)([^>]*)>(.*?)</script>", re.S | re.I)


def guide_dir(settings: Settings) -> Path | None:
    """The built guide's directory, or None when it is not built (no index.html there)."""
    root = Path(settings.guide_dir) if settings.guide_dir is not None else ROOT / "site"
    return root.resolve() if (root / "index.html").is_file() else None


def not_built_page() -> str:
    body = """<p>The user guide is not built on this machine. Its sources are the Markdown
pages in <code>docs/</code> of the repository, with <code>mkdocs.yml</code> at its root.
Build it there with</p>
<pre><code>mkdocs build</code></pre>
<p>(<code>pip install -e ".[docs]"</code> installs mkdocs; <code>./dev serve</code> builds
the guide while the explorer starts). The explorer serves the built guide from
<code>site/</code> at the repository root, or from the directory the setting
<code>ROLLING_GUIDE_DIR</code> names; reload this page once it is built.</p>
<p>Meanwhile, <a href="/how-we-check">How we check</a> says what each check computes,
the <a href="/glossary">glossary</a> defines every symbol, and <a href="/docs">the API
page</a> documents every REST address.</p>"""
    return layout("User guide", body, "/guide/")


@lru_cache(maxsize=256)
def _csp_for(path: str, mtime_ns: int) -> str:
    """The CSP of one built page: its inline scripts allowed by hash (JSON data blocks are
    not scripts a browser runs, and need none)."""
    text = Path(path).read_text(encoding="utf-8", errors="replace")
    hashes = []
    for attrs, code in _INLINE.findall(text):
        if re.search(r"type\s*=\s*[\"']?application/(?:ld\+)?json", attrs, re.I):
            continue
        digest = base64.b64encode(hashlib.sha256(code.encode()).digest()).decode()
        hashes.append(f"'sha256-{digest}'")
    extra = " ".join(dict.fromkeys(hashes))
    return CSP.replace("script-src 'self'", f"script-src 'self' {extra}".rstrip())


@router.get("/guide/{path:path}")
async def guide(path: str, settings: SettingsDep) -> Response:
    root = guide_dir(settings)
    if root is None:
        if path in ("", "index.html"):
            return HTMLResponse(not_built_page())
        return not_found_page(settings.static_dir, "The guide is not built",
                              "The user guide is not built on this machine: /guide/ says "
                              "how to build it.")
    target = (root / path).resolve()
    if not target.is_relative_to(root):
        return not_found_page(settings.static_dir, "No such page",
                              f"/guide/{path} is not a page of the guide.")
    if target.is_dir():
        if path and not path.endswith("/"):
            return RedirectResponse(f"/guide/{path}/", status_code=308)
        target = target / "index.html"
    if not target.is_file():
        return not_found_page(settings.static_dir, "No such page",
                              f"/guide/{path} is not a page of the guide.")
    if target.suffix == ".html":
        csp = _csp_for(str(target), target.stat().st_mtime_ns)
        return HTMLResponse(target.read_bytes(), headers={"content-security-policy": csp})
    return FileResponse(target)
