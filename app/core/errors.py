"""Error answers: every failure the service designs for is a Problem with a message a
person understands, never a 500.

FastAPI's default 422 handler echoes the offending input, and a body with NaN or 1e999
(which json.loads turns into inf) then fails to serialise and becomes a 500; the handler
here renders non-finite numbers as text first.
"""

from __future__ import annotations

import html
import math
import re
from pathlib import Path
from typing import Annotated

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import HTMLResponse, JSONResponse, Response
from markupsafe import Markup
from pydantic import BaseModel, TypeAdapter, ValidationError
from starlette.exceptions import HTTPException as StarletteHTTPException

from app.core.disconnect import ClientDisconnected
from app.core.pool import DeadlineExceeded, QueueFull, WorkerCrashed, WorkerUnavailable
from app.schemas.common import FieldError, Problem
from solvers.errors import InputError


class NotAcceptable(Exception):
    """The client's Accept header names none of the types a route answers with (406)."""


# pydantic error types -> the reason in words (otherwise pydantic's own message)
_REASONS = {
    "finite_number": "must be a finite number (NaN and infinities are not accepted)",
    "missing": "is required",
    "extra_forbidden": "is not a field of this request",
    "float_type": "must be a number",
    "float_parsing": "must be a number",
    "int_type": "must be an integer",
    "int_parsing": "must be an integer",
    "int_from_float": "must be an integer",
    "bool_type": "must be true or false",
    "bool_parsing": "must be true or false",
    "list_type": "must be a list of numbers",
    "dict_type": "must be an object of NAME: number",
    "string_type": "must be a string",
}


def _safe(value, depth: int = 0):
    """The input as JSON can carry it: non-finite floats as text, big inputs cut short."""
    if isinstance(value, float) and not math.isfinite(value):
        return "NaN" if math.isnan(value) else ("Infinity" if value > 0 else "-Infinity")
    if depth > 3:
        return "..."
    if isinstance(value, dict):
        return {str(k): _safe(v, depth + 1) for k, v in list(value.items())[:20]}
    if isinstance(value, list | tuple):
        return [_safe(v, depth + 1) for v in list(value)[:20]]
    if isinstance(value, str) and len(value) > 200:
        return value[:200] + "..."
    if isinstance(value, int) and abs(value) > 10**30:
        return f"{str(value)[:20]}... ({len(str(value))} digits)"
    return value


def _part(p) -> str | int:
    """A piece of an error's location; a dict key comes from the input: cut it short."""
    if isinstance(p, int):
        return p
    text = str(p)
    return text if len(text) <= 40 else text[:37] + "..."


def _field(loc) -> str:
    parts = [str(_part(p)) for p in loc if p not in ("body", "path", "query")]
    out = ""
    for p in parts:
        out += f"[{p}]" if p.isdigit() else (f".{p}" if out else p)
    return out or "body"


def _short(value) -> str:
    if isinstance(value, float) and not math.isfinite(value):
        return str(_safe(value))
    text = repr(_safe(value))
    return text if len(text) <= 60 else text[:57] + "..."


# bounds by pydantic's error types: said with the bound as a person writes it (pydantic
# writes 1e-300 with three hundred digits)
_BOUNDS = {"greater_than": ("gt", "greater than"),
           "greater_than_equal": ("ge", "greater than or equal to"),
           "less_than": ("lt", "less than"), "less_than_equal": ("le", "less than or equal to")}


def _number(v) -> str:
    if isinstance(v, float) and v.is_integer() and abs(v) < 1e16:
        return str(int(v))
    return repr(v)


def _sentence(err: dict) -> str:
    kind = err.get("type", "")
    if kind == "json_invalid":
        return f"the body is not valid JSON ({err.get('ctx', {}).get('error', 'parse error')})"
    reason = _REASONS.get(kind) or err.get("msg", "is invalid").replace(
        "Input should be", "must be").replace("Value error, ", "")
    key, words = _BOUNDS.get(kind, (None, None))
    if key is not None and isinstance(err.get("ctx", {}).get(key), int | float):
        reason = f"must be {words} {_number(err['ctx'][key])}"
    field = _field(err.get("loc", ()))
    if kind == "literal_error" and "''" in str(err.get("ctx", {}).get("expected", "")):
        # a filter that may be empty (any): the values it accepts, without the empty one
        allowed = str(err["ctx"]["expected"]).replace("'', ", "", 1)
        reason = f"must be one of {allowed} (or empty: any)"
    if kind == "missing" or "input" not in err or isinstance(err["input"], dict):
        return f"{field} {reason}" if kind in _REASONS else f"{field}: {reason}"
    return f"{field} = {_short(err['input'])}: {reason}"


def refusal(model: type[BaseModel], values: dict) -> str | None:
    """The API's 422 message for the first of `values` (field name -> value) that the
    request model `model` refuses by its own Field definition, or None: the command line
    checks its options by the same bounds and says the same words."""
    for name, value in values.items():
        info = model.model_fields[name]
        try:
            TypeAdapter(Annotated[info.annotation, info]).validate_python(value)
        except ValidationError as e:
            err = e.errors()[0]
            return _sentence({**err, "loc": ("body", name, *err.get("loc", ()))})
    return None


def problem(status: int, detail: str, errors: list[FieldError] | None = None,
            headers: dict | None = None) -> JSONResponse:
    body = Problem(detail=detail, errors=errors or [])
    return JSONResponse(body.model_dump(), status_code=status, headers=headers)


async def _validation(request: Request, exc: RequestValidationError) -> Response:
    errs = list(exc.errors())
    sentences = [_sentence(e) for e in errs]
    detail = "; ".join(sentences[:3]) + (f" (and {len(errs) - 3} more)" if len(errs) > 3 else "")
    if not _is_api(request.url.path):
        # a page (e.g. /search with a 300-character q): a page in return, not JSON
        return error_page(request.app.state.settings.static_dir, 422,
                          "This address cannot be shown", detail or "invalid request")
    items = [FieldError(loc=[_part(p) for p in e.get("loc", ())],
                        msg=s, type=str(e.get("type", "invalid")))
             for e, s in zip(errs, sentences, strict=True)]
    return problem(422, detail or "invalid request", items)


_NAMED = re.compile(r"^\|?([A-Za-z_][A-Za-z0-9_]*)\|? = ")
_RUN_FIELDS = {"t_end", "rtol", "atol", "samples", "method", "project", "frames", "state",
               "step", "energy", "direction", "points", "trajectories", "initial", "seed"}
_STATE = {"M1", "M2", "M3", "g1", "g2", "g3", "r1", "r2", "gamma"}


def _input_loc(msg: str) -> list[str | int]:
    """Where an InputError points, from its 'name = value: why' form."""
    m = _NAMED.match(msg)
    if not m:
        return ["body"]
    name = m.group(1)
    if name in _RUN_FIELDS:
        return ["body", name]
    if name == "g0":
        return ["body", "section"]
    if name in _STATE:
        return ["body", "state"]
    return ["body", "params", name]


_NUMPY_REPR = re.compile(r"np\.(?:float|int)\d*\(([^()]*)\)")


async def _input(request: Request, exc: InputError) -> JSONResponse:
    msg = _NUMPY_REPR.sub(r"\1", str(exc))  # np.float64(0.5) -> 0.5 for people
    loc = _input_loc(msg)
    return problem(422, msg, [FieldError(loc=loc, msg=msg, type="input_error")])


async def _deadline(request: Request, exc: DeadlineExceeded) -> JSONResponse:
    # a limit of this server, not bad input: 504, documented as such (DEADLINE_RESPONSES)
    return problem(504, str(exc))


async def _not_acceptable(request: Request, exc: NotAcceptable) -> JSONResponse:
    return problem(406, str(exc))


async def _busy(request: Request, exc: QueueFull) -> JSONResponse:
    return problem(503, f"busy: {exc}", headers={"Retry-After": str(exc.retry_after)})


async def _crashed(request: Request, exc: WorkerCrashed) -> JSONResponse:
    return problem(503, str(exc), headers={"Retry-After": "1"})


async def _unavailable(request: Request, exc: WorkerUnavailable) -> JSONResponse:
    return problem(503, str(exc), headers={"Retry-After": str(exc.retry_after)})


async def _gone(request: Request, exc: ClientDisconnected) -> Response:
    return Response(status_code=499)  # nginx's "client closed request"; nobody reads it


def not_found_page(static_dir: Path, heading: str, message: str) -> HTMLResponse:
    """The HTML 404 page (with the site's navigation) for a person who mistyped an
    address; /api/* keeps its JSON Problem answers."""
    return error_page(static_dir, 404, heading, message)


def error_page(static_dir: Path, status: int, heading: str, message: str) -> HTMLResponse:
    """An HTML error page with the site's navigation (the 404 page's template)."""
    text = (Path(static_dir) / "404.html").read_text()
    # lazy: the site's navigation (app.services.reader_pages: jinja2, and numba through
    # the checks the pages describe), not at the start of the command line, which imports
    # this module for `refusal` (app/cli/common.py)
    from app.services.reader_pages import render_page

    return HTMLResponse(render_page(text, "404.html", heading=Markup(html.escape(heading)),
                                    message=Markup(html.escape(message[:500]))),
                        status_code=status)


def _is_api(path: str) -> bool:
    """Machine addresses answer JSON even when they do not exist."""
    return path.startswith(("/api/", "/openapi.json")) or path == "/api"


async def _http(request: Request, exc: StarletteHTTPException) -> Response:
    if exc.status_code in (204, 304):
        return Response(status_code=exc.status_code, headers=exc.headers)
    detail = exc.detail if isinstance(exc.detail, str) else str(exc.detail)
    if exc.status_code == 404 and not _is_api(request.url.path):
        return not_found_page(request.app.state.settings.static_dir, "Page not found",
                              f"Nothing lives at {request.url.path}.")
    if exc.status_code == 400 and "parsing the body" in detail:
        # FastAPI's answer to a body json.loads could not take: bad input like any other,
        # said as what it is (the cause FastAPI chained)
        cause = exc.__cause__
        if isinstance(cause, RecursionError):
            msg = "the body is not valid JSON here: it is nested too deeply"
        elif isinstance(cause, UnicodeError):
            msg = "the body is not valid JSON (it is not UTF-8 text)"
        else:
            msg = f"the body is not valid JSON ({type(cause).__name__ if cause else 'error'})"
        return problem(422, msg, [FieldError(loc=["body"], msg=msg, type="json_invalid")])
    return problem(exc.status_code, detail, headers=exc.headers)


def install(app: FastAPI) -> None:
    app.add_exception_handler(RequestValidationError, _validation)
    app.add_exception_handler(InputError, _input)
    app.add_exception_handler(DeadlineExceeded, _deadline)
    app.add_exception_handler(QueueFull, _busy)
    app.add_exception_handler(NotAcceptable, _not_acceptable)
    app.add_exception_handler(WorkerCrashed, _crashed)
    app.add_exception_handler(WorkerUnavailable, _unavailable)
    app.add_exception_handler(ClientDisconnected, _gone)
    app.add_exception_handler(StarletteHTTPException, _http)
