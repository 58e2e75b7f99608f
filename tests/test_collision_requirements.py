"""The collision requirements of ``mechopt design`` (``mechopt.requirements.collisions``).

Independent checks: the base width by arithmetic (``2 r3 - d - c``), a keep-out margin
by hand, the joint angles by the law of cosines, and the clearance of every front design
of a design run over a 201 x 201 grid of its task with a segment distance written in
``tests/test_collisions.py`` (Ericson's closest points), with shapely capsules where the
clearance is smallest.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
import shapely

from mechopt.analysis.collisions import Collisions, task_samples
from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.core.bodies import Shapes
from mechopt.mechanisms import design_spec
from mechopt.requirements import Requirements
from test_collisions import _grid, ends, ericson_distance

TASK = Task.rect(200, 120, (0, 230))
DESIGN = dict(r1=150.0, r2=250.0, r3=60.0, mode="+-", task_x=0.0, task_y=230.0)


def _evaluate(objectives=("size",), **req):
    ev = DesignEvaluator("five-bar", TASK, Requirements(**req), objectives, mode="+-", place="fixed",
                         max_length=2000.0)
    return ev.evaluate(DESIGN)


def _independent_minimum(spec, mech, task, shapes, n=201):
    """The smallest capsule clearance over an n x n grid of the task (Ericson's distance)."""
    col = Collisions(spec, mech, shapes)
    x, y = _grid(task, n)
    b = col.bodies(x, y)
    c = np.stack([ericson_distance(*ends(b[i]), *ends(b[j])) - 0.5 * (b[i].width + b[j].width) for i, j in col.pairs])
    k = np.unravel_index(np.nanargmin(c), c.shape)
    return float(c[k]), col.pairs[k[0]], (x[k[1]], y[k[1]]), b


def test_base_margin_is_the_base_width_less_the_housings():
    r = _evaluate(min_base=100.0, motor_diameter=50.0, min_clearance=5.0)
    assert r["margin"]["base"] == pytest.approx(min(120 - 100, 120 - 50 - 5), abs=1e-12)
    assert r["g"]["base"] == pytest.approx(-20 / TASK.diameter)
    r = _evaluate(motor_diameter=130.0)  # 2 r3 = 120 < 130: the housings overlap
    assert r["margin"]["base"] == pytest.approx(-10.0, abs=1e-12) and r["g"]["base"] > 0


def test_clearance_margin_against_the_samples_and_a_dense_grid():
    C = 5.0
    r = _evaluate(("size", "clearance"), min_clearance=C)
    spec = design_spec("five-bar")
    mech = r["mechanism"]
    shapes = Shapes.default("mm")
    x, y, _ = task_samples(TASK)
    sampled = float(np.min(Collisions(spec, mech, shapes).clearance(x, y)))
    dense, _, _, _ = _independent_minimum(spec, mech, TASK, shapes)
    m = r["margin"]["clearance"] + C
    assert m == r["objectives"]["clearance"] == r["values"]["clearance_min"]
    assert m <= sampled + 1e-12  # refined from the samples
    assert abs(m - dense) <= 1e-6 * TASK.diameter  # here the minimum is at a corner of the task
    assert r["values"]["clearance_bound"] <= dense


def test_keep_out_and_joint_angle_margins():
    r = _evaluate(keep_out="below:-40", min_joint_angle=math.radians(20))
    x, y = _grid(TASK, 121)
    mech = r["mechanism"]
    t1, t2, _ = mech.ik(x, y)
    # the lowest body: a 60 mm housing about y = 0 (30 mm down) or a 20 mm wide crank
    # whose elbow dips below the base (its lowest point 10 mm under the elbow)
    lowest = min(-30.0, float(np.min(150 * np.sin(np.r_[t1, t2]))) - 10.0)
    assert r["margin"]["keep_out"] == pytest.approx(lowest + 40, abs=1e-3)
    assert r["values"]["keep_out_bound"] <= lowest + 40
    angles = []
    for ax, th in ((-60.0, t1), (60.0, t2)):  # at the elbows, by the law of cosines
        d2 = (x - ax) ** 2 + y ** 2
        angles.append(np.arccos((150 ** 2 + 250 ** 2 - d2) / (2 * 150 * 250)))
    b1 = np.array([-60 + 150 * np.cos(t1), 150 * np.sin(t1)])
    b2 = np.array([60 + 150 * np.cos(t2), 150 * np.sin(t2)])
    u, v = b1 - np.array([x, y]), b2 - np.array([x, y])  # at the tool, between the distal links
    angles.append(np.arccos(np.sum(u * v, 0) / 250 ** 2))
    dense = float(np.min(angles))
    assert r["margin"]["joint_angle"] + math.radians(20) == pytest.approx(dense, abs=1e-3)
    assert r["values"]["joint_angle_bound"] <= dense


def test_bad_collision_options_are_one_line(capsys, tmp_path):
    for args, msg in ((["--keep-out", "left:3"], "--keep-out must be task"),
                      (["--min-joint-angle", "200"], "min_joint_angle must lie in (0, pi)"),
                      (["--link-width", "-1"], "link_width")):
        assert main(["design", "five-bar", "--task", "rect:100,60@0,250", "--out", str(tmp_path / "x"), *args]) == 2
        err = capsys.readouterr().err
        assert msg in err and err.count("\n") == 1
    assert not (tmp_path / "x").exists()


def test_a_design_run_with_a_base_width_and_a_clearance(tmp_path):
    """Every front design of a run keeps 2 r3 >= 50 + 5 and its capsules 5 mm apart over a
    201 x 201 grid of the task (independent distance; shapely where closest)."""
    out = tmp_path / "run"
    main(["design", "five-bar", "--task", "rect:100,60@0,250", "--min-base", "60", "--motor-diameter", "50",
          "--min-clearance", "5", "--objectives", "size,clearance", "--pop", "10", "--gen", "3", "--no-polish",
          "--out", str(out)])
    front = pd.read_csv(out / "front.csv")
    assert len(front) >= 1 and {"margin_clearance", "margin_base", "clearance"} <= set(front.columns)
    spec, task = design_spec("five-bar"), Task.rect(100, 60, (0, 250))
    shapes = Shapes.default("mm", housing_diameter=50.0)
    for row in front.itertuples():
        assert 2 * row.r3 >= 60 - 1e-9 and 2 * row.r3 >= 55 - 1e-9
        assert row.margin_base == pytest.approx(min(2 * row.r3 - 60, 2 * row.r3 - 55), abs=1e-5)
        mech = spec.build(dict(r1=row.r1, r2=row.r2, r3=row.r3), row.mode)
        dense, (i, j), (px, py), bodies = _independent_minimum(spec, mech, task.moved_to(row.task_x, row.task_y),
                                                               shapes)
        assert dense >= 5 - 1e-6 * task.diameter  # no intersection, the clearance held
        assert abs(row.clearance - dense) <= 1e-5 * task.diameter
        # shapely's capsules (polygons inscribed in them) at the closest pose: apart
        at = Collisions(spec, mech, shapes).bodies(np.array([px]), np.array([py]))
        caps = [shapely.buffer(shapely.LineString([(b.x0[0], b.y0[0]), (b.x1[0], b.y1[0])])
                               if (b.x0[0], b.y0[0]) != (b.x1[0], b.y1[0]) else shapely.Point(b.x0[0], b.y0[0]),
                               b.width / 2, quad_segs=32) for b in (at[i], at[j])]
        assert not caps[0].intersects(caps[1]) and caps[0].distance(caps[1]) >= 5 - 1e-6 * task.diameter
    record = json.loads((out / "design.json").read_text())
    assert record["values"]["clearance_bound"] <= record["values"]["clearance_min"]
