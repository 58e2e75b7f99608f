"""The search's settled requirements (Sampling.settle, Requirement.settled): a requirement
the samples show comfortably met keeps its unrefined minimum during the search.

* on random designs of several tasks, every objective is bit for bit the fully refined
  evaluation's, every constraint has the same sign (feasible stays feasible), and a
  settled constraint is the samples' value (never above the refined one's feasible
  side: refinement only lowers a minimum);
* the min-lci objective keeps the LCI minimum refined;
* a seeded design run gives the same front.csv with and without settling.
"""
from __future__ import annotations

import numpy as np
import pytest

import mechopt.workflows.design as design_module
from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.sampling import Sampling
from mechopt.analysis.task import parse_task
from mechopt.requirements import Requirements
from mechopt.workflows.design import design

STAR = "polygon:0,200;12,166;47,166;19,145;29,111;0,131;-29,111;-19,145;-47,166;-12,166"
SPEED_FORCE = dict(actuator_speed=10.0, actuator_torque=5.0, min_speed=2.0, min_force=1.0)
CASES = [  # mechanism, task, placement, objectives, longest link, requirements besides LCI >= 0.3
    ("five-bar", "rect:100,60@0,180", "fixed", ("size", "min-lci"), 250, {}),
    ("five-bar", STAR, "free-y", ("size",), 250, {}),
    ("five-bar", "circle:40@0,150", "free", ("size", "mean-lci"), 250, dict(SPEED_FORCE, actuator_norm="2")),
    ("asymmetric-five-bar", "rect:80,50@0,170", "fixed", ("size",), 400, {}),
    ("biglide", "rect:80,50@0,150", "fixed", ("size",), 400, {}),
    ("gantry", "rect:500,400@0,500", "fixed", ("size", "speed"), 1500, SPEED_FORCE),
]
LIMITS = tuple(map(np.radians, (-60.0, 240.0)))


def _designs(ev, n, seed):
    """``n`` designs near a refined one (the first refined design of seeded random draws:
    a design nearly feasible on the samples), lengths scaled by up to 15 % and the task
    moved by up to a tenth of its diameter: on both sides of the requirements' edges."""
    rng = np.random.default_rng(seed)
    for _ in range(3000):
        v0 = ev.decode(ev.xl + rng.uniform(size=len(ev.xl)) * (ev.xu - ev.xl))
        if ev.spec.validity({k: v0[k] for k in ev.spec.lengths}, ev.max_length) <= 0 \
                and ev.context(v0, Sampling()).refine:
            break
    else:
        raise AssertionError("no nearly feasible design in 3000 draws")
    out, d = [], ev.task.diameter
    while len(out) < n:
        v = {**v0, **{k: v0[k] * rng.uniform(0.85, 1.15) for k in ev.spec.lengths},
             "task_x": v0["task_x"] + 0.1 * d * rng.uniform(-1, 1) * (ev.place == "free"),
             "task_y": v0["task_y"] + 0.1 * d * rng.uniform(-1, 1) * (ev.place != "fixed")}
        if ev.spec.validity({k: v[k] for k in ev.spec.lengths}, ev.max_length) <= 0:
            out.append(v)
    return out


@pytest.mark.parametrize("mechanism, task, place, objectives, longest, extra", CASES)
def test_settling_keeps_every_objective_and_every_verdict(mechanism, task, place, objectives, longest, extra):
    limits = {"joint_limits": LIMITS} if mechanism.endswith("five-bar") else {}
    ev = DesignEvaluator(mechanism, parse_task(task), Requirements(min_lci=0.3, **limits, **extra),
                         objectives, place=place, max_length=longest)
    full, settling = Sampling(), Sampling(settle=True)
    n_settled, seen = 0, set()
    for v in _designs(ev, 30, 7):
        a, b = ev.evaluate(v, full), ev.evaluate(v, settling)
        assert ev.objective_values(a) == ev.objective_values(b)  # bit for bit
        ctx = ev.context(v, settling)
        for name in a["g"]:
            ga, gb = a["g"][name], b["g"][name]
            assert (ga <= 0) == (gb <= 0), (name, v, ga, gb)
            if name in ctx.settled:
                n_settled += 1
                assert gb <= 0 and gb <= ga  # the samples' minimum is at or above the refined one
            else:
                assert ga == gb or not (np.isfinite(ga) and np.isfinite(gb)) and str(ga) == str(gb)
        # a minimum an objective reads is never settled
        for objective, requirement in (("min-lci", "lci"), ("speed", "speed"), ("force", "force")):
            if objective in objectives:
                assert requirement not in ctx.settled
        seen |= ctx.settled
    assert seen >= {"singular"} | {r for r in ("speed", "force") if r in ev.req.names(ev.spec)} - set(objectives)
    assert n_settled > 0  # the property is exercised, not vacuous


def test_a_settling_search_gives_the_same_front(monkeypatch, tmp_path):
    kw = dict(mechanism="five-bar", task=parse_task("rect:100,60@0,180"),
              requirements=Requirements(min_lci=0.4, joint_limits=LIMITS), objectives=("size", "min-lci"),
              max_length=250, pop=16, gen=4, seed=3, n_jobs=1, polish=False, plot=False)
    settled = design(**kw, out=tmp_path / "settled")
    monkeypatch.setattr(design_module, "SEARCH", Sampling())  # the search refines everything
    refined = design(**kw, out=tmp_path / "refined")
    assert len(settled.front) > 0
    for name in ("front.csv", "history.csv"):
        assert (tmp_path / "settled" / name).read_bytes() == (tmp_path / "refined" / name).read_bytes(), name
    assert settled.info["settings"]["sampling"]["settle"] is True
    assert refined.info["settings"]["sampling"]["settle"] is False
