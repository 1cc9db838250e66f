"""The bytes of a run: JSON (orjson straight from the numpy arrays), Arrow IPC, and the
content negotiation between them.

Turning a run into JSON through Python lists (`ndarray.tolist()` then `json.dumps`) took
many times longer than the run itself (docs/performance.md); orjson writes the arrays
themselves.
JSON stays strict: a non-finite number is `null`, as before (orjson writes NaN and
+-inf as null, in arrays and scalars alike).

Arrow (`application/vnd.apache.arrow.stream`, one record batch): one float64 column per
series, named as in the CSV and the JSON (`t`, the state labels, then the invariants under
their output names, `M_squared` for |M|^2 beside the component `M2`:
solvers/models/observables.py); the rest of the JSON answer (case, params, status,
message, state_labels, invariants: the invariants' column names, stats, provenance) is in
the schema's metadata, each value a JSON text under its own key. Floats are IEEE doubles
there, so a non-finite value stays NaN or inf (Arrow has no need of null for it).
"""

from __future__ import annotations

import json
import math

import numpy as np
import orjson

from app.core.errors import NotAcceptable

JSON = "application/json"
ARROW = "application/vnd.apache.arrow.stream"
CSV = "text/csv"
OFFERED = (JSON, ARROW, CSV)      # in order of preference when the client has none
_OPTS = orjson.OPT_SERIALIZE_NUMPY | orjson.OPT_NON_STR_KEYS


def _ranges(accept: str):
    for part in accept.split(","):
        fields = [f.strip() for f in part.split(";")]
        media = fields[0].lower()
        if not media:
            continue
        q = 1.0
        for f in fields[1:]:
            k, _, v = f.partition("=")
            if k.strip().lower() == "q":
                try:
                    q = float(v)
                except ValueError:
                    q = 0.0
        yield media, q


def negotiate(accept: str | None, offered=OFFERED) -> str:
    """The offered type the Accept header prefers (RFC 9110 12.5.1: the most specific
    range decides a type's quality; ties go to the order of `offered`). No header, or
    */*: the first offered (JSON). Raises NotAcceptable if every offered type has q = 0."""
    if not accept or not accept.strip():
        return offered[0]
    ranges = list(_ranges(accept))
    best, best_q = None, 0.0
    for typ in offered:
        major = typ.split("/")[0]
        q, spec = 0.0, -1
        for media, mq in ranges:
            s = (2 if media == typ else 1 if media == f"{major}/*" else 0 if media == "*/*"
                 else -1)
            if s > spec:
                q, spec = mq, s
        if q > best_q:
            best, best_q = typ, q
    if best is None:
        raise NotAcceptable(f"Accept: {accept[:200]!r} names none of the types this route "
                            f"answers with: {', '.join(offered)}")
    return best


def dumps(obj) -> bytes:
    """Strict JSON of plain data that may hold numpy arrays and scalars; non-finite
    numbers become null."""
    try:
        return orjson.dumps(obj, option=_OPTS)
    except TypeError:       # something orjson does not take (a >64-bit int, an object)
        return json.dumps(finite(_plain(obj)), allow_nan=False,
                          separators=(",", ":")).encode()


def finite(x):
    """Plain data with every non-finite float replaced by None (strict JSON's null)."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: finite(v) for k, v in x.items()}
    if isinstance(x, list):
        return [finite(v) for v in x]
    return x


def csv_header(state_labels: list[str], invariants: list[str]) -> list[str]:
    """t, the state, then the invariants under their output names (the JSON's keys,
    solvers/models/observables.py): unique by construction, |M|^2 is `M_squared` beside
    the component `M2`."""
    header = ["t", *state_labels, *invariants]
    if len(set(header)) != len(header):
        raise ValueError(f"column names repeat: {header}")
    return header


def _plain(x):
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, np.generic):
        return x.item()
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_plain(v) for v in x]
    return x


def result_dict(res, max_steps: int, prov: dict | None = None) -> dict:
    """The JSON answer of a run (SimulateResponse), arrays left as numpy arrays; `prov`:
    the run's provenance (app/services/provenance.py), stamped with the time it ran."""
    # lazy: the provenance's glossary (the catalogue's pydantic models), not at the start of
    # the command line's JSON output, which imports this module for `dumps`
    from app.services.provenance import stamped

    out = res.to_json(arrays=True)
    out["stats"] = {**out["stats"], "max_steps": max_steps}
    if prov is not None:
        out["provenance"] = stamped(prov, res, out["stats"])
    return out


def json_bytes(res, max_steps: int, prov: dict | None = None) -> bytes:
    return dumps(result_dict(res, max_steps, prov))


def arrow_bytes(res, max_steps: int, prov: dict | None = None) -> bytes:
    # lazy: pyarrow, whose imports take a noticeable time and which only this answer needs,
    # not at the server's start
    import pyarrow as pa

    out = result_dict(res, max_steps, prov)
    labels = list(res.state_labels)
    names = list(res.invariants)
    header = csv_header(labels, names)
    state = np.asarray(res.state, dtype=np.float64).reshape(len(res.t), len(labels))
    cols = [np.asarray(res.t, dtype=np.float64)]
    cols += [np.ascontiguousarray(state[:, j]) for j in range(len(labels))]
    cols += [np.asarray(res.invariants[n], dtype=np.float64) for n in names]
    meta = {k: dumps(out[k]) for k in ("case", "params", "status", "message", "state_labels",
                                        "stats", "provenance") if k in out}
    meta["invariants"] = dumps(names)
    batch = pa.record_batch([pa.array(c, type=pa.float64()) for c in cols], names=header)
    batch = batch.replace_schema_metadata(meta)
    sink = pa.BufferOutputStream()
    with pa.ipc.new_stream(sink, batch.schema) as writer:
        writer.write_batch(batch)
    return sink.getvalue().to_pybytes()
