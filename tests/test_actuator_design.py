"""Per-actuator limits in ``mechopt design``: the default reading of ``--min-speed``,
``--min-force`` and the speed/force/torque objectives, checked against a brute-force
sweep of directions over the task; Liu's Euclidean budget by name (``--actuator-norm
2``); per-actuator values; the power bound of the precheck."""
from __future__ import annotations

import json

import numpy as np
import pytest

from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.requirements import Requirements

N_DIR = 3600
TASK = Task.rect(300, 200, (0, 250))
#: the design `mechopt design` chose for the designer's case (3 rad/s, 8 N m, 0.5 m/s,
#: 20 N, per-actuator limits), rounded: lengths [mm], the task's centre moved to y = 270.84
DESIGN = dict(r1=233.308, r2=200.416, r3=0.0, mode="+-", task_x=0.0, task_y=270.84)


def _task_grid(n=25, cx=0.0, cy=270.84, W=300.0, H=200.0):
    """Points covering the placed task (W x H mm about (cx, cy)): its boundary finely,
    its interior on a grid [mm]."""
    s = np.linspace(0.0, 1.0, 4 * n)
    x0, x1, y0, y1 = cx - W / 2, cx + W / 2, cy - H / 2, cy + H / 2
    bx = np.concatenate([x0 + W * s, np.full_like(s, x1), x1 - W * s, np.full_like(s, x0)])
    by = np.concatenate([np.full_like(s, y0), y0 + H * s, np.full_like(s, y1), y1 - H * s])
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    return np.concatenate([bx, gx.ravel()]), np.concatenate([by, gy.ravel()])


def _sweep(J, w, t):
    """Independent brute force over N_DIR directions u at each pose: the largest speed
    with every ``|q_dot_i| <= w_i`` and the largest force whose balancing efforts
    ``J^-T f u`` (solved by numpy) stay within ``t_i``; minima over directions and poses."""
    a = np.linspace(0.0, 2.0 * np.pi, N_DIR, endpoint=False)
    U = np.stack([np.cos(a), np.sin(a)])
    w, t = (np.broadcast_to(np.asarray(v, float), (2,))[None, :, None] for v in (w, t))
    qd = np.abs(np.einsum("pij,jn->pin", J, U))
    tau = np.abs(np.linalg.solve(np.swapaxes(J, 1, 2), np.broadcast_to(U, (len(J), 2, N_DIR))))
    with np.errstate(divide="ignore"):  # a zero rate or effort: no limit from that actuator
        return float(np.min(w / qd)), float(np.min(t / tau))


#: (mechanism, design, task box (cx, cy, W, H) [mm], N m -> N factor of the sweep):
#: the chosen five-bar (symmetric: its legs' row norms agree at every point), and a
#: Biglide on a task off its axis, whose two actuators' minima differ (the pairing of
#: each limit with its actuator shows)
CASES = {"five-bar": ("five-bar", DESIGN, (0.0, 270.84, 300.0, 200.0), 1e3),
         "biglide": ("biglide", dict(l1=20.697526493504693, l2=67.96359733903873, mode="--", task_x=15.0,
                                     task_y=100.0), (15.0, 100.0, 40.0, 30.0), 1.0)}


@pytest.mark.parametrize("case, w, t", [("five-bar", 3.0, 8.0), ("five-bar", (3.0, 2.5), (8.0, 6.0)),
                                        ("biglide", (2.5, 3.0), (6.0, 8.0)), ("biglide", (3.0, 2.5), (8.0, 6.0))])
def test_guaranteed_speed_and_force_match_a_direction_sweep_over_the_task(case, w, t):
    """The design's guaranteed speed [mm/s] and force [N] under per-actuator limits equal
    the brute-force minimum over the task and 3600 directions (the sweep's grid is a
    subset of the task and its directions a subset of the circle, so it can only be
    above: the refined value is below it and within 0.2 %)."""
    name, design, (cx, cy, W, H), per_newton = CASES[case]
    ev = DesignEvaluator(name, Task.rect(W, H, (cx, cy)), Requirements(
        min_speed=1.0, actuator_speed=w, min_force=1.0, actuator_torque=t), ("size",), max_length=1000)
    res = ev.evaluate(design)
    J = res["mechanism"].jacobian(*_task_grid(cx=cx, cy=cy, W=W, H=H))
    v_sweep, f_sweep = _sweep(J, w, t)
    f_sweep *= per_newton  # a crank's J in rad/mm: the sweep's force in N m/mm
    v, f = res["values"]["speed"], res["values"]["force"]
    assert v <= v_sweep * (1 + 1e-9) and v == pytest.approx(v_sweep, rel=2e-3)
    assert f <= f_sweep * (1 + 1e-9) and f == pytest.approx(f_sweep, rel=2e-3)
    # the margins are these values minus the requirements
    assert res["margin"]["speed"] == pytest.approx(v - 1.0) and res["margin"]["force"] == pytest.approx(f - 1.0)


def test_liu_reading_by_name_is_the_singular_values():
    """``actuator_norm=2``: ``w / max s_max(J)`` and ``t min s_min(J)`` (Liu 2006 eq. 10,
    13) by numpy's SVD on the grid; below the per-actuator values of the same design."""
    req = dict(min_speed=1.0, actuator_speed=3.0, min_force=1.0, actuator_torque=8.0)
    liu = DesignEvaluator("five-bar", TASK, Requirements(**req, actuator_norm=2), ("size",),
                          max_length=1000).evaluate(DESIGN)
    box = DesignEvaluator("five-bar", TASK, Requirements(**req), ("size",), max_length=1000).evaluate(DESIGN)
    s = np.linalg.svd(liu["mechanism"].jacobian(*_task_grid()), compute_uv=False)
    assert liu["values"]["speed"] == pytest.approx(3.0 / s[:, 0].max(), rel=2e-3)
    assert liu["values"]["force"] == pytest.approx(8e3 * s[:, 1].min(), rel=2e-3)
    assert box["values"]["speed"] > 1.1 * liu["values"]["speed"]
    assert box["values"]["force"] > 1.1 * liu["values"]["force"]


def test_the_power_bound_holds_per_actuator_and_is_attained():
    """Precheck of ``--min-speed`` with ``--min-force``: at every pose ``v f <= min_i w_i
    t_i`` (by the direction sweep, on random matrices and limits), and a pose reaches it."""
    rng = np.random.default_rng(7)
    J = rng.normal(size=(100, 2, 2))
    for _ in range(3):
        w, t = rng.uniform(0.5, 5.0, 2), rng.uniform(0.5, 5.0, 2)
        a = np.linspace(0.0, 2.0 * np.pi, N_DIR, endpoint=False)
        U = np.stack([np.cos(a), np.sin(a)])
        v = np.min(w[None, :, None] / np.abs(np.einsum("pij,jn->pin", J, U)), axis=(1, 2))
        tau = np.abs(np.linalg.solve(np.swapaxes(J, 1, 2), np.broadcast_to(U, (len(J), 2, N_DIR))))
        f = np.min(t[None, :, None] / tau, axis=(1, 2))
        assert np.all(v * f <= np.min(w * t) * (1 + 1e-9))
        # attained: orthogonal rows, a2 / a1 between t1/t2 and w2/w1 (the smaller w_i t_i first)
        i = int(np.argmin(w * t))
        lo, hi = (t[0] / t[1], w[1] / w[0]) if i == 0 else (w[1] / w[0], t[0] / t[1])
        ratio = np.sqrt(lo * hi)
        Jo = np.diag([1.0, ratio])[None]
        vo, fo = _sweep(Jo, w, t)
        assert vo * fo == pytest.approx(np.min(w * t), rel=1e-6)


def test_per_actuator_values_on_the_command_line(tmp_path, capsys):
    """``--actuator-speed 3,2.5`` and ``--actuator-torque 8Nm,6000Nmm`` are read per
    actuator (units each); three values, a negative one or an unknown reading are one
    line and exit 2, with nothing written."""
    from mechopt import mechanisms
    from mechopt.requirements import options

    spec = mechanisms.design_spec("five-bar")
    opt = options()["actuator_torque"][0]
    assert opt.check(opt.parse("8Nm,6000Nmm"), spec, "mm") == (8.0, 6.0)
    assert opt.check(opt.parse("8"), spec, "mm") == 8.0
    speed = options()["actuator_speed"][0]
    assert speed.check(speed.parse("30rpm, 3"), spec, "mm") == pytest.approx((np.pi, 3.0), rel=1e-15)
    base = ["design", "five-bar", "--task", "rect:300,200@0,250", "--min-speed", "0.5m/s"]
    for extra, message in ((["--actuator-speed", "3,2,1"], "actuator_speed takes one value (both actuators) or two"),
                           (["--actuator-speed", "3,-2"], "actuator_speed"),
                           (["--actuator-speed", "3", "--actuator-norm", "1"], "norm must be one of")):
        out = tmp_path / "never"
        assert main(base + extra + ["--out", str(out)]) == 2 and not out.exists()
        err = capsys.readouterr().err.strip().splitlines()
        assert message in err[-1] and err[-1].startswith("mechopt")


def test_power_precheck_names_the_weaker_actuator(tmp_path, capsys):
    """0.5 m/s x 20 N = 10 W: actuator 1 has 3 rad/s x 8 N m = 24 W, actuator 2 only
    3 rad/s x 3 N m = 9 W: refused before any run, naming actuator 2."""
    out = tmp_path / "never"
    code = main(["design", "five-bar", "--task", "rect:300,200@0,250", "--min-speed", "0.5m/s", "--min-force", "20",
                 "--actuator-speed", "3", "--actuator-torque", "8,3", "--out", str(out)])
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert code == 2 and not out.exists()
    assert "speed x force = 10 W exceeds actuator 2's 3 rad/s x 3 N m = 9 W" in last


def _size(out):
    return json.loads((out / "design.json").read_text())["objectives"]["size"]


@pytest.mark.slow
@pytest.mark.parametrize("norm, expected", [("box", 869.5), ("2", 1024.6)])
def test_the_designers_case(tmp_path, norm, expected):
    """The issue's designer: a five-bar for a 300 x 200 mm rectangle, motors of 3 rad/s
    and 8 N m, 0.5 m/s and 20 N everywhere. Per-actuator limits: the size an independent
    brute force found, 869.5 mm; Liu's budget (``--actuator-norm 2``): 1024.6 mm; each
    within 1 %."""
    out = tmp_path / norm
    code = main(["design", "five-bar", "--task", "rect:300,200@0,250", "--place", "free-y", "--actuator-speed", "3",
                 "--actuator-torque", "8", "--min-speed", "0.5m/s", "--min-force", "20", "--objectives", "size",
                 "--actuator-norm", norm, "--out", str(out)])
    assert code == 0
    assert _size(out) == pytest.approx(expected, rel=0.01)
