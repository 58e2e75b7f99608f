"""``--actuator``: a motor's datasheet (rated and peak torque, max speed, gear ratio,
rotor inertia) read inline or from a JSON/TOML file, turned into the output-side
limits of ``mechopt design`` and into the reflected rotor inertia of the motion
requirement's dynamics."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

from mechopt import mechanisms
from mechopt.analysis import dynamics as dyn
from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.core import motion as mo
from mechopt.core.actuators import Motor, read_motors
from mechopt.requirements import Requirements

SPEC = "rated_torque=0.32Nm,peak_torque=0.95,max_speed=3000rpm,gear_ratio=10,rotor_inertia=45gcm^2"
FIVE_BAR = mechanisms.design_spec("five-bar")


def test_inline_json_and_toml_read_alike(tmp_path):
    """The same two motors inline (``;``), in JSON and in TOML; units converted to SI
    (3000 rpm = 100 pi rad/s, 45 g cm^2 = 4.5e-6 kg m^2)."""
    one = dict(rated_torque=0.32, peak_torque=0.95, max_speed=100 * math.pi, gear_ratio=10.0, rotor_inertia=4.5e-6)
    two = dict(rated_torque=1.2, peak_torque=3.5, max_speed=200.0, gear_ratio=5.0, rotor_inertia=0.0)
    (tmp_path / "m.json").write_text(json.dumps({"motor": [one, two]}))
    (tmp_path / "m.toml").write_text(
        '[[motor]]\nrated_torque = "0.32Nm"\npeak_torque = 0.95\nmax_speed = "3000rpm"\ngear_ratio = 10\n'
        'rotor_inertia = "45gcm^2"\n[[motor]]\nrated_torque = 1.2\npeak_torque = 3.5\nmax_speed = 200\n'
        'gear_ratio = 5\n')
    inline = read_motors(SPEC + ";rated_torque=1.2,peak_torque=3.5,max_speed=200,gear_ratio=5")
    got = [inline, read_motors(str(tmp_path / "m.json"))]
    try:
        import tomllib  # noqa: F401  (Python >= 3.11)
        got.append(read_motors(str(tmp_path / "m.toml")))
    except ImportError:
        with pytest.raises(ValueError, match="TOML needs Python >= 3.11"):
            read_motors(str(tmp_path / "m.toml"))
    for motors in got:
        for m, want in zip(motors, (one, two)):
            for k, v in want.items():
                assert getattr(m, k) == pytest.approx(v, rel=1e-12, abs=1e-18)
    assert read_motors(SPEC)[0] == read_motors(SPEC)[1]  # one spec for both actuators


def test_output_side_limits_follow_the_gear():
    """At the output: torque x N, speed / N; the checked requirements take the rated
    torque for the force guarantee and, with a cycle time, the peak and rated torque for
    the motion's peak and RMS limits; a value given explicitly wins."""
    req = Requirements(min_force=10.0, actuator=SPEC + ";rated_torque=1.2,peak_torque=3.5,max_speed=200,gear_ratio=5")
    c = req.checked(FIVE_BAR, "mm")
    assert c.actuator_speed == pytest.approx((10 * math.pi, 40.0), rel=1e-12)
    assert c.actuator_torque == pytest.approx((3.2, 6.0), rel=1e-12)
    assert c.max_torque is None and c.max_rms_torque is None  # no cycle: no motion limits
    t = Requirements(actuator=SPEC, cycle_time=0.5, max_torque=5.0).checked(FIVE_BAR, "mm")
    assert t.max_torque == 5.0 and t.max_rms_torque == pytest.approx(3.2, rel=1e-12)
    assert t.actuator_speed == pytest.approx(10 * math.pi, rel=1e-12)
    # a slider: the ratio in rad/m (a 10 mm lead screw: 2 pi / 0.01), speeds in the task's unit
    biglide = mechanisms.design_spec("biglide")
    s = Requirements(min_speed=1.0, actuator=f"rated_torque=0.3,peak_torque=0.9,max_speed=3000rpm,"
                                             f"gear_ratio={2 * math.pi / 0.01}").checked(biglide, "mm")
    assert s.actuator_speed == pytest.approx(500.0, rel=1e-12)  # 50 rev/s x 10 mm
    assert s.actuator_torque == pytest.approx(0.3 * 2 * math.pi / 0.01, rel=1e-12)


@pytest.mark.parametrize("text, message", [
    ("rated_torque=1,peak_torque=0.5,max_speed=3", "peak_torque 0.5 is below its rated_torque 1"),
    ("rated_torque=1,peak=2,max_speed=3", "unknown key 'peak'"),
    ("rated_torque=-1,peak_torque=2,max_speed=3", "rated_torque must be a positive finite number"),
    ("rated_torque=1,peak_torque=2,max_speed=3kg", "unknown unit 'kg' for max_speed"),
    ("rated_torque=1,peak_torque=2", "max_speed is missing"),
    ("rated_torque=1,peak_torque=2,max_speed=nan", "max_speed"),
    ("nowhere.json", "no such file"),
])
def test_bad_specs_are_one_line(text, message):
    with pytest.raises(ValueError, match=message) as exc:
        read_motors(text)
    assert "\n" not in str(exc.value)


def test_bad_files_and_the_command_line(tmp_path, capsys):
    """A malformed JSON, a folder, three motors: one line; from the command line exit 2
    and nothing written."""
    (tmp_path / "bad.json").write_text("{not json")
    (tmp_path / "dir.json").mkdir()
    (tmp_path / "three.json").write_text(json.dumps([{"rated_torque": 1, "peak_torque": 2, "max_speed": 3}] * 3))
    for name, message in (("bad.json", "is not valid"), ("dir.json", "is a folder"), ("three.json", "got 3")):
        with pytest.raises(ValueError, match=message):
            read_motors(str(tmp_path / name))
    out = tmp_path / "never"
    code = main(["design", "five-bar", "--task", "rect:300,200@0,250", "--min-speed", "0.5m/s", "--actuator",
                 str(tmp_path / "bad.json"), "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and not out.exists() and "is not valid" in err[-1]


def test_reflected_rotor_inertia_enters_the_cycle_efforts():
    """The peak effort along the pick-and-place cycle with a geared motor equals the
    effort without rotors plus ``I_r N^2 q_ddot_i``, the actuators' accelerations taken
    here by central differences of the inverse kinematics on a 200 times finer timing
    (independent of the dynamics code's rotor term); the RMS limit is the rated torque
    x N, per actuator."""
    task = Task.rect(300, 200, (0, 300))
    design = dict(r1=250.0, r2=300.0, r3=50.0, mode="+-", task_x=0.0, task_y=300.0)
    motor = Motor(rated_torque=0.32, peak_torque=0.95, max_speed=300.0, gear_ratio=20.0, rotor_inertia=2e-5)
    ev = DesignEvaluator("five-bar", task, Requirements(cycle_time=0.5, actuator=motor), ("size", "peak-torque"),
                         max_length=1000)
    res = ev.evaluate(design)
    mech = res["mechanism"]
    # the effort without rotors, from the dynamics along the same cycle
    from mechopt.requirements.motion import SAMPLES

    path = mo.pick_and_place_path(task.bbox, task.contains)
    m = mo.timed_motion(path, 0.5, "cycloidal", SAMPLES)
    base = dyn.inverse_dynamics(mech, m, dyn.mass_model(mech, length_unit=1e-3), None, 1e-3)["tau"]
    k = 200
    fine = mo.timed_motion(path, 0.5, "cycloidal", k * (SAMPLES - 1) + 1)
    q = np.unwrap(np.stack(mech.ik(fine["x"], fine["y"])[:2], -1), axis=0)
    h = fine["t"][1] - fine["t"][0]
    qdd = np.empty_like(q)
    qdd[1:-1] = (q[2:] - 2 * q[1:-1] + q[:-2]) / h ** 2
    qdd[0], qdd[-1] = qdd[1], qdd[-2]  # the cycle starts and ends at rest
    tau = base + motor.rotor_inertia * motor.gear_ratio ** 2 * qdd[::k]
    assert res["objectives"]["peak-torque"] == pytest.approx(np.max(np.abs(tau)), rel=1e-3)
    assert res["objectives"]["peak-torque"] > np.max(np.abs(base)) * 1.01  # the rotors matter here
    # the motion limits from the datasheet, per actuator: peak 0.95 x 20, RMS 0.32 x 20 N m
    rms = np.sqrt(np.trapezoid(tau ** 2, m["t"], axis=0) / 0.5)
    assert res["margin"]["peak_torque"] == pytest.approx(19.0 - np.max(np.abs(tau)), rel=1e-3)
    assert res["margin"]["rms_torque"] == pytest.approx(6.4 - np.max(rms), rel=1e-3)


def test_a_datasheet_survives_run_json(tmp_path):
    """The requirements are written into run.json and design.json (``settings``): the
    motors as the lists of their five values, read back into the same requirements."""
    from mechopt.run.io import write_json

    ev = DesignEvaluator("five-bar", Task.rect(300, 200, (0, 300)),
                         Requirements(min_speed=100.0, actuator=SPEC, cycle_time=0.5), ("size",), max_length=1000)
    write_json(ev.settings(), tmp_path / "run.json")
    back = json.loads((tmp_path / "run.json").read_text())["requirements"]
    assert back["actuator"][0] == [0.32, 0.95, pytest.approx(100 * math.pi), 10.0, pytest.approx(4.5e-6)]
    assert Requirements(**back).checked(FIVE_BAR, "mm") == ev.req


def test_motion_command_takes_the_datasheet(tmp_path, capsys):
    """``mechopt motion DIR --actuator SPEC``: the efforts grow by ``I_r N^2 q_ddot_i`` (the
    table's own accelerations) and the limits checked are peak x N and rated x N; a bad
    spec is one line and exit 2."""
    import csv

    from test_motion import _design_dir

    d = _design_dir(tmp_path / "d")
    runs = {}
    for name, extra in (("plain", []), ("geared", ["--actuator", SPEC])):
        out = tmp_path / name
        assert main(["motion", str(d), "--cycle-time", "0.5", "--samples", "101", "--out", str(out)] + extra) == 0
        rows = list(csv.DictReader(open(out / "motion.csv")))
        runs[name] = ({k: np.array([float(r[k]) for r in rows]) for k in rows[0]},
                      json.loads((out / "motion.json").read_text()))
    (a, _), (b, summary) = runs["plain"], runs["geared"]
    for i in (1, 2):
        # motion.csv holds about 9 significant digits: 1e-8 N m of the 0.04 N m rotor term
        np.testing.assert_allclose(b[f"tau_{i}"] - a[f"tau_{i}"], 4.5e-6 * 100 * b[f"qdd_{i}"], rtol=1e-6, atol=1e-8)
        assert np.abs(b[f"tau_{i}"] - a[f"tau_{i}"]).max() > 0.01
    assert summary["limits"]["max_torque"] == pytest.approx([9.5, 9.5])
    assert summary["limits"]["rms_limit"] == pytest.approx([3.2, 3.2])
    assert summary["limits"]["max_speed"] == pytest.approx([10 * math.pi] * 2)
    capsys.readouterr()
    assert main(["motion", str(d), "--actuator", "rated_torque=1", "--out", str(tmp_path / "bad")]) == 2
    assert "peak_torque is missing" in capsys.readouterr().err and not (tmp_path / "bad").exists()
