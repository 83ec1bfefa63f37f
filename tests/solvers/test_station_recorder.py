"""The one station recorder of the stepping methods: what a march held when it passed each station."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from persson_fp.solvers.base import StationRecorder


@settings(max_examples=200, deadline=None)
@given(st.lists(st.integers(1, 50), min_size=1, max_size=12), st.integers(1, 4))
def test_records_the_state_of_each_station_step(steps, n_loads):
    """Oracle: after step n a march holds f(n) = (n, n^2) per load; station i must hold f(steps[i]) -- stations that
    share a step hold the same state, a step without a station records nothing."""
    steps = sorted(steps)
    rec = StationRecorder(steps, state=(n_loads, 2), total=())
    for n in range(1, max(steps) + 1):
        state = np.tile([float(n), float(n) ** 2], (n_loads, 1))
        assert (n in rec) == (n in steps)
        rec.record(n, state=state, total=float(n) * n_loads)
    want = np.asarray(steps, dtype=float)
    np.testing.assert_array_equal(rec["state"][:, :, 0], np.repeat(want[:, None], n_loads, axis=1))
    np.testing.assert_array_equal(rec["state"][:, :, 1], np.repeat(want[:, None] ** 2, n_loads, axis=1))
    np.testing.assert_array_equal(rec["total"], want * n_loads)


def test_one_load_at_a_time():
    """A method that marches the loads one after another records each load's row."""
    rec = StationRecorder([2, 3], P0=(3, 4))
    for j in range(3):
        for n in (1, 2, 3):
            rec.record(n, load=j, P0=np.full(4, 10.0 * j + n))
    np.testing.assert_array_equal(rec["P0"][:, :, 0], [[2.0, 12.0, 22.0], [3.0, 13.0, 23.0]])
