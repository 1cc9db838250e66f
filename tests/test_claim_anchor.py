"""A claim's anchor has one rule per language (app/services/anchors.py for the server's
pages, app/static/js/anchor.js for the browser's): both give the same anchor for every claim
of the catalogue, and every page module that links to a claim takes it from there."""

import json
import os
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from app.services.anchors import claim_anchor
from catalogue.load import load_catalogue

STATIC = Path(__file__).resolve().parents[1] / "app" / "static" / "js"
ODD = ["plane/round-disk/eq2.4", "a b", "x//y", "é-ü_1", "sphere/body-of-revolution/(3.2)"]


def test_python_and_javascript_give_the_same_anchors(tmp_path):
    node = shutil.which("node") or shutil.which("nodejs")
    if node is None:
        if os.environ.get("CI"):
            pytest.fail("node is needed to run the page's anchor rule")
        pytest.skip("node not installed (Debian: apt-get install nodejs)")
    ids = [cl.id for case in load_catalogue().cases() for cl in case.claims] + ODD
    script = tmp_path / "anchors.mjs"
    script.write_text(
        "const { claimAnchor } = await import(process.argv[2]);\n"
        "const ids = JSON.parse(process.argv[3]);\n"
        "console.log(JSON.stringify(ids.map(claimAnchor)));\n")
    out = subprocess.run([node, str(script), (STATIC / "anchor.js").as_uri(), json.dumps(ids)],
                         capture_output=True, text=True, timeout=60, check=True)
    assert json.loads(out.stdout) == [claim_anchor(i) for i in ids]
    assert len(ids) > len(ODD)


def test_the_anchor_is_a_fragment_without_odd_characters():
    for i in ODD:
        assert re.fullmatch(r"claim-[A-Za-z0-9_-]+", claim_anchor(i)), i
    assert claim_anchor("plane/round-disk/eq2.4") == "claim-plane_round-disk_eq2_4"


def test_no_page_script_writes_the_rule_again():
    for path in STATIC.glob("*.js"):
        if path.name == "anchor.js":
            continue
        assert '"claim-" +' not in path.read_text(encoding="utf-8"), path.name
