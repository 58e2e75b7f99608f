"""The compiled zoom (mechopt.core.zoom, the five-bar's point kernels) gives the NumPy
searches' minima bit for bit (mechopt.analysis.sampling.region_mins over the mechanism's
methods): the LCI and the type-II function's minima over rectangles, polygons (convex
or not), paths and point sets, for random five-bars in every working mode, with the
search's and the certification's samplings, and sign factors +1 and -1. The NumPy
searches are the reference: they call the mechanism's public methods (jacobian, LCI,
type2_function) and Task.boundary_at / Task.contains, none of the compiled code's
per-point formulas.
"""
from __future__ import annotations

import struct

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis import sampling as _s
from mechopt.analysis.sampling import Sampling, bad_to
from mechopt.analysis.task import Task, parse_task
from mechopt.core import indices as ix
from mechopt.core import jit
from mechopt.mechanisms.five_bar.model import MODES
from mechopt.requirements import Requirements
from mechopt.requirements.speed import _box_rows

pytestmark = pytest.mark.skipif(not jit.HAVE_NUMBA, reason="the compiled zoom is a numba loop (the fast extra)")

STAR = "polygon:0,200;12,166;47,166;19,145;29,111;0,131;-29,111;-19,145;-47,166;-12,166"
TASKS = {
    "rect": parse_task("rect:100,60@0,180"),
    "star": parse_task(STAR),
    "L": parse_task("polygon:-60,120;60,120;60,150;-20,150;-20,220;-60,220"),
    "path": Task.path([(-50.0, 150.0), (0.0, 210.0), (40.0, 160.0), (60.0, 200.0)]),
    "points": Task.points([(-30.0, 160.0), (10.0, 190.0), (35.0, 175.0)]),
}


def bits(v):
    return struct.pack("<d", v)


def _numpy_parts(ctx, F, vals):
    """``(boundary minimum, interior minimum)`` of the NumPy searches
    (:func:`sampling._boundary_search`, :func:`sampling._interior_search`) of ``F``."""
    nb = ctx.n_boundary
    return tuple(r[0] for r in _s.minimise(lambda x, y: F(x, y)[None], [
        _s._boundary_search(ctx.samples, vals[None, :nb], True),
        _s._interior_search(ctx.samples, vals[None, nb:], True)], ctx.task))


def _minima(ev, v, sampling):
    """For the LCI and the type-II function times +1 and -1 (NaN -> -1) of the decoded
    design ``v``: the boundary and interior minima of the NumPy searches over the
    mechanism's public methods, and of the compiled zoom."""
    jit.load_numba()  # the twins and the zoom run (Twin.compiled)
    ctx = ev.context(v, sampling)
    m = ctx.mech
    cases = [("lci", 1.0, 0.0, lambda x, y: bad_to(ix.lci(m.jacobian(x, y)), 0.0), ctx.lci)]
    for s0 in (1.0, -1.0):
        cases.append(("type2", s0, -1.0, lambda x, y, s0=s0: bad_to(s0 * m.type2_function(x, y), -1.0),
                      bad_to(s0 * ctx.type2_raw, -1.0)))
    ref, got = [], []
    for q, scale, bad, F, vals in cases:
        ref.append(_numpy_parts(ctx, F, vals))
        got.append(_s.compiled_region_min(ctx.samples, m.zoom_kernel(q), scale, bad, vals))
    return ref, got


def _design(ev, r1, r2, r3, mode):
    """A decoded design with the task where it was given (its reference point)."""
    x, y = ev.task.reference
    return {"r1": r1, "r2": r2, "r3": r3, "mode": mode, "task_x": float(x), "task_y": float(y)}


@pytest.mark.parametrize("task", list(TASKS))
@settings(max_examples=25, deadline=None)
@given(r1=st.floats(40.0, 250.0), r2=st.floats(40.0, 250.0), r3=st.floats(0.0, 120.0), mode=st.sampled_from(MODES),
       fine=st.booleans())
def test_compiled_zoom_gives_the_numpy_minimum_bit_for_bit(task, r1, r2, r3, mode, fine):
    ev = DesignEvaluator("five-bar", TASKS[task], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    v = _design(ev, r1, r2, r3, mode)
    ref, got = _minima(ev, v, Sampling.fine() if fine else Sampling())
    assert [[bits(a) for a in g] for g in got] == [[bits(b) for b in r] for r in ref], (ref, got)


def test_the_compiled_zoom_runs_and_refines():
    """Not vacuous: on the star polygon the compiled path is taken (the kernel exists,
    the task is a polygon) and its refined minimum is below the samples' own minimum for
    a design whose LCI dips between samples (toward a singular point: 0.0032 on the
    samples, about 1e-6 refined)."""
    jit.load_numba()
    ev = DesignEvaluator("five-bar", TASKS["star"], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    v = _design(ev, 141.97, 83.26, 0.0, "+-")
    ctx = ev.context(v, Sampling())
    assert ctx.mech.zoom_kernel("lci") is not None
    calls = []
    kernel = ctx.mech.zoom_kernel("lci")
    orig = type(kernel).run

    def spy(self, *a):
        calls.append(a)
        return orig(self, *a)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(type(kernel), "run", spy)
        ctx.refine = True
        low = ctx.quantity_min("lci", ctx.lci)
    assert calls, "the compiled zoom did not run"
    assert 0.0 <= low < 1e-3 < float(ctx.lci.min())


def test_a_circle_task_keeps_the_numpy_search():
    jit.load_numba()
    task = parse_task("circle:40@0,180")
    ev = DesignEvaluator("five-bar", task, Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    ctx = ev.context(_design(ev, 141.97, 83.26, 10.0, "+-"), Sampling())
    from mechopt.analysis.sampling import compiled_region_min

    assert compiled_region_min(ctx.samples, ctx.mech.zoom_kernel("lci"), 1.0, 0.0, ctx.lci) is None


def test_a_wrong_kernel_is_caught(monkeypatch):
    """The comparison can fail: the LCI kernel's zoom in place of the type-II one gives
    other minima on the README rectangle."""
    import mechopt.mechanisms.five_bar.model as fb

    ev = DesignEvaluator("five-bar", TASKS["rect"], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    v = _design(ev, 141.97, 83.26, 5.0, "+-")
    ref, got = _minima(ev, v, Sampling())
    assert [bits(a) for a in got[1]] == [bits(b) for b in ref[1]]
    monkeypatch.setitem(fb._ZOOMS, "type2", fb._ZOOMS["lci"])
    ref, got = _minima(ev, v, Sampling())
    assert [bits(a) for a in got[0]] == [bits(b) for b in ref[0]]
    assert [bits(a) for a in got[1]] != [bits(b) for b in ref[1]]


@pytest.mark.parametrize("task", ["rect", "star", "L", "path"])
@settings(max_examples=25, deadline=None)
@given(r1=st.floats(40.0, 250.0), r2=st.floats(40.0, 250.0), r3=st.floats(0.0, 120.0), mode=st.sampled_from(MODES),
       fine=st.booleans())
def test_compiled_crank_ranges_are_the_numpy_ones_bit_for_bit(task, r1, r2, r3, mode, fine):
    """The crank ranges over the boundary (the joints requirement): the NumPy search
    over FiveBar.ik, and the compiled zoom (NumPy's arccos and arctan2 in its
    interpreted block)."""
    jit.load_numba()
    ev = DesignEvaluator("five-bar", TASKS[task], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    ctx = ev.context(_design(ev, r1, r2, r3, mode), Sampling.fine() if fine else Sampling())
    kernel = ctx.mech.zoom_kernel("ik")
    assert kernel is not None
    ref = _s.leg_ranges(ctx.samples, ctx.mech.ik, True)
    got = _s.leg_ranges(ctx.samples, ctx.mech.ik, True, kernel=kernel)
    assert [bits(v) for r in got for v in r] == [bits(v) for r in ref for v in r], (ref, got)


def test_compiled_crank_ranges_refine():
    """Not vacuous: the compiled ranges of a design for the README rectangle are wider
    than the boundary samples' (an extreme lies between samples: 0.04 rad in all)."""
    jit.load_numba()
    ev = DesignEvaluator("five-bar", TASKS["rect"], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=300.0)
    ctx = ev.context(_design(ev, 123.9, 88.6, 45.0, "+-"), Sampling())
    sampled = _s.leg_ranges(ctx.samples, ctx.mech.ik, False)
    got = _s.leg_ranges(ctx.samples, ctx.mech.ik, True, kernel=ctx.mech.zoom_kernel("ik"))
    assert sum(g[1] - g[0] - (s[1] - s[0]) for g, s in zip(got, sampled)) > 0.01
    assert all(g[0] <= s[0] and g[1] >= s[1] for g, s in zip(got, sampled))


SLIDER_CASES = [("biglide", ("l1", "l2")), ("gantry", ("d1", "l"))]


def _slider_parts(ev, v, sampling):
    """The two-slider mechanisms' LCI, type-II (times +1 and -1) and box speed/force rows:
    boundary and interior minima of the NumPy searches over the mechanism's public
    methods and of the compiled zoom (None where no kernel)."""
    jit.load_numba()
    ctx = ev.context(v, sampling)
    m = ctx.mech
    box = _box_rows(ctx.jacobian)
    cases = [(m.zoom_kernel("lci"), 1.0, 0.0, lambda x, y: bad_to(ix.lci(m.jacobian(x, y)), 0.0), ctx.lci)]
    for s0 in (1.0, -1.0):
        cases.append((m.zoom_kernel("type2"), s0, -1.0, lambda x, y, s0=s0: bad_to(s0 * m.type2_function(x, y), -1.0),
                      bad_to(s0 * ctx.type2_raw, -1.0)))
    for r in range(4):
        cases.append((m.zoom_kernel("box").with_row(r), 1.0, 0.0,
                      lambda x, y, r=r: _box_rows(m.jacobian(x, y))[r], box[r]))
    ref, got = [], []
    for kernel, scale, bad, F, vals in cases:
        ref.append(_numpy_parts(ctx, F, np.ascontiguousarray(vals)))
        got.append(_s.compiled_region_min(ctx.samples, kernel, scale, bad, np.ascontiguousarray(vals)))
    return ref, got


@pytest.mark.parametrize("mech,names", SLIDER_CASES)
@pytest.mark.parametrize("task", ["rect", "star", "path"])
@settings(max_examples=15, deadline=None)
@given(a=st.floats(0.05, 1.5), b=st.floats(0.05, 3.0), mode=st.integers(0, 3), fine=st.booleans())
def test_two_slider_kernels_give_the_numpy_minima_bit_for_bit(mech, names, task, a, b, mode, fine):
    """Biglide and gantry (their strokes derived from the task), the guide distance ``a``
    times the task's size and the link ``1 + b`` times that (longer, so that the links
    meet): the LCI, the type-II function and the four box speed/force factors."""
    ev = DesignEvaluator(mech, TASKS[task], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=2000.0)
    x, y = ev.task.reference
    D = ev.task.diameter
    v = {names[0]: a * D, names[1]: (1.0 + b) * a * D, "mode": ev.spec.modes[mode], "task_x": float(x),
         "task_y": float(y)}
    ref, got = _slider_parts(ev, v, Sampling.fine() if fine else Sampling())
    assert [[bits(a) for a in g] for g in got] == [[bits(b) for b in r] for r in ref], (ref, got)


def test_a_wrong_box_row_is_caught():
    """The comparison can fail: row 0's kernel searching row 2's samples (the force
    factor ``|det J| / ||row_1||`` of a gantry) refines to another minimum (0.7189
    against 0.7633 inside); the right row gives the NumPy search's."""
    jit.load_numba()
    ev = DesignEvaluator("gantry", TASKS["rect"], Requirements(min_lci=0.3), ("size", "min-lci"), max_length=2000.0)
    x, y = ev.task.reference
    ctx = ev.context({"d1": 60.0, "l": 150.0, "mode": "--", "task_x": float(x), "task_y": float(y)}, Sampling())
    box = np.ascontiguousarray(_box_rows(ctx.jacobian))
    kernel = ctx.mech.zoom_kernel("box")
    assert kernel is not None
    right = _s.compiled_region_min(ctx.samples, kernel.with_row(2), 1.0, 0.0, box[2])
    wrong = _s.compiled_region_min(ctx.samples, kernel.with_row(0), 1.0, 0.0, box[2])
    ref = _numpy_parts(ctx, lambda x, y: _box_rows(ctx.mech.jacobian(x, y))[2], box[2])
    assert [bits(a) for a in right] == [bits(b) for b in ref]
    assert [bits(a) for a in wrong] != [bits(b) for b in ref]
