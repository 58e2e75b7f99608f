"""Task-driven dimensional synthesis as a pymoo Problem (``mechopt design``).

:class:`DesignProblem` is built from (mechanism, task, requirements, objectives);
the kinematics and the evaluation live in :mod:`mechopt.analysis.design_eval`
(:class:`~mechopt.analysis.design_eval.DesignEvaluator`), the requirements in :mod:`mechopt.requirements`. Variables (pymoo's
``X``): each length ``L`` of the mechanism as ``ln_L = ln(L + min_length)`` (or the
scale ``ln_D`` of a fixed ``shape``), ``mode`` (an index into the mechanism's working
modes) with ``mode="any"``, and the task placement relative to the design's reach,
``task_x_rel`` in [-1, 1] and ``task_y_rel`` in [0, 1], when it is free; front.csv
(written by :func:`mechopt.workflows.design.design`) has the lengths and ``task_x, task_y`` in
the task's unit.
Constraints are ``G <= 0``, one per requirement, normalised (see
:mod:`mechopt.workflows.design`); an infeasible design has finite objectives and ``G > 0``.

Without arguments the problem is the issue's example: a five-bar for the
100 x 60 mm rectangle centred at (0, 180) mm with LCI >= 0.4, links <= 250 mm,
minimising size and maximising the minimum LCI.
"""
from __future__ import annotations

from dataclasses import asdict

import numpy as np

from mechopt.analysis.design_eval import DesignEvaluator
from mechopt.analysis.sampling import Sampling
from mechopt.core.jit import load_numba
from mechopt.requirements import Requirements

from mechopt.run.problem import MechoptProblem, Objective

__all__ = ["DesignProblem", "EXAMPLE"]

#: the issue's example (``mechopt design five-bar --task rect:100,60@0,180 --min-lci 0.4``)
EXAMPLE = dict(mechanism="five-bar", task="rect:100,60@0,180", min_lci=0.4, max_length=250.0)


class DesignProblem(MechoptProblem):
    """``DesignProblem(mechanism, task, requirements, objectives, mode=None,
    place="fixed", min_length=None, max_length=None, shape=None, sampling=None,
    side="above")``; ``side="below"`` searches a free placement below the base line
    (the mirror image of a search above it; no effect on a fixed placement or a
    mechanism whose placement is searched around the task's own height).

    Parameters
    ----------
    mechanism : str
        A designed mechanism.
    task : Task or str
        The task (or its CLI syntax).
    requirements : Requirements, optional
        What must hold over the task.
    objectives : sequence of str
        Objective names.
    mode : str, optional
        Working mode or ``"any"``.
    place : str
        ``"fixed"``, ``"free-y"`` or ``"free"``.
    min_length, max_length : float, optional
        Link length bounds [L].
    shape : sequence of float, optional
        Fixed link ratios (the variable is the scale D [L]).
    sampling : mechopt.analysis.sampling.Sampling, optional
        The task's sampling during the search.
    side : str
        ``"above"`` or ``"below"`` the base line, for a free placement.
    **kwargs : 
        pymoo's :class:`~pymoo.core.problem.Problem` keywords (``elementwise_runner``,
        ``callback``).

    Raises
    ------
    ValueError
        One line, for invalid inputs.
    """

    name = "design"
    summary = "task-driven sizing (mechopt design): any mechanism, a task region, requirements over the whole task"
    default_algorithm = "nsga2"
    default_pop = 40
    default_gen = 50

    def __init__(self, mechanism="five-bar", task=None, requirements=None, objectives=("size", "min-lci"),
                 mode=None, place="fixed", min_length=None, max_length=None, shape=None, sampling=None,
                 side="above", **kwargs):
        from mechopt.analysis.task import parse_task

        if task is None:
            task = EXAMPLE["task"]
            requirements = requirements or Requirements(min_lci=EXAMPLE["min_lci"])
            max_length = EXAMPLE["max_length"] if max_length is None else max_length
        if isinstance(task, str):
            task = parse_task(task)
        self.evaluator = ev = DesignEvaluator(mechanism, task, requirements, objectives, mode, place,
                                              min_length, max_length, shape, side)
        self.sampling = sampling or Sampling()
        self.var_names = ev.var_names
        self.objectives = tuple(Objective(name, sense, unit, bounds) for name, sense, unit, bounds in ev.objective_specs())
        self.constr_names = ev.req.names(ev.spec)
        if len(self.objectives) == 1:
            self.default_algorithm = "ga"
        self.summary = f"design {ev.spec.name} for {task.label}"
        # every option recorded (run.json, the manifest key): the evaluation's sampling too
        self.settings = {**ev.settings(), "sampling": asdict(self.sampling)}
        super().__init__(ev.xl, ev.xu, **kwargs)

    def evaluate_designs(self, X):
        X = np.atleast_2d(np.asarray(X, float))
        if len(X) > 1:  # a population: the compiled twins repay loading numba (mechopt.core.jit.Twin)
            load_numba()
        ev = self.evaluator
        F = np.empty((len(X), self.n_obj))
        G = np.empty((len(X), len(self.constr_names)))
        extra = {k: np.empty(len(X)) for k in ("size", "lci_min", "reach_margin", "mode_index")}
        for i, x in enumerate(X):
            v = ev.decode(x)
            res = ev.evaluate(v, self.sampling)
            vals = ev.objective_values(res)
            F[i] = [ob.sense * val for ob, val in zip(self.objectives, vals)]
            G[i] = [res["g"][n] for n in self.constr_names]
            extra["size"][i] = res["values"]["size"]
            extra["lci_min"][i] = res["values"]["lci_min"]
            extra["reach_margin"][i] = res["margin"]["reach"]
            extra["mode_index"][i] = ev.spec.modes.index(v["mode"])
        # a constraint that cannot be computed fails (NaN g: far from feasible)
        G = np.where(np.isfinite(G), G, 1e3)
        # an objective a design does not define (NaN: a torque without force capacity) is
        # left undefined: only on rows a requirement makes infeasible, whose objectives
        # pymoo's survival and tournaments never read (they rank them by constraint
        # violation alone)
        undefined = ~np.isfinite(F)
        if np.any(undefined.any(axis=1) & np.all(G <= 0, axis=1)):
            raise RuntimeError("an objective is undefined on a feasible design: a requirement is missing")
        return {"F": F, "G": G, "extra": extra}
