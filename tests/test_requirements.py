"""The requirement/objective plug-ins of ``mechopt design`` (mechopt.requirements).

* a contract over every declared member (names, options, units, certificates, bounds);
* a toy requirement written in ONE file of its own (a module in a temporary folder,
  added to a monkeypatched registry) is used by the command line, the problem, the
  evaluator, front.csv, design.json and the certification, with no edit elsewhere;
* no placeholder objective: a design without force capacity has an undefined torque
  and is infeasible through its constraints.
"""
from __future__ import annotations

import json
import math
import sys
import textwrap

import numpy as np
import pandas as pd
import pytest

from mechopt import mechanisms as mechanism_package
from mechopt import requirements as req_package
from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.requirements import Requirements
from mechopt.requirements.base import Objective, Requirement

TOY = textwrap.dedent('''
    """A toy requirement: the task's centre within R of the base midpoint (exact: the
    placed task's reference point is known)."""
    import math

    from mechopt.requirements.base import Option, Requirement


    class CentreNear(Requirement):
        name = "centre"
        options = (Option("max_centre_distance", "largest distance of the task's centre from the base [unit]"),)
        margin_text = "R minus the distance of the task's centre from the base midpoint"
        margin_unit = "{L}"
        certificate = "exact: one point"
        proven = True

        def describe(self, req, unit):
            return f"the task's centre within {req.max_centre_distance} {unit} of the base"

        def evaluate(self, ctx):
            x, y = ctx.task.reference
            m = ctx.req.max_centre_distance - math.hypot(x, y)
            return m, -m / ctx.req.max_centre_distance


    MEMBERS = (CentreNear(),)
''')


@pytest.fixture
def toy_registry(tmp_path, monkeypatch):
    """The toy module on sys.path and in a monkeypatched copy of the registry."""
    (tmp_path / "toy_centre_requirement.py").write_text(TOY)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(req_package, "MODULES", req_package.MODULES + ("toy_centre_requirement",))
    yield
    sys.modules.pop("toy_centre_requirement", None)


# ---------------------------------------------------------------- the contract
def test_every_member_declares_the_protocol():
    members = req_package.registry()
    names = [m.name for m in members if isinstance(m, Requirement)]
    assert len(names) == len(set(names)) and names[:2] == ["reach", "singular"]
    assert set(req_package.objectives()) == {"size", "footprint", "min-lci", "mean-lci", "speed", "force", "torque",
                                             "error", "clearance", "peak-torque", "rms-torque", "moving-mass"}
    options = req_package.options()  # raises on an option declared twice
    assert "min_lci" in options and "singularity_margin" in options
    spec = mechanism_package.design_spec("five-bar")
    for m in members:
        assert m.name and isinstance(m.options, tuple)
        if isinstance(m, Requirement):
            assert m.certificate and m.margin_text and m.margin_unit
        else:
            assert m.sense in (1, -1) and m.description and m.unit
            for needed in m.requires:
                assert needed in options, f"objective {m.name} requires an undeclared option {needed}"
        for o in m.options:
            assert o.flag.startswith("--") and o.help
    # every requirement the five-bar can have is named by the constraint order
    full = Requirements(min_lci=0.5, joint_limits=(0, 1), min_speed=1, actuator_speed=1, min_force=1,
                        actuator_torque=1).checked(spec)
    assert full.names(spec) == ("reach", "singular", "lci", "joints", "speed", "force")


@pytest.mark.parametrize("mechanism", mechanism_package.designed())
def test_objective_bounds_give_a_hypervolume(mechanism):
    """Every objective declares a finite reference range: the design problem's history
    has a hypervolume (the progress line printed ``hv nan`` before)."""
    from mechopt.problems.design import DesignProblem

    task = Task.rect(40, 30, (0, 120))
    req = Requirements(actuator_speed=2.0, actuator_torque=3.0, payload=5.0, error_model={"encoder_counts": 16384},
                       cycle_time=0.5)
    p = DesignProblem(mechanism, task, req, tuple(req_package.objectives()), max_length=300)
    for ob in p.objectives:
        lo, hi = ob.bounds
        assert math.isfinite(lo) and math.isfinite(hi) and lo < hi
    F = np.array([[ob.sense * 0.5 * (ob.bounds[0] + ob.bounds[1]) for ob in p.objectives]])
    hv = p.hypervolume(F)
    assert math.isfinite(hv) and hv > 0


def test_requirements_refuse_what_does_not_apply():
    with pytest.raises(ValueError, match="unknown requirement 'min_lcl'"):
        Requirements(min_lcl=0.4)
    with pytest.raises(ValueError, match="link_angle applies to the biglide and the gantry, not the five-bar"):
        DesignEvaluator("five-bar", Task.rect(40, 30, (0, 120)), Requirements(link_angle=(0.1, 1.0)), ("size",))
    with pytest.raises(ValueError, match="min_speed needs actuator_speed"):
        DesignEvaluator("five-bar", Task.rect(40, 30, (0, 120)), Requirements(min_speed=10.0), ("size",))
    r = Requirements(min_lci=0.4)
    assert r == Requirements(min_lci=0.4) and hash(r) == hash(Requirements(min_lci=0.4))
    assert r.replace(min_lci=0.5).min_lci == 0.5 and r.min_lci == 0.4
    with pytest.raises(AttributeError):
        r.min_lci = 0.3


# ---------------------------------------------------------------- a toy plug-in
def test_a_requirement_in_one_file_is_used_everywhere(toy_registry, tmp_path, capsys):
    """The toy module alone: the CLI grows its option, the problem a constraint column,
    front.csv a margin column, design.json a margin and its certificate; a bound no
    design can meet is named in the one-line refusal."""
    from mechopt.problems.design import DesignProblem

    out = tmp_path / "run"
    argv = ["design", "five-bar", "--task", "rect:60,40@0,150", "--min-lci", "0.3", "--max-centre-distance",
            "210", "--max-length", "200", "--gen", "8", "--pop", "12", "--no-polish", "--n-jobs", "1",
            "--out", str(out)]
    assert main(argv) == 0
    front = pd.read_csv(out / "front.csv")
    # the task is fixed at (0, 150): the margin is exactly 210 - 150 on every row
    assert np.allclose(front["margin_centre"], 60.0, rtol=0, atol=1e-12)
    rec = json.loads((out / "design.json").read_text())
    assert rec["margins"]["centre"] == pytest.approx(60.0, abs=1e-12)
    assert rec["constraints_g"]["centre"] == pytest.approx(-60.0 / 210.0, abs=1e-15)
    assert rec["tolerance"]["centre"] == "exact: one point"
    p = DesignProblem("five-bar", Task.rect(60, 40, (0, 150)), Requirements(max_centre_distance=100.0),
                      ("size",), max_length=200)
    assert p.constr_names[-1] == "centre"
    ev = p.evaluator
    v = {**{k: rec["variables"][k] for k in ("r1", "r2", "r3", "mode")}, "task_x": 0.0, "task_y": 150.0}
    res = certify(ev, v)
    assert res["margin"]["centre"] == pytest.approx(-50.0) and not res["feasible"]
    never = [a if a != "210" else "100" for a in argv[:-1]] + [str(tmp_path / "never")]
    capsys.readouterr()
    assert main(never) == 0  # no feasible design is a result
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last.startswith("no design satisfies the task's centre within 100.0 mm of the base")
    assert "misses it by 50 mm" in last  # the centre is 150 mm away: exactly 50 mm too far
    assert not (tmp_path / "never" / "front.csv").exists() and (tmp_path / "never" / "population.csv").exists()


def test_the_toy_is_gone_without_the_registry():
    """Nothing but the registry knew the toy: without it the option is unknown."""
    with pytest.raises(ValueError, match="unknown requirement 'max_centre_distance'"):
        Requirements(max_centre_distance=100.0)


# ---------------------------------------------------------------- no placeholder
def test_torque_without_force_capacity_is_undefined_and_infeasible():
    """A five-bar whose task crosses a type-I singularity (out of reach in part): the
    torque to hold the payload is not defined (NaN, not a clamped number) and the
    design is infeasible through reach."""
    task = Task.rect(40, 30, (0, 120))
    ev = DesignEvaluator("five-bar", task, Requirements(payload=10.0), ("size", "torque"), max_length=300)
    v = dict(r1=40.0, r2=60.0, r3=20.0, mode="+-", task_x=0.0, task_y=120.0)  # reach 100 < 135
    res = ev.evaluate(v)
    assert math.isnan(res["objectives"]["torque"]) and res["g"]["reach"] > 0
    ok = ev.evaluate(dict(r1=90.0, r2=120.0, r3=20.0, mode="+-", task_x=0.0, task_y=120.0))
    assert all(g <= 0 for g in ok["g"].values())
    # per actuator (the default): tau = J^-T F, so actuator i needs payload x ||column i of
    # J^-1|| in the worst direction; the largest over a dense grid, with numpy's inverse
    fb = ok["mechanism"]
    x, y = np.meshgrid(np.linspace(-20, 20, 201), np.linspace(105, 135, 151))
    J = fb.jacobian(x.ravel(), y.ravel())
    worst = np.linalg.norm(np.linalg.inv(J), axis=1).max()  # [mm/rad]: the largest column norm
    assert ok["objectives"]["torque"] == pytest.approx(10.0 * worst * 1e-3, rel=1e-4)
    # --actuator-norm 2 (Liu 2006 eq. 13): payload / min s_min(J) [N m], by the singular values
    liu = DesignEvaluator("five-bar", task, Requirements(payload=10.0, actuator_norm=2), ("size", "torque"),
                          max_length=300).evaluate(dict(r1=90.0, r2=120.0, r3=20.0, mode="+-", task_x=0.0,
                                                        task_y=120.0))
    smin = np.linalg.svd(J, compute_uv=False)[:, -1].min()  # rad/mm
    assert liu["objectives"]["torque"] == pytest.approx(10.0 / (smin * 1e3), rel=1e-4)
    assert liu["objectives"]["torque"] > ok["objectives"]["torque"]


def test_bipod_footprint_counts_its_base_joints_at_half_the_base():
    """The bipod's base joints sit at x = -+b/2: with a wide base they are the farthest
    joints (the footprint once put one at x = -b, twice too far)."""
    ev = DesignEvaluator("bipod", Task.circle(5, (0, 80)), Requirements(), ("size", "footprint"), max_length=400)
    res = ev.evaluate(dict(b=300.0, mode="up", task_x=0.0, task_y=80.0))
    assert res["objectives"]["footprint"] == pytest.approx(150.0, rel=1e-12)
    narrow = ev.evaluate(dict(b=20.0, mode="up", task_x=0.0, task_y=80.0))
    far = max(np.hypot(5 * np.cos(t), 80 + 5 * np.sin(t)) for t in np.linspace(0, 2 * np.pi, 20001))
    assert narrow["objectives"]["footprint"] == pytest.approx(far, rel=1e-6)  # the task's top, 85 mm
