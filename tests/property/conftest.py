"""Two depths for every hypothesis test of this folder: ``[fast]`` in the default run (a few derandomised
examples, no example database, so a run is reproducible) and ``[slow]`` in the ``-m slow`` group (many examples).

Each ``@given`` test is parametrised over ``_depth``; the fixture sets the test's hypothesis settings for that
depth before hypothesis reads them (a test may scale its own count with ``@depth_scale``).
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, settings

FAST_EXAMPLES = 5
SLOW_EXAMPLES = 100
_COMMON = dict(
    deadline=None,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large],
)


def pytest_generate_tests(metafunc):
    if getattr(metafunc.function, "is_hypothesis_test", False):
        metafunc.parametrize("_depth", ["fast", pytest.param("slow", marks=pytest.mark.slow)], indirect=True)


@pytest.fixture(autouse=True)
def _depth(request):
    if not hasattr(request, "param"):  # not a hypothesis test
        return None
    fn = request.function
    assert hasattr(fn, "_hypothesis_internal_use_settings"), "hypothesis moved its settings attribute"
    scale = getattr(fn, "_slow_scale", 1.0)
    if request.param == "fast" and getattr(fn, "_slow_only", False):
        pytest.skip("too costly for the default run's sample: in the slow group only")
    if request.param == "fast":
        fn._hypothesis_internal_use_settings = settings(max_examples=FAST_EXAMPLES, derandomize=True, **_COMMON)
    else:
        fn._hypothesis_internal_use_settings = settings(
            max_examples=max(FAST_EXAMPLES, int(SLOW_EXAMPLES * scale)), derandomize=True, **_COMMON
        )
    return request.param
