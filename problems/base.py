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

    #: why the front is a single design, when it is (shown by ``mechopt problems``
    #: and written to ``run.json``); None for a problem with a real trade-off
    single_optimum: str | None = None

    def __init__(self, xl, xu, **kwargs):
        """``kwargs`` go to :class:`pymoo.core.problem.Problem` (e.g. ``callback``)."""
        super().__init__(n_var=len(self.var_names), n_obj=len(self.objectives),
                         n_ieq_constr=len(self.constr_names), xl=np.asarray(xl, float),
                         xu=np.asarray(xu, float), **kwargs)
        self.n_jobs = 1
        self.client = None
        self.on_chunk = None

    def __repr__(self):
        opts = ", ".join(f"{k}={v!r}" for k, v in self.settings.items())
        return f"{type(self).__name__}({opts})  # {self.name!r}"

    def __str__(self):
        # pymoo's Problem.__str__ calls self.name(); ours is the registry key (a str)
        senses = ", ".join(f"{'max' if o.sense < 0 else 'min'} {o.name}" for o in self.objectives)
        return (f"# name: {self.name}\n# summary: {self.summary}\n# n_var: {self.n_var} "
                f"({', '.join(self.var_names)})\n# objectives: {senses}\n"
                f"# n_ieq_constr: {self.n_ieq_constr}\n")

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

    def check_designs(self, X) -> np.ndarray:
        """``X`` as an ``(n, n_var)`` float array; ValueError on NaN or a value
        outside ``[xl, xu]`` (beyond rounding): such a design is not of this problem."""
        X = np.asarray(X, float)
        if X.ndim == 1 and X.size == self.n_var:
            X = X[None, :]
        if X.ndim != 2 or X.shape[1] != self.n_var:
            raise ValueError(f"X must have shape (n, {self.n_var}) for {self.name}, got {X.shape}")
        if not np.all(np.isfinite(X)):
            raise ValueError(f"X must be finite for {self.name}; got NaN or inf")
        tol = 1e-9 * np.maximum(1.0, np.abs(self.xu - self.xl))
        bad = (X < self.xl - tol) | (X > self.xu + tol)
        if bad.any():
            i, j = np.argwhere(bad)[0]
            raise ValueError(f"{self.var_names[j]} = {X[i, j]!r} is outside [{self.xl[j]!r}, "
                             f"{self.xu[j]!r}] of {self.name}")
        return np.clip(X, self.xl, self.xu)

    def _evaluate(self, X, out, *args, **kwargs):
        X = self.check_designs(X)
        if len(X) == 0:
            out["F"] = np.empty((0, self.n_obj))
            if self.n_ieq_constr:
                out["G"] = np.empty((0, self.n_ieq_constr))
            return
        n_workers = 1 if self.client is None else max(1, len(self.client.ncores()))
        n_workers = max(n_workers, self.n_jobs)
        parts = parallel_map(_evaluate_chunk, [(self, c) for c in chunks(X, n_workers)],
                             n_jobs=self.n_jobs, client=self.client)
        out["F"] = np.concatenate([p["F"] for p in parts])
        if self.n_ieq_constr:
            out["G"] = np.concatenate([p["G"] for p in parts])
        # derived quantities under their names, so that res.pop.get("r_mic") works
        for key in parts[0].get("extra", {}):
            if key not in ("F", "G", "H", "X"):
                out[key] = np.concatenate([np.asarray(p["extra"][key], float).reshape(-1)
                                           for p in parts])

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
