"""A trajectory as a path (the polyline through its points, every point of it), not only
its way-points: ``Task.path`` / ``--task path:FILE.csv``."""
from __future__ import annotations

import json

import numpy as np
import pytest

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import Task, parse_task
from mechopt.mechanisms.five_bar import FiveBar
from mechopt.requirements import Requirements
from mechopt.workflows.design import design

#: a five-bar whose holes |P - A_i| < r1 - r2 = 40 mm sit about the base: the straight cut
#: between two reachable way-points passes through them
HOLED = dict(r1=100.0, r2=60.0, r3=10.0, mode="+-")
CUT = [[-60.0, 10.0], [60.0, 10.0]]


def _evaluate(task):
    ev = DesignEvaluator("five-bar", task, Requirements(), ("size",), max_length=300)
    x, y = task.reference
    return ev.evaluate({**HOLED, "task_x": x, "task_y": y})


def test_a_cut_through_a_hole_passes_as_points_and_fails_as_a_path():
    fb = FiveBar(**HOLED)
    _, _, ok = fb.ik(np.array([-60.0, 0.0, 60.0]), np.array([10.0, 10.0, 10.0]))
    assert list(ok) == [True, False, True]  # the way-points reachable, the middle not
    points = _evaluate(Task.points(CUT))
    path = _evaluate(Task.path(CUT))
    assert points["g"]["reach"] <= 0  # checked at the points alone: it holds there
    assert path["g"]["reach"] > 0 and path["margin"]["reach"] < -20.0  # 30 mm deep into the hole


def test_path_samples_run_along_the_polyline():
    t = Task.path([[0.0, 0.0], [30.0, 0.0], [30.0, 40.0]])
    assert t.perimeter == pytest.approx(70.0) and t.area == 0.0 and not t.is_region and t.is_path
    s, gap = t.boundary_params(70)
    x, y = t.boundary_at(s)
    assert (x[0], y[0]) == (0.0, 0.0) and (x[-1], y[-1]) == (30.0, 40.0)
    assert gap <= 1.0 + 1e-12
    assert np.all(np.minimum(np.abs(y), np.abs(x - 30.0)) < 1e-12)  # on one of the two segments
    d = np.hypot(np.diff(x), np.diff(y))
    assert d.max() <= gap * (1 + 1e-12)
    moved = t.moved_to(0.0, 100.0)
    assert moved.is_path and moved.reference == pytest.approx((0.0, 100.0))
    assert Task.from_dict(t.to_dict()).pts.tolist() == t.pts.tolist()


def test_a_path_design_holds_along_every_segment(tmp_path):
    """A designed five-bar for an L-shaped path: on 10 000 points per segment it reaches
    every point in one type-II sign with LCI >= 0.3 (to the zoom's resolution)."""
    csv = tmp_path / "path.csv"
    csv.write_text("x,y\n-30,140\n30,140\n30,180\n")
    task = parse_task(f"path:{csv}")
    res = design("five-bar", task, Requirements(min_lci=0.3), ("size",), max_length=200, pop=12, gen=8, n_jobs=1,
                 polish=False, out=tmp_path / "run")
    rec = json.loads((tmp_path / "run" / "design.json").read_text())
    assert "path_gap" in rec["tolerance"] and rec["feasible"]
    v = rec["variables"]
    fb = FiveBar(r1=v["r1"], r2=v["r2"], r3=v["r3"], mode=v["mode"])
    dx = rec["task_placement"]["task_x"] - task.reference[0]
    dy = rec["task_placement"]["task_y"] - task.reference[1]
    s = np.linspace(0.0, 1.0, 10_000)
    for (x0, y0), (x1, y1) in zip(task.pts[:-1], task.pts[1:]):
        x, y = x0 + dx + s * (x1 - x0), y0 + dy + s * (y1 - y0)
        _, _, ok = fb.ik(x, y)
        assert ok.all()
        f = fb.type2_function(x, y)
        assert np.all(np.sign(f) == np.sign(f[0])) and np.abs(f).min() > 1e-3
        assert fb.lci(x, y).min() >= 0.3 - 1e-6
    assert len(res.front) >= 1


def test_a_point_task_says_it_is_checked_at_its_points_only():
    ev = DesignEvaluator("five-bar", Task.points(CUT), Requirements(), ("size",), max_length=300)
    res = certify(ev, {**HOLED, "task_x": 0.0, "task_y": 10.0})
    assert "only there" in res["tolerance"]["points"] and "path:" in res["tolerance"]["points"]
