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

from mechopt.core import validation as _v
from mechopt.run.parallel import chunks, parallel_map

__all__ = ["MechoptProblem", "Objective", "HV_REFERENCE"]


class Objective:
    """A named objective: ``sense=+1`` minimised, ``-1`` maximised.

    ``bounds = (lo, hi)`` is the range of its natural value over the problem's
    design space, known from the formulation (each problem says why in a comment):
    the runner normalises every objective with it to [0, 1] (0 at the best end,
    1 at the worst, :meth:`normalise`) and takes the hypervolume of ``history.csv``
    against the reference point :data:`HV_REFERENCE` in every direction, so that
    it rises with real progress and compares between runs. A value outside the
    bounds is allowed (it normalises outside [0, 1]); beyond the reference point
    it adds no hypervolume.
    """

    def __init__(self, name: str, sense: int, unit: str = "-", bounds=None):
        if sense not in (1, -1):
            raise ValueError(f"sense must be +1 (minimise) or -1 (maximise), got {sense!r}")
        self.name, self.sense, self.unit = name, sense, unit
        if bounds is not None:
            try:
                lo, hi = (float(b) for b in bounds)
            except (TypeError, ValueError):
                raise ValueError(f"bounds of objective {name!r} must be (lo, hi), got {bounds!r}") from None
            if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi):
                raise ValueError(f"bounds of objective {name!r} must be finite with lo < hi, got {bounds!r}")
            bounds = (lo, hi)
        self.bounds = bounds

    def with_bounds(self, lo, hi) -> "Objective":
        """The same objective with the range ``(lo, hi)`` (for bounds an instance computes)."""
        return Objective(self.name, self.sense, self.unit, (lo, hi))

    def normalise(self, f):
        """``f`` in pymoo's minimisation form (``sense * value``) mapped to [0, 1] by
        :attr:`bounds`: 0 at the best natural value, 1 at the worst."""
        if self.bounds is None:
            raise ValueError(f"objective {self.name!r} declares no bounds")
        lo, hi = self.bounds
        best = lo if self.sense == 1 else -hi  # the best end in minimisation form
        return (np.asarray(f, float) - best) / (hi - lo)

    def __repr__(self):
        rng = "" if self.bounds is None else f", bounds=({self.bounds[0]:g}, {self.bounds[1]:g})"
        return f"Objective({self.name!r}, {'min' if self.sense == 1 else 'max'}{rng})"


#: hypervolume reference point of the normalised objectives, in every direction
HV_REFERENCE = 1.1


def _plain(v):
    """An option's value as plain JSON data (tuples as lists, numpy scalars as numbers)."""
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, (tuple, list, np.ndarray)):
        return [_plain(u) for u in v]
    return v


def _evaluate_chunk(args):
    problem, X = args
    return problem.evaluate_designs(X)


class MechoptProblem(Problem):
    """Common machinery; see the module docstring.

    Class attributes to set: ``name`` (registry key), ``summary`` (one line),
    ``var_names``, ``objectives`` (tuple of :class:`Objective`, each with its
    ``bounds``), ``constr_names``, ``default_algorithm``, ``default_pop``,
    ``default_gen`` (the default run, chosen by measurement against a brute-force
    front: ``benchmarks/bench_fronts.py``), and ``options`` (the names of the
    constructor's options, each kept under an attribute of the same name).

    :attr:`settings` holds every option's value (those of :attr:`options`, and what a
    subclass assigns to ``settings`` itself): it is written to ``run.json`` and the
    run folder's manifest key (a folder of a run with other options is refused) and
    shown by ``repr``.
    """

    name = "base"
    summary = ""
    var_names: tuple[str, ...] = ()
    objectives: tuple[Objective, ...] = ()
    constr_names: tuple[str, ...] = ()
    default_algorithm = "nsga2"
    default_pop = 40
    default_gen = 30
    #: the constructor's options (e.g. the quadrature of the Liu means), each stored under
    #: an attribute of its name; their values are the :attr:`settings`
    options: tuple[str, ...] = ()

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

    @property
    def settings(self) -> dict:
        """Every option's value, ``{name: plain value}`` (numbers, strings, booleans,
        lists): those named by :attr:`options`, then any a subclass assigned to
        ``settings``. Written to ``run.json`` and the manifest key, so that a front can
        be recomputed elsewhere and a run folder is never reused by another problem."""
        out = {k: _plain(getattr(self, k)) for k in self.options}
        out.update(self.__dict__.get("_assigned_settings", {}))
        return out

    @settings.setter
    def settings(self, value: dict):
        self.__dict__["_assigned_settings"] = dict(value)

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

    def normalise(self, F) -> np.ndarray:
        """Objectives ``F`` (minimisation form, ``(n, n_obj)``) scaled to [0, 1] by each
        objective's declared bounds (:meth:`Objective.normalise`)."""
        F = np.asarray(F, float).reshape(-1, self.n_obj)
        return np.column_stack([ob.normalise(F[:, j]) for j, ob in enumerate(self.objectives)]) \
            if len(F) else np.empty((0, self.n_obj))

    def hypervolume(self, F) -> float:
        """Hypervolume of ``F`` (minimisation form) in normalised objectives against the
        reference point :data:`HV_REFERENCE` in every direction: between 0 and
        ``HV_REFERENCE ** n_obj``, comparable between runs of the problem. NaN when
        an objective declares no bounds."""
        if any(ob.bounds is None for ob in self.objectives):
            return float("nan")
        F = self.normalise(F)
        F = F[np.all(F < HV_REFERENCE, axis=1)]
        if not len(F):
            return 0.0
        from pymoo.indicators.hv import HV

        return float(HV(ref_point=np.full(self.n_obj, HV_REFERENCE))(F))

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
        tol = _v.RESOLUTION * np.maximum(1.0, np.abs(self.xu - self.xl))
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
