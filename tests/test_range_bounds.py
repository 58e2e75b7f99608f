"""Proven outer ranges of the actuator coordinates (issue 28 item 3: joints and strokes):
:func:`mechopt.core.interval.atan2` / :func:`~mechopt.core.interval.acos`, each
mechanism's ``actuator_enclosure``, :func:`mechopt.analysis.bounds.outer_range` and the
``joints`` / ``stroke`` entries of certificates.

Independent checks: the interval functions against mpmath at 50 digits (and the libm
assumption they rest on: ``np.arctan2`` / ``np.arccos`` within 1 ulp of mpmath); each
enclosure against the mechanism's point inverse kinematics (``ik``, libm's atan2/acos on
floats) at random points of random boxes; each outer range against the range of ``ik``
over a dense grid and boundary (a different algorithm: no intervals, no search).
Stated gap: with the default budget each end of the outer range lies within
``GAP_STATED * scale`` of the dense one (scale 1 rad for crank angles, the task's
diameter for slider positions and strut lengths).
"""
from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bounds_cases import KINDS, TASK_KINDS, random_task
from mechanism_cases import CASES, sample_away_from_singularities
from mechopt.analysis import bounds as B
from mechopt.analysis.task import Task
from mechopt.core import interval as iv
from mechopt.core.interval import Interval

#: each end of the outer range within this fraction of the scale of the dense range's end
GAP_STATED = 5e-3
#: the dense range is computed in floating point: an outer end may be inside it by this
#: (relative to the scale)
ROUND_SLACK = 1e-9
mpmath.mp.dps = 50


# ------------------------------------------------------------------ interval functions
def _ulps(a, exact):
    """How many ulps of ``a`` the float ``a`` lies from the mpmath value ``exact``."""
    return float(abs(mpmath.mpf(a) - exact) / mpmath.mpf(np.spacing(abs(a)) if a != 0 else 5e-324))


@settings(max_examples=100, deadline=None)
@given(y=st.floats(-1e6, 1e6, allow_subnormal=False), x=st.floats(-1e6, 1e6, allow_subnormal=False),
       u=st.floats(-1.0, 1.0, allow_subnormal=False))
def test_libm_within_one_ulp(y, x, u):
    """The assumption of :data:`mechopt.core.interval.LIBM_ULPS`: ``np.arctan2`` and
    ``np.arccos`` within 1 ulp of the exact value (mpmath, 50 digits); off the branch cut
    (``y = 0, x <= 0``: a signed zero decides between -pi and pi, which
    :func:`~mechopt.core.interval.atan2` encloses together)."""
    if y != 0.0 or x > 0.0:
        assert _ulps(float(np.arctan2(y, x)), mpmath.atan2(mpmath.mpf(y), mpmath.mpf(x))) <= 1.0
    assert _ulps(float(np.arccos(u)), mpmath.acos(mpmath.mpf(u))) <= 1.0


def _box(rng, n, scale):
    """``n`` random boxes (widths over ten decades, degenerate ones) about random centres."""
    c = rng.uniform(-scale, scale, (2, n))
    w = scale * 10.0 ** rng.uniform(-10, 0, (2, n)) * (rng.random((2, n)) > 0.1)
    return Interval(c[0] - w[0], c[0] + w[0]), Interval(c[1] - w[1], c[1] + w[1])


def _inside(rng, I):
    f = rng.choice([0.0, 1.0, 0.5, 0.37, 0.91], I.lo.shape)
    return np.clip(I.lo + f * (I.hi - I.lo), I.lo, I.hi)


def _atan2_misses(fn, seed, n=300):
    rng = np.random.default_rng(seed)
    X, Y = _box(rng, n, 10.0)
    ang, cont = fn(Y, X)
    miss = 0
    for _ in range(3):
        px, py = _inside(rng, X), _inside(rng, Y)
        for k in np.flatnonzero(cont):
            e = mpmath.atan2(mpmath.mpf(py[k]), mpmath.mpf(px[k]))
            miss += not (mpmath.mpf(ang.lo[k]) <= e <= mpmath.mpf(ang.hi[k]))
        # where not continuous: the whole circle
        assert np.all(ang.lo[~cont] <= -math.pi) and np.all(ang.hi[~cont] >= math.pi)
    return miss, int(cont.sum())


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_atan2_encloses_exact_angles(seed):
    """At points of random boxes (corners among them) the exact angle (mpmath) lies in the
    enclosure where it says continuous; elsewhere the enclosure is [-pi, pi]."""
    miss, n = _atan2_misses(iv.atan2, seed)
    assert n > 100 and miss == 0


def test_atan2_from_two_corners_misses():
    """The check above can fail: an atan2 from the two corners ``(lo, lo)``, ``(hi, hi)``
    alone misses angles of the other two."""
    def two_corners(y, x):
        lo, hi = np.arctan2(y.lo, x.lo), np.arctan2(y.hi, x.hi)
        return iv._make(np.minimum(lo, hi), np.maximum(lo, hi)), np.ones(lo.shape, bool)
    assert sum(_atan2_misses(two_corners, s)[0] for s in range(3)) > 0


def test_atan2_branch_cut_and_pi():
    """Boxes beside the cut are continuous and tight (their corners' angles); a box across
    it, or about the origin, is the whole circle; PI contains pi."""
    ang, cont = iv.atan2(Interval([-1.0, 1.0, -0.5, -1.0], [-1.0, 1.0, 0.5, 1.0]),
                         Interval([-2.0, -2.0, -2.0, -1.0], [-1.0, -1.0, -1.0, 1.0]))
    assert cont.tolist() == [True, True, False, False]
    assert ang.lo[0] <= math.atan2(-1, -2) and ang.hi[0] >= math.atan2(-1, -1)
    assert ang.lo[0] >= math.atan2(-1, -2) - 1e-15 and ang.hi[0] <= math.atan2(-1, -1) + 1e-15
    assert ang.lo[1] <= math.atan2(1, -1) and ang.hi[1] >= math.atan2(1, -2)
    assert np.all(ang.lo[2:] <= -math.pi) and np.all(ang.hi[2:] >= math.pi)
    assert mpmath.mpf(float(iv.PI.lo)) < mpmath.pi < mpmath.mpf(float(iv.PI.hi))


@settings(max_examples=10, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_acos_encloses_exact_values(seed):
    """Points of random sub-intervals of [-1.2, 1.2] (clipped to [-1, 1] as the point
    evaluators clip): the exact arccos (mpmath) lies in the enclosure."""
    rng = np.random.default_rng(seed)
    c = rng.uniform(-1.2, 1.2, 300)
    w = 10.0 ** rng.uniform(-16, -0.5, 300) * (rng.random(300) > 0.1)
    U = Interval(c - w, c + w)
    A = iv.acos(U)
    for _ in range(3):
        p = np.clip(_inside(rng, U), -1.0, 1.0)
        for k in range(len(p)):
            assert mpmath.mpf(A.lo[k]) <= mpmath.acos(mpmath.mpf(p[k])) <= mpmath.mpf(A.hi[k]), (U[k], p[k])


# ------------------------------------------------------------------ enclosures
@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_actuator_enclosure_contains_point_ik(case):
    """At random points of random boxes (up to 5 % of the length scale), where the
    enclosure is certain the point is reachable and both coordinates of ``ik`` lie in it."""
    _, factory, _ = case
    mech = factory()
    rng = np.random.default_rng(8)
    x0, x1, y0, y1 = mech.bounding_box()
    n = 600  # half about reachable points, half anywhere in the bounding box
    px, py = sample_away_from_singularities(mech, rng, n // 2)
    cx = np.concatenate([px, rng.uniform(x0, x1, n - len(px))])
    cy = np.concatenate([py, rng.uniform(y0, y1, n - len(py))])
    hw = mech.length_scale * 0.05 * rng.random((2, n)) ** 3
    X, Y = Interval(cx - hw[0], cx + hw[0]), Interval(cy - hw[1], cy + hw[1])
    (Q1, Q2), certain = mech.actuator_enclosure(X, Y)
    assert certain.sum() > 100
    for _ in range(3):
        px, py = _inside(rng, X), _inside(rng, Y)
        q1, q2, ok = mech.ik(px, py)
        assert np.all(ok[certain])
        tol = 1e-12 * (1.0 + np.abs(q1[certain]))  # ik's own rounding (a few ulps)
        assert np.all((Q1.lo[certain] - tol <= q1[certain]) & (q1[certain] <= Q1.hi[certain] + tol))
        tol = 1e-12 * (1.0 + np.abs(q2[certain]))
        assert np.all((Q2.lo[certain] - tol <= q2[certain]) & (q2[certain] <= Q2.hi[certain] + tol))


# ------------------------------------------------------------------ outer ranges
def _scale(kind, task):
    return 1.0 if kind.endswith("five-bar") else task.diameter


def dense_range(mech, task, i, n_grid, n_boundary):
    """``(min, max)`` of ``ik``'s coordinate ``i`` over an ``n_grid`` x ``n_grid`` grid of
    the task's box (kept inside) and ``n_boundary`` points of its boundary (NaN: some
    point out of reach)."""
    lo, hi = math.inf, -math.inf

    def see(v):
        nonlocal lo, hi
        if np.any(np.isnan(v)):
            lo = hi = math.nan
        elif not math.isnan(lo):
            lo, hi = min(lo, float(v.min())), max(hi, float(v.max()))
    if task.is_region:
        x0, x1, y0, y1 = task.bbox
        gx = np.linspace(x0, x1, n_grid)
        for row in np.linspace(y0, y1, n_grid):
            keep = task.contains(gx, np.full_like(gx, row))
            if keep.any():
                see(mech.ik(gx[keep], np.full(keep.sum(), row))[i])
    if task.kind == "points":
        see(mech.ik(task.pts[:, 0], task.pts[:, 1])[i])
    else:
        see(mech.ik(*task.boundary_at(np.linspace(0.0, 1.0, n_boundary, endpoint=task.is_path)))[i])
    return lo, hi


def _reachable_task(mech, rng, kind):
    """A random task of ``kind`` that ``mech`` reaches (strokes included)."""
    for _ in range(100):
        task = random_task(mech, rng, kind)
        if not math.isnan(dense_range(mech, task, 0, 21, 400)[0]):
            return task
    raise AssertionError("no reachable task")


def _check_ranges(n_per_kind, n_grid, n_boundary, seed, kinds=TASK_KINDS):
    """Outer range contains the dense range (to rounding), each end within GAP_STATED;
    the largest gap relative to the scale."""
    rng = np.random.default_rng(seed)
    worst = 0.0
    for m, (kind, cases) in enumerate(KINDS.items()):
        for j in range(n_per_kind):
            mech = cases[rng.integers(len(cases))][1]()
            task = _reachable_task(mech, rng, kinds[(j + m) % len(kinds)])
            sc = _scale(kind, task)
            r = B.outer_range(mech, task, sc)
            for i in range(2):
                lo, hi = dense_range(mech, task, i, n_grid, n_boundary)
                (olo, ohi), (ilo, ihi) = r.outer[i], r.inner[i]
                assert olo <= lo + ROUND_SLACK * sc and ohi >= hi - ROUND_SLACK * sc, (kind, task.label, i, r.outer, lo, hi)
                gap = max(lo - olo, ohi - hi) / sc
                assert gap <= GAP_STATED, (kind, task.label, i, r.outer, lo, hi)
                # the values found are values at task points: inside the outer range
                assert olo <= ilo <= ihi <= ohi
                worst = max(worst, gap)
    return worst


def test_outer_ranges_contain_dense_ranges():
    """Every mechanism, three tasks (the kinds rectangle, polygon, circle, path, points in
    turn: each kind on three mechanisms): the outer range of each coordinate contains its
    range over a 201 x 201 grid + 10^4 boundary points, each end within GAP_STATED of the
    scale."""
    _check_ranges(3, 201, 10_000, seed=31)


@pytest.mark.slow
def test_outer_ranges_issue_28_full():
    """The issue's version: 20 tasks per mechanism, 1001 x 1001 grid + 10^5 boundary points."""
    worst = _check_ranges(20, 1001, 100_000, seed=2029)
    print(f"worst gap to the dense range: {worst:.3g} of the scale")


def _without_remainder(mech, monkeypatch):
    """``mech`` whose closure enclosure's ``A`` is zero: the mean value form's remainder
    ``grad q_i(C) . (C - c)`` (gradient ``a_i / b_i``) dropped, the form reduced to
    ``q_i(c)``. (A gradient of the wrong sign would not do: about the centre ``C - c`` is
    symmetric, so is the remainder.)"""
    real = mech.closure_enclosure

    def zero(x, y, lengths=None):
        A, b, certain = real(x, y, lengths)
        return tuple(tuple(a * 0.0 for a in row) for row in A), b, certain
    monkeypatch.setattr(mech, "closure_enclosure", zero)
    return mech


@pytest.mark.parametrize("kind", ["five-bar", "asymmetric-five-bar", "biglide", "bipod", "gantry"])
def test_a_mean_value_form_without_remainder_is_caught(kind, monkeypatch):
    """The dense check fails when the mean value form drops its remainder."""
    rng = np.random.default_rng(41)
    mech = KINDS[kind][0][1]()
    caught = 0
    for _ in range(3):
        task = _reachable_task(mech, rng, "rect")
        sc = _scale(kind, task)
        dense = [dense_range(mech, task, i, 61, 2000) for i in range(2)]
        with monkeypatch.context() as m:
            r = B.outer_range(_without_remainder(mech, m), task, sc, budget=2000)
        caught += any(olo > lo + ROUND_SLACK * sc or ohi < hi - ROUND_SLACK * sc
                      for (olo, ohi), (lo, hi) in zip(r.outer, dense))
    assert caught > 0


def test_smaller_budget_never_tightens_the_range():
    """As the cell budget shrinks, each outer end moves outward (or stays), and always
    contains the dense range."""
    from mechopt.mechanisms.five_bar.model import FiveBar

    mech = FiveBar(120.0, 160.0, 50.0, "+-")
    task = Task.rect(100.0, 60.0, center=(0.0, 180.0))
    dense = [dense_range(mech, task, i, 201, 10_000) for i in range(2)]
    outs = [B.outer_range(mech, task, 1.0, budget=n, rtol=1e-5).outer for n in (20_000, 2_000, 200, 40, 10, 1)]
    for (lo, hi), ranges in zip(dense, zip(*outs)):
        assert all(a <= lo and b >= hi for a, b in ranges)
        assert all(a1 >= a2 and b1 <= b2 for (a1, b1), (a2, b2) in zip(ranges, ranges[1:])), ranges
        assert ranges[0][1] - ranges[0][0] < ranges[-1][1] - ranges[-1][0]


def test_out_of_reach_is_unbounded():
    """A task partly out of reach: every end infinite, flagged."""
    from mechopt.mechanisms.five_bar.model import FiveBar

    r = B.outer_range(FiveBar(1.0, 1.2, 0.5, "+-"), Task.rect(1.0, 1.0, center=(0.0, 2.2)), 1.0, budget=200)
    assert r.outer == [(-math.inf, math.inf)] * 2 and r.may_unreachable


def test_across_the_branch_cut_is_unbounded():
    """A task across the negative x axis seen from a base joint (where ``ik``'s angle jumps
    by 2 pi): no finite bound of leg 1's angle there, and the dense range is that wide."""
    from mechopt.mechanisms.five_bar.model import FiveBar

    mech = FiveBar(1.0, 1.2, 0.2, "+-")
    task = Task.rect(0.3, 0.3, center=(-1.0, 0.0))
    lo, hi = dense_range(mech, task, 0, 101, 2000)
    assert hi - lo > math.pi
    r = B.outer_range(mech, task, 1.0, budget=500)
    assert r.outer[0][0] <= lo and r.outer[0][1] >= hi


def test_range_over_a_length_box_contains_every_mechanism_of_the_box():
    """A five-bar's outer range over the task and every length within +-T (0.1 % of the
    length scale) contains the dense range of each of 12 mechanisms drawn in the box
    (its 8 corners included), within 1 % of a radian."""
    from mechopt.mechanisms.five_bar.model import FiveBar

    mech = FiveBar(120.0, 160.0, 50.0, "+-")
    task = Task.rect(100.0, 60.0, center=(0.0, 180.0))
    T = 0.001 * mech.length_scale
    nominal = np.array([mech.r1, mech.r2, mech.r3])
    rng = np.random.default_rng(3)
    offs = np.vstack([np.array(np.meshgrid(*[[-1.0, 1.0]] * 3)).reshape(3, -1).T, rng.uniform(-1, 1, (4, 3))])
    dense = [[dense_range(FiveBar(*(nominal + T * o), "+-"), task, i, 41, 2000) for o in offs] for i in range(2)]
    r = B.outer_range(mech, task, 1.0, lengths={n: (L - T, L + T) for n, L in zip(("r1", "r2", "r3"), nominal)})
    for (olo, ohi), d in zip(r.outer, dense):
        lo, hi = min(a for a, _ in d), max(b for _, b in d)
        assert olo <= lo and ohi >= hi and max(lo - olo, ohi - hi) <= 0.01, (olo, ohi, lo, hi)


def test_bad_arguments():
    from mechopt.mechanisms.five_bar.model import FiveBar

    with pytest.raises(ValueError, match="actuator"):
        B.range_quantity(2, 1.0, 1.0)
    with pytest.raises(ValueError, match="budget"):
        B.outer_range(FiveBar(1.0, 1.2, 0.5), Task.rect(0.2, 0.2, center=(0.0, 1.2)), 1.0, budget=0)


# ------------------------------------------------------------------ certificates
def test_readme_rectangle_with_joint_limits_is_proven(tmp_path, capsys):
    """``mechopt design five-bar --task rect:100,60@0,180 --min-lci 0.4
    --joint-limits=-60,240`` (small run): certificate.json calls ``joints`` proven, its
    proven outer ranges contain the design's dense crank ranges and the sampled ones, and
    ``mechopt check`` prints it proven."""
    import json

    from mechopt.cli import main
    from mechopt.mechanisms.five_bar.model import FiveBar

    out = tmp_path / "d"
    assert main(["design", "five-bar", "--task", "rect:100,60@0,180", "--min-lci", "0.4", "--joint-limits=-60,240",
                 "--max-length", "250", "--pop", "12", "--gen", "6", "--seed", "1", "--no-polish",
                 "--out", str(out)]) == 0
    cert = json.loads((out / "certificate.json").read_text())
    task = Task.rect(100.0, 60.0, center=(0.0, 180.0))
    for d in cert["designs"]:
        e = d["requirements"]["joints"]
        b = e["bound"]
        assert e["method"] == "proven" and b["proven_margin"] >= 0 and "outer ranges" in e["certificate"]
        assert b["lower_bound"] <= b["estimate"] and b["gap"] <= GAP_STATED
        v = d["variables"]
        mech = FiveBar(v["r1"], v["r2"], v["r3"], v["mode"])
        for i, ((olo, ohi), (slo, shi)) in enumerate(zip(b["ranges"], b["estimate_ranges"])):
            lo, hi = dense_range(mech, task.moved_to(d["task_placement"]["task_x"], d["task_placement"]["task_y"]),
                                 i, 101, 4000)
            assert olo <= min(lo, slo) and ohi >= max(hi, shi)
    capsys.readouterr()
    assert main(["check", str(out / "design.json")]) == 0
    line = next(s for s in capsys.readouterr().out.splitlines() if s.startswith("joints:"))
    assert "holds, proven" in line


@pytest.mark.parametrize("mechanism", ["biglide", "gantry"])
def test_stroke_is_proven(mechanism):
    """A Biglide / gantry with ``max_stroke``: the longest proven outer range is at most
    it, ``stroke`` is proven, and the outer ranges contain the sampled strokes."""
    from mechopt.analysis.design_eval import DesignEvaluator, certify
    from mechopt.analysis.task import parse_task
    from mechopt.requirements import Requirements
    from mechopt.workflows.certificate import proven_bounds, requirement_entries

    ev = DesignEvaluator(mechanism, parse_task("rect:100,60@0,180"), Requirements(min_lci=0.3, max_stroke=300.0),
                         ("size",), max_length=400)
    names = list(ev.spec.lengths)
    v = {names[0]: 37.0, names[1]: 124.0, "mode": "--", "task_x": 0.0, "task_y": 180.0}
    res = certify(ev, v)
    e = requirement_entries(ev, res, proven_bounds(ev, v, res["margin"]))["stroke"]
    b = e["bound"]
    assert e["method"] == "proven" and e["holds"]
    longest = max(hi - lo for lo, hi in b["ranges"])
    assert longest <= 300.0 and b["proven_margin"] == pytest.approx(300.0 - longest, abs=1e-9)
    for (olo, ohi), (slo, shi) in zip(b["ranges"], b["estimate_ranges"]):
        assert olo <= slo <= shi <= ohi
    assert 0 <= b["gap"] <= GAP_STATED * ev.task.diameter
