"""Shapes shared by every route: the error body and the finite-number type."""

from typing import Annotated

from pydantic import BaseModel, Field

# A float that is a number: JSON's NaN, Infinity and 1e999 (which parses to inf) are
# rejected in the request schema, before any domain code sees them.
FiniteFloat = Annotated[float, Field(allow_inf_nan=False)]


class FieldError(BaseModel):
    loc: list[str | int] = Field(description="where: 'body', then field names / indices")
    msg: str = Field(description="why, in words")
    type: str = Field(description="machine-readable kind of error")


class Problem(BaseModel):
    """Every error answer: one line a person can act on, plus the field-level details."""

    detail: str = Field(description="what is wrong and what to do, one line")
    errors: list[FieldError] = Field(default_factory=list)


PROBLEM_RESPONSES: dict[int | str, dict] = {
    422: {"model": Problem, "description": "bad input: the message names the field, the "
          "value and why (nothing was computed or changed)"},
}
# what app.core.guards answers to a request with a body, before any route sees it
GUARD_RESPONSES: dict[int | str, dict] = {
    400: {"model": Problem, "description": "a malformed request (Content-Length not a "
          "number, a Host not served here)"},
    403: {"model": Problem, "description": "the Origin of the request is another site"},
    413: {"model": Problem, "description": "the body is larger than the server's limit "
          "(1 MB by default)"},
    415: {"model": Problem, "description": "the body is not JSON (Content-Type must be "
          "application/json)"},
}
DEADLINE_RESPONSES: dict[int | str, dict] = {
    504: {"model": Problem, "description": "a limit of this server: the computation needed "
          "more than the deadline of one request and was stopped (not bad input; a "
          "smaller request fits)"},
}
BUSY_RESPONSES: dict[int | str, dict] = {
    503: {"model": Problem, "description": "every worker is busy and the queue is full: "
          "retry after the number of seconds in the Retry-After header",
          "headers": {"Retry-After": {"description": "seconds to wait",
                                      "schema": {"type": "integer"}}}},
}
NOT_ACCEPTABLE_RESPONSES: dict[int | str, dict] = {
    406: {"model": Problem, "description": "the Accept header names none of the types "
          "this route answers with (application/json, application/vnd.apache.arrow.stream, "
          "text/csv; */* is fine)"},
}
NOT_FOUND: dict[int | str, dict] = {404: {"model": Problem, "description": "no such case"}}
