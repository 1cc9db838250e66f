"""GET /api/errata, /api/conventions, /api/findings: the paper's misprints with their
corrections, the printed forms that hold under another convention, and what the project
found that the paper does not have (solvers.verify.errata, from the verdicts computed so
far: cases not yet verified contribute nothing, see /api/health)."""

import json
from pathlib import Path

from fastapi import APIRouter

from app.api.deps import SettingsDep, VerdictsDep
from app.schemas.errata import ConventionPublic, ErratumPublic, FindingPublic
from app.services.errata_pages import with_symbols
from catalogue.load import load_catalogue
from solvers.verify import errata

router = APIRouter(tags=["errata"])


def store_records(store) -> list[dict]:
    return [r for recs in store.records.values() for r in recs]


@router.get("/errata", response_model=list[ErratumPublic])
async def get_errata(store: VerdictsDep) -> list[dict]:
    """Every printed formula that fails where the project's correction holds (misprints,
    and failures inherited from one), with both forms, both residuals, where it is printed,
    the exact witness when there is one and the command that reproduces it."""
    return with_symbols(errata.errata(store_records(store), load_catalogue()))


@router.get("/conventions", response_model=list[ConventionPublic])
async def get_conventions(store: VerdictsDep) -> list[dict]:
    """Printed forms that hold under another convention (e.g. the orientation of a
    Poisson bracket), with the convention and the residuals under it and under ours."""
    return with_symbols(errata.conventions(store_records(store), load_catalogue()))


@router.get("/findings", response_model=list[FindingPublic])
async def get_findings(store: VerdictsDep, settings: SettingsDep) -> list[dict]:
    """What the project found that the paper does not have: hedged claims answered and
    printed statements refuted, with their evidence; checks that could not decide while
    what they found leans against the paper (inconclusive); and the paper's figures whose
    caption the recomputed figure does not confirm."""
    cat = load_catalogue()
    return with_symbols(errata.findings(store_records(store), cat) + figure_findings_of(
        settings.static_dir / "data" / "paper_figures.json"))


def figure_findings_of(path: Path) -> list[dict]:
    """From the figure data bench/paper_figures.py writes (about a megabyte of points:
    parsed again only when the file changes)."""
    if not path.is_file():
        return []
    key = (str(path), path.stat().st_mtime_ns)
    if _FIGURES.get("key") != key:
        figs = json.loads(path.read_text(encoding="utf-8"))["figures"]
        _FIGURES.update(key=key, out=errata.figure_findings(figs, load_catalogue()))
    return [dict(f) for f in _FIGURES["out"]]


_FIGURES: dict = {}
