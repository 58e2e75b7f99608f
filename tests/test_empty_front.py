"""Issue 18: a run that finds no feasible design is an answer, not a traceback.

For every registered problem, ``optimize`` and ``sweep`` (through the CLI) end
with status 0 and the line ``no feasible design in N evaluations; least
violation V at <design>``; ``front.csv`` has its header and no rows; ``run.json``
has ``"feasible": 0``, the evaluations and the least-violating design with its
violation per ``g_*`` constraint; the figure shows the population. The Liu 2006
regions are infeasible for a tiny budget (seed 9: least violation >= 0.38);
the other problems always have feasible designs, so they get one more
requirement that no design meets (:class:`Unreachable`).
"""
import json
import re

import numpy as np
import pandas as pd
import pytest

import mechopt.problems
from mechopt.cli import main
from mechopt.problems import get, names
from mechopt.run.problem import MechoptProblem
from mechopt.run.runner import optimize, sweep

SEED = "9"


def _tiny(problem):
    """4 designs, 2 generations (6 for 5 objectives: NSGA-III wants a population at
    least as large as its 5 reference directions, else pymoo prints a warning)."""
    return ["--pop", "4" if problem.n_obj <= 3 else "6", "--gen", "2", "--seed", SEED, "--n-jobs", "1"]


WEIGHTS = [0.0, 1.0]
NATURAL = {n for n in names() if n.startswith("liu2006-") and n != "liu2006-many"}
LINE = re.compile(r"no feasible design in (\d+) evaluations; least violation (\S+) at (.+)")


class Unreachable(MechoptProblem):
    """``base`` plus the requirement ``unreachable``: g = 0.5 + mean position in the
    bounds (0 at the lower corner, 1 at the upper) > 0 for every design."""

    def __init__(self, base):
        self.base = base
        for attr in ("name", "summary", "var_names", "objectives", "default_algorithm", "settings"):
            setattr(self, attr, getattr(base, attr))
        self.constr_names = tuple(base.constr_names) + ("unreachable",)
        if hasattr(base, "weighted_sum"):
            self.weighted_sum = base.weighted_sum
        super().__init__(base.xl, base.xu)

    def evaluate_designs(self, X):
        res = dict(self.base.evaluate_designs(X))
        g = 0.5 + ((X - self.xl) / (self.xu - self.xl)).mean(axis=1)
        res["G"] = np.column_stack([res.get("G", np.zeros((len(X), 0))), g])
        return res


def _infeasible(name):
    return get(name) if name in NATURAL else Unreachable(get(name))


def _cli(monkeypatch, capsys, argv, problem):
    monkeypatch.setattr(mechopt.problems, "get", lambda name: problem)
    code = main(argv)
    out, err = capsys.readouterr()
    assert "Traceback" not in out + err
    assert code == 0, err
    assert out.count("\n") == 1, out
    m = LINE.fullmatch(out.strip())
    assert m, out
    return m


def _check_infeasible_info(info, problem, m):
    cons = [f"g_{n}" for n in problem.constr_names]
    assert info["feasible"] == 0 and info["evaluations"] > 0
    assert set(info["constraint_violations"]) == set(cons)
    assert all(v >= 0 for v in info["constraint_violations"].values())
    assert info["least_violation"] > 0
    assert info["least_violation"] == pytest.approx(sum(info["constraint_violations"].values()))
    design = info["least_violating_design"]
    assert set(design) == set(problem.var_names)  # run.json sorts its keys
    assert all(problem.xl[i] <= design[n] <= problem.xu[i] for i, n in enumerate(problem.var_names))
    # the terminal line says the same as run.json
    assert int(m.group(1)) == info["evaluations"]
    assert float(m.group(2)) == pytest.approx(info["least_violation"], rel=1e-5)
    assert m.group(3) == ", ".join(f"{k}={design[k]:.6g}" for k in problem.var_names)


def _header(problem):
    return list(problem.describe(((problem.xl + problem.xu) / 2)[None, :]))


@pytest.mark.parametrize("name", names())
def test_optimize_without_feasible_design(tmp_path, monkeypatch, capsys, name):
    problem, out = _infeasible(name), tmp_path / "run"
    m = _cli(monkeypatch, capsys, ["optimize", name, *_tiny(problem), "--out", str(out)], problem)
    front = pd.read_csv(out / "front.csv")
    assert len(front) == 0 and list(front.columns) == _header(problem)
    info = json.loads((out / "run.json").read_text())
    _check_infeasible_info(info, problem, m)
    hist = pd.read_csv(out / "history.csv")
    assert info["evaluations"] == hist["evaluations"].iloc[-1]
    assert (out / "front.png").read_bytes()[:4] == b"\x89PNG"


@pytest.mark.parametrize("name", names())
def test_sweep_without_feasible_design(tmp_path, monkeypatch, capsys, name):
    problem, out = _infeasible(name), tmp_path / "sweep"
    argv = ["sweep", name, *_tiny(problem), "--weights", "0,1", "--out", str(out)]
    if problem.n_obj != 2:  # not a sweep problem: the usual one-line error
        monkeypatch.setattr(mechopt.problems, "get", lambda name: problem)
        assert main(argv) == 2 and "needs a 2-objective problem" in capsys.readouterr().err
        return
    m = _cli(monkeypatch, capsys, argv, problem)
    assert len(pd.read_csv(out / "front.csv")) == 0
    info = json.loads((out / "run.json").read_text())
    _check_infeasible_info(info["sweep"], problem, m)
    assert info["feasible"] == 0 and info["sweep"]["feasible_weights"] == 0
    assert info["sweep"]["evaluations"] > info["evaluations"]  # the front run and each weight
    table = pd.read_csv(out / "sweep.csv")
    assert list(table["weight"]) == WEIGHTS and not table["feasible"].any()
    objectives = [ob.name for ob in problem.objectives if ob.name not in problem.var_names]
    assert table[["z", *objectives]].isna().all().all()
    assert (table["violation"] > 0).all() and table[list(problem.var_names)].notna().all().all()
    assert {f"g_{n}" for n in problem.constr_names} <= set(table.columns)
    assert (out / "sweep.png").read_bytes()[:4] == b"\x89PNG"


def test_api_empty_front_keeps_its_columns():
    problem = Unreachable(get("wu2008"))
    res = optimize(problem, pop=4, gen=2, seed=1, n_jobs=1, progress=False, plot=False)
    assert res.front.empty and list(res.front.columns) == _header(problem)
    assert res.info["least_violation"] == pytest.approx(res.population["violation"].min())
    assert res.least.iloc[0][list(problem.var_names)].to_dict() == res.info["least_violating_design"]


def test_sweep_marks_only_the_infeasible_weights(tmp_path, monkeypatch, capsys):
    """Weight 1 made infeasible (every g > 0), weight 0 left alone: one optimum, one
    row with feasible False, NaN objectives and its violation."""
    from mechopt.run.weighted import WeightedSum

    plain = WeightedSum.evaluate_designs

    def weight_one_infeasible(self, X):
        res = plain(self, X)
        if self.weight == 1.0:
            res["G"] = np.abs(res["G"]) + 1.0
        return res

    monkeypatch.setattr(WeightedSum, "evaluate_designs", weight_one_infeasible)
    out = tmp_path / "mixed"
    assert main(["sweep", "liu2006-w-gci", "--pop", "8", "--gen", "3", "--seed", "3", "--n-jobs", "1",
                 "--weights", "0,1", "--out", str(out)]) == 0
    line = capsys.readouterr().out.strip()
    assert line.startswith("1 weighted-sum optima (1 weights without a feasible design); wrote")
    table = pd.read_csv(out / "sweep.csv")
    assert list(table["feasible"]) == [True, False]
    assert table.loc[0, "violation"] == 0 and np.isfinite(table.loc[0, ["z", "r_mic", "gci"]].astype(float)).all()
    assert table.loc[1, "violation"] >= 1 and table.loc[1, ["z", "r_mic", "gci"]].isna().all()
    info = json.loads((out / "run.json").read_text())["sweep"]
    assert info["feasible_weights"] == 1 and "least_violation" not in info
    assert (out / "sweep.png").exists()


def test_issue_command_in_a_real_process(tmp_path):
    """The command of issue 18, as a user runs it: status 0, one line, no traceback."""
    import subprocess
    import sys

    out = tmp_path / "d"
    done = subprocess.run([sys.executable, "-m", "mechopt.cli", "optimize", "liu2006-w-gci", "--pop", "8",
                           "--gen", "2", "--seed", "4", "--n-jobs", "1", "--out", str(out)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    assert LINE.fullmatch(done.stdout.strip()) and done.stdout.count("\n") == 1
    assert json.loads((out / "run.json").read_text())["evaluations"] == 16
    assert {p.name for p in out.iterdir()} == {"front.csv", "history.csv", "run.json", "front.png", "manifest.json"}
