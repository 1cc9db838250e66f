"""Helpers of the browser tests that read drawn plots and save screenshots."""

import os
from pathlib import Path

import numpy as np


def drawn(y):
    """A trace's values as drawn (null: a gap) as floats."""
    return np.array([np.nan if v is None else v for v in y], dtype=float)


def shot_dirs(artifacts: Path) -> list[Path]:
    """Where a screenshot goes: the test artifacts, and ROLLING_DOC_SHOTS/ when it is set
    (the guide's screenshots), each made if missing."""
    out = [artifacts]
    if os.environ.get("ROLLING_DOC_SHOTS"):
        out.append(Path(os.environ["ROLLING_DOC_SHOTS"]))
    for d in out:
        d.mkdir(parents=True, exist_ok=True)
    return out
