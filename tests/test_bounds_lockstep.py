"""The outward rounding of mechopt.core.interval and the lock-step searches of
mechopt.analysis.bounds (lower_bounds_of_designs).

Independent checks: the rounding against ``np.nextafter`` (libm's predecessor and
successor) and exact rationals (fractions) over floats of every exponent, the powers of
two and their neighbours, subnormals, zeros, the largest doubles, infinities and NaN, on
arrays of both sizes (few elements: ``np.nextafter`` itself; many: the arithmetic); the
searches of several designs run together against each design's searches run alone (the
same bound bit for bit: lock-step only batches the enclosures) and against the dense
minimum of the point evaluators (a different algorithm).
"""
from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest

from bounds_cases import dense_min
from mechopt.analysis import bounds as B
from mechopt.analysis.task import Task
from mechopt.core import interval as iv
from mechopt.mechanisms.five_bar import FiveBar

MAX = np.finfo(float).max
TINY = np.finfo(float).tiny  # 2^-1022


def _floats(rng, n=20000):
    """Finite floats of every magnitude, the powers of two and their neighbours, subnormals,
    zeros and the largest doubles."""
    p2 = 2.0 ** np.arange(-1074, 1024, dtype=float)
    raw = rng.integers(0, 2 ** 63, n, dtype=np.int64).view(float)  # every bit pattern
    parts = [rng.standard_normal(n) * 10.0 ** rng.integers(-320, 308, n), raw[np.isfinite(raw)], p2, -p2,
             np.nextafter(p2, 0.0), np.nextafter(p2, np.inf), -np.nextafter(p2, 0.0),
             np.array([0.0, -0.0, MAX, -MAX, TINY, -TINY, 5e-324, -5e-324])]
    return np.concatenate(parts)


@pytest.mark.parametrize("size", ["few", "many"])
def test_rounding_moves_at_least_one_ulp_outward(size):
    rng = np.random.default_rng(3)
    v = _floats(rng)
    chunks = [v[i:i + 100] for i in range(0, len(v), 100)] if size == "few" else [v]
    assert (len(chunks[0]) < iv._FEW) == (size == "few") and all(len(c) > 0 for c in chunks)
    with np.errstate(over="ignore"):
        down = np.concatenate([iv._down(c) for c in chunks])
        up = np.concatenate([iv._up(c) for c in chunks])
        pred, succ = np.nextafter(v, -np.inf), np.nextafter(v, np.inf)
    assert np.all(down <= pred) and np.all(up >= succ)  # at least one ulp: an enclosure
    near = (np.abs(v) >= TINY) & (np.abs(v) <= 4 * TINY)  # Rump et al.: exact outside this range
    assert np.array_equal(down[~near], pred[~near]) and np.array_equal(up[~near], succ[~near])
    assert np.all(down[near] >= np.nextafter(pred[near], -np.inf))  # and at most two there
    assert np.all(up[near] <= np.nextafter(succ[near], np.inf))
    for k in rng.choice(len(v), 300, replace=False):  # exactly: strictly outside
        if np.isfinite(down[k]):
            assert Fraction(float(down[k])) < Fraction(float(v[k]))
        if np.isfinite(up[k]):
            assert Fraction(float(up[k])) > Fraction(float(v[k]))


@pytest.mark.parametrize("n", [3, 400])
def test_rounding_of_infinities_and_nan(n):
    v = np.resize(np.array([np.inf, -np.inf, np.nan]), n)
    with np.errstate(all="raise"):  # no warning either
        down, up = iv._down(v), iv._up(v)
    assert np.array_equal(down[:3], [MAX, -np.inf, -np.inf])  # +inf: pred(inf); NaN: unbounded
    assert np.array_equal(up[:3], [np.inf, -MAX, np.inf])


#: the tutorial's task and designs about its knee (two differ in the working mode)
TASK = Task.rect(100.0, 60.0, center=(0.0, 180.0))
DESIGNS = [FiveBar(129.4, 144.9, 3.57, "+-"), FiveBar(135.0, 140.0, 0.0, "+-"),
           FiveBar(125.0, 150.0, 8.0, "+-"), FiveBar(129.4, 144.9, 3.57, "-+")]
MOVES = [(0.0, 0.0), (3.0, -20.0), (-5.5, 10.0), (0.0, 0.0)]


def _quantities(k):
    """Every kind of quantity, with parameters that differ between designs of one group
    (quantities of different parameters must not share an evaluation)."""
    w, t = ([3.0, 2.0], [2.0, 1.0]) if k % 2 else ([2.0, 3.0], [1.0, 2.5])
    return [B.lci_quantity(), B.type2_quantity(1.0 if k < 3 else -1.0), B.speed_quantity(w, "box"),
            B.speed_quantity(w, 2), B.force_quantity(t, "box", 1.5), B.force_quantity(t, 2, 1.0 + k)] \
        + B.range_quantities(1.0)


def _shifted(dx, dy):
    return lambda x, y: (np.asarray(x) + dx, np.asarray(y) + dy)


def test_designs_in_lock_step_bound_as_alone():
    budget = 600
    batch = [(m, _shifted(*d), _quantities(k), None) for k, (m, d) in enumerate(zip(DESIGNS, MOVES))]
    together = B.lower_bounds_of_designs(TASK, batch, budget=budget, names=("r1", "r2", "r3"))
    for k, (m, d) in enumerate(zip(DESIGNS, MOVES)):
        for q, b in zip(_quantities(k), together[k]):
            alone = B.lower_bound(m, TASK, q, to_mech=_shifted(*d), budget=budget)
            assert b == alone, (k, q.name)  # every field, bit for bit
            if q.actuator is None:  # and a bound: below the dense minimum (a different algorithm)
                placed = Task.rect(100.0, 60.0, center=(d[0], 180.0 + d[1]))
                ref = dense_min(m, placed, q, 31, 120)
                assert b.lower <= ref + 1e-9 * max(abs(ref), 1.0), (k, q.name)
    assert sum(b.cells for bs in together for b in bs) > 20 * len(DESIGNS)  # the searches split cells


def test_lock_step_groups_designs_that_differ_in_lengths_only():
    assert B._alike(DESIGNS[0], DESIGNS[1], ("r1", "r2", "r3"))
    assert not B._alike(DESIGNS[0], DESIGNS[3], ("r1", "r2", "r3"))  # the mode
    assert not B._alike(DESIGNS[0], DESIGNS[1], ("r1", "r2"))  # r3 differs and is not batched


def _split_reference(task, rows, levels):
    """Each level: every cell's four quarters (quarter by quarter, cells in order), kept
    where the task's signed distance at the centre is at least minus the half diagonal
    (and the margin); a piece of path's two halves."""
    parent = np.arange(len(rows))
    for _ in range(levels):
        if rows.shape[1] == 4:
            x0, x1, y0, y1 = rows.T
            xm, ym = (x0 + x1) / 2, (y0 + y1) / 2
            quads = [(x0, xm, y0, ym), (xm, x1, y0, ym), (x0, xm, ym, y1), (xm, x1, ym, y1)]
            kids = np.concatenate([np.stack(q, 1) for q in quads])
            c = kids.T
            sd = task.signed_distance((c[0] + c[1]) / 2, (c[2] + c[3]) / 2)
            keep = sd >= -np.hypot(c[1] - c[0], c[3] - c[2]) / 2 - B._KEEP_MARGIN * task.diameter
            rows, parent = kids[keep], np.tile(parent, 4)[keep]
        else:
            k, t0, t1 = rows.T
            tm = (t0 + t1) / 2
            rows, parent = np.concatenate([np.stack([k, t0, tm], 1), np.stack([k, tm, t1], 1)]), np.tile(parent, 2)
    return rows, parent


@pytest.mark.parametrize("task", [Task.polygon([(-50, 150), (50, 140), (10, 220), (-30, 200)]),
                                  Task.path([(-50, 150), (50, 140), (10, 220)])], ids=["polygon", "path"])
def test_cells_of_several_searches_split_at_once_as_each_alone(task):
    """The rounds split every search's cells in one call (each distinct cell once): each
    search gets the children and parents of its own split, in its order."""
    cells = B._Cells(task)
    rng = np.random.default_rng(2)
    grown, _ = cells.split(cells.rows, 2)
    grown, _ = cells.split(grown, 1)
    # overlapping picks of the same cells, in other orders, with repeats, one and two levels
    picks = [grown[rng.choice(len(grown), n, replace=bool(n % 2) or n > len(grown))] for n in (5, 40, len(grown), 17, 1)]
    levels = [1, 2, 1, 2, 2]
    together = cells.split_each(picks, levels)
    for rows, n, (kids, parent) in zip(picks, levels, together):
        ref_kids, ref_parent = _split_reference(task, rows, n)
        assert kids.tobytes() == ref_kids.tobytes() and kids.shape == ref_kids.shape
        assert np.array_equal(parent, ref_parent)
    assert cells.kind != "box" or any(len(k) < 4 ** n * len(r) for r, n, (k, _) in zip(picks, levels, together))


@pytest.mark.parametrize("n_range", [40, 300])
def test_enclosure_parts_over_the_cells_their_searches_read(n_range):
    """A round's closure part is computed over the cells its quantities read and the
    ranges' part over theirs: each cell's intervals those of the whole batch, bit for bit
    (a part of fewer than _FEW cells of a larger batch is computed over the whole batch:
    the rounding's size class)."""
    cells = B._Cells(TASK)
    rows, _ = cells.split(cells.rows, 2)
    rows, _ = cells.split(rows, 1)
    n = len(rows)
    assert n >= 2 * iv._FEW
    rng = np.random.default_rng(4)
    closure = rng.random(n) < 0.6
    ranges = np.zeros(n, bool)
    ranges[rng.choice(n, n_range, replace=False)] = True
    mech = DESIGNS[0]
    whole = B._Enclosures(mech, cells, rows, 3.0, -20.0, None, 0.0, True, True)
    part = B._Enclosures(mech, cells, rows, 3.0, -20.0, None, 0.0, closure, ranges)
    assert (part._rpos is None) == (n_range < iv._FEW) and part._cpos is not None
    for q in [B.lci_quantity(), B.type2_quantity(-1.0)] + B.range_quantities(1.0):
        idx = np.flatnonzero(ranges if q.actuator is not None else closure)
        a, b = whole.bound(q, idx), part.bound(q, idx)
        assert a[0].tobytes() == b[0].tobytes() and np.array_equal(a[1], b[1]), q.name
    if n_range >= iv._FEW:
        assert len(part.act[0][0].lo) == n_range  # only the ranges' cells


def test_a_search_without_cells_in_a_round_gets_no_bounds():
    """A search whose cells' children all miss the task has no cells in the round, so its
    part of the enclosures is not computed: its bounds are empty."""
    cells = B._Cells(TASK)
    rows = cells.rows
    only_ranges = np.ones(len(rows), bool)
    enc = B._Enclosures(DESIGNS[0], cells, rows, 0.0, 0.0, None, 0.0, False, only_ranges)
    for q in (B.lci_quantity(), B.range_quantity(0, 1.0, 1.0)):
        lb, unk = enc.bound(q, np.zeros(0, int))
        assert lb.shape == unk.shape == (0,) and lb.dtype == float and unk.dtype == bool
    lb, _ = enc.bound(B.range_quantity(0, 1.0, 1.0), np.arange(len(rows)))
    assert lb.shape == (len(rows),)
