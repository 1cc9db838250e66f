"""The explorer's pages: / (Tables 1 and 2), /case/{id} (a permalink per case), /errata, and
plotly.js served from the installed plotly package (not copied into the repository)."""

from functools import cache
from pathlib import Path

from fastapi import APIRouter, HTTPException
from fastapi.responses import FileResponse, HTMLResponse

from app.api.deps import SettingsDep
from catalogue.load import load_catalogue

router = APIRouter(include_in_schema=False)
_ONE_DAY = {"Cache-Control": "public, max-age=86400"}


@cache
def plotly_js() -> Path:
    import plotly

    return Path(plotly.__file__).parent / "package_data" / "plotly.min.js"


@router.get("/")
async def home(settings: SettingsDep) -> FileResponse:
    return FileResponse(settings.static_dir / "index.html", media_type="text/html")


@router.get("/case/{case_id:path}")
async def case_page(case_id: str, settings: SettingsDep):
    try:
        load_catalogue().case(case_id)
    except KeyError:
        return HTMLResponse((settings.static_dir / "404.html").read_text(), status_code=404)
    return FileResponse(settings.static_dir / "case.html", media_type="text/html")


@router.get("/errata")
async def errata_page(settings: SettingsDep) -> FileResponse:
    return FileResponse(settings.static_dir / "errata.html", media_type="text/html")


@router.get("/vendor/plotly.min.js")
async def plotly() -> FileResponse:
    path = plotly_js()
    if not path.is_file():
        raise HTTPException(404, "plotly.js not found in the plotly package")
    return FileResponse(path, media_type="text/javascript", headers=_ONE_DAY)
