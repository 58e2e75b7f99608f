"""Base class of every mechopt Problem: named variables and objectives, population
evaluation split over the package's single parallel map.

A subclass fixes sizes, bounds and names in ``__init__`` and implements
:meth:`MechoptProblem.evaluate_designs` on a whole (sub-)population; it must call
only the shared evaluators. Objectives are stored for pymoo as minimisation
(``F = sense * value``, ``sense = -1`` for a maximised quantity); constraints are
``G <= 0``, each divided by a scale of its quantity so that they are comparable.
"""
from __future__ import annotations

import numpy as np
from pymoo.core.problem import Problem

from mechopt.parallel import chunks, parallel_map

__all__ = ["MechoptProblem", "Objective"]


class Objective:
    """A named objective: ``sense=+1`` minimised, ``-1`` maximised."""

    def __init__(self, name: str, sense: int, unit: str = "-"):
        if sense not in (1, -1):
            raise ValueError(f"sense must be +1 (minimise) or -1 (maximise), got {sense!r}")
        self.name, self.sense, self.unit = name, sense, unit

    def __repr__(self):
        return f"Objective({self.name!r}, {'min' if self.sense == 1 else 'max'})"


def _evaluate_chunk(args):
    problem, X = args
    return problem.evaluate_designs(X)


class MechoptProblem(Problem):
    """Common machinery; see the module docstring.

    Class attributes to set: ``name`` (registry key), ``summary`` (one line),
    ``var_names``, ``objectives`` (tuple of :class:`Objective`), ``constr_names``,
    ``default_algorithm``, ``default_pop``, ``default_gen``, and ``settings`` (the
    constructor options that change the numbers).
    """

    name = "base"
    summary = ""
    var_names: tuple[str, ...] = ()
    objectives: tuple[Objective, ...] = ()
    constr_names: tuple[str, ...] = ()
    default_algorithm = "nsga2"
    default_pop = 40
    default_gen = 30
    #: options that change the numbers (e.g. the quadrature of the Liu means);
    #: written to ``run.json`` so that a front can be recomputed elsewhere
    settings: dict = {}

    def __init__(self, xl, xu):
        super().__init__(n_var=len(self.var_names), n_obj=len(self.objectives),
                         n_ieq_constr=len(self.constr_names), xl=np.asarray(xl, float),
                         xu=np.asarray(xu, float))
        self.n_jobs = 1
        self.client = None
        self.on_chunk = None

    # the runner sets these; they never travel to the workers
    def use_parallel(self, n_jobs: int = 1, client=None):
        self.n_jobs, self.client = int(n_jobs), client
        return self

    def __getstate__(self):
        state = self.__dict__.copy()
        state.update(client=None, n_jobs=1, on_chunk=None)
        return state

    def evaluate_designs(self, X) -> dict:
        """Return ``{"F": (n, n_obj), "G": (n, n_constr), "extra": {name: (n,)}}``."""
        raise NotImplementedError

    def _evaluate(self, X, out, *args, **kwargs):
        X = np.atleast_2d(np.asarray(X, float))
        n_workers = 1 if self.client is None else max(1, len(self.client.ncores()))
        n_workers = max(n_workers, self.n_jobs)
        parts = parallel_map(_evaluate_chunk, [(self, c) for c in chunks(X, n_workers)],
                             n_jobs=self.n_jobs, client=self.client)
        out["F"] = np.concatenate([p["F"] for p in parts])
        if self.n_ieq_constr:
            out["G"] = np.concatenate([p["G"] for p in parts])

    def describe(self, X) -> dict:
        """Columns for ``front.csv``: variables, objective values (natural sign),
        constraint values and every derived index, for designs ``X``."""
        X = np.atleast_2d(np.asarray(X, float))
        res = self.evaluate_designs(X)
        cols = {name: X[:, i] for i, name in enumerate(self.var_names)}
        for j, ob in enumerate(self.objectives):
            cols[ob.name] = ob.sense * res["F"][:, j]
        for j, name in enumerate(self.constr_names):
            cols[f"g_{name}"] = res["G"][:, j]
        for k, v in res.get("extra", {}).items():
            cols.setdefault(k, np.asarray(v))
        return cols
