"""Points checked once (mechopt.core.protocol.mark_in_reach): a marked array passes
through as_points unchanged, an unmarked or unmarkable one is checked as before (far
coordinates and NaN become NaN), and a mark leaves with its array."""
import gc

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mechopt.analysis.sampling import Sampling, samples
from mechopt.analysis.task import parse_task
from mechopt.core import protocol
from mechopt.core.protocol import POINT_MAX, as_points, mark_in_reach

coordinates = st.one_of(st.floats(-2 * POINT_MAX, 2 * POINT_MAX), st.just(np.nan), st.just(np.inf))


def _expected(v):
    """as_points' rule, written out: NaN beyond POINT_MAX (NaN stays NaN)."""
    with np.errstate(invalid="ignore"):
        return np.where(np.abs(v) <= POINT_MAX, v, np.nan)


@settings(max_examples=200, deadline=None)
@given(arrays(np.float64, st.integers(0, 12), elements=coordinates),
       arrays(np.float64, st.integers(0, 12), elements=coordinates), st.booleans())
def test_marking_never_changes_what_as_points_returns(x, y, read_only):
    n = min(x.size, y.size)
    x, y = x[:n].copy(), y[:n].copy()
    if read_only:
        x.setflags(write=False)
        y.setflags(write=False)
    mark_in_reach(x, y)
    px, py = as_points(x, y)
    np.testing.assert_array_equal(px, _expected(x))
    np.testing.assert_array_equal(py, _expected(y))
    within = n == 0 or bool(np.all(np.abs(x) <= POINT_MAX))
    # marked exactly when read-only and every coordinate within reach
    assert (id(x) in protocol._IN_REACH) == (read_only and within)


def test_a_mark_leaves_with_its_array():
    x = np.linspace(-1.0, 1.0, 7)
    x.setflags(write=False)
    mark_in_reach(x)
    key = id(x)
    assert key in protocol._IN_REACH and as_points(x, x)[0] is x
    del x
    gc.collect()
    assert key not in protocol._IN_REACH  # a later array at this address is checked again


def test_a_writeable_array_is_not_marked():
    x = np.linspace(-1.0, 1.0, 7)
    mark_in_reach(x)  # writeable: not marked, it could change after the check
    assert id(x) not in protocol._IN_REACH
    x[0] = 10 * POINT_MAX
    assert np.isnan(as_points(x, x)[0][0])


def test_an_evaluations_samples_are_marked():
    s = samples(parse_task("polygon:0,200;12,166;47,166;19,145;29,111;0,131;-29,111;-19,145;-47,166;-12,166"),
                Sampling())
    for a, b in (("allx", "ally"), ("bx", "by"), ("ix", "iy")):
        assert id(s[a]) in protocol._IN_REACH and id(s[b]) in protocol._IN_REACH
        px, py = as_points(s[a], s[b])
        assert px is s[a] and py is s[b]
