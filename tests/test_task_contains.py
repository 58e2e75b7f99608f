"""``Task.contains`` against an independent point-in-polygon test (matplotlib's Path) and
against its definition (``signed_distance >= -ROUNDING * diameter``), on random simple
polygons (stars about a centre) and on points on and beside the boundary."""
from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from matplotlib.path import Path

from mechopt.analysis.task import Task
from mechopt.core import validation as _v


def _star(seed, n):
    """``n`` vertices in increasing angle about (0, 150), every angular gap below pi: a
    star-shaped, simple polygon."""
    rng = np.random.default_rng(seed)
    a = 2 * np.pi * (np.arange(n) + rng.uniform(0.25, 0.75, n)) / n
    r = rng.uniform(20, 60, n)
    return np.column_stack([r * np.cos(a), 150 + r * np.sin(a)])


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 10**6), st.integers(4, 12))
def test_contains_agrees_with_matplotlib_away_from_the_boundary_and_with_its_definition(seed, n):
    V = _star(seed, n)
    task = Task.polygon(V)
    rng = np.random.default_rng(seed + 1)
    x, y = rng.uniform(-70, 70, 4000), rng.uniform(80, 220, 4000)
    tb, _ = task.boundary_params(400)
    bx, by = task.boundary_at(tb)
    ex = 1e-9 * task.diameter  # beside the boundary, well within the rounding band ... and outside it
    x = np.r_[x, bx, bx + ex, bx - ex, bx + 1e-3, bx - 1e-3]
    y = np.r_[y, by, by - ex, by + ex, by - 1e-3, by + 1e-3]
    got = task.contains(x, y)
    assert np.array_equal(got, task.signed_distance(x, y) >= -_v.ROUNDING * task.diameter)
    far = np.abs(task.signed_distance(x, y)) > 1e-6
    ref = Path(V).contains_points(np.column_stack([x, y]))
    assert np.array_equal(got[far], ref[far]) and far.sum() > 3000
    assert got[:4000].any() and not got[:4000].all()  # both verdicts occur
    # the boundary itself is inside, and shapes broadcast
    assert task.contains(bx, by).all()
    assert task.contains(x[:600].reshape(3, 200), y[:600].reshape(3, 200)).shape == (3, 200)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 10**6), st.integers(3, 12), st.integers(8, 3000), st.booleans())
def test_boundary_params_are_their_definition_bit_for_bit(seed, n, count, path):
    """``Task.boundary_params(count)`` (vectorised) against its definition edge by edge:
    ``m_i = max(1, ceil(count L_i / total))`` samples on edge ``i`` at the fractions
    ``cum_i + (cum_{i+1} - cum_i) k / m_i``, ``k < m_i`` (a path's last point too), and
    the largest gap ``max_i L_i / m_i``: the same floats bit for bit."""
    V = _star(seed, n)
    task = Task.path(V) if path else Task.polygon(V)
    pts = V if path else np.vstack([V, V[:1]])
    L = np.hypot(*np.diff(pts, axis=0).T)
    total = L.sum()
    cum = np.r_[0.0, np.cumsum(L)] / total
    ref, gap = [], 0.0
    for i, li in enumerate(L):
        m = max(1, int(np.ceil(count * li / total)))
        ref.append(cum[i] + (cum[i + 1] - cum[i]) * np.arange(m) / m)
        gap = max(gap, li / m)
    if path:
        ref.append(np.ones(1))
    t, g = task.boundary_params(count)
    assert t.tobytes() == np.concatenate(ref).tobytes()
    assert float(g) == float(gap)
