"""A resolved bibliography: every complete entry of
catalogue/references.yaml takes each of its fields from a named source (the seed itself or a
checked source that gives that field), an unresolved entry says what is missing, and
/bibliography shows both. The target of the issue, at least 35 of the 41 keys complete, is
stated as its own test and marked as not met while the sources read do not reach it."""

import copy
import html
import re
from pathlib import Path
from typing import get_args

import pytest
import yaml
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests
from catalogue.load import DATA_DIR, load_catalogue
from catalogue.schema import BIB_FIELDS, Reference, SourceKind

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

TARGET = 35     # the threshold of complete keys, out of the paper's 41
# the kinds of source an entry may be checked in: the catalogue's own list, one definition
KINDS = get_args(SourceKind)


@pytest.fixture(scope="module")
def client():
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        yield c


def _raw() -> list[dict]:
    return yaml.safe_load(Path(DATA_DIR, "references.yaml").read_text(encoding="utf-8"))


def _complete() -> list[Reference]:
    return [r for r in load_catalogue().references if r.status == "complete"]


def test_every_field_of_a_complete_entry_names_its_source():
    complete = _complete()
    assert complete
    for r in complete:
        sources = r.field_sources()
        # the fields a complete entry needs are there, each with at least one source
        needed = ["authors", "title", "journal", "year"]
        if r.form == "article":
            needed += ["volume", "pages"]
        for f in needed:
            assert f in sources, (r.id, f)
        for f, srcs in sources.items():
            assert srcs, (r.id, f)
            for s in srcs:
                assert s == "seed" or s.startswith(("http://", "https://")), (r.id, f, s)
        # a source named as giving a field is a checked source of this entry, of a known
        # kind, read at least in part; it gives only fields the entry has
        for c in r.checked_in:
            assert c.kind in KINDS and c.access in ("full", "abstract", "snippet"), r.id
            assert c.source.strip(), r.id
            assert set(c.gives) <= set(sources), (r.id, c.url, c.gives)
        # only the paper's own entry takes fields from the seed
        assert not r.seed_gives or r.id == "this-paper", r.id
        assert r.id == "this-paper" or r.identity, r.id


def test_an_unresolved_entry_says_what_is_missing():
    for r in load_catalogue().references:
        if r.status == "unresolved":
            assert r.missing, r.id
            assert not (set(r.missing) - {"authors", "title", "journal", "year", "volume",
                                          "pages", "checked source"}), r.id


def test_a_field_no_source_gives_is_refused():
    raw = _raw()
    entry = next(e for e in raw if e["id"] == "korteweg")
    # drop the only source of the title: the entry may no longer say complete
    bad = copy.deepcopy(entry)
    bad["checked_in"] = [c for c in bad["checked_in"] if "title" not in c.get("gives", [])]
    with pytest.raises(ValueError, match=r"\['title'\] are given by no named source"):
        Reference.model_validate(bad)
    # a complete article without pages is refused as complete
    bad = copy.deepcopy(entry)
    del bad["pages"]
    with pytest.raises(ValueError, match="missing"):
        Reference.model_validate(bad)
    # the same fields without any source read is unresolved, and says so
    bad = copy.deepcopy(entry)
    bad.update(status="unresolved", checked_in=[], identity=None)
    assert Reference.model_validate(bad).missing == ["checked source"]
    # the valid entry itself loads, with every field sourced
    assert Reference.model_validate(entry).unsourced == []
    assert set(BIB_FIELDS) >= set(Reference.model_validate(entry).field_sources())


def test_the_page_counts_and_shows_each_entry_with_its_sources(client):
    page = client.get("/bibliography").text
    refs = load_catalogue().references
    done = sum(r.status == "complete" for r in refs)
    assert f"{done} complete, {len(refs) - done} unresolved." in page
    for r in refs:
        m = re.search(rf'<li id="ref-{re.escape(r.id)}" data-status="(\w+)">(.*?)<p>Cited for',
                      page, re.S)
        assert m and m[1] == r.status, r.id
        item = m[2]
        if r.status == "unresolved":
            assert "missing: " + html.escape(", ".join(r.missing)) in item, r.id
            continue
        for c in r.checked_in:
            assert f'href="{html.escape(c.url)}"' in item, r.id
            if c.gives:
                assert f'data-gives="{" ".join(c.gives)}"' in item, (r.id, c.url)
        if r.seed_gives:
            assert f'data-gives="{" ".join(r.seed_gives)}"' in item, r.id


def test_the_api_gives_each_field_with_its_sources(client):
    refs = {r["id"]: r for r in client.get("/api/references").json()}
    for r in load_catalogue().references:
        got = refs[r.id]
        assert got["field_sources"] == r.field_sources(), r.id
        if r.status == "complete":
            assert all(got["field_sources"].values()), r.id


@pytest.mark.xfail(strict=True, reason="the target of 35 complete keys is not met: the stored "
                   "sources (reference lists read only in their first entries, database "
                   "records) resolve fewer keys; each unresolved entry says what is missing")
def test_at_least_35_of_the_41_keys_are_complete():
    refs = load_catalogue().references
    assert len(refs) == 41
    assert sum(r.status == "complete" for r in refs) >= TARGET
