"""The design specs: ``mechopt design`` finds each mechanism's spec in its own module.

* every registered mechanism with a ``design_spec`` is offered, under its
  ``cli_name``, the asymmetric five-bar among them, and ``mechopt design
  asymmetric-five-bar`` runs end to end;
* independent check: with equal legs the asymmetric five-bar's evaluation is the
  five-bar's (every constraint, margin, objective and derived value), with unequal
  legs it is not;
* a toy mechanism defined here, given to the registry, is sized with no other edit.
"""
from __future__ import annotations

import json
import math
import pickle

import numpy as np
import pandas as pd
import pytest

from mechopt import mechanisms as mechanism_package
from mechopt.analysis.design_eval import DesignEvaluator, get_spec, mechanisms
from mechopt.analysis.task import Task
from mechopt.requirements import Requirements
from mechopt.cli import main
from mechopt.core.design_spec import DesignSpec
from mechopt.mechanisms.asymmetric_five_bar import AsymmetricFiveBar
from mechopt.mechanisms.five_bar.model import FiveBar, FiveBarDesignSpec
from mechopt.problems.design import DesignProblem


# ------------------------------------------------------------------ the registry
def test_every_spec_of_the_registry_is_offered_under_its_name():
    names = mechanisms()
    assert names == mechanisms()
    assert {"five-bar", "biglide", "bipod", "gantry", "asymmetric-five-bar"} <= set(names)
    registry = mechanism_package.registry()
    assert names == tuple(n for n in registry if registry[n].design_spec is not None)  # registry order
    for n in names:
        spec = get_spec(n)
        assert isinstance(spec, DesignSpec) and spec.name == n
        assert spec.default_mode in spec.modes
        assert len(spec.lower_bounds(1.0)) == len(spec.lengths)
        assert pickle.loads(pickle.dumps(spec)).name == n  # travels to workers
    with pytest.raises(ValueError, match="mechanism must be one of 'asymmetric-five-bar', 'biglide'"):
        get_spec("six-bar")


def test_the_asymmetric_spec():
    spec = get_spec("asymmetric-five-bar")
    assert spec.lengths == ("a1", "c1", "a2", "c2", "r3") and spec.angular
    assert spec.modes == FiveBar.modes and spec.default_mode == "+-"
    assert spec.lower_bounds(2.0) == [2.0, 2.0, 2.0, 2.0, 0.0]
    v = dict(a1=1.0, c1=2.0, a2=3.0, c2=4.5, r3=0.25)
    assert spec.size_of(v) == pytest.approx(1 + 2 + 3 + 4.5 + 0.5, rel=1e-15)
    assert spec.placement_scale(v, 100.0) == 7.5 and spec.reach_radius(10.0) == 20.0
    mech = spec.build(v, "-+")
    assert isinstance(mech, AsymmetricFiveBar) and mech.mode == "-+"
    assert spec.holes(mech) == [(-0.25, 0.0), (0.25, 0.0)]
    assert spec.link_angles is None


def test_cli_designs_an_asymmetric_five_bar(tmp_path, capsys):
    out = tmp_path / "asym"
    argv = ["design", "asymmetric-five-bar", "--task", "rect:40,30@0,120", "--min-lci", "0.3",
            "--min-length", "40", "--max-length", "150", "--pop", "16", "--gen", "10", "--n-jobs", "1",
            "--no-polish", "--out", str(out)]
    assert main(argv) == 0
    assert "AsymmetricFiveBar(" in capsys.readouterr().out
    front = pd.read_csv(out / "front.csv")
    assert list(front.columns[:8]) == ["a1", "c1", "a2", "c2", "r3", "mode", "task_x", "task_y"]
    chosen = json.loads((out / "design.json").read_text())
    assert chosen["mechanism_name"] == "asymmetric-five-bar" and chosen["feasible"]
    assert set(chosen["variables"]) == {"a1", "c1", "a2", "c2", "r3", "mode"}
    assert all(m >= 0 for m in chosen["margins"].values())
    assert (out / "design.png").stat().st_size > 0
    # the chosen design covers the task with LCI >= 0.3, by the mechanism's own methods
    var = chosen["variables"]
    mech = AsymmetricFiveBar(var["a1"], var["c1"], var["a2"], var["c2"], var["r3"], var["mode"])
    x, y = np.meshgrid(np.linspace(-20, 20, 41), np.linspace(105, 135, 31))
    assert mech.reachable(x, y).all() and mech.lci(x, y).min() >= 0.3 - 1e-9


# ------------------------------------------------------------------ independent check
TASK = Task.rect(40, 30, (10, 130))
REQ = Requirements(min_lci=0.3, joint_limits=((-1.0, 4.0), (-1.0, 4.0)), min_speed=5.0, min_force=1.0,
                   actuator_speed=1.0, actuator_torque=1.0, payload=2.0)
OBJ = ("size", "footprint", "min-lci", "mean-lci", "speed", "force", "torque")


def _evaluate(name, v, place="fixed"):
    ev = DesignEvaluator(name, TASK, REQ, OBJ, place=place, max_length=250)
    return ev, ev.evaluate({**v, "mode": "+-", "task_x": 10.0, "task_y": 130.0})


def _numbers(res):
    out = {f"g_{k}": v for k, v in res["g"].items()}
    out.update({f"margin_{k}": v for k, v in res["margin"].items()})
    out.update({f"value_{k}": v for k, v in res["values"].items()})
    for leg, (lo, hi) in enumerate(res["derived"]["joint_ranges"]):
        out[f"theta{leg}_lo"], out[f"theta{leg}_hi"] = lo, hi
    return out


@pytest.mark.parametrize("r1, r2, r3", [(90.0, 110.0, 15.0), (70.0, 95.0, 0.0)])
def test_equal_legs_evaluate_as_the_five_bar(r1, r2, r3):
    """The asymmetric spec with ``a1 = a2 = r1``, ``c1 = c2 = r2`` gives the five-bar
    spec's numbers to 1e-12 (the five-bar's own type-II function differs from the
    protocol's generic one in rounding only)."""
    ev5, sym = _evaluate("five-bar", dict(r1=r1, r2=r2, r3=r3))
    eva, asym = _evaluate("asymmetric-five-bar", dict(a1=r1, c1=r2, a2=r1, c2=r2, r3=r3))
    a, b = _numbers(sym), _numbers(asym)
    assert set(a) == set(b) and len(a) > 20
    for k in a:
        assert b[k] == pytest.approx(a[k], rel=1e-12, abs=1e-12 * max(1.0, abs(a[k]))), k
    assert ev5.objective_values(sym) == pytest.approx(eva.objective_values(asym), rel=1e-12)
    assert a["value_size"] == pytest.approx(2 * (r1 + r2 + r3), rel=1e-15)
    # the same placement search: a free-y placement decodes to the same task height
    f5 = DesignEvaluator("five-bar", TASK, REQ, OBJ, place="free-y", max_length=250)
    fa = DesignEvaluator("asymmetric-five-bar", TASK, REQ, OBJ, place="free-y", max_length=250)
    v5 = f5.decode(np.r_[f5.encode({"r1": r1, "r2": r2, "r3": r3, "mode": "+-", "task_x": 10.0,
                                    "task_y": 130.0})[:-1], 0.37])
    va = fa.decode(np.r_[fa.encode({"a1": r1, "c1": r2, "a2": r1, "c2": r2, "r3": r3, "mode": "+-",
                                    "task_x": 10.0, "task_y": 130.0})[:-1], 0.37])
    assert va["task_y"] == pytest.approx(v5["task_y"], rel=1e-14)


def test_unequal_legs_evaluate_otherwise():
    _, sym = _evaluate("five-bar", dict(r1=90.0, r2=110.0, r3=15.0))
    _, asym = _evaluate("asymmetric-five-bar", dict(a1=90.0, c1=110.0, a2=80.0, c2=125.0, r3=15.0))
    a, b = _numbers(sym), _numbers(asym)
    assert b["value_size"] == pytest.approx(90 + 110 + 80 + 125 + 30, rel=1e-15)
    # leg 1 is the same, so is its crank range; leg 2's and every index over the task differ
    # (the footprint and the reach margin may be set by the task's far corner and leg 1)
    assert (a["theta0_lo"], a["theta0_hi"]) == pytest.approx((b["theta0_lo"], b["theta0_hi"]), rel=1e-12)
    for k in ("value_lci_min", "value_lci_mean", "g_lci", "value_type2_min", "theta1_lo", "theta1_hi",
              "value_speed", "value_force", "value_torque"):
        assert not math.isclose(a[k], b[k], rel_tol=1e-6), k


# ------------------------------------------------------------------ a toy mechanism
class ToyDesignSpec(FiveBarDesignSpec):
    """A five-bar whose cranks and distal links are one length ``r``."""

    name = "toy-five-bar"
    lengths = ("r", "r3")

    def lower_bounds(self, lmin):
        return [lmin, 0.0]

    def build(self, v, mode, strokes=None, pad=0.0):
        return ToyFiveBar(v["r"], v["r"], v["r3"], mode)

    def size(self, mech, derived):
        return 2.0 * (mech.r1 + mech.r2 + mech.r3)

    def placement_scale(self, v, lmax):
        return 2.0 * v["r"]


class ToyFiveBar(FiveBar):
    cli_name = "toy-five-bar"
    design_spec = ToyDesignSpec


class NotSized(FiveBar):
    cli_name = "not-sized"
    design_spec = None


def test_a_new_mechanism_is_sized_from_its_module_alone(monkeypatch):
    """Nothing but the registry knows the toy: get_spec, the evaluator, the problem and
    the CLI's choices pick it up; a mechanism without a spec is not offered."""
    base = mechanism_package.registry()
    assert "toy-five-bar" not in mechanisms()
    monkeypatch.setattr(mechanism_package, "registry",
                        lambda: {**base, "not-sized": NotSized, "toy-five-bar": ToyFiveBar})
    assert "toy-five-bar" in mechanisms() and "toy-five-bar" in mechanisms()
    assert "not-sized" not in mechanisms()
    with pytest.raises(ValueError, match="mechanism must be one of .*'toy-five-bar'.*got 'not-sized'"):
        get_spec("not-sized")
    assert isinstance(get_spec("toy-five-bar"), ToyDesignSpec)
    _, toy = _evaluate("toy-five-bar", dict(r=100.0, r3=15.0))
    _, ref = _evaluate("five-bar", dict(r1=100.0, r2=100.0, r3=15.0))
    assert toy["values"]["size"] == pytest.approx(430.0, rel=1e-15)
    assert toy["g"] == pytest.approx(ref["g"], rel=1e-12)
    problem = DesignProblem("toy-five-bar", TASK, Requirements(min_lci=0.3), ("size", "min-lci"),
                            max_length=250)
    assert problem.var_names == ("ln_r", "ln_r3") and problem.summary.startswith("design toy-five-bar")
    out = problem.evaluate_designs(np.array([[math.log(100.0 + 0.25), math.log(15.0 + 0.25)]]))
    assert out["F"][0, 0] == pytest.approx(430.0, rel=1e-12) and np.all(out["G"] <= 0)
