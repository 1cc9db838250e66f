"""The explorer's pages: / (Tables 1 and 2), /case/{id} (a permalink per case), /errata, and
plotly.js served from the installed plotly package (not copied into the repository)."""

from functools import cache
from pathlib import Path

from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, RedirectResponse, Response

from app.api.deps import PagesDep, SettingsDep, VerdictsDep
from app.core.errors import not_found_page
from app.services import ssr, views
from app.services.reader_pages import render_page

router = APIRouter(include_in_schema=False)
_ONE_DAY = {"Cache-Control": "public, max-age=86400"}


@cache
def plotly_js() -> Path:
    import plotly

    return Path(plotly.__file__).parent / "package_data" / "plotly.min.js"


@router.get("/")
async def home(settings: SettingsDep, verdicts: VerdictsDep, pages: PagesDep) -> HTMLResponse:
    # Tables 1 and 2 in the HTML itself (readable with scripts off); the script redraws
    # them with typeset formulas and verdict marks
    path = settings.static_dir / "index.html"

    def build() -> str:
        by_claim, pending = verdicts.by_claim(), verdicts.pending()
        tables = {tid: views.table(tid, by_claim, pending) for tid in ("plane", "sphere")}
        summary = views.cells_sentence(views.tables_cell_marks(tables.values()))
        return render_page(ssr.home_page(path.read_text(), tables, summary), "index.html")

    return HTMLResponse(pages.get("/", pages.stamp(verdicts, path), build))


@router.get("/case/{case_id:path}")
async def case_page(case_id: str, settings: SettingsDep, verdicts: VerdictsDep,
                    pages: PagesDep):
    if case_id.endswith("/") and case_id.rstrip("/"):
        return RedirectResponse(f"/case/{case_id.rstrip('/')}", status_code=308)
    if not views.is_case(case_id):
        return not_found_page(settings.static_dir, "No such case",
                              f"{case_id!r} names no case of Tables 1 and 2.")
    path = settings.static_dir / "case.html"

    def build() -> str:
        # the claims and their verdicts in the HTML itself (readable with scripts off)
        detail = views.case_detail(case_id, verdicts.by_claim(), verdicts.corrections(),
                                   verdicts.case_state(case_id))
        return render_page(ssr.case_page(path.read_text(), detail), "case.html")

    return HTMLResponse(pages.get(f"/case/{case_id}", pages.stamp(verdicts, path), build))


@router.get("/errata")
async def errata_page(settings: SettingsDep) -> HTMLResponse:
    return HTMLResponse(render_page((settings.static_dir / "errata.html").read_text(),
                                    "errata.html"))


@router.get("/vendor/plotly.min.js")
async def plotly(request: Request) -> Response:
    path = plotly_js()
    if not path.is_file():
        raise HTTPException(404, "plotly.js not found in the plotly package")
    plain = FileResponse(path, media_type="text/javascript", headers=_ONE_DAY)
    # megabytes as it is, a fraction of that as Brotli (app.core.compress)
    return await request.app.state.assets.response(path, request.headers, plain)
