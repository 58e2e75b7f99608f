"""The design evaluation's fast paths give the values of the plain ones bit for bit:
the compiled twins (mechopt.core.jit.Twin) those of the NumPy paths, the zoom's starts
chosen by a partition and the searches of several functions run together
(mechopt.analysis.sampling) those of the full sort and of one search per function.

Each hot NumPy path of the design evaluation has a numba loop that repeats its
operations point by point; the evaluation switches to the loops after its first
half second of NumPy work, so any difference would make a design's results depend on
how long the process had run. Every output array is compared byte for byte (NaN
payloads, signed zeros and all), on random designs and points and on the special
points (base joints, the annulus' rims, NaN, inf, far away, the task's boundary).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechopt.analysis.task import Task, parse_task
from mechopt.core import indices as ix
from mechopt.core import jit
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
from mechopt.requirements.speed import _box_rows
from mechopt.mechanisms.five_bar.model import MODES, FiveBar, legs_closure, legs_elbows, legs_ik

pytestmark = pytest.mark.skipif(not jit.HAVE_NUMBA, reason="the twins are numba loops (the fast extra)")

STAR = "polygon:0,200;12,166;47,166;19,145;29,111;0,131;-29,111;-19,145;-47,166;-12,166"


def both(monkeypatch, f):
    """``f()`` on the NumPy paths and on the compiled twins."""
    monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: False))
    ref = f()
    monkeypatch.setattr(jit.Twin, "compiled", staticmethod(lambda: True))
    return ref, f()


def assert_same_bits(ref, got):
    ref = ref if isinstance(ref, tuple) else (ref,)
    got = got if isinstance(got, tuple) else (got,)
    assert len(ref) == len(got)
    for u, v in zip(ref, got):
        u, v = np.asarray(u), np.asarray(v)
        assert u.dtype == v.dtype and u.shape == v.shape
        assert u.tobytes() == v.tobytes(), np.flatnonzero(u.view(np.uint8) != v.view(np.uint8))[:5]


def _points(rng, r3, reach):
    """Random points around the base and the special ones."""
    n = 400
    x = rng.uniform(-1.5, 1.5, n) * reach
    y = rng.uniform(-1.5, 1.5, n) * reach
    # on the rims of leg 1's annulus and at the base joints, NaN, inf, far away
    t = rng.uniform(0, 2 * np.pi, 8)
    special_x = [-r3, r3, np.nan, np.inf, 1e300, 0.0, -np.inf, 5e15]
    special_y = [0.0, 0.0, 1.0, 0.0, 0.0, np.nan, 2.0, 0.0]
    x = np.concatenate([x, special_x, -r3 + reach * np.cos(t)])
    y = np.concatenate([y, special_y, reach * np.sin(t)])
    return x, y


@settings(max_examples=60, deadline=None)
@given(st.floats(1.0, 300.0), st.floats(1.0, 300.0), st.floats(0.0, 200.0), st.sampled_from(MODES),
       st.integers(0, 2**31))
def test_five_bar_kinematics_bit_for_bit(r1, r2, r3, mode, seed):
    rng = np.random.default_rng(seed)
    m = FiveBar(r1, r2, r3, mode=mode)
    x, y = _points(rng, r3, r1 + r2)
    legs = m._legs()
    with pytest.MonkeyPatch.context() as mp:
        for f in (lambda: legs_elbows(x, y, r3, legs), lambda: legs_closure(x, y, r3, legs),
                  lambda: legs_ik(x, y, r3, legs), lambda: m.jacobian(x, y), lambda: ix.lci(m.jacobian(x, y)),
                  lambda: m.type2_function(x, y),
                  # shapes other than 1-d, scalars
                  lambda: legs_closure(x[:12].reshape(3, 4), y[:12].reshape(3, 4), r3, legs),
                  lambda: legs_ik(float(x[0]), float(y[0]), r3, legs), lambda: ix.lci(m.jacobian(x[1], y[1]))):
            assert_same_bits(*both(mp, f))
        # lengths as arrays (a caller broadcasting designs over the points): the NumPy path
        arr = ((np.array([[r1], [1.1 * r1]]), r2, legs[0][2]), (r1, np.array([[r2], [0.9 * r2]]), legs[1][2]))
        for f in (lambda: legs_elbows(x[:9], y[:9], r3, arr), lambda: legs_closure(x[:9], y[:9], np.array([[r3]]), arr),
                  lambda: legs_ik(x[:9], y[:9], r3, arr)):
            ref, got = both(mp, f)
            assert np.shape(got[-1]) == (2, 9)  # reachability, broadcast over the designs
            assert_same_bits(ref, got)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(1.0, 300.0), min_size=4, max_size=4), st.floats(0.0, 200.0), st.integers(0, 2**31))
def test_asymmetric_legs_bit_for_bit(lengths, r3, seed):
    a1, c1, a2, c2 = lengths
    rng = np.random.default_rng(seed)
    m = AsymmetricFiveBar(a1, c1, a2, c2, r3)
    x, y = _points(rng, r3, max(a1 + c1, a2 + c2))
    with pytest.MonkeyPatch.context() as mp:
        for f in (lambda: m.closure(x, y), lambda: m.ik(x, y), lambda: ix.lci(m.jacobian(x, y))):
            assert_same_bits(*both(mp, f))


@pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning")  # entries near the largest double
@settings(max_examples=80, deadline=None)
@given(st.integers(0, 2**31), st.sampled_from([1e-300, 1e-160, 1e-5, 1.0, 1e5, 1e160, 1e300, "mixed"]))
def test_lci_and_row_norms_of_matrices_bit_for_bit(seed, scale):
    rng = np.random.default_rng(seed)
    if scale == "mixed":  # every entry its own magnitude, from subnormal to near the largest double
        J = rng.normal(size=(200, 2, 2)) * 10.0 ** rng.uniform(-320, 307.5, size=(200, 2, 2))
        J[6] = [[1.7e308, -1.6e308], [3.0, 1e-300]]  # the largest entry's power of two 2^1024
        J[7] = [[3e-310, 1e-320], [-2e-315, 5e-324]]  # subnormal entries only
    else:
        J = rng.normal(size=(200, 2, 2)) * scale
    J[0] = 0.0
    J[1, 0, 0] = np.nan
    J[2, 1, 1] = np.inf
    J[3] = [[1.0, 2.0], [2.0, 4.0]]  # singular
    J[4, 0, 1] = 5e-324  # subnormal
    J[5] = [[np.inf, 1.0], [1.0, 0.0]]
    with pytest.MonkeyPatch.context() as mp:
        assert_same_bits(*both(mp, lambda: ix.lci(J)))
        assert_same_bits(*both(mp, lambda: ix.lci(J[:8].reshape(2, 4, 2, 2))))
        assert_same_bits(*both(mp, lambda: ix.lci(J[7])))
        assert_same_bits(*both(mp, lambda: _box_rows(J)))
        assert_same_bits(*both(mp, lambda: _box_rows(J[:8].reshape(2, 4, 2, 2))))


def _random_polygon(rng, n):
    """A simple polygon, star-shaped about its centre: one vertex per sector of angle
    2 pi / n, random radii."""
    a = (np.arange(n) + rng.uniform(0.0, 0.8, n)) * (2 * np.pi / n)
    r = rng.uniform(20, 100, n)
    return Task.polygon(np.c_[r * np.cos(a), 150 + r * np.sin(a)])


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**31), st.integers(3, 12))
def test_task_boundary_and_contains_bit_for_bit(seed, n):
    rng = np.random.default_rng(seed)
    tasks = [parse_task("rect:100,60@0,180"), parse_task(STAR), _random_polygon(rng, n),
             Task.path(np.array([[0.0, 0.0], [10.0, 5.0], [20.0, -3.0], [40.0, 0.0]])),
             parse_task(STAR).moved_to(*rng.uniform(-60.0, 60.0, 2))]  # a placement's samples
    t = np.concatenate([rng.uniform(-2.0, 3.0, 300), np.linspace(-1.0, 2.0, 61), [-0.0, 0.0, 1.0, np.nan]])
    with pytest.MonkeyPatch.context() as mp:
        for task in tasks:
            bx, by = task.boundary_at(t)
            assert_same_bits(*both(mp, lambda: task.boundary_at(t)))
            assert_same_bits(*both(mp, lambda: task.boundary_at(t[:6].reshape(2, 3))))
            # random points over the task's box widened by half its size each way (the task
            # fills a good part of its box: both verdicts occur; over a fixed box a small
            # random triangle could hold none of them), points within rounding of the
            # boundary, vertices, NaN and inf
            x0, x1, y0, y1 = task.bbox
            w, h = x1 - x0, y1 - y0
            x = np.concatenate([rng.uniform(x0 - w / 2, x1 + w / 2, 300), bx + rng.normal(0, 1e-9, bx.size),
                                [np.nan, np.inf, 0.0]])
            y = np.concatenate([rng.uniform(y0 - h / 2, y1 + h / 2, 300), by + rng.normal(0, 1e-9, by.size),
                                [0.0, 0.0, np.nan]])
            assert_same_bits(*both(mp, lambda: task.contains(x, y)))
            assert_same_bits(*both(mp, lambda: task.contains(x[:6].reshape(3, 2), 170.0)))
            # the grid (Task.grid: np.linspace's nodes, containment row by row) and the
            # boundary's parameters, every size of the samplings and smaller ones
            for m in (2, 3, 13, 37, 61):
                assert_same_bits(*both(mp, lambda: task.grid(m)))
            for m in (8, 11, 192, 2048):
                assert_same_bits(*both(mp, lambda: task.boundary_params(m)))
            if task.is_region:
                got = task.contains(x, y)
                assert got[:300].any() and not got[:300].all()  # both verdicts occur


def test_the_switch_happens_after_the_numpy_time(monkeypatch):
    """Twin.compiled(): False in a process that has not loaded numba and spent less
    than TWIN_AFTER_SECONDS in the twins' NumPy paths, True after."""
    monkeypatch.setattr(jit, "_numba", None)
    monkeypatch.setattr(jit, "_twin_numpy_seconds", 0.0)
    assert not jit.Twin.compiled()
    m = FiveBar(100.0, 120.0, 20.0)
    x = np.linspace(-50, 50, 1000)
    while jit._twin_numpy_seconds < jit.TWIN_AFTER_SECONDS:
        legs_elbows(x, np.full_like(x, 150.0), m.r3, m._legs())
    assert jit.Twin.compiled()


# --- the zoom's starts: the set of the k lowest samples, not their order ----------------------
from mechopt.analysis import sampling as S  # noqa: E402


def _argsort_lowest(vals, k):
    return np.argsort(vals)[:k]


@settings(max_examples=200, deadline=None)
@given(st.integers(0, 2**31), st.integers(1, 6), st.integers(2, 40))
def test_lowest_is_the_full_sorts_set(seed, k, n):
    """``_lowest`` picks the set of ``np.argsort(vals)[:k]``, and the full sort's very
    indices when a tie straddles the k-th place; values drawn from a few levels (ties
    everywhere), with inf and NaN."""
    rng = np.random.default_rng(seed)
    vals = rng.integers(0, 4, n).astype(float)
    vals[rng.random(n) < 0.1] = np.inf
    vals[rng.random(n) < 0.05] = np.nan
    ref = _argsort_lowest(vals, k)
    with pytest.MonkeyPatch.context() as mp:  # the NumPy partition and the compiled pass
        for got in both(mp, lambda: S._lowest(vals, k)):
            assert sorted(got) == sorted(ref)
            s = np.sort(vals)
            if len(vals) > k and not s[k - 1] < s[k]:
                assert list(got) == list(ref)


def test_design_evaluations_do_not_depend_on_the_order_of_the_starts(monkeypatch):
    """Every value of the design evaluation (refined minima, ranges) is the same with
    the full sort's starts, on designs whose samples tie (mirror-symmetric five-bars on
    a task centred on their axis) and others."""
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.sampling import Sampling
    from mechopt.requirements import Requirements

    ev = DesignEvaluator("five-bar", parse_task("rect:100,60@0,180"),
                         Requirements(min_lci=0.3, joint_limits=(-60, 240)), ("size", "min-lci"), max_length=300)
    rng = np.random.default_rng(0)
    designs = [dict(r1=129.4, r2=144.9, r3=3.57, mode="+-", task_x=0.0, task_y=180.0)]
    designs += [dict(r1=float(a), r2=float(b), r3=float(c), mode=m, task_x=float(x), task_y=180.0)
                for a, b, c, m, x in zip(rng.uniform(90, 200, 12), rng.uniform(90, 200, 12), rng.uniform(0, 60, 12),
                                         ["+-", "-+", "++", "--"] * 3, [0.0] * 6 + list(rng.uniform(-20, 20, 6)))]
    ties = 0
    for s in (Sampling(), Sampling.fine()):
        for v in designs:
            got = ev.evaluate(v, s)
            with monkeypatch.context() as mp:
                mp.setattr(S, "_lowest", _argsort_lowest)
                ref = ev.evaluate(v, s)
            for key in ("g", "margin", "objectives", "values"):
                assert repr(got[key]) == repr(ref[key])
            assert repr(got["derived"]) == repr(ref["derived"])
            vals = ev.context(v, s).lci[:ev.context(v, s).n_boundary]
            srt = np.sort(vals)
            ties += int(np.any(srt[1:4] == srt[:3]))
    assert ties > 0  # the designs exercise tied starts


@pytest.mark.parametrize("task", ["rect:100,60@0,180", STAR])
def test_searches_of_several_rows_are_those_of_one_row_each(task):
    """``region_mins`` of several functions zooms them together (one search over all
    rows); every minimum is bit for bit the one the function's own search finds."""
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.sampling import Sampling
    from mechopt.requirements import Requirements

    ev = DesignEvaluator("five-bar", parse_task(task), Requirements(min_lci=0.3), ("size",), max_length=300)
    rng = np.random.default_rng(2)
    checked = 0
    for a, b, c, mode in zip(rng.uniform(90, 220, 8), rng.uniform(90, 220, 8), rng.uniform(0, 60, 8),
                             ["+-", "-+", "++", "--"] * 2):
        v = dict(r1=float(a), r2=float(b), r3=float(c), mode=mode, task_x=0.0, task_y=float(rng.uniform(150, 200)))
        for s in (Sampling(), Sampling.fine()):
            ctx = ev.context(v, s)
            m = ctx.mech

            def F(x, y):
                x, y = ctx.to_mech(x, y)
                t2 = m.type2_function(x, y)
                return np.stack([S.bad_to(ix.lci(m.jacobian(x, y)), 0.0), S.bad_to(t2, 2.0), S.bad_to(-t2, 2.0),
                                 S.bad_to(m.ik(x, y)[0], 9.0)])

            vals = F(ctx.samples["allx"], ctx.samples["ally"])
            together = S.region_mins(ctx.samples, F, True, vals)
            alone = [S.region_mins(ctx.samples, lambda x, y, r=r: F(x, y)[r:r + 1], True, vals[r:r + 1])[0]
                     for r in range(len(vals))]
            assert [float(t).hex() for t in together] == [float(t).hex() for t in alone]
            ranges = S.leg_ranges(ctx.samples, lambda x, y: m.ik(*ctx.to_mech(x, y)), True)
            q = lambda x, y, i, sg: sg * S.bad_to(m.ik(*ctx.to_mech(x, y))[i], sg * np.inf)  # noqa: E731
            for i, (lo, hi) in enumerate(ranges):
                for sg, want in ((1.0, lo), (-1.0, -hi)):
                    def G(x, y, i=i, sg=sg):
                        return q(x, y, i, sg)[None]
                    nb = ctx.samples["bx"].size
                    got = S.minimise(G, [S._boundary_search(ctx.samples, G(ctx.samples["bx"], ctx.samples["by"]),
                                                            True)], ctx.samples["task"])[0][0]
                    assert float(got).hex() == float(want).hex()
                    checked += nb > 0
    assert checked > 0


@settings(max_examples=40, deadline=None)
@given(st.sampled_from(["biglide", "gantry"]), st.floats(20.0, 300.0), st.floats(50.0, 400.0),
       st.sampled_from(["+-", "-+", "++", "--"]), st.integers(0, 2**31))
def test_slider_closure_bit_for_bit(kind, half, link, mode, seed):
    from mechopt.mechanisms.biglide import Biglide
    from mechopt.mechanisms.gantry import Gantry
    rng = np.random.default_rng(seed)
    if kind == "biglide":  # guides at +-l1, links l2 > l1, strokes of either sign
        m = Biglide(half, half + link, -link, 1.5 * link, mode=mode)
    else:  # the gantry's link l, half span d1, a stroke from q_min, the tool offset l2
        m = Gantry(half, half + link, 2.0 * link, q_min=-link, l2=float(rng.uniform(0, 50)), mode=mode)
    x = np.concatenate([rng.uniform(-2, 2, 400) * (half + link), [np.nan, np.inf, 0.0, half + link, half]])
    y = np.concatenate([rng.uniform(-2, 2, 400) * (half + link), [0.0, 0.0, np.nan, 0.0, 0.0]])
    with pytest.MonkeyPatch.context() as mp:
        for f in (lambda: m.closure(x, y), lambda: ix.lci(m.jacobian(x, y)), lambda: m.closure(x[:6].reshape(2, 3), 1.0)):
            assert_same_bits(*both(mp, f))
