"""The reader's data: the glossary covers every parameter and state variable of every case
(validated by its pydantic model), and every reference key the catalogue uses resolves."""

import re

import pytest
import yaml
from conftest import find_seed
from pydantic import ValidationError

from catalogue.glossary import PATH, Glossary, load_glossary
from catalogue.load import load_catalogue
from catalogue.numbering import printed
from solvers.models.bodies import STATE_LABELS
from solvers.models.cases import registry


def test_every_parameter_and_state_variable_has_an_entry():
    g = load_glossary()
    names = {n for spec in registry().values() for n in spec.param_names}
    names |= {n for labels in STATE_LABELS.values() for n in labels}
    missing = sorted(n for n in names if g.get(n) is None)
    assert not missing, missing


def test_glossary_cites_the_paper_by_printed_numbers():
    for e in load_glossary().entries:
        for lab in e.paper:
            assert printed(lab), f"{e.symbol}: {lab} has no printed number"


def test_glossary_rejects_unknown_fields():
    data = yaml.safe_load(PATH.read_text())
    data["entries"][0]["unit"] = "kg"
    with pytest.raises(ValidationError):
        Glossary.model_validate(data)


def test_every_reference_key_resolves():
    cat = load_catalogue()
    ids = {r.id for r in cat.references}
    used = {a.ref for case in cat.cases() for c in case.claims for a in c.attribution}
    used |= {a.ref for case in cat.cases() for cell in case.cells.values()
             for a in cell.attribution}
    assert used and used <= ids, sorted(used - ids)


def test_every_cite_key_of_the_seed_resolves():
    seed = find_seed()
    if seed is None:
        pytest.skip("seed not found (ROLLING_SEED)")
    keys = {k.strip() for grp in re.findall(r"\\cite\{([^}]*)\}", seed.read_text())
            for k in grp.split(",")}
    ids = {r.id for r in load_catalogue().references}
    assert keys and keys <= ids, sorted(keys - ids)
