"""`rolling verify` and `rolling errata`: the catalogue's claims checked, printed as the
paper's tables with verdict marks, and the misprints, conventions and findings."""

from collections import Counter
from typing import Annotated

import typer

from app.cli.common import (
    TimeoutOpt,
    check_timeout,
    check_workers,
    fail,
    input_message,
    time_limit,
    write_json,
)
from solvers.errors import InputError


def verify(
    case: Annotated[str | None, typer.Option(help="only this case id")] = None,
    claim: Annotated[str | None, typer.Option(help="only this claim id")] = None,
    as_json: Annotated[bool, typer.Option("--json", help="print a JSON list of records")] = False,
    workers: Annotated[int, typer.Option(help="worker processes (0: one per core)")] = 0,
    timeout: TimeoutOpt = None,
):
    """Check every claim of Tables 1-2 and the text; print the tables with verdict marks."""
    # lazy: the catalogue (yaml, pydantic) and the parallel checks, not at the CLI's start
    from catalogue.load import load_catalogue
    from solvers.verify.parallel import verify_parallel

    check_workers(workers, zero="one per core")
    check_timeout(timeout)
    if claim is not None:
        known = {cl.id for c in load_catalogue().cases() if case in (None, c.id)
                 for cl in c.claims}
        if claim not in known:
            where = f" of case {case}" if case else ""
            fail(f"--claim {claim!r}: no such claim{where} (the claim ids: rolling "
                  "verify --json, or GET /api/cases/{id})")
    try:
        with time_limit(timeout):
            records = verify_parallel(case=case, claim=claim, workers=workers)
    except InputError as e:
        fail(input_message(e))
    if as_json:
        write_json(records)
        return
    verify_tables(records, case)


def verify_tables(records, only_case):
    # lazy: rich's tables, not at the CLI's start
    from rich.console import Console
    from rich.markup import escape
    from rich.table import Table

    # lazy: the catalogue (yaml, pydantic) and the checks' marks, not at the CLI's start
    from catalogue.load import load_catalogue
    from catalogue.numbering import cite
    from solvers.verify import marks as vocab
    from solvers.verify.table import cell_id

    con = Console(width=max(Console().width, 160))
    cat = load_catalogue()
    by_claim = {r["claim"]: r for r in records}
    # the same marks, shapes and words as the explorer and /how-we-check (marks.yaml)
    con.print("marks: " + "  ".join(f"{m.shape} {m.name}" for m in vocab.vocabulary()
                                    if m.id != "pending"), markup=False, soft_wrap=True)
    for table in cat.tables():
        cases = [c for c in table.cases if only_case in (None, c.id)]
        if not cases:
            continue
        tab = Table(title=f"{table.caption_plain} "
                    "(cells: the property each states)", show_lines=True)
        tab.add_column("row")
        for c in cases:
            tab.add_column(c.id.split("/", 1)[1], overflow="fold")
        for row in table.rows:
            cells = []
            for c in cases:
                cell = c.cells[row.key]
                rec = by_claim.get(cell_id(c.id, row.key.value))
                plain = cite(cell.plain)      # printed numbers before the cut
                text = plain if len(plain) < 60 else plain[:57] + "..."
                if rec is None:
                    cells.append(escape(text))
                    continue
                m = vocab.by_id()[rec["mark"]]
                cells.append(escape(f"{m.shape} {m.word}: {text}"))
            tab.add_row(row.plain, *cells)
        con.print(tab)
    _verify_summary(con, records)


def _verify_summary(con, records):
    # lazy: the catalogue (yaml) and the checks' marks, not at the CLI's start
    from catalogue.numbering import cite, printed
    from solvers.verify import marks as vocab

    for level in ("cell", "formula"):
        # the project's corrections are records of their own, not claims of the paper
        recs = [r for r in records if r.get("level", "formula") == level
                and r.get("origin") != "project-correction"]
        counts = Counter(r["mark"] for r in recs)
        unit, units = ("cell", "cells") if level == "cell" else ("claim", "claims")
        what = " (properties of table cells)" if level == "cell" else " (printed formulas " \
            "and statements)"
        con.print(f"{units}: {len(recs)}{what}: " + vocab.sentence(
            {k: counts[k] for k in vocab.IDS if counts.get(k)}, unit, units), markup=False)
    con.print(exact_summary(records))
    quals = Counter(r.get("qualifier") for r in records if r.get("qualifier"))
    if quals:
        con.print("formula qualifiers: " + ", ".join(f"{k}: {v}" for k, v in sorted(
            quals.items())))
    cells = [r for r in records if r.get("level") == "cell"]
    shown = [r for r in cells if r["mark"] != "as-printed"]
    if shown:
        con.print("cells that do not simply hold as printed:")
    for r in shown:
        m = vocab.by_id()[r["mark"]]
        note = f": {cite(r['mark_note'])}" if r.get("mark_note") else ""
        errata = f" (errata: {', '.join(r['errata'])})" if r.get("errata") else ""
        con.print(f"{m.shape} {m.name}: cell {r['claim']}{note}{errata}", markup=False)
    con.print("claims that do not hold as printed, or that a check could not decide "
              "(errata: `rolling errata`):")
    for r in records:
        if r.get("level", "formula") != "formula" or r.get("origin") == "project-correction":
            continue
        if r["mark"] in ("as-printed", "evidence-for", "open", "not-checkable"):
            continue
        res = "n/a" if r["residual"] is None else f"{r['residual']:.2e}"
        num = printed(r["label"]) or r["label"] or ""
        where = f" ({num})" if num else ""
        m = vocab.by_id()[r["mark"]]
        note = cite(r.get("mark_note") or r["message"])
        con.print(f"{m.shape} {m.name}: {r['claim']}{where}: residual {res} — {note}",
                  markup=False)


def errata(
    as_json: Annotated[bool, typer.Option("--json", help="print errata, conventions and "
                                          "findings as one JSON object")] = False,
    workers: Annotated[int, typer.Option(help="worker processes (0: one per core)")] = 0,
):
    """List the paper's misprints (printed vs corrected form, residuals, exact witness,
    the command that reproduces each), the conventions and the findings."""
    # lazy: the catalogue (yaml, pydantic) and the checks, not at the CLI's start
    from catalogue.load import load_catalogue
    from solvers.verify import errata as er
    from solvers.verify.parallel import verify_parallel

    check_workers(workers, zero="one per core")
    cat = load_catalogue()
    records = verify_parallel(workers=workers)
    out = {"errata": er.errata(records, cat), "conventions": er.conventions(records, cat),
           "findings": er.findings(records, cat)}
    if as_json:
        write_json(out)
        return
    from rich.console import Console  # lazy: rich, not at the CLI's start

    con = Console(width=max(Console().width, 140))

    def res(x):
        return "n/a" if x is None else f"{x:.2e}"

    con.print(f"[bold]Errata[/bold]: {len(out['errata'])} printed formulas fail; "
              "the project's correction of each holds")
    for e in out["errata"]:
        where = e["number"] or e["where"] or ""
        inh = f" (inherits {e['inherits']})" if e["inherits"] else ""
        con.print(f"✗ [{e['kind']}]{inh} {e['claim']} — {where}"
                  f"{', ' + e['section'] if e['section'] else ''}", markup=False)
        con.print(f"   printed:   {' '.join(e['printed'].split())[:200]}", markup=False)
        con.print(f"   corrected: {e['corrected']}", markup=False)
        if e.get("corrected_display"):
            con.print(f"   display corrected: {e['corrected_display']} — {e['change']}",
                      markup=False)
        con.print(f"   residual printed {res(e['residual_printed'])}, corrected "
                  f"{res(e['residual_corrected'])}", markup=False)
        ex = e.get("exact")
        if ex and ex.get("witness") is not None:
            con.print(f"   exact witness: {ex['witness']}", markup=False)
        con.print(f"   reproduce: {e['reproduce']}", markup=False)
    con.print(f"[bold]Conventions[/bold]: {len(out['conventions'])} printed forms hold "
              "under another convention")
    for e in out["conventions"]:
        con.print(f"✓ {e['claim']} ({e['number'] or e['label']}): {e['convention']}", markup=False)
        con.print(f"   residual under it {res(e['residual_under_convention'])}, with ours "
                  f"{res(e['residual_printed'])}; reproduce: {e['reproduce']}", markup=False)
    con.print(f"[bold]Findings the paper does not have[/bold]: {len(out['findings'])}")
    for e in out["findings"]:
        con.print(f"• [{e['kind']}] {e['title']}", markup=False)
        con.print(f"   {e['finding']}", markup=False)
        num = e["number"] or e["label"]
        con.print(f"   claim {e['claim']} ({num}); reproduce: {e['reproduce']}", markup=False)


def exact_summary(records) -> str:
    """One line: of the verified formula records, how many are proved symbolically, how
    many certified with a Schwartz-Zippel bound (N and k read from the code), how many
    neither (solvers/verify/exact/report.py gives each one's reason); and how many failing
    records an exact rational witness settles."""
    # lazy: the exact checks (numba, scipy, python-flint), not at the CLI's start
    from solvers.verify.exact.report import exact_counts
    c = exact_counts(records)
    return (f"exact: of {c['verified']} verified formula records, {c['proved']} proved "
            f"symbolically, {c['certified']} certified (Schwartz-Zippel, N = 2^{c['bits']} "
            f"grid values per coordinate, k = {c['k']} points seeded by the claim id), "
            f"{c['neither']} neither; {c['witnessed']} of {c['fails']} failing records settled "
            "exactly (rational witness or certified counter-object)")
