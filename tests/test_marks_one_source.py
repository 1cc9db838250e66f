"""The marks and the coarse verdicts' signs are defined once, in solvers/verify/marks.yaml:
/how-we-check's API lists exactly its verdicts, in its order, with its signs and meanings,
and no page script keeps a table of its own."""

from pathlib import Path

import pytest
import yaml
from fastapi.testclient import TestClient

from app.main import create_app
from app.testing import settings_for_tests

ROOT = Path(__file__).resolve().parents[1]
pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")


def test_how_we_check_gives_the_verdicts_of_marks_yaml():
    raw = yaml.safe_load((ROOT / "solvers" / "verify" / "marks.yaml").read_text())
    with TestClient(create_app(settings_for_tests(warm_workers=False))) as c:
        body = c.get("/api/how-we-check").json()
    assert [(v["verdict"], v["mark"], v["meaning"]) for v in body["verdicts"]] == [
        (v["id"], v["shape"], v["meaning"]) for v in raw["verdicts"]]
    assert [m["id"] for m in body["marks"]] == [m["id"] for m in raw["marks"]]


def test_no_script_keeps_its_own_table_of_verdict_signs():
    signs = {v["shape"] for v in yaml.safe_load(
        (ROOT / "solvers" / "verify" / "marks.yaml").read_text())["verdicts"]}
    for path in (ROOT / "app" / "static" / "js").glob("*.js"):
        text = path.read_text(encoding="utf-8")
        assert not ("evidence:" in text and any(f'"{s}"' in text for s in signs)), path.name
