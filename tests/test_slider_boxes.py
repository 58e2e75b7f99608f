"""Tolerance boxes of the Biglide, the gantry and the Bipod (issue 28, item 4): their
closure enclosures over length intervals, the proven bounds over a box, and ``mechopt
design --tolerance``.

Every mechanism of a box is built the way the design workflow builds it: its strokes
cover the task (they are derived from it), here wide strokes, so a build reaches a point
exactly where its links reach their guides (the struts are not of zero length). The
Bipod's box keeps the base's midpoint where the design spec places it: a point ``(x, y)``
of the nominal bipod's frame is ``(x + (b' - b)/2, y)`` in the frame of the bipod of base
``b'``. The references are each build's own point kinematics (``closure``, ``jacobian``,
``type2_function``, ``lci``), a different algorithm from the interval code.
"""
from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from bounds_cases import random_task
from mechopt.analysis import bounds as B
from mechopt.analysis.task import parse_task
from mechopt.core.interval import Interval
from mechopt.mechanisms.biglide import Biglide
from mechopt.mechanisms.bipod import Bipod
from mechopt.mechanisms.gantry import Gantry
from mechopt.requirements import Requirements
from mechopt.workflows.design import design

#: a stroke half-length far beyond every task here [L]: the builds' strokes cover the task
WIDE = 1e4
#: ``(kind, names, nominal lengths, modes)``
KINDS = {
    "biglide": (("l1", "l2"), (40.0, 100.0), ("--", "++", "+-", "-+")),
    "gantry": (("d1", "l"), (40.0, 100.0), ("--", "++", "+-", "-+")),
    "bipod": (("b",), (60.0,), ("up", "down", "full")),
}
CASES = [(k, m) for k, (_, _, modes) in KINDS.items() for m in modes]


def build(kind, L, mode, strokes=(-WIDE, WIDE)):
    """The mechanism of ``kind`` with lengths ``L`` (in :data:`KINDS`' order) and strokes."""
    lo, hi = strokes
    if kind == "biglide":
        return Biglide(L[0], L[1], lo, hi, mode=mode)
    if kind == "gantry":
        return Gantry(L[0], L[1], hi - lo, q_min=lo, mode=mode)
    return Bipod(L[0], max(lo, 1e-6 * L[0]), hi, branch=mode)


def to_build(kind, nominal, L, x, y):
    """Points of the nominal mechanism's frame in the frame of the build of lengths ``L``."""
    return (x + 0.5 * (L[0] - nominal[0]), y) if kind == "bipod" else (x, y)


def moderate(kind, L, mode):
    """The same mechanism with strokes of the size of its links (tasks are drawn in its
    bounding box)."""
    s = L[-1]
    return build(kind, L, mode, (0.2 * s, 2.0 * s) if kind == "bipod" else (-2.0 * s, 2.0 * s))


def offsets(n, n_random, rng):
    """The ``2^n`` corners of ``[-1, 1]^n`` and ``n_random`` uniform points inside."""
    corners = np.array(list(itertools.product((-1.0, 1.0), repeat=n)))
    return np.vstack([corners, rng.uniform(-1.0, 1.0, (n_random, n))])


# ------------------------------------------------------------------ (a) enclosures
@pytest.mark.parametrize("kind, mode", CASES)
def test_enclosure_over_a_length_box_contains_every_build_s_closure(kind, mode):
    """Random cells (up to 5 % of the links), lengths within +-2 % of the nominal ones:
    where the enclosure says the cell is certain, every build of the box (its 2^n
    corners and 12 random ones) at corners and random points of the cell reaches the
    point and its closure ``A``, ``diag B`` lies inside the intervals."""
    names, nominal, _ = KINDS[kind]
    rng = np.random.default_rng(5)
    mech = build(kind, nominal, mode)
    T = 0.02 * nominal[-1]
    x0, x1, y0, y1 = moderate(kind, nominal, mode).bounding_box()
    n = 800
    cx, cy = rng.uniform(x0, x1, n), rng.uniform(y0, y1, n)
    hw = 0.05 * nominal[-1] * rng.random((2, n)) ** 2
    X, Y = Interval(cx - hw[0], cx + hw[0]), Interval(cy - hw[1], cy + hw[1])
    box = {k: Interval(v - T, v + T) for k, v in zip(names, nominal)}
    EA, Eb, certain = mech.closure_enclosure(X, Y, lengths=box)
    assert certain.mean() > 0.2  # not vacuous
    checked = 0
    for off in offsets(len(names), 12, rng):
        L = np.asarray(nominal) + T * off
        m = build(kind, L, mode)
        for f in rng.choice([0.0, 1.0, 0.5, 0.3, 0.9], (3, 2, n)):  # points of each cell, corners among them
            px = np.clip(X.lo + f[0] * (X.hi - X.lo), X.lo, X.hi)
            py = np.clip(Y.lo + f[1] * (Y.hi - Y.lo), Y.lo, Y.hi)
            A, b, ok = m.closure(*to_build(kind, nominal, L, px, py))
            assert np.all(ok[certain])
            for i in range(2):
                assert np.all(Eb[i][certain].contains(b[certain, i])), (off, i)
                for j in range(2):
                    assert np.all(EA[i][j][certain].contains(A[certain, i, j])), (off, i, j)
            checked += int(certain.sum())
    assert checked > 10_000


@pytest.mark.parametrize("kind", list(KINDS))
def test_enclosure_rejects_a_length_the_design_does_not_have(kind):
    names, nominal, modes = KINDS[kind]
    mech = build(kind, nominal, modes[0])
    with pytest.raises(ValueError, match="has no length 'r1'"):
        mech.closure_enclosure(Interval([0.0]), Interval([50.0]), lengths={"r1": Interval(1.0)})


@pytest.mark.parametrize("kind", list(KINDS))
def test_without_lengths_the_strokes_still_decide(kind):
    """The no-lengths enclosure tests the mechanism's own strokes (the point evaluator's
    reach): a cell beyond them is not certain; with lengths it is, for every build has
    strokes of its own."""
    names, nominal, modes = KINDS[kind]
    mech = build(kind, nominal, modes[0], (0.5 * nominal[-1], 0.6 * nominal[-1]) if kind == "bipod"
                 else (1000.0, 1001.0))
    x, y = (Interval([25.0], [26.0]), Interval([40.0], [41.0])) if kind == "bipod" else \
        (Interval([1.0], [2.0]), Interval([0.0], [1.0]))
    box = {names[0]: Interval(nominal[0] - 0.1, nominal[0] + 0.1)}
    assert not mech.closure_enclosure(x, y)[2][0]
    assert mech.closure_enclosure(x, y, lengths=box)[2][0]
    if kind == "bipod":  # a cell on a base joint: a strut of length 0, out of every build's reach
        assert not build(kind, nominal, "up").reachable(0.0, 0.0)
        assert not mech.closure_enclosure(Interval([-1e-9], [1e-9]), Interval([0.0], [1e-9]), lengths=box)[2][0]


# ------------------------------------------------------------------ (b) bounds over a box
def _task_points(task, n_grid, n_boundary):
    """An ``n_grid`` x ``n_grid`` grid of the task's box kept inside, and ``n_boundary``
    points of its boundary."""
    x0, x1, y0, y1 = task.bbox
    gx, gy = (v.ravel() for v in np.meshgrid(np.linspace(x0, x1, n_grid), np.linspace(y0, y1, n_grid)))
    keep = task.contains(gx, gy)
    bx, by = task.boundary_at(np.linspace(0.0, 1.0, n_boundary, endpoint=False))
    return np.r_[gx[keep], bx], np.r_[gy[keep], by]


def _quantities(mech, x, y, rng):
    """LCI, the type-II function with the sign it has at the task's first point, speed and
    force in both readings with random limits."""
    s0 = float(np.sign(mech.type2_function(x[:1], y[:1])[0])) or 1.0
    w, t = rng.uniform(0.5, 3.0, 2), rng.uniform(0.5, 3.0, 2)
    return [B.lci_quantity(), B.type2_quantity(s0), B.speed_quantity(w, "box"), B.speed_quantity(w, 2),
            B.force_quantity(t, "box", 2.0), B.force_quantity(t, 2, 2.0)]


def _box_bounds_below_builds(kind, mode, n_random, n_grid, n_boundary, seed, budget=4000):
    """The proven bound over the task, the box of lengths +-T and the placement +-T
    (T = 0.1 % of the links) against the smallest value of each of the box's builds (the
    2^(n+2) corners of lengths and placement, ``n_random`` random) on a dense grid: below
    it (to rounding), within 5 % of it. Returns the largest relative gap."""
    names, nominal, _ = KINDS[kind]
    rng = np.random.default_rng(seed)
    mech = build(kind, nominal, mode)
    T = 1e-3 * nominal[-1]
    while True:
        task = random_task(moderate(kind, nominal, mode), rng, "rect")
        x, y = _task_points(task, 31, 400)
        if np.nanmin(mech.lci(x, y)) > 0.05:
            break
    x, y = _task_points(task, n_grid, n_boundary)
    lengths = {k: (v - T, v + T) for k, v in zip(names, nominal)}
    worst_gap = 0.0
    offs = offsets(len(names) + 2, n_random, rng)
    for q in _quantities(mech, x, y, rng):
        worst = math.inf
        for off in offs:
            L = np.asarray(nominal) + T * off[:len(names)]
            m = build(kind, L, mode)
            bx, by = to_build(kind, nominal, L, x + T * off[-2], y + T * off[-1])
            worst = min(worst, float(np.min(q.point(m, bx, by))))
        assert worst > q.floor  # every build reaches the task, off its singularities
        b = B.lower_bound(mech, task, q, lengths=lengths, shift=T, upper=worst, budget=budget)
        scale = max(abs(worst), q.scale, 1e-300)
        assert b.lower <= worst + 1e-9 * scale, (q.name, b.lower, worst)
        assert worst - b.lower <= 0.05 * scale, (q.name, b.lower, worst)
        worst_gap = max(worst_gap, (worst - b.lower) / scale)
    return worst_gap


@pytest.mark.parametrize("kind", list(KINDS))
def test_bound_over_a_box_below_every_build_on_a_dense_grid(kind):
    mode = KINDS[kind][2][0]
    _box_bounds_below_builds(kind, mode, n_random=4, n_grid=101, n_boundary=2000, seed=11)


@pytest.mark.slow
@pytest.mark.parametrize("kind, mode", CASES)
def test_bound_over_a_box_below_every_build_on_a_dense_grid_all_modes(kind, mode):
    _box_bounds_below_builds(kind, mode, n_random=40, n_grid=301, n_boundary=6000, seed=29, budget=30000)


# ------------------------------------------------------------------ (c) mechopt design --tolerance
TASK, GAMMA, TOL = "rect:100,60@0,180", 0.15, 0.05


def _violations(kind, row, n_builds, n_grid, n_boundary, seed, tol=TOL):
    """Builds inside the +-``tol`` box of the front row ``row`` (its lengths and the task's
    placement; the corners among them), each with strokes derived from the dense points
    (so reach is the links' or struts'), that fail somewhere on the dense check: every
    point reached, one sign of the type-II function (margin 1e-3), LCI >= gamma. And the
    smallest LCI met."""
    names, _, _ = KINDS[kind]
    task = parse_task(TASK).moved_to(0.0, 0.0)
    x0, y0 = _task_points(task, n_grid, n_boundary)
    rng = np.random.default_rng(seed)
    offs = offsets(len(names) + 2, n_builds, rng) * tol
    bad, low = [], math.inf
    for off in offs:
        L = np.array([row[k] for k in names]) + off[:len(names)]
        x, y = x0 + row["task_x"] + off[-2], y0 + row["task_y"] + off[-1]
        if kind == "bipod":
            x = x + 0.5 * L[0]  # the task frame has the base's midpoint at the origin
            q = np.hypot(x, y), np.hypot(x - L[0], y)
        else:
            q = build(kind, L, row["mode"]).slider_positions(x, y)
        if not np.all(np.isfinite(q)):
            bad.append(off)
            continue
        lo, hi = min(v.min() for v in q), max(v.max() for v in q)
        mech = build(kind, L, row["mode"], (lo, hi)) if kind != "bipod" else \
            Bipod(L[0], min(q[0].min(), q[1].min()), max(q[0].max(), q[1].max()), branch=row["mode"])
        f, lci = mech.type2_function(x, y), mech.lci(x, y)
        ok = mech.reachable(x, y).all() and (np.all(f >= 1e-3) or np.all(f <= -1e-3)) and lci.min() >= GAMMA
        low = min(low, float(np.nanmin(lci)))
        if not ok:
            bad.append(off)
    return bad, low


#: the gantry is the Biglide mirrored (the same front): its run is behind ``-m slow``
#: the smallest runs with a front of several designs: ``(pop, gen)``
BUDGETS = {"biglide": (10, 4), "gantry": (10, 4), "bipod": (6, 2)}


@pytest.fixture(scope="module", params=["biglide", "bipod", pytest.param("gantry", marks=pytest.mark.slow)])
def small_run(request, tmp_path_factory):
    kind = request.param
    pop, gen = BUDGETS[kind]
    res = design(kind, parse_task(TASK), Requirements(min_lci=GAMMA), ("size", "min-lci"), max_length=400,
                 seed=1, n_jobs=1, tolerance=TOL, out=tmp_path_factory.mktemp(kind) / "run", pop=pop, gen=gen,
                 polish=False)
    return kind, res


def test_design_with_a_tolerance_proves_each_front_design_s_box(small_run):
    """Every front design's box is proven (LCI, type-II, reach; the bipod's strut
    lengths stay sampled: not a bounded requirement) and builds inside it pass a dense
    check; the proven LCI bound lies below every build's LCI."""
    kind, res = small_run
    assert len(res.front) >= 2 and res.info["tolerance"] == TOL
    for i, row in res.front.iterrows():
        box = res.boxes[i]
        assert {n: box["methods"][n] for n in ("reach", "singular", "lci")} == dict.fromkeys(
            ("reach", "singular", "lci"), "proven"), (kind, i, box["methods"])
        bad, low = _violations(kind, row, 16, 101, 2000, seed=i)
        assert not bad, (kind, i, bad[:3])
        assert box["proven"]["lci"]["lower_bound"] <= low + 1e-12
        assert row["tolerance_max"] >= TOL
        bad, _ = _violations(kind, row, 16, 101, 2000, seed=100 + i, tol=row["tolerance_max"])
        assert not bad, (kind, i, row["tolerance_max"], bad[:3])
