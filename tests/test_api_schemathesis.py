"""Property-based tests of the whole API from its OpenAPI schema (schemathesis), positive
and negative data: no 5xx at all, and every answer, its status included, conforms to the
documented schema (a status the schema does not list fails). 503 (busy) and 504 (deadline)
are documented, but the settings here (a queue longer than one client fills, a generous
deadline) leave no reason for them, so one would be a fault. Bounded: a fixed number of
examples per operation, derandomized (the same cases every run); 200 examples for the two
computing operations the issue names."""

import pytest
import schemathesis
from hypothesis import HealthCheck, settings
from schemathesis.specs.openapi.checks import positive_data_acceptance

from app.main import create_app
from app.testing import settings_for_tests

pytestmark = pytest.mark.filterwarnings("ignore::DeprecationWarning")

# a small step budget keeps every generated run quick; the deadline is generous so that a
# loaded machine does not turn a quick run into a 504, which schemathesis rightly counts as
# a server error (a deadline is tested on its own: tests/test_api_workers.py)
app = create_app(settings_for_tests(max_steps=20_000, deadline_s=120.0,
                                    verify_deadline_s=120.0, queue_size=16))
schema = schemathesis.openapi.from_asgi("/openapi.json", app)


# the two operations that compute: 200 examples each (a small step budget keeps each quick)
HEAVY = ["/api/poincare", "/api/simulate"]
CHECKS = {"excluded_checks": [positive_data_acceptance], "timeout": 120}


def _call(case):
    # positive_data_acceptance is left out on purpose: a body can fit the schema and still
    # describe no body (negative mass, |gamma| != 1, a disk lying flat): that is a 422 by design
    response = case.call_and_validate(**CHECKS)
    assert response.status_code < 500, response.text


@schema.exclude(path=HEAVY).parametrize()
@settings(max_examples=40, derandomize=True, deadline=None, database=None,
          suppress_health_check=list(HealthCheck))
def test_api(case):
    _call(case)


@schema.include(path=HEAVY[0]).include(path=HEAVY[1]).parametrize()
@settings(max_examples=200, derandomize=True, deadline=None, database=None,
          suppress_health_check=list(HealthCheck))
def test_api_computing_operations(case):
    _call(case)
