"""The accuracy budget on the command line: ``mechopt evaluate --error-model --at`` and
``mechopt design ... --max-error 50um --encoder 16384`` (its error map below 50 um on a
dense grid; an unreachable requirement is one line with the best value reached)."""
from __future__ import annotations

import json

import numpy as np
import pytest

from mechopt import FiveBar
from mechopt.analysis import accuracy as acc
from mechopt.analysis.accuracy import ErrorModel
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.requirements import Requirements
from test_accuracy_task import _dense_max

TASK = Task.rect(100, 60, (0, 180))


# ---------------------------------------------------------------- mechopt evaluate
def test_evaluate_prints_the_error_at_poses(capsys):
    """``mechopt evaluate five-bar ... --error-model ... --at`` prints the pose bounds of
    :func:`pose_error` in um, inputs echoed; the same design in cm prints the same um;
    bad poses, a missing --at or --error-model are one line on stderr."""
    argv = ["evaluate", "five-bar", "--r1", "0.85", "--r2", "1.6", "--r3", "0.55", "--unit", "m",
            "--error-model", "encoder_counts=16384,clearance_um=5", "--at", "0,1.2", "--at", "0.3,1.4"]
    assert main(argv + ["--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    want = acc.pose_error(FiveBar(0.85, 1.6, 0.55), ErrorModel(encoder_counts=16384, clearance_um=5),
                          np.array([0.0, 0.3]), np.array([1.2, 1.4]), "m")
    assert d["error_at"] == [[0.0, 1.2], [0.3, 1.4]]
    np.testing.assert_allclose(d["error_bound_um"], 1e6 * want["bound"], rtol=1e-12)
    np.testing.assert_allclose(d["error_linear_um"], 1e6 * want["linear"], rtol=1e-12)
    np.testing.assert_allclose(d["error_x_um"], 1e6 * want["x"], rtol=1e-12)
    assert 1 < d["error_bound_um"][0] < 1e3
    assert d["inputs"]["error_model"]["clearance_um"] == 5.0 and d["inputs"]["unit"] == "m"
    # the same design in cm, printed as a table: the same error in um
    cm = ["evaluate", "five-bar", "--r1", "85", "--r2", "160", "--r3", "55", "--unit", "cm",
          "--error-model", "encoder_counts=16384,clearance_um=5", "--at", "0,120"]
    assert main(cm) == 0
    line = next(x for x in capsys.readouterr().out.splitlines() if "error_bound_um" in x)
    assert float(line.split("[")[1].rstrip("]")) == pytest.approx(d["error_bound_um"][0], rel=1e-5)
    for extra in (["--at", "0,1.2"], ["--error-model", "encoder_counts=16384"],
                  ["--error-model", "encoder_counts=16384", "--at", "0"],
                  ["--error-model", "bogus=1", "--at", "0,1.2"]):
        assert main(argv[:10] + extra) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1, err


# ---------------------------------------------------------------- the design command
def _front_below(front, limit, n):
    """Every front design's largest bound on an independent ``n x n`` grid and dense
    boundary (:func:`_dense_max`) is <= ``limit`` [um] and its margin is >= 0."""
    from mechopt.mechanisms import design_spec

    spec = design_spec("five-bar")
    model = ErrorModel(encoder_counts=16384)
    assert len(front) >= 1
    worst = 0.0
    for _, row in front.iterrows():
        assert row["margin_error"] >= 0
        mech = spec.build({k: row[k] for k in ("r1", "r2", "r3")}, row["mode"])
        worst = max(worst, _dense_max(mech, spec, model, TASK.moved_to(row["task_x"], row["task_y"]), n))
    assert worst <= limit
    return worst


def test_max_error_feasible_designs_hold_on_a_dense_grid():
    """What ``mechopt design ... --max-error 50um --encoder 16384`` keeps: seeded five-bar
    designs evaluated by the design loop's evaluator; each one it calls feasible
    (``g_error <= 0``) stays below 50 um on an independent 81 x 81 grid and dense
    boundary, and the set holds feasible and infeasible designs (the check can fail)."""
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.analysis.sampling import Sampling
    from mechopt.mechanisms import design_spec

    spec = design_spec("five-bar")
    ev = DesignEvaluator("five-bar", TASK, Requirements(max_error=50.0, encoder=16384), ("size",))
    rng = np.random.default_rng(3)
    model = ErrorModel(encoder_counts=16384)
    kept = dropped = dropped_by_error = 0
    for _ in range(12):
        v = {"r1": rng.uniform(90, 200), "r2": rng.uniform(150, 240), "r3": rng.uniform(0, 50), "mode": "+-",
             "task_x": 0.0, "task_y": 180.0}
        res = ev.evaluate(v, Sampling())
        if not all(g <= 0 for g in res["g"].values()):
            dropped += 1
            dropped_by_error += res["g"]["error"] > 0 and all(g <= 0 for k, g in res["g"].items() if k != "error")
            continue
        kept += 1
        mech = spec.build({k: v[k] for k in ("r1", "r2", "r3")}, "+-")
        assert res["values"]["error_um"] <= 50.0
        assert _dense_max(mech, spec, model, TASK, 81) <= 50.0
    assert kept >= 2 and dropped_by_error >= 1, (kept, dropped, dropped_by_error)


@pytest.mark.slow
def test_design_max_error_with_encoder_holds_on_a_dense_grid(tmp_path, capsys):
    """``mechopt design five-bar --task rect:100,60@0,180 --max-error 50um --encoder 16384``:
    every front design's error, on an independent 401 x 401 grid and dense boundary,
    stays below 50 um; an unreachable requirement is the one line "no design satisfies"
    naming the least-violating design's miss and the error it reaches."""
    import pandas as pd

    out = tmp_path / "d"
    argv = ["design", "five-bar", "--task", "rect:100,60@0,180", "--max-error", "50um", "--encoder", "16384",
            "--max-length", "250", "--pop", "16", "--gen", "6", "--n-jobs", "1", "--no-polish", "--out", str(out)]
    assert main(argv) == 0, capsys.readouterr().err
    _front_below(pd.read_csv(out / "front.csv", comment="#"), 50.0, 401)
    capsys.readouterr()
    bad = argv[:5] + ["0.001um"] + argv[6:-1] + [str(tmp_path / "e")]
    assert main(bad) == 0  # an empty result is a result (tests/test_design.py)
    line = capsys.readouterr().out.strip().splitlines()[-1]
    assert line.startswith("no design satisfies position error <= 0.001 um over the task"), line
    miss = float(line.split("misses it by ")[1].split(" um")[0])
    reached = float(line.split("reaching ")[1].split(" um")[0])
    assert reached == pytest.approx(0.001 + miss, rel=1e-3) and reached > 1.0
    info = json.loads((tmp_path / "e" / "run.json").read_text())
    assert "reaching" in info["no_design"]
