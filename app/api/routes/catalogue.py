"""GET /api/catalogue (JSON) and /api/catalogue.yaml: the whole validated catalogue."""

import json
from functools import cache

import yaml
from fastapi import APIRouter
from fastapi.responses import Response

from catalogue.load import load_catalogue

router = APIRouter(tags=["catalogue"])


@cache
def _dump() -> dict:
    return load_catalogue().model_dump(mode="json", by_alias=True)


@cache
def _json() -> bytes:
    return json.dumps(_dump(), ensure_ascii=False, indent=1).encode()


@cache
def _yaml() -> bytes:
    return yaml.safe_dump(_dump(), allow_unicode=True, sort_keys=False, width=100).encode()


_SCHEMA = {"description": "the catalogue (catalogue/schema.py: Catalogue)",
           "content": {"application/json": {"schema": {"type": "object"}}}}


@router.get("/catalogue", responses={200: _SCHEMA})
async def catalogue_json() -> Response:
    """Tables 1 and 2, every claim, the references and the formulas, as JSON."""
    return Response(_json(), media_type="application/json", headers={
        "Content-Disposition": 'inline; filename="rolling-hierarchy-catalogue.json"'})


@router.get("/catalogue.yaml", responses={200: {"content": {"application/yaml": {}}}})
async def catalogue_yaml() -> Response:
    """The same as YAML."""
    return Response(_yaml(), media_type="application/yaml; charset=utf-8", headers={
        "Content-Disposition": 'attachment; filename="rolling-hierarchy-catalogue.yaml"'})
