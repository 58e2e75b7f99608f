"""What a designer types and reads (issue: a designer is never misled): working modes and
negative values on the command line, values with units, the power condition refused
before any run, the choice of a design, the printed time and placement."""
from __future__ import annotations

import math
import re
import subprocess
import sys
import time

import numpy as np
import pytest

from mechopt import mechanisms as mechanism_package
from mechopt.analysis.design_eval import DesignEvaluator, pick_index
from mechopt.analysis.task import Task
from mechopt.cli import build_parser, main
from mechopt.requirements import Requirements


# ---------------------------------------------------------------- the command line
@pytest.mark.parametrize("mode", ["-+", "--", "+-", "++"])
def test_every_mode_parses_as_the_next_word(mode):
    args = build_parser().parse_args(["design", "five-bar", "--task", "rect:10,10@0,100", "--mode", mode,
                                      "--out", "x"])
    assert args.mode == mode
    args = build_parser().parse_args(["evaluate", "five-bar", "--r1", "1", "--r2", "2", "--r3", "0.5",
                                      "--mode", mode])
    assert args.mode == mode


def test_negative_values_parse_as_the_next_word():
    args = build_parser().parse_args(["design", "five-bar", "--task", "rect:10,10@0,100", "--joint-limits",
                                      "-60,240", "--out", "x"])
    assert args.req_joint_limits == "-60,240"
    # an option that follows is still an option, not a value
    args = build_parser().parse_args(["design", "five-bar", "--task", "rect:10,10@0,100", "--mode", "-+",
                                      "--place", "free-y", "--out", "x"])
    assert args.mode == "-+" and args.place == "free-y"


def test_values_with_units_equal_bare_values_in_the_task_unit():
    spec = mechanism_package.design_spec("five-bar")
    opts = build_parser()
    with_units = opts.parse_args(["design", "five-bar", "--task", "rect:10,10@0,100", "--min-speed", "0.5m/s",
                                  "--actuator-speed", "30rpm", "--min-force", "2kN", "--actuator-torque", "500Nmm",
                                  "--out", "x"])
    from mechopt import requirements as _req

    parse = {n: o for n, (o, _) in _req.options().items()}
    a = Requirements(**{n: parse[n].parse(getattr(with_units, f"req_{n}"))
                        for n in ("min_speed", "actuator_speed", "min_force", "actuator_torque")}).checked(spec, "mm")
    assert a.min_speed == 500.0 and a.min_force == 2000.0 and a.actuator_torque == 0.5
    assert a.actuator_speed == pytest.approx(math.pi, rel=1e-15)  # 30 rpm = pi rad/s
    b = Requirements(min_speed=500.0, actuator_speed=3.0).checked(spec, "mm")
    assert a.min_speed == b.min_speed
    # a task in metres: 500 mm/s is 0.5
    assert Requirements(min_speed="500mm/s", actuator_speed=3.0).checked(spec, "m").min_speed == 0.5
    with pytest.raises(ValueError, match="unknown unit 'kg' for a speed"):
        Requirements(min_speed="3kg", actuator_speed=3.0).checked(spec, "mm")


def test_a_speed_100_times_too_small_is_warned(tmp_path, capsys):
    """``--min-speed 0.5`` on a task in mm is 0.5 mm/s: echoed with its unit and warned
    (the run itself is refused here for another reason, before it starts)."""
    code = main(["design", "five-bar", "--task", "rect:100,60@0,180", "--min-speed", "0.5", "--actuator-speed",
                 "3", "--min-force", "1e9", "--actuator-torque", "1", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert "min_speed 0.5 mm/s" in err and "warning: --min-speed 0.5 mm/s is over 100 times below" in err
    assert code == 2


def test_impossible_power_is_refused_before_the_run(tmp_path, capsys):
    """0.5 m/s x 20 N = 10 W > 3 rad/s x 2 N m = 6 W: no geometry meets both (speed x force
    <= w t s_min/s_max <= w t); one line, exit 2, no folder written."""
    out = tmp_path / "never"
    code = main(["design", "five-bar", "--task", "rect:300,200@0,250", "--place", "free-y", "--min-speed", "0.5m/s",
                 "--min-force", "20", "--actuator-speed", "3", "--actuator-torque", "2", "--out", str(out)])
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert code == 2 and not out.exists()
    assert "speed x force = 10 W exceeds the actuators' 3 rad/s x 2 N m = 6 W" in last


def test_the_power_condition_holds_for_every_design():
    """The necessary condition is a true bound: on random five-bars and poses, the
    guaranteed speed x force (Liu eq. 10, 13) never exceeds w t."""
    rng = np.random.default_rng(0)
    from mechopt.mechanisms.five_bar import FiveBar

    for _ in range(50):
        r1, r2, r3 = rng.uniform(0.2, 2.0, 3)
        fb = FiveBar(r1=r1, r2=r2, r3=r3, mode="+-")
        x, y = rng.uniform(-1, 1, 200), rng.uniform(0.1, 2.5, 200)
        J = fb.jacobian(x, y)
        ok = np.all(np.isfinite(J), axis=(1, 2))
        s = np.linalg.svd(J[ok], compute_uv=False)
        w, t = 3.0, 2.0
        assert np.all((w / s[:, 0]) * (t * s[:, 1]) <= w * t * (1 + 1e-12))


# ---------------------------------------------------------------- the choice
def test_asf_reaches_a_non_convex_part_of_a_front():
    """On a front with a non-convex middle no weighted sum picks the middle design; the
    achievement scalarizing function with equal weights does."""
    F = np.array([[0.0, 1.0], [0.6, 0.6], [1.0, 0.0]])
    for w in np.linspace(0.01, 0.99, 25):
        assert pick_index(F, ("a", "b"), f"a={w},b={1 - w}") != 1
    assert pick_index(F, ("a", "b"), "asf:a=1,b=1") == 1
    assert pick_index(F, ("a", "b"), "asf:a=1,b=0") == 0
    assert pick_index(F, ("a", "b"), "pseudo:a=0.5,b=0.5") == 1
    with pytest.raises(ValueError, match="--pick method must be one of"):
        pick_index(F, ("a", "b"), "best:a=1")


# ---------------------------------------------------------------- what is printed
def test_printed_time_covers_the_whole_command_and_the_placement_is_printed(tmp_path):
    """The final line gives the command's wall time (optimisation, polish, certification
    and files) and where the task was placed."""
    out = tmp_path / "d"
    argv = [sys.executable, "-m", "mechopt.cli", "design", "five-bar", "--task", "rect:60,40@0,150", "--min-lci",
            "0.4", "--max-length", "200", "--objectives", "size", "--pop", "16", "--gen", "6", "--n-jobs", "1",
            "--out", str(out)]
    t0 = time.perf_counter()
    proc = subprocess.run(argv, capture_output=True, text=True, timeout=600)
    wall = time.perf_counter() - t0
    assert proc.returncode == 0, proc.stderr
    line = proc.stdout.strip().splitlines()[-1]
    m = re.search(r"\(([\d.]+) s: optimisation ([\d.]+), polish ([\d.]+), certification ([\d.]+), files ([\d.]+)\)$",
                  line)
    assert m, line
    printed = float(m.group(1))
    # the interpreter's start and imports come before the timer: a generous margin
    assert printed <= wall and printed >= 0.6 * wall - 1.0
    assert float(m.group(3)) > 0  # the polish ran and is counted
    placed = re.search(r"task centre at \(([-\d.e]+), ([-\d.e]+)\) mm", line)
    assert placed and (float(placed.group(1)), float(placed.group(2))) == (0.0, 150.0)


# ---------------------------------------------------------------- what helps, measured
def _annulus_clearance(px, py, r1, r2, r3):
    """Distance [mm] from points inside both legs' annuli to the nearer annulus boundary
    (five-bar, base joints at (-r3, 0) and (r3, 0), Le 2013): written from the geometry,
    not from the package's reach code."""
    out = np.inf
    for ax in (-r3, r3):
        d = np.hypot(px - ax, py)
        out = np.minimum(out, np.minimum(r1 + r2 - d, d - abs(r1 - r2)))
    return float(np.min(out))


def test_sensitivity_of_the_reach_margin_equals_the_closed_form():
    """Each change :func:`sensitivity` measures, against the annulus clearance of the
    changed design written here: links 10 % longer/shorter, the task moved by 10 % of
    its diameter in four directions."""
    from mechopt.analysis.design_eval import sensitivity

    pts = np.array([[0.0, 250.0], [30.0, 260.0], [-20.0, 240.0]])
    ev = DesignEvaluator("five-bar", Task.points(pts), Requirements(), ("size",), max_length=400)
    r1, r2, r3 = 150.0, 140.0, 40.0
    cx, cy = ev.task.reference
    v = {"r1": r1, "r2": r2, "r3": r3, "mode": "+-", "task_x": cx, "task_y": cy}
    sens = sensitivity(ev, v, "reach")
    d = 0.1 * ev.task.diameter
    expect = {"longer links": _annulus_clearance(*pts.T, 1.1 * r1, 1.1 * r2, 1.1 * r3),
              "shorter links": _annulus_clearance(*pts.T, 0.9 * r1, 0.9 * r2, 0.9 * r3),
              "task moved up": _annulus_clearance(pts[:, 0], pts[:, 1] + d, r1, r2, r3),
              "task moved down": _annulus_clearance(pts[:, 0], pts[:, 1] - d, r1, r2, r3),
              "task moved right": _annulus_clearance(pts[:, 0] + d, pts[:, 1], r1, r2, r3),
              "task moved left": _annulus_clearance(pts[:, 0] - d, pts[:, 1], r1, r2, r3)}
    assert set(sens) == set(expect)
    for k, m in expect.items():
        assert sens[k] == pytest.approx(m, abs=1e-9), k


def test_no_design_names_what_helps_as_measured(tmp_path, capsys):
    """The designer's pick-and-place arm with the task where it is asked (fixed
    placement, 300 x 200 mm at y = 250 mm; motors of 3 rad/s and 8 N m; 0.5 m/s and 20
    N everywhere): the message gives the least-violating design's miss in mm/s and,
    measured at that design, that moving the task helps, each change with the miss it
    leaves; run.json records every change measured; what does not help is not listed."""
    import json

    out = tmp_path / "fixed"
    assert main(["design", "five-bar", "--task", "rect:300,200@0,250", "--actuator-speed", "3", "--actuator-torque",
                 "8", "--min-speed", "0.5m/s", "--min-force", "20", "--objectives", "size", "--pop", "16", "--gen",
                 "10", "--n-jobs", "1", "--no-polish", "--out", str(out)]) == 0
    line = capsys.readouterr().out.strip().splitlines()[-1]
    m = re.search(r"misses it by ([0-9.]+) (mm/s|N)\); what helps, measured at that design \(10 % each\): (.*); wrote",
                  line)
    assert line.startswith("no design satisfies guaranteed") and m, line
    miss, helps = float(m.group(1)), m.group(3)
    assert "task moved" in helps, helps
    sens = json.loads((out / "run.json").read_text())["sensitivity"]
    assert set(sens) >= {"longer links", "shorter links", "task moved up", "task moved down"}
    for change, margin in sens.items():
        assert (change in helps) == (margin > -miss * (1 - 1e-3) and change in
                                     sorted(sens, key=lambda c: -sens[c])[:3]), (change, margin, helps)


# ---------------------------------------------------------------- the knee
def test_the_knee_of_a_two_objective_front_is_its_sharpest_bend():
    """On fronts force = 50 x^p + 3 N against size = 1000 x + 200 mm (p < 1: the force
    gained early, p > 1: late) sampled unevenly, the knee (largest distance from the chord between the extremes, in the
    front's normalised box) is the sample nearest the closed-form bend, where the slope
    equals the chord's: x* = (1/p)^(1/(p-1)); never an extreme."""
    from mechopt.analysis.design_eval import knee_index

    rng = np.random.default_rng(5)
    for p in (0.3, 0.5, 2.0, 3.0, 6.0):
        x = np.sort(np.concatenate([[0.0, 1.0], rng.uniform(0, 1, 400)]))
        F = np.column_stack([1000 * x + 200, -(50 * x ** p + 3)])  # size [mm], -force [N]: minimised
        # normalised: z1 = x, z2 = 1 - x^p; the chord z1 + z2 = 1; the distance |x - x^p| is
        # largest where p x^(p-1) = 1
        xs = (1.0 / p) ** (1.0 / (p - 1.0))
        k = knee_index(F)
        assert 0 < k < len(x) - 1
        assert abs(x[k] - xs) <= np.max(np.diff(x)) + 1e-12, (p, x[k], xs)


@pytest.mark.slow
def test_the_gantry_knee_is_not_a_far_extreme(tmp_path):
    """The gantry speed/force case (Wu 2008's 500 x 400 mm task; 500 mm/s and 500 N
    actuators; size, speed and force): the knee is a design of a few metres, not one
    of the long designs that buy a few per cent of force with twice the size."""
    import json

    import pandas as pd

    out = tmp_path / "g"
    assert main(["design", "gantry", "--task", "rect:500,400@0,500", "--actuator-speed", "500",
                 "--actuator-torque", "500", "--objectives", "size,speed,force", "--n-jobs", "1",
                 "--out", str(out)]) == 0
    chosen = json.loads((out / "design.json").read_text())["objectives"]
    front = pd.read_csv(out / "front.csv")
    assert chosen["size"] < 4000
    for name in ("size", "speed", "force"):
        assert front[name].min() < chosen[name] < front[name].max()


def test_the_stage_times_cover_the_search_below_the_base_line():
    """A free-y five-bar of one mode runs a second search below the base line before the
    main one: run.json's stages list it (``other searches``), and their sum covers the
    call (a generous margin: the problem's construction is outside the stages)."""
    from mechopt.workflows.design import design

    t0 = time.perf_counter()
    res = design("five-bar", Task.rect(60, 40, (0, 150)), Requirements(min_lci=0.4), ("size",), place="free-y",
                 max_length=200, pop=16, gen=6, n_jobs=1, polish=False)
    wall = time.perf_counter() - t0
    stages = res.info["stage_times_s"]
    assert list(stages)[:2] == ["other searches", "optimisation"] and stages["other searches"] > 0
    assert res.info["wall_time_s"] == pytest.approx(sum(stages.values()))
    assert wall >= res.info["wall_time_s"] >= 0.8 * wall - 0.5
