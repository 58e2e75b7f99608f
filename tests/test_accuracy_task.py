"""The accuracy budget over a task: the refined maximum of the proven pose bound
(``--max-error``, the ``error`` objective) against an independent dense grid, per-motor
error models and ``--encoder``, ``mechopt evaluate --error-model``, and a design run
whose error map stays below its ``--max-error``."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from mechopt import FiveBar
from mechopt.analysis import accuracy as acc
from mechopt.analysis.accuracy import ErrorModel
from mechopt.analysis.task import Task
from mechopt.requirements import Requirements

TASK = Task.rect(100, 60, (0, 180))
MODEL = {"encoder_counts": 16384, "backlash_arcmin": 1.0, "clearance_um": 5.0, "link_tol_um": 10.0}


def _dense_max(mech, spec, model, task, n):
    """The largest pose bound [um] on an ``n x n`` grid over the task's box (kept inside)
    and ``16 n`` points along its boundary: an independent sampling, in chunks."""
    x0, x1, y0, y1 = task.bbox
    X, Y = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    inside = task.contains(X, Y)
    tx, ty = X[inside], Y[inside]
    ox, oy = task.outline()
    s = np.linspace(0.0, 1.0, 16 * n)
    seg = np.r_[0.0, np.cumsum(np.hypot(np.diff(ox), np.diff(oy)))]
    bx, by = np.interp(s * seg[-1], seg, ox), np.interp(s * seg[-1], seg, oy)
    px, py = np.r_[tx, bx], np.r_[ty, by]
    best = 0.0
    for i in range(0, px.size, 20000):
        mx, my = spec.to_mech(mech, px[i:i + 20000], py[i:i + 20000])
        b = acc.pose_error(mech, model, mx, my, task.unit)["bound"]
        best = max(best, float(np.max(np.where(np.isnan(b), np.inf, b))))
    return best * acc.UM_PER_UNIT[task.unit]


def _evaluate(v, model=MODEL, task=TASK, mechanism="five-bar", **req):
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.sampling import Sampling

    ev = DesignEvaluator(mechanism, task, Requirements(max_error=1e6, error_model=model, **req), ("size",))
    return ev, ev.evaluate(v, Sampling())


DESIGNS = [
    {"r1": 163.7, "r2": 183.7, "r3": 1.285, "mode": "+-", "task_x": 0.0, "task_y": 180.0},
    {"r1": 150.0, "r2": 200.0, "r3": 30.0, "mode": "+-", "task_x": 0.0, "task_y": 180.0},
    {"r1": 120.0, "r2": 210.0, "r3": 60.0, "mode": "+-", "task_x": 0.0, "task_y": 150.0},
]


@pytest.mark.parametrize("v", DESIGNS[:2])
def test_refined_max_never_below_a_dense_grid(v):
    """The requirement's maximum (samples + zoom) is >= the largest bound of an
    independent 101 x 101 grid and dense boundary, and >= the samples' maximum."""
    from mechopt.analysis.sampling import Sampling, samples

    ev, res = _evaluate(v)
    got = res["values"]["error_um"]
    task = TASK.moved_to(v["task_x"], v["task_y"])
    mech = ev.spec.build({k: v[k] for k in ("r1", "r2", "r3")}, v["mode"])
    model = ErrorModel(**MODEL)
    s = samples(task, Sampling())
    on_samples = 1e3 * acc.max_error(mech, model, *ev.spec.to_mech(mech, s["allx"], s["ally"]))
    dense = _dense_max(mech, ev.spec, model, task, 101)
    assert math.isfinite(got)
    assert got >= on_samples
    assert got >= dense * (1 - 1e-9), (got, dense)
    assert got <= dense * 1.02  # a located maximum, not an inflated one


@pytest.mark.slow
@pytest.mark.parametrize("v", DESIGNS)
def test_refined_max_never_below_a_401_grid(v):
    ev, res = _evaluate(v)
    task = TASK.moved_to(v["task_x"], v["task_y"])
    mech = ev.spec.build({k: v[k] for k in ("r1", "r2", "r3")}, v["mode"])
    dense = _dense_max(mech, ev.spec, ErrorModel(**MODEL), task, 401)
    assert res["values"]["error_um"] >= dense * (1 - 1e-9)


def test_refinement_finds_an_interior_peak():
    """A task whose largest bound lies strictly between samples (a disk's boundary
    between two boundary samples, say) is found by the zoom: the refined value exceeds
    the samples' maximum when the dense grid does."""
    from mechopt.analysis.sampling import Sampling, samples

    task = Task.circle(40, (0, 200))
    v = {"r1": 150.0, "r2": 200.0, "r3": 30.0, "mode": "+-", "task_x": 0.0, "task_y": 200.0}
    ev, res = _evaluate(v, task=task)
    mech = ev.spec.build({k: v[k] for k in ("r1", "r2", "r3")}, v["mode"])
    model = ErrorModel(**MODEL)
    s = samples(task, Sampling())
    on_samples = 1e3 * acc.max_error(mech, model, *ev.spec.to_mech(mech, s["allx"], s["ally"]))
    dense = _dense_max(mech, ev.spec, model, task, 161)
    got = res["values"]["error_um"]
    assert got >= dense * (1 - 1e-9) and dense >= on_samples
    if dense > on_samples * (1 + 1e-9):
        assert got > on_samples


# ---------------------------------------------------------------- per-motor error models
def test_per_motor_values_move_each_motor_alone():
    """A model with motor 2 exact errs as the first-order map of motor 1 alone: the
    bound's linear part along x and y is ``t |dP/dtheta1|`` (from the inverse of the
    mechanism's own Jacobian, an independent route), and swapping the motors' values
    gives motor 2's column."""
    fb = FiveBar(163.7, 183.7, 1.285)
    x, y = np.array([10.0, -30.0, 40.0]), np.array([170.0, 200.0, 190.0])
    t = math.pi / 16384
    Jinv = np.linalg.inv(fb.jacobian(x, y))  # p_dot = J^-1 q_dot
    for i, model in enumerate((ErrorModel(encoder_counts=(16384, 0)), ErrorModel(encoder_counts=(0, 16384)))):
        pe = acc.pose_error(fb, model, x, y)
        np.testing.assert_allclose(pe["x"], t * np.abs(Jinv[:, 0, i]), rtol=1e-9)
        np.testing.assert_allclose(pe["y"], t * np.abs(Jinv[:, 1, i]), rtol=1e-9)
    both = acc.pose_error(fb, ErrorModel(encoder_counts=16384), x, y)
    same = acc.pose_error(fb, ErrorModel(encoder_counts=(16384, 16384)), x, y)
    np.testing.assert_array_equal(both["bound"], same["bound"])


def test_per_motor_model_inputs(tmp_path):
    assert ErrorModel(encoder_counts=[16384, 4096]).encoder_counts == (16384.0, 4096.0)
    assert acc.parse_error_model("encoder_counts=16384/4096,backlash_um=2") == \
        ErrorModel(encoder_counts=(16384, 4096), backlash_um=2)
    p = tmp_path / "m.json"
    p.write_text(json.dumps({"resolution_um": [1, 2]}))
    assert acc.load_error_model(p).resolution_um == (1.0, 2.0)
    for bad in ({"encoder_counts": [1, 2, 3]}, {"backlash_arcmin": [1, -1]}, {"encoder_counts": "16384/x"}):
        with pytest.raises(ValueError, match="encoder_counts|backlash_arcmin"):
            ErrorModel.from_dict(bad)
    # a slider's per-motor resolution: the biglide's columns scale with each motor's count
    from mechopt.mechanisms.biglide import Biglide

    bg = Biglide(40.0, 160.0, -400.0, 400.0)
    one = acc.pose_error(bg, ErrorModel(resolution_um=(2.0, 0.0)), [0.0], [-150.0])["x"]
    two = acc.pose_error(bg, ErrorModel(resolution_um=(4.0, 0.0)), [0.0], [-150.0])["x"]
    np.testing.assert_allclose(two, 2 * one, rtol=1e-12)
    assert one[0] > 0


def test_encoder_option_sets_the_model():
    """``encoder`` alone is an error model (encoder resolution only); with an
    ``error_model`` it replaces its encoder_counts; refused for sliders and when <= 0."""
    from mechopt.requirements.accuracy import model_of
    from mechopt.analysis.design_eval import DesignEvaluator

    v = DESIGNS[0]
    ev_a, a = _evaluate(v, model=None, encoder=16384)
    ev_b, b = _evaluate(v, model={"encoder_counts": 16384})
    assert a["values"]["error_um"] == b["values"]["error_um"]
    assert model_of(ev_a.req) == ErrorModel(encoder_counts=16384)
    ev_c, _ = _evaluate(v, model={"encoder_counts": 1024, "clearance_um": 5}, encoder="16384,4096")
    assert model_of(ev_c.req) == ErrorModel(encoder_counts=(16384, 4096), clearance_um=5)
    with pytest.raises(ValueError, match="counts per revolution"):
        DesignEvaluator("biglide", TASK, Requirements(max_error=50, encoder=16384), ("size",))
    with pytest.raises(ValueError, match="encoder"):
        DesignEvaluator("five-bar", TASK, Requirements(max_error=50, encoder=-1), ("size",))
    with pytest.raises(ValueError, match="error_model .*or encoder"):
        DesignEvaluator("five-bar", TASK, Requirements(max_error=50), ("size",))
