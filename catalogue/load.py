"""Load the catalogue YAML files once and validate them against `catalogue.schema`.

    from catalogue.load import load_catalogue
    cat = load_catalogue()            # cached: parsed and validated on first call only
    cat.case("plane/routh-ball").claims

`read_raw` / `build` are the two halves, exposed for tests (e.g. feeding a broken entry).
"""

from __future__ import annotations

from functools import cache
from pathlib import Path
from typing import Any

import yaml

from catalogue.schema import Catalogue, CorrectedForm, CorrectedForms, RubberTables

DATA_DIR = Path(__file__).resolve().parent
FILES = {
    "plane": "plane.yaml",
    "sphere": "sphere.yaml",
    "references": "references.yaml",
    "formulas": "formulas.yaml",
}


class UniqueKeyLoader(yaml.SafeLoader):
    """SafeLoader that refuses duplicate mapping keys (PyYAML silently keeps the last)."""


def _mapping_no_duplicates(loader: yaml.SafeLoader, node: yaml.MappingNode) -> dict[Any, Any]:
    seen: set[Any] = set()
    for key_node, _ in node.value:
        key = loader.construct_object(key_node)
        if key in seen:
            raise yaml.constructor.ConstructorError(
                None, None, f"duplicate key {key!r}", key_node.start_mark
            )
        seen.add(key)
    return loader.construct_mapping(node)


UniqueKeyLoader.add_constructor(
    yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _mapping_no_duplicates
)


def read_raw(directory: Path = DATA_DIR) -> dict[str, Any]:
    """The four YAML files as plain data, keyed like the fields of `Catalogue`."""
    raw: dict[str, Any] = {}
    for field, name in FILES.items():
        with open(directory / name, encoding="utf-8") as fh:
            raw[field] = yaml.load(fh, Loader=UniqueKeyLoader)  # a SafeLoader subclass
    return raw


def build(raw: dict[str, Any]) -> Catalogue:
    """Validate plain data into a `Catalogue` (raises pydantic.ValidationError)."""
    return Catalogue.model_validate(raw)


@cache
def load_catalogue() -> Catalogue:
    """The catalogue shipped with the package, parsed and validated once per process."""
    return build(read_raw(DATA_DIR))


@cache
def load_corrected_forms(directory: Path = DATA_DIR) -> dict[str, CorrectedForm]:
    """corrected_forms.yaml validated: formula id -> its corrected form (latex, change and
    the formula whose display is corrected); every `display` names a formula."""
    with open(directory / "corrected_forms.yaml", encoding="utf-8") as fh:
        raw = yaml.load(fh, Loader=UniqueKeyLoader)
    forms = CorrectedForms.model_validate(raw).root
    known = {f.id for f in load_catalogue().formulas} if directory == DATA_DIR else None
    for fid, cf in forms.items():
        if known is not None and (fid not in known or (cf.display and cf.display not in known)):
            raise ValueError(f"corrected form {fid}: unknown formula {fid!r} or {cf.display!r}")
    return forms


RUBBER_FILES = {"sources": "rubber_sources.yaml", "plane": "rubber_plane.yaml",
                "sphere": "rubber_sphere.yaml"}


def read_rubber_raw(directory: Path = DATA_DIR) -> dict[str, Any]:
    """The three YAML files of the rubber tables as plain data, keyed like RubberTables."""
    raw: dict[str, Any] = {}
    for field, name in RUBBER_FILES.items():
        with open(directory / name, encoding="utf-8") as fh:
            raw[field] = yaml.load(fh, Loader=UniqueKeyLoader)
    raw["sources"] = raw["sources"]["sources"]
    return raw


@cache
def load_rubber() -> RubberTables:
    """The rubber tables (beyond the 2002 paper) and their sources, validated once."""
    return RubberTables.model_validate(read_rubber_raw(DATA_DIR))
