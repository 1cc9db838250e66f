"""The explorer's pages: / (Tables 1 and 2), /case/{id} (a permalink per case), /errata (with
its exports /errata.csv and /errata.bib), and
plotly.js served from the installed plotly package (not copied into the repository)."""

from functools import cache
from pathlib import Path

import plotly as plotly_package
from fastapi import APIRouter, HTTPException, Request
from fastapi.responses import FileResponse, HTMLResponse, RedirectResponse, Response

from app.api.deps import PagesDep, SettingsDep, VerdictsDep
from app.api.routes.errata import figure_findings_of, store_records
from app.core.errors import not_found_page
from app.services import errata_pages, ssr, views
from app.services.reader_pages import render_page
from catalogue.load import load_catalogue
from solvers.verify import errata

router = APIRouter(include_in_schema=False)
_ONE_DAY = {"Cache-Control": "public, max-age=86400"}


@cache
def plotly_js() -> Path:
    return Path(plotly_package.__file__).parent / "package_data" / "plotly.min.js"


@router.get("/")
async def home(settings: SettingsDep, verdicts: VerdictsDep, pages: PagesDep) -> HTMLResponse:
    # Tables 1 and 2 in the HTML itself (readable with scripts off); the script redraws
    # them with typeset formulas and verdict marks
    path = settings.static_dir / "index.html"

    def build() -> str:
        by_claim, pending = verdicts.by_claim(), verdicts.pending()
        tables = {tid: views.table(tid, by_claim, pending) for tid in ("plane", "sphere")}
        summary = views.cells_sentence(views.tables_cell_marks(tables.values()))
        return render_page(path.read_text(), "index.html", **ssr.home_context(tables, summary))

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
        return render_page(path.read_text(), "case.html", **ssr.case_context(detail))

    return HTMLResponse(pages.get(f"/case/{case_id}", pages.stamp(verdicts, path), build))


def _errata_rows(verdicts, settings) -> tuple[list[dict], list[dict], list[dict]]:

    records, cat = store_records(verdicts), load_catalogue()
    return (errata.errata(records, cat), errata.conventions(records, cat),
            errata.findings(records, cat) + figure_findings_of(
                settings.static_dir / "data" / "paper_figures.json"))


def _base_url(request: Request, settings) -> str:
    """The configured public address, else the address this request was made to."""
    return settings.public_url or str(request.base_url).rstrip("/")


@router.get("/errata")
async def errata_page(settings: SettingsDep, verdicts: VerdictsDep,
                      pages: PagesDep) -> HTMLResponse:
    # the counts, the index and every row in the HTML itself (readable with scripts off);
    # errata.js redraws them with typeset formulas
    path = settings.static_dir / "errata.html"

    def build() -> str:
        ers, cvs, fds = _errata_rows(verdicts, settings)
        return render_page(path.read_text(), "errata.html", **errata_pages.errata_context(
            ers, cvs, fds, verdicts.state, len(verdicts.records), len(verdicts.case_ids)))

    # the figure findings come from a file of their own: its change is a new page too
    figures = settings.static_dir / "data" / "paper_figures.json"
    stamp = (*pages.stamp(verdicts, path),
             figures.stat().st_mtime_ns if figures.is_file() else None)
    return HTMLResponse(pages.get("/errata", stamp, build))


def _errata_export(request: Request, settings, verdicts, written, media_type: str,
                   filename: str) -> Response:
    """The misprints as a file: `written(rows, base_url)` served inline as `filename`."""
    ers, _, _ = _errata_rows(verdicts, settings)
    return Response(written(ers, _base_url(request, settings)), media_type=media_type,
                    headers={"Content-Disposition": f'inline; filename="{filename}"'})


@router.get("/errata.csv")
async def errata_csv(request: Request, settings: SettingsDep,
                     verdicts: VerdictsDep) -> Response:
    """The misprints' table, one line per row (the verdicts computed so far)."""
    return _errata_export(request, settings, verdicts, errata_pages.errata_csv,
                          "text/csv; charset=utf-8", "errata.csv")


@router.get("/errata.bib")
async def errata_bib(request: Request, settings: SettingsDep,
                     verdicts: VerdictsDep) -> Response:
    """The paper's BibTeX entry and one @misc per misprint (the explorer's erratum)."""
    return _errata_export(request, settings, verdicts, errata_pages.errata_bibtex,
                          "application/x-bibtex; charset=utf-8", "errata.bib")


@router.get("/vendor/plotly.min.js")
async def plotly(request: Request) -> Response:
    path = plotly_js()
    if not path.is_file():
        raise HTTPException(404, "plotly.js not found in the plotly package")
    plain = FileResponse(path, media_type="text/javascript", headers=_ONE_DAY)
    # megabytes as it is, a fraction of that as Brotli (app.core.compress)
    return await request.app.state.assets.response(path, request.headers, plain)
