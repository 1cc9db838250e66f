"""The catalogue's data in a reader's words (catalogue/plain_words.py; issue 17, item 7)."""

from __future__ import annotations

import pytest
from typer.testing import CliRunner

from catalogue.load import load_catalogue
from catalogue.plain_words import cite_names, invariant_name, phrase, phrases
from solvers.errors import InputError
from solvers.models.cases import build


@pytest.mark.parametrize("key,value,shown", [
    ("potential", "any", "any potential U(γ)"),
    ("S", "zero", "no gyrostat (S = 0)"),
    ("I", "I1!=I2!=I3!=I1", "I1 ≠ I2 ≠ I3 ≠ I1"),
    ("I", "I=mu*E+lambda*m*B", "I = μE + λmB"),
    ("I", "I1=I2, I1<I3", "I1 = I2, I1 < I3"),
    ("a", "nonzero", "a ≠ 0"),
    ("lambda_", "not 0 or 1", "λ ≠ 0, 1"),
    ("text", "eq3.12 with a = 2R", "(3.10) with a = 2R"),
])
def test_conditions_read_as_words(key, value, shown):
    assert phrase(key, value) == shown


def test_every_condition_of_the_catalogue_reads_without_data_syntax():
    for case in load_catalogue().cases():
        conds = [case.model.model_dump(mode="json", by_alias=True).get("conditions") or {}]
        conds += [c.conditions.model_dump(mode="json", by_alias=True) for c in case.claims]
        for cond in conds:
            for text in phrases(cond):
                assert "!=" not in text and "*" not in text and "_" not in text, text
                assert not text.startswith(("potential:", "S:", "I:")), text


def test_cited_authors_replace_reference_keys():
    assert cite_names(r"functions~\cite{bormam-2} that") == \
        r"functions~\cite{Borisov, Mamaev} that"
    assert cite_names(r"\cite{BF,yaroshuk}") == r"\cite{Borisov, Fedorov; Yaroschuk}"
    assert cite_names(r"\cite{kholm}") == r"\cite{kholm}"     # authors not named: the key


def test_integrals_have_a_readers_name():
    assert invariant_name("unbalanced_F") == "F = M² − m r² (M, ω)"
    assert "_" not in invariant_name("some_new_integral")


def test_the_triangle_inequality_message_names_no_flag_but_the_cli_does():
    with pytest.raises(InputError) as e:
        build("plane/chaplygin-ball", {"I1": 9.0, "I2": 2.0, "I3": 3.0, "m": 1.0, "R": 1.0})
    assert "triangle inequality" in str(e.value) and "--" not in str(e.value)
    assert e.value.option == "allow_any_inertia"
    from app import cli

    res = CliRunner().invoke(cli.cli, ["simulate", "plane/chaplygin-ball", "--set", "I1=9",
                                       "--set", "I2=2", "--set", "I3=3", "--set", "m=1",
                                       "--set", "R=1", "--example"])
    assert res.exit_code != 0
    assert "--allow-any-inertia" in res.output
