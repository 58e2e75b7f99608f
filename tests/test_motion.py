"""Timed motions (profiles, paths) and ``mechopt motion`` on a design folder."""
from __future__ import annotations

import csv
import json
import numpy as np
import pytest

from mechopt import FiveBar
from mechopt.cli import main
from mechopt.analysis.dynamics import mass_model, motion_efforts, peak_torque, rms_torque
from mechopt.core import motion as mo
from mechopt.mechanisms.gantry import wu2008_gantry
from mechopt.mechanisms.gantry_dynamics import wu2008_driving_forces


@pytest.mark.parametrize("kind", mo.PROFILES)
def test_profiles_are_rest_to_rest_and_consistent(kind):
    tau = np.linspace(0.0, 1.0, 20001)
    s, sd, sdd = mo.profile(kind, tau, accel_fraction=0.3, jerk_fraction=0.2)
    assert s[0] == 0.0 and s[-1] == pytest.approx(1.0, abs=1e-14)
    assert abs(sd[0]) < 1e-14 and abs(sd[-1]) < 1e-12
    # s' integrates to s and s'' to s' (trapezoidal rule, independent of the phases)
    S = np.concatenate([[0], np.cumsum(0.5 * (sd[1:] + sd[:-1]) * np.diff(tau))])
    V = np.concatenate([[0], np.cumsum(0.5 * (sdd[1:] + sdd[:-1]) * np.diff(tau))])
    assert np.max(np.abs(S - s)) < 1e-7
    # (the trapezoid's acceleration jumps: the rule errs by half a step times the jump there)
    assert np.max(np.abs(V - sd)) < (3e-4 if kind == "trapezoidal" else 1e-6)
    peaks = {"cycloidal": (2.0, 2 * np.pi), "trapezoidal": (1 / 0.7, 1 / (0.3 * 0.7)),
             "s-curve": (1 / 0.7, 1 / (0.7 * 0.3 * 0.8))}[kind]
    assert np.max(sd) == pytest.approx(peaks[0], rel=1e-6)
    assert np.max(np.abs(sdd)) == pytest.approx(peaks[1], rel=1e-6)


def test_pick_and_place_cycle_scaled_to_the_task():
    m = mo.timed_motion(mo.pick_and_place_path((-150.0, 150.0, 200.0, 300.0)), 0.5, "cycloidal", 1001)
    s = 300.0 / 305.0
    assert (m["x"][0], m["x"][-1]) == (-150.0, 150.0)
    assert m["y"][0] == pytest.approx(250.0 - 12.5 * s) and m["y"].max() == pytest.approx(250.0 + 12.5 * s)
    assert m["t"][-1] == 0.5
    # rest at the start, the corners and the end
    assert np.all(np.hypot(m["xd"], m["yd"])[[0, -1]] < 1e-9)
    # the across piece: durations proportional to sqrt(length)
    across = m["piece"] == 1
    frac = np.sqrt(305.0) / (2 * np.sqrt(25.0) + np.sqrt(305.0))
    assert np.ptp(m["t"][across]) == pytest.approx(0.5 * frac, abs=1e-3)
    # speeds and accelerations are the derivatives of the positions
    fine = mo.timed_motion(mo.pick_and_place_path((-150.0, 150.0, 200.0, 300.0)), 0.5, "cycloidal", 20001)
    for p, v in (("x", "xd"), ("y", "yd"), ("xd", "xdd"), ("yd", "ydd")):
        num, m = np.gradient(fine[p], fine["t"]), fine
        assert np.max(np.abs(num - m[v])[1:-1]) < 5e-3 * np.max(np.abs(m[v]))  # jerk jumps at corners


def test_spline_path_from_csv(tmp_path):
    f = tmp_path / "p.csv"
    f.write_text("x,y\n0,0\n10,5\n20,0\n30,5\n")
    pts = mo.read_path_csv(f)
    m = mo.timed_motion(mo.polyline_path(pts), 1.0, "trapezoidal", 401)
    assert (m["x"][0], m["y"][0], m["x"][-1], m["y"][-1]) == (0.0, 0.0, 30.0, 5.0)
    for bad, match in (("x,z\n1,2\n", "needs numeric columns x and y"), ("x,y\n1,2\n", "at least two points")):
        f.write_text(bad)
        with pytest.raises(ValueError, match=match):
            mo.read_path_csv(f)


def test_bad_motion_inputs():
    path = mo.segment_path((0, 0), (1, 0))
    with pytest.raises(ValueError, match="^cycle_time must be > 0"):
        mo.timed_motion(path, 0.0)
    with pytest.raises(ValueError, match="^profile must be"):
        mo.timed_motion(path, 1.0, "bang")
    fb = FiveBar(0.25, 0.35, 0.1)
    m = mo.timed_motion(mo.segment_path((0.0, 0.3), (0.0, 0.9)), 1.0)
    with pytest.raises(ValueError, match="^the motion leaves the reachable workspace at t = "):
        motion_efforts(fb, m, mass_model(fb))


def test_wu_table3_forces_through_the_generic_dynamics():
    g = wu2008_gantry(10.0, unit="m")
    ref = wu2008_driving_forces(g)
    model = mass_model(g)  # the gantry's default: Wu's Table 2
    assert model.source == "wu2008-table2" and model.g == 9.8
    tab, summ = motion_efforts(g, ref, model)
    scale = np.max(np.abs(ref["F1"]))
    assert np.max(np.abs(tab["tau_1"] - ref["F1"])) < 1e-9 * scale
    assert np.max(np.abs(tab["tau_2"] - ref["F2"])) < 1e-9 * scale
    assert peak_torque(g, ref, model) == pytest.approx([np.max(np.abs(ref["F1"])), np.max(np.abs(ref["F2"]))])
    rms = rms_torque(g, ref, model)
    assert rms[0] == pytest.approx(np.sqrt(np.trapezoid(ref["F1"] ** 2, ref["t"]) / ref["t"][-1]))


def _design_dir(tmp, name="five-bar", variables=None, strokes=None):
    tmp.mkdir(exist_ok=True)
    variables = variables or {"r1": 200.0, "r2": 300.0, "r3": 80.0, "mode": "+-"}
    rec = {"mechanism_name": name, "unit": "mm", "variables": variables,
           "task_placement": {"task_x": 0.0, "task_y": 300.0}}
    if strokes:
        rec["strokes"] = strokes
    (tmp / "design.json").write_text(json.dumps(rec))
    (tmp / "run.json").write_text(json.dumps({"design": {"task": {
        "kind": "rect", "unit": "mm", "vertices": [[-150, -100], [150, -100], [150, 100], [-150, 100]]}}}))
    return tmp


def _cli(capsys, *args):
    code = main(list(args))
    out = capsys.readouterr()
    return code, out.out, out.err


def test_motion_command_writes_its_files(tmp_path, capsys):
    d = _design_dir(tmp_path / "d")
    code, out, err = _cli(capsys, "motion", str(d), "--cycle-time", "0.5", "--max-torque", "8", "--max-speed", "30",
             "--gravity", "off", "--samples", "201")
    assert code == 0, err
    assert out.count("\n") == 1 and "actuator 1: peak" in out
    rows = list(csv.DictReader(open(d / "motion.csv")))
    assert len(rows) == 201
    assert list(rows[0]) == ["t", "x", "y", "q_1", "q_2", "qd_1", "qd_2", "qdd_1", "qdd_2",
                             "tau_1", "tau_2", "power_1", "power_2"]
    bodies = json.load(open(d / "bodies.json"))
    names = {b["name"] for b in bodies["bodies"]}
    assert {"crank1", "distal1", "crank2", "distal2", "payload", "motor1", "motor2"} == names
    summ = json.load(open(d / "motion.json"))
    tau = np.array([[float(r["tau_1"]), float(r["tau_2"])] for r in rows])
    assert np.allclose(summ["tau_peak"], np.max(np.abs(tau), 0), rtol=1e-8)
    assert summ["within_limits"] == bool(np.all(np.max(np.abs(tau), 0) <= 8.0)
                                         and max(summ["qd_peak"]) <= 30.0)
    assert (d / "motion.png").stat().st_size > 10000


@pytest.mark.parametrize("args, match", [
    (("--cycle-time", "0"), "cycle_time must be > 0"),
    (("--masses", "MASSES"), "mass of body crank1 must be >= 0"),
    (("--masses", "MATERIAL"), "material must be one of"),
    (("--path", "segment:0,300,0,900"), "the motion leaves the reachable workspace"),
    (("--profile", "bang"), "profile must be one of"),
])
def test_motion_command_bad_input(tmp_path, capsys, args, match):
    d = _design_dir(tmp_path / "d")
    (tmp_path / "m.json").write_text(json.dumps({"bodies": {"crank1": {"mass": -1.0}}}))
    (tmp_path / "mat.json").write_text(json.dumps({"law": {"material": "unobtainium"}}))
    args = [str(tmp_path / "m.json") if a == "MASSES" else str(tmp_path / "mat.json") if a == "MATERIAL"
            else a for a in args]
    code, _, err = _cli(capsys, "motion", str(d), *args)
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and match in lines[0], err
    assert not (d / "motion.csv").exists()


def test_motion_outputs_are_documented(tmp_path, capsys):
    """Every column of motion.csv and key of motion.json / bodies.json is on docs/outputs.md."""
    from pathlib import Path

    page = (Path(__file__).resolve().parents[1] / "docs" / "outputs.md").read_text()
    d = _design_dir(tmp_path / "d")
    assert _cli(capsys, "motion", str(d), "--samples", "11")[0] == 0
    names = set(next(csv.reader(open(d / "motion.csv"))))

    def keys(v):
        if isinstance(v, dict):
            return set(v) | set().union(*(keys(x) for x in v.values()))
        if isinstance(v, list):
            return set().union(set(), *(keys(x) for x in v))
        return set()
    names |= keys(json.load(open(d / "motion.json"))) | keys(json.load(open(d / "bodies.json")))
    missing = sorted(n for n in names if f"`{n}`" not in page)
    assert not missing, missing


@pytest.mark.parametrize("limit", [1.0, 5.0])
def test_torque_requirements_and_objectives_of_mechopt_design(limit):
    """--max-torque/--max-rms-torque with --cycle-time: the margins and objectives are the
    extremes of the inverse dynamics along the task's pick-and-place cycle."""
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.task import Task
    from mechopt.requirements import Requirements
    from mechopt.requirements.motion import SAMPLES

    task = Task.rect(300, 200, (0, 250))
    req = Requirements(max_torque=limit, max_rms_torque=limit, cycle_time=0.5)
    ev = DesignEvaluator("five-bar", task, req, ("size", "peak-torque", "rms-torque", "moving-mass"),
                         max_length=600)
    v = dict(r1=200.0, r2=300.0, r3=80.0, mode="+-", task_x=0.0, task_y=250.0)
    res = ev.evaluate(v)
    fb = FiveBar(200.0, 300.0, 80.0)
    model = mass_model(fb, length_unit=1e-3)
    m = mo.timed_motion(mo.pick_and_place_path((-150, 150, 150, 350)), 0.5, "cycloidal", SAMPLES)
    _, s = motion_efforts(fb, m, model, length_unit=1e-3)
    peak, rms = max(s["tau_peak"]), max(s["tau_rms"])
    assert res["margin"]["peak_torque"] == pytest.approx(limit - peak, rel=1e-12)
    assert res["margin"]["rms_torque"] == pytest.approx(limit - rms, rel=1e-12)
    assert (res["g"]["peak_torque"] > 0) == (peak > limit)
    obj = dict(zip(ev.objectives, ev.objective_values(res)))
    assert obj["peak-torque"] == pytest.approx(peak) and obj["rms-torque"] == pytest.approx(rms)
    assert obj["moving-mass"] == pytest.approx(model.moving_mass)
    # the moving mass of the law: four tubes of 0.3888 kg/m and the 0.2 kg payload
    assert model.moving_mass == pytest.approx(2700 * 1.44e-4 * 2 * 0.5 + 0.2, rel=1e-12)


def test_pick_and_place_cycle_shrinks_into_a_circle_task():
    inside = lambda x, y: np.hypot(x, y - 200.0) <= 100.0  # noqa: E731
    path = mo.pick_and_place_path((-100.0, 100.0, 100.0, 300.0), inside)
    corners = np.array([p.p0 for p in path] + [path[-1].p1])
    assert np.all(inside(corners[:, 0], corners[:, 1]))
    # the largest of the 0.95^k steps: one step more would leave the circle
    half = corners[2, 0]
    assert not np.all(inside(np.array([half / 0.95]), np.array([200.0 + 12.5 / 152.5 * half / 0.95])))
