"""Base class of every mechopt Problem: named variables and objectives, population
evaluation split over the package's single parallel map.

A subclass fixes sizes, bounds and names in ``__init__`` and implements
:meth:`MechoptProblem.evaluate_designs` on a whole (sub-)population; it must call
only the shared evaluators. Objectives are stored for pymoo as minimisation
(``F = sense * value``, ``sense = -1`` for a maximised quantity;
:meth:`MechoptProblem.natural` turns them back); constraints are ``G <= 0``, each
divided by a scale of its quantity so that they are comparable.

pymoo's conventions hold: ``p.name()`` is the registry name (``p.name`` is that
string too, :class:`ProblemName`), ``p.pareto_front()`` the brute-force front of a
problem with at most two variables (:mod:`mechopt.run.reference`), and a pymoo
parallelisation passed as ``elementwise_runner=`` (``StarmapParallelization``,
``DaskParallelization``, ``JoblibParallelization``) maps slices of each population
(the problems are vectorised: one design at a time would be slower).
"""
from __future__ import annotations

import os
import warnings

import numpy as np
from pymoo.core.problem import LoopedElementwiseEvaluation, Problem

from mechopt.core import validation as _v
from mechopt.run.parallel import chunks, parallel_map

__all__ = ["MechoptProblem", "Objective", "HV_REFERENCE", "ProblemName"]


class ProblemName(str):
    """A problem's registry name that can also be called, as pymoo's ``Problem.name()``:
    ``p.name == "wu2008"`` and ``p.name() == "wu2008"`` both hold, so code written for
    pymoo (``"%s" % problem.name()``) and mechopt's own (``problem.name`` in file names,
    run.json) read the same name."""

    __slots__ = ()

    def __call__(self) -> str:
        return str(self)


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

    Parameters
    ----------
    name : str
        The objective's name (a front.csv column).
    sense : int
        +1 minimised, -1 maximised.
    unit : str
        Its unit (``"-"``: dimensionless).
    bounds : tuple of float, optional
        ``(lo, hi)`` of its natural value.

    Raises
    ------
    ValueError
        For a sense other than +1 or -1, or invalid bounds.
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
        """The same objective with the range ``(lo, hi)`` (for bounds an instance computes).

        Parameters
        ----------
        lo : float
            Lower end of the natural value.
        hi : float
            Upper end, > ``lo``.

        Returns
        -------
        Objective
            A new objective.
        """
        return Objective(self.name, self.sense, self.unit, (lo, hi))

    def normalise(self, f):
        """``f`` in pymoo's minimisation form (``sense * value``) mapped to [0, 1] by
        :attr:`bounds`: 0 at the best natural value, 1 at the worst.

        Parameters
        ----------
        f : array_like
            Values in minimisation form.

        Returns
        -------
        ndarray
            The normalised values (outside [0, 1] for values outside the bounds).

        Raises
        ------
        ValueError
            When the objective has no bounds.
        """
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


class _ChunkEvaluation:
    """What a pymoo elementwise runner maps: ``evaluate_designs`` of one slice of a
    population (picklable: the problem travels without its runner)."""

    def __init__(self, problem):
        self.problem = problem

    def __call__(self, X):
        return self.problem.evaluate_designs(X)


def _runner_workers(runner, n: int) -> int:
    """Slices of a population of ``n`` designs for a pymoo runner: one per worker where
    the runner tells (a Dask client's workers, a pool's processes), else one per CPU."""
    client = getattr(runner, "client", None)
    if client is not None and hasattr(client, "ncores"):
        workers = len(client.ncores())
    else:
        pool = getattr(getattr(runner, "starmap", None), "__self__", None)
        workers = getattr(pool, "_processes", None) or os.cpu_count() or 1
    return max(1, min(n, int(workers)))


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

    Parameters
    ----------
    xl, xu : array_like
        Lower and upper bounds of the variables (their units).
    **kwargs
        Passed to :class:`pymoo.core.problem.Problem` (e.g. ``callback``,
        ``elementwise_runner``).
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

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if isinstance(cls.__dict__.get("name"), str):
            cls.name = ProblemName(cls.__dict__["name"])

    def __setattr__(self, key, value):
        if key == "name" and isinstance(value, str):  # an instance's own name (the Liu region)
            value = ProblemName(value)
        super().__setattr__(key, value)

    def __init__(self, xl, xu, **kwargs):
        """``kwargs`` go to :class:`pymoo.core.problem.Problem` (e.g. ``callback``,
        ``elementwise_runner``)."""
        super().__init__(n_var=len(self.var_names), n_obj=len(self.objectives),
                         n_ieq_constr=len(self.constr_names), xl=np.asarray(xl, float),
                         xu=np.asarray(xu, float), **kwargs)
        self.n_jobs = 1
        self.client = None
        self.on_chunk = None
        self._warned_runner = False

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
        senses = ", ".join(f"{'max' if o.sense < 0 else 'min'} {o.name}" for o in self.objectives)
        return (f"# name: {self.name}\n# summary: {self.summary}\n# n_var: {self.n_var} "
                f"({', '.join(self.var_names)})\n# objectives: {senses}\n"
                f"# n_ieq_constr: {self.n_ieq_constr}\n")

    # the runner sets these; they never travel to the workers
    def use_parallel(self, n_jobs: int = 1, client=None):
        """Evaluate each population in slices on ``n_jobs`` local processes, or on the
        Dask ``client``'s workers (:func:`mechopt.run.parallel.parallel_map`); what
        ``mechopt optimize --n-jobs/--dask`` uses. Returns the problem.

        Parameters
        ----------
        n_jobs : int
            Local worker processes (1: this process).
        client : dask.distributed.Client, optional
            A Dask client instead of local processes.

        Returns
        -------
        MechoptProblem
            ``self``.
        """
        self.n_jobs, self.client = int(n_jobs), client
        return self

    def __getstate__(self):
        state = self.__dict__.copy()
        # a pymoo runner holds a pool or a client: it stays in this process
        state.update(client=None, n_jobs=1, on_chunk=None, elementwise_runner=LoopedElementwiseEvaluation())
        return state

    def natural(self, F) -> np.ndarray:
        """Objectives ``F`` in pymoo's minimisation form (``(n, n_obj)``) in their natural
        sign and unit (``sense * F``: a maximised quantity positive again).

        Parameters
        ----------
        F : array_like, shape (n, n_obj)
            Minimisation form, e.g. ``res.F`` of ``pymoo.optimize.minimize``.

        Returns
        -------
        numpy.ndarray, shape (n, n_obj)
            Column ``j`` is the value of ``objectives[j]`` in ``objectives[j].unit``.
        """
        F = np.asarray(F, float).reshape(-1, self.n_obj)
        return F * np.array([ob.sense for ob in self.objectives], float)

    def _calc_pareto_front(self, quick: bool = False, n_jobs: int = 1):
        """The brute-force front (:func:`mechopt.run.reference.reference_front`, minimisation
        form) of a problem with at most two variables, None otherwise (pymoo's answer
        for an unknown front). Computed on demand by the first ``pareto_front()`` and
        kept by this instance (pymoo's cache): a one-variable problem evaluates about
        2,300 designs, a two-variable one about 30,000 (``quick=True``: 300 and 2,500)."""
        if self.n_var > 2:
            return None
        from mechopt.run.reference import reference_front

        return reference_front(self, quick=quick, n_jobs=n_jobs)["F"]

    def normalise(self, F) -> np.ndarray:
        """Objectives ``F`` (minimisation form, ``(n, n_obj)``) scaled to [0, 1] by each
        objective's declared bounds (:meth:`Objective.normalise`).

        Parameters
        ----------
        F : array_like
            Objectives in minimisation form, ``(n, n_obj)``.

        Returns
        -------
        ndarray
            The normalised objectives.
        """
        F = np.asarray(F, float).reshape(-1, self.n_obj)
        return np.column_stack([ob.normalise(F[:, j]) for j, ob in enumerate(self.objectives)]) \
            if len(F) else np.empty((0, self.n_obj))

    def hypervolume(self, F) -> float:
        """Hypervolume of ``F`` (minimisation form) in normalised objectives against the
        reference point :data:`HV_REFERENCE` in every direction: between 0 and
        ``HV_REFERENCE ** n_obj``, comparable between runs of the problem. NaN when
        an objective declares no bounds.

        Parameters
        ----------
        F : array_like
            Objectives in minimisation form, ``(n, n_obj)``.

        Returns
        -------
        float
            The hypervolume (normalised units).
        """
        if any(ob.bounds is None for ob in self.objectives):
            return float("nan")
        F = self.normalise(F)
        F = F[np.all(F < HV_REFERENCE, axis=1)]
        if not len(F):
            return 0.0
        from pymoo.indicators.hv import HV

        return float(HV(ref_point=np.full(self.n_obj, HV_REFERENCE))(F))

    def evaluate_designs(self, X) -> dict:
        """Return ``{"F": (n, n_obj), "G": (n, n_constr), "extra": {name: (n,)}}``.

        Parameters
        ----------
        X : array_like
            Designs, shape ``(n, n_var)``, in the variables' units.

        Returns
        -------
        dict
            ``F`` (minimisation form), ``G`` (<= 0 feasible) and ``extra``.

        Raises
        ------
        NotImplementedError
            In the base class: each problem implements it.
        """
        raise NotImplementedError

    def check_designs(self, X) -> np.ndarray:
        """``X`` as an ``(n, n_var)`` float array; ValueError on NaN or a value
        outside ``[xl, xu]`` (beyond rounding): such a design is not of this problem.

        Parameters
        ----------
        X : array_like
            Designs, shape ``(n, n_var)``, in the variables' units.

        Returns
        -------
        ndarray
            ``(n, n_var)`` floats.

        Raises
        ------
        ValueError
            On NaN or a value outside ``[xl, xu]``.
        """
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
        runner = getattr(self, "elementwise_runner", None)
        # (elementwise=True: pymoo itself maps the designs with the runner)
        foreign = (runner is not None and not isinstance(runner, LoopedElementwiseEvaluation)
                   and not self.elementwise)
        if foreign and (self.n_jobs > 1 or self.client is not None):
            if not getattr(self, "_warned_runner", False):
                warnings.warn(f"{self.name}: elementwise_runner {type(runner).__name__} is not used: "
                              f"use_parallel(n_jobs={self.n_jobs}, client={self.client!r}) is set",
                              stacklevel=2)
                self._warned_runner = True
            foreign = False
        if foreign:  # pymoo's parallelisation, over slices of the population
            parts = list(runner(_ChunkEvaluation(self), chunks(X, _runner_workers(runner, len(X)))))
        else:
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
        constraint values and every derived index, for designs ``X``.

        Parameters
        ----------
        X : array_like
            Designs, shape ``(n, n_var)``, in the variables' units.

        Returns
        -------
        dict
            ``{column: ndarray}``.
        """
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
