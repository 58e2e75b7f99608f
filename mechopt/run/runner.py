"""One seeded runner for every Problem: ``optimize`` and weighted-sum ``sweep``.

Population evaluation goes through the Problem's chunked
:func:`mechopt.run.parallel.parallel_map` (joblib or Dask), so the same seed gives
the same front for any ``n_jobs`` and either backend. ``n_jobs=None`` (the
default) chooses: the first two generations run in this process and are timed
(CPU time, so that a busy machine does not mislead it); if a generation takes
:data:`PARALLEL_SECONDS` or more, the rest runs on two processes (on cheap
problems the processes cost more than they save). The
algorithm is a name of :data:`ALGORITHMS` (the problem's ``default_algorithm``
by default) or any pymoo algorithm object, the termination ``("n_gen", gen)``,
a tolerance ``tol`` (pymoo's default termination with that ``ftol``, ``gen``
its maximum) or any pymoo termination (a tuple or a ``Termination`` object).
Outputs go through :mod:`mechopt.run.io` (atomic writes):

``front.csv``    one row per non-dominated feasible design (variables, objectives
                 with their natural sign, constraint values, derived indices)
``history.csv``  one row per generation: ``generation``; ``evaluations`` (designs
                 evaluated so far); ``n_front`` (designs in the algorithm's current
                 optimum); ``best_<objective>`` per objective (natural sign, best over
                 that optimum; empty while no design is feasible); with two or more
                 objectives ``hypervolume``: of the feasible optimum in objectives
                 normalised to [0, 1] by their declared bounds
                 (:class:`mechopt.run.problem.Objective`), against the reference
                 point 1.1 in every direction, so it lies in [0, 1.1^m], rises with
                 real progress and compares between runs and seeds of a problem (0
                 while nothing is feasible; empty if an objective declares no bounds)
``run.json``     problem, settings, ``algorithm`` (name, pop, gen: the maximum
                 number of generations, null if the termination sets none),
                 ``algorithm_settings`` (class, population and operator settings:
                 sampling, selection, crossover, mutation, survival),
                 ``termination`` (class and parameters), ``generations`` (run),
                 seed, ``n_jobs`` (used), ``n_jobs_auto`` (chosen by timing) and
                 ``seconds_per_generation`` (the timed generation), backend,
                 versions, wall time, ``feasible`` (feasible designs in the final
                 population) and ``evaluations``
``front.png``    the front (or the convergence curve of a single
                 objective)
``manifest.json`` the run (problem, settings, algorithm, seed) and, written
                 last, that the set is complete with each file's sha256

A run may end without any feasible design (a small budget, a demanding
requirement). That is an answer, not an error: ``front.csv`` keeps its header
and has no rows, ``run.json`` has ``"feasible": 0`` and the least-violating
design of the final population (``least_violating_design``, its
``least_violation`` = sum of max(0, g) and ``constraint_violations`` per
``g_*`` column), and ``front.png`` shows the population coloured by constraint
violation; :func:`infeasible_line` is the one-line summary the CLI prints.
"""
from __future__ import annotations

import copy
import numbers
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from mechopt import __version__
from mechopt.run import io as _io
from mechopt.core import validation as _v
from mechopt.run.progress import Progress

__all__ = ["ALGORITHMS", "make_algorithm", "optimize", "resume", "sweep", "parse_weights", "RunResult",
           "infeasible_line", "describe_algorithm", "describe_termination", "PARALLEL_SECONDS"]

ALGORITHMS = ("ga", "de", "nsga2", "nsga2-mnn", "nsga3")
#: the algorithms of :data:`ALGORITHMS` for a single objective
SINGLE_OBJECTIVE = ("ga", "de")

#: DE's variant and parameters (``de``): best/1/bin with a crossover rate 0.7 rather
#: than pymoo's 0.2: on the Le 2013 ridges (the tied and relaxed square problems) it
#: reaches the brute-force optimum from every seed tried, GA and DE with CR 0.2 do not
#: (benchmarks/bench_fronts.py)
DE_VARIANT, DE_F, DE_CR = "DE/best/1/bin", 0.5, 0.7
#: a generation that takes this long in one process (seconds) makes ``n_jobs=None``
#: use two processes for the rest of the run; below it the process start-up and the
#: transfers cost more than they save (measured on 2 cores: 0.1 s per generation is
#: break-even, 0.27 s runs 1.5x faster on two)
PARALLEL_SECONDS = 0.2

#: largest population and number of generations accepted (a typo such as
#: ``--pop 100000000000`` would otherwise exhaust memory or never end)
MAX_POP = MAX_GEN = 1_000_000


def _probability(name, value):
    if value is None:
        return None
    out = _v.finite_number(name, value)
    if not 0.0 <= out <= 1.0:
        raise ValueError(f"{name} must lie in [0, 1], got {_v.show(value)}")
    return out


def _eta(name, value):
    if value is None:
        return None
    out = _v.finite_number(name, value)
    if not 0.0 < out <= 1e6:
        raise ValueError(f"{name} must be a positive distribution index (at most 1e6), got {_v.show(value)}")
    return out


def make_algorithm(name: str, pop: int, n_obj: int, crossover_prob=None, mutation_prob=None,
                   crossover_eta=None, mutation_eta=None):
    """A pymoo algorithm by name with population ``pop``: ``ga`` (GA), ``de`` (DE,
    :data:`DE_VARIANT`), ``nsga2`` (NSGA-II), ``nsga2-mnn`` (NSGA-II whose crowding
    distance is pymoo's M-nearest-neighbour pruning, ``crowding_func="mnn"``: it keeps
    a many-objective front spread where the plain crowding distance lets it
    cluster) and ``nsga3`` (NSGA-III: Das-Dennis reference directions, as many
    partitions as fit in ``pop``).

    ``crossover_prob`` and ``crossover_eta`` set the SBX crossover (probability of
    a mating being crossed, distribution index); ``mutation_prob`` and
    ``mutation_eta`` the polynomial mutation (probability of an offspring being
    mutated, distribution index). For ``de`` the crossover probability is DE's
    rate CR and the mutation that of its polynomial mutation. Unset values keep
    each algorithm's defaults (pymoo's; for DE :data:`DE_CR`).

    Parameters
    ----------
    name : str
        One of :data:`ALGORITHMS`.
    pop : int
        Population size.
    n_obj : int
        Number of objectives (NSGA-III's reference directions).
    crossover_prob, mutation_prob : float, optional
        Probabilities, in [0, 1].
    crossover_eta, mutation_eta : float, optional
        Distribution indices, > 0.

    Returns
    -------
    Algorithm
        A fresh pymoo algorithm.

    Raises
    ------
    ValueError
        One line, for an unknown name, an algorithm that does not fit the number of
        objectives, or an invalid setting.
    """
    _v.choice("algorithm", name, ALGORITHMS)
    pop = _v.integer("pop", pop, 2, MAX_POP)
    cp, mp = _probability("crossover_prob", crossover_prob), _probability("mutation_prob", mutation_prob)
    ce, me = _eta("crossover_eta", crossover_eta), _eta("mutation_eta", mutation_eta)
    if name in ("nsga3", "nsga2-mnn") and n_obj < 2:
        raise ValueError(f"algorithm {name!r} needs at least 2 objectives, the problem has {n_obj}")
    if name in SINGLE_OBJECTIVE and n_obj != 1:
        raise ValueError(f"algorithm {name!r} needs a single objective, the problem has {n_obj}")
    if name == "de":
        from pymoo.algorithms.soo.nonconvex.de import DE

        if ce is not None:
            raise ValueError("crossover_eta does not apply to 'de' (its crossover is binomial)")
        algo = DE(pop_size=pop, variant=DE_VARIANT, F=DE_F, CR=DE_CR if cp is None else cp)
        if mp is not None or me is not None:
            from pymoo.operators.mutation.pm import PM

            old = algo.mating.mutation  # a fresh PM of this DE object, not a shared default
            algo.mating.mutation = PM(prob=_value(old.prob) if mp is None else mp, at_least_once=True,
                                      eta=_value(old.eta) if me is None else me)
        return algo
    # pymoo's defaults per algorithm: (SBX prob, SBX eta, PM prob, PM eta)
    defaults = {"ga": (0.9, 15, 0.9, 20), "nsga2": (0.9, 15, 0.9, 20), "nsga2-mnn": (0.9, 15, 0.9, 20),
                "nsga3": (1.0, 30, 0.9, 20)}[name]
    ops = {}
    if cp is not None or ce is not None:  # new operator objects: pymoo's defaults are shared
        from pymoo.operators.crossover.sbx import SBX

        ops["crossover"] = SBX(prob=defaults[0] if cp is None else cp, eta=defaults[1] if ce is None else ce)
    if mp is not None or me is not None:
        from pymoo.operators.mutation.pm import PM

        ops["mutation"] = PM(prob=defaults[2] if mp is None else mp, eta=defaults[3] if me is None else me)
    if name == "ga":
        from pymoo.algorithms.soo.nonconvex.ga import GA

        return GA(pop_size=pop, eliminate_duplicates=True, **ops)
    if name in ("nsga2", "nsga2-mnn"):
        from pymoo.algorithms.moo.nsga2 import NSGA2

        if name == "nsga2-mnn":
            from pymoo.operators.survival.rank_and_crowding import RankAndCrowding

            ops["survival"] = RankAndCrowding(crowding_func="mnn")
        return NSGA2(pop_size=pop, **ops)
    from pymoo.algorithms.moo.nsga3 import NSGA3
    from pymoo.util.ref_dirs import get_reference_directions

    from math import comb

    p = 1
    while comb(p + 1 + n_obj - 1, n_obj - 1) <= pop:
        p += 1
    ref = get_reference_directions("das-dennis", n_obj, n_partitions=p)
    return NSGA3(ref_dirs=ref, pop_size=pop, **ops)


def _value(v):
    """The value of a pymoo ``Variable`` (an operator parameter), else ``v``."""
    return getattr(v, "value", v)


def _plain(v):
    """``v`` as a JSON value if it is a plain setting (number, bool, str, None), else KeyError."""
    v = _value(v)
    if v is None or isinstance(v, (bool, np.bool_, str)):
        return v if not isinstance(v, np.bool_) else bool(v)
    if isinstance(v, numbers.Integral):
        return int(v)
    if isinstance(v, numbers.Real):
        return float(v) if np.isfinite(v) else str(v)
    raise KeyError


def _operator(op, depth=1) -> dict | None:
    """``{"class": ..., setting: value}`` of a pymoo operator (its plain public attributes,
    nested operators one level down)."""
    if op is None:
        return None
    out = {"class": type(op).__name__}
    for key, v in sorted(vars(op).items()):
        if key.startswith("_") or key in ("name", "vtype"):
            continue
        try:
            out[key] = _plain(v)
        except KeyError:
            if depth > 0 and type(v).__module__.startswith("pymoo.") and hasattr(v, "__dict__"):
                out[key] = _operator(v, depth - 1)
    return out


def describe_algorithm(algo) -> dict:
    """Class, population and operator settings of a pymoo algorithm (``run.json``).

    Parameters
    ----------
    algo : Algorithm
        A pymoo algorithm.

    Returns
    -------
    dict
        ``class``, ``module``, ``pop_size``, ``n_offsprings`` and each operator's
        class and settings.
    """
    init, mating = getattr(algo, "initialization", None), getattr(algo, "mating", None)
    out = {"class": type(algo).__name__, "module": type(algo).__module__}
    for key in ("pop_size", "n_offsprings"):
        if hasattr(algo, key):
            try:
                out[key] = _plain(getattr(algo, key))
            except KeyError:
                pass
    if init is not None:
        out["sampling"] = _operator(getattr(init, "sampling", None), 0)
    if mating is not None:
        if type(mating).__name__ == "Mating":  # the genetic algorithms
            for key in ("selection", "crossover", "mutation"):
                out[key] = _operator(getattr(mating, key, None), 0)
        else:  # e.g. DE's variant: selection scheme, F, CR and its mutation
            out["mating"] = _operator(mating, 1)
    if getattr(algo, "survival", None) is not None:
        out["survival"] = {"class": type(algo.survival).__name__}
        crowding = getattr(algo.survival, "crowding_func", None)
        if crowding is not None:
            out["survival"]["crowding"] = type(crowding).__name__
    elim = getattr(algo, "eliminate_duplicates", None)
    if elim is not None:
        out["eliminate_duplicates"] = type(elim).__name__ != "NoDuplicateElimination"
    if getattr(algo, "ref_dirs", None) is not None:
        out["n_ref_dirs"] = int(len(algo.ref_dirs))
    if type(algo).__module__.split(".")[0] != "pymoo" or not out.keys() - {"class", "module"}:
        out["settings"] = _operator(algo, 0)  # a class of the user's: its plain attributes
    return out


def describe_termination(term) -> dict:
    """Class and parameters of a pymoo termination (``run.json``); for pymoo's default
    terminations also their tolerances and maxima.

    Parameters
    ----------
    term : Termination
        A pymoo termination.

    Returns
    -------
    dict
        ``class`` and its parameters (``n_max_gen``, tolerances, ...).
    """
    out = {"class": type(term).__name__}
    for key in ("n_max_gen", "n_max_evals", "max_time", "fmin"):
        if hasattr(term, key):
            try:
                out[key] = _plain(getattr(term, key))
            except KeyError:
                pass
    for part, keys in (("x", ("tol",)), ("cv", ("tol",)), ("f", ("tol",)), ("max_gen", ("n_max_gen",)),
                       ("max_evals", ("n_max_evals",))):
        crit = getattr(term, part, None)
        if crit is None or isinstance(crit, (numbers.Number, str)):
            continue
        inner = getattr(crit, "termination", crit)  # RobustTermination wraps the criterion
        name = {"x": "xtol", "cv": "cvtol", "f": "ftol"}.get(part)
        for k in keys:
            if hasattr(inner, k):
                out[name or k] = _plain(getattr(inner, k))
        window = getattr(getattr(crit, "history", None), "size", None)  # RobustTermination's period
        if isinstance(window, numbers.Integral):
            out["period"] = int(window)
    return out


def _max_gen(term):
    """The generation limit of a termination (None if it sets none)."""
    for t in (term, getattr(term, "max_gen", None)):
        n = getattr(t, "n_max_gen", None)
        if isinstance(n, numbers.Integral) or (isinstance(n, float) and np.isfinite(n)):
            return int(n)
    return None


def _termination(problem, termination, gen, tol):
    """A fresh pymoo Termination from the arguments of :func:`optimize`."""
    from pymoo.core.termination import Termination

    if termination is not None:
        if tol is not None or gen is not None:
            raise ValueError("give either termination or gen/tol, not both")
        if isinstance(termination, Termination):
            return copy.deepcopy(termination)  # terminations keep state: the caller's stays fresh
        if isinstance(termination, (tuple, list)) and termination and isinstance(termination[0], str):
            from pymoo.termination import get_termination

            try:
                return get_termination(*termination)
            except Exception as exc:  # noqa: BLE001 - pymoo raises a bare Exception
                raise ValueError(f"termination {_v.show(termination)} is not a pymoo termination: "
                                 f"{exc}") from None
        raise ValueError(f"termination must be a pymoo Termination or a tuple such as ('n_gen', 10), "
                         f"got {_v.show(termination)}")
    if tol is not None:
        ftol = _v.finite_number("tol", tol)
        if not ftol > 0:
            raise ValueError(f"tol must be a positive number, got {_v.show(tol)}")
        from pymoo.termination.default import (DefaultMultiObjectiveTermination,
                                               DefaultSingleObjectiveTermination)

        kind = DefaultMultiObjectiveTermination if problem.n_obj > 1 else DefaultSingleObjectiveTermination
        kw = {} if gen is None else {"n_max_gen": _check_sizes(2, gen)[1]}
        return kind(ftol=ftol, **kw)
    from pymoo.termination.max_gen import MaximumGenerationTermination

    return MaximumGenerationTermination(_check_sizes(2, problem.default_gen if gen is None else gen)[1])


def _user_algorithm(algorithm, pop, operators):
    """A fresh copy of the caller's pymoo algorithm object (it is not changed)."""
    from pymoo.core.algorithm import Algorithm

    if not isinstance(algorithm, Algorithm):
        raise ValueError(f"algorithm must be one of {', '.join(map(repr, ALGORITHMS))} or a pymoo "
                         f"algorithm object, got {_v.show(algorithm)}")
    if pop is not None or any(v is not None for v in operators.values()):
        raise ValueError("pop and the operator settings (crossover_prob, ...) apply to a named "
                         "algorithm; set them on the algorithm object")
    if getattr(algorithm, "problem", None) is not None or getattr(algorithm, "is_initialized", False):
        raise ValueError("the algorithm object has already been set up or run; pass a new one")
    return copy.deepcopy(algorithm)


@dataclass
class RunResult:
    """The outcome of :func:`optimize` and :func:`resume`.

    Parameters
    ----------
    front : DataFrame
        The feasible non-dominated designs: variables and objectives in their
        natural sign and units (front.csv, :doc:`outputs`).
    history : DataFrame
        One row per generation (history.csv).
    info : dict
        run.json's content.
    population : DataFrame, optional
        The final population: variables, objectives (natural sign), ``g_*`` and
        ``violation`` (sum of max(0, g), pymoo's CV).
    least : DataFrame, optional
        One row: the least-violating design when no design is feasible, else None.
    result : Result, optional
        pymoo's own ``Result`` of the run (``X``, ``F``, ``G``, ``pop``, ``opt``,
        ``algorithm``, ``exec_time``, as ``pymoo.optimize.minimize`` returns it; ``F``
        in minimisation form).
    """

    front: pd.DataFrame
    history: pd.DataFrame
    info: dict
    #: the final population: variables, objectives (natural sign), ``g_*`` and
    #: ``violation`` (sum of max(0, g), pymoo's CV)
    population: pd.DataFrame | None = None
    #: ``describe`` row (one-row table) of the least-violating design when no
    #: design is feasible, else None
    least: pd.DataFrame | None = None
    #: pymoo's own ``Result`` of the run (``algorithm.result()``: ``X``, ``F``, ``G``,
    #: ``pop``, ``opt``, ``algorithm``, ``exec_time``, as ``pymoo.optimize.minimize``
    #: returns it; its ``F`` in minimisation form, :meth:`MechoptProblem.natural`)
    result: object | None = None


def _check_sizes(pop, gen):
    pop = _v.integer("pop", pop)
    gen = _v.integer("gen", gen)
    if pop < 2:
        raise ValueError(f"pop must be at least 2, got {pop}")
    if gen < 1:
        raise ValueError(f"gen must be at least 1, got {gen}")
    if pop > MAX_POP or gen > MAX_GEN:
        raise ValueError(f"pop and gen must be at most {MAX_POP:,}, got pop {pop}, gen {gen}")
    return pop, gen


def _optimum(algo):
    """The non-dominated feasible designs (the best one, for a single objective; the
    least violating if none is feasible) among the algorithm's population and its
    optimum, duplicates dropped. pymoo's own ``opt`` is not enough: NSGA-III keeps
    only the designs nearest to its reference directions (a tenth of a population on
    these fronts), and a local search's population is not its best."""
    from pymoo.core.population import Population
    from pymoo.util.optimum import filter_optimum

    pop, opt = algo.pop, algo.opt
    if pop is None or not len(pop):
        pop = opt
    elif opt is not None and len(opt):
        seen = {np.ascontiguousarray(x).tobytes() for x in pop.get("X")}
        extra = [i for i, x in enumerate(opt.get("X")) if np.ascontiguousarray(x).tobytes() not in seen]
        if extra:
            pop = Population.merge(pop, opt[extra])
    best = filter_optimum(pop, least_infeasible=True)
    if best is None or not len(best):
        return None
    _, first = np.unique(best.get("X"), axis=0, return_index=True)
    return best[np.sort(first)]


class _History:
    """pymoo callback: one history row per generation, and the progress line."""

    def __init__(self, problem, progress: Progress | None, total: int | None, user=None):
        self.problem, self.progress, self.total, self.rows = problem, progress, total, []
        self.user = user  # the caller's pymoo callback, called after the row

    def __call__(self, algorithm):
        opt = _optimum(algorithm)
        n_obj = self.problem.n_obj
        F = opt.get("F") if opt is not None else np.empty((0, n_obj))
        feas = opt.get("FEAS")[:, 0] if opt is not None else np.zeros(0, bool)
        row = {"generation": algorithm.n_gen, "evaluations": algorithm.evaluator.n_eval,
               "n_front": int(len(F))}
        info = ""
        for j, ob in enumerate(self.problem.objectives):
            best = (F[feas, j].min() if feas.any() else np.nan) * ob.sense
            row[f"best_{ob.name}"] = float(best)
        if F.shape[1] >= 2:
            row["hypervolume"] = self.problem.hypervolume(F[feas]) if feas.any() else 0.0
            info = f"hv {row['hypervolume']:.5g}"
        elif F.shape[1] == 1:
            name = self.problem.objectives[0].name
            info = f"best {name} {row[f'best_{name}']:.6g}" if feas.any() else "no feasible design yet"
        self.rows.append(row)
        if self.progress is not None:
            if self.total is None:  # no generation limit: the termination's own progress
                self.progress.update(int(round(100 * _termination_progress(algorithm))), info)
            else:
                self.progress.update(algorithm.n_gen, info)
        if self.user is not None:
            self.user(algorithm)


def _termination_progress(algorithm) -> float:
    try:
        return float(min(max(algorithm.termination.perc, 0.0), 1.0))
    except (AttributeError, TypeError, ValueError):
        return 0.0


def _front_table(problem, X) -> pd.DataFrame:
    df = pd.DataFrame(problem.describe(X))
    keys = [ob.name for ob in problem.objectives] + list(problem.var_names)
    return df.sort_values(keys, kind="mergesort").reset_index(drop=True)


CHECKPOINT = "checkpoint.pkl"


def _n_jobs(n_jobs):
    """``None`` (choose by timing) or a checked number of processes."""
    return None if n_jobs is None else _v.integer("n_jobs", n_jobs, 1)


def optimize(problem, algorithm=None, pop: int | None = None, gen: int | None = None,
             seed: int = 1, n_jobs: int | None = None, client=None, out=None, progress: bool = True,
             plot: bool = True, checkpoint_every: int | None = None, termination=None,
             tol: float | None = None, crossover_prob: float | None = None,
             mutation_prob: float | None = None, crossover_eta: float | None = None,
             mutation_eta: float | None = None, overwrite: bool = False, callback=None) -> RunResult:
    """Run ``problem`` with a seeded pymoo algorithm; write the run folder if ``out``.

    ``algorithm`` is a name of :data:`ALGORITHMS` (default: the problem's
    ``default_algorithm``; ``pop`` and the operator settings apply to it, see
    :func:`make_algorithm`) or a pymoo algorithm object such as ``NSGA2(...)``
    (copied; the caller's object is left as it is). The run ends after ``gen``
    generations (default: the problem's ``default_gen``); with ``tol``, when
    pymoo's default termination with ``ftol=tol`` says so (``gen``, if given, its
    maximum; otherwise pymoo's, 1000); or by ``termination``, any pymoo termination
    (``("n_gen", 10)``, ``("n_eval", 500)``, a ``Termination`` object such as
    ``DefaultMultiObjectiveTermination(ftol=1e-3)``; not together with gen or tol).

    ``n_jobs=None`` chooses 1 or 2 processes by timing the first generations
    (:data:`PARALLEL_SECONDS`); the front does not depend on it.

    With ``checkpoint_every=K`` (needs ``out``) the whole algorithm state (population,
    random generator, termination, history) is saved atomically to
    ``out/checkpoint.pkl`` every K generations, authenticated (see
    :mod:`mechopt.run.checkpoint`); :func:`resume` continues from it and ends with the
    same ``front.csv``, byte for byte, as an uninterrupted run. The saved algorithm
    (``mechopt.run.checkpoint.read(path)[1]["algorithm_state"]``) can also be stepped
    directly with ``has_next()``/``next()``.

    Before the first evaluation the run's memory and time are estimated
    (:mod:`mechopt.run.budget`): a run that cannot fit in memory, or would take longer
    than 30 days, is refused with the estimate; one above an hour says so.

    The outputs (``front.csv``, ``history.csv``, ``run.json``, ``front.png``) are
    written as one set, and ``out/manifest.json`` records the run (its problem,
    settings, algorithm and seed) and, last, that the set is complete
    (:func:`mechopt.run.io.output_set`). A folder holding another run is refused unless
    ``overwrite`` (then the files that run wrote are replaced); files no manifest
    accounts for are refused, never removed.

    ``callback`` is a pymoo callback (a ``pymoo.core.callback.Callback`` or any
    ``callback(algorithm)``), called after every generation as with
    ``pymoo.optimize.minimize(..., callback=)``; it is not saved in a checkpoint. The
    result's ``result`` is pymoo's own ``Result`` of the run.

    Parameters
    ----------
    problem : str or Problem
        A registered problem's name (:func:`mechopt.problems.get`) or a problem
        instance.
    algorithm : str or Algorithm, optional
        A name of :data:`ALGORITHMS` or a pymoo algorithm object.
    pop, gen : int, optional
        Population size and generations.
    seed : int
        Random seed.
    n_jobs : int, optional
        Worker processes (None: chosen by timing).
    client : dask.distributed.Client, optional
        Evaluate on a Dask cluster.
    out : str or Path, optional
        Output folder.
    progress : bool
        Log one line per generation.
    plot : bool
        Draw front.png (with ``out``).
    checkpoint_every : int, optional
        Checkpoint every K generations (needs ``out``).
    termination : tuple or Termination, optional
        A pymoo termination (not with ``gen`` or ``tol``).
    tol : float, optional
        pymoo's default termination with ``ftol=tol``.
    crossover_prob, mutation_prob, crossover_eta, mutation_eta : float, optional
        Operator settings (:func:`make_algorithm`).
    overwrite : bool
        Replace another run that ``out`` holds.
    callback : Callback or callable, optional
        Called after every generation with the algorithm.

    Returns
    -------
    RunResult
        The front, history, run information, final population and pymoo's ``Result``.

    Raises
    ------
    ValueError
        One line, for invalid options, a run that cannot fit in memory or time, or a
        folder holding another run.
    """
    operators = {"crossover_prob": crossover_prob, "mutation_prob": mutation_prob,
                 "crossover_eta": crossover_eta, "mutation_eta": mutation_eta}
    if algorithm is None or isinstance(algorithm, str):
        name = algorithm or problem.default_algorithm
        pop = _check_sizes(problem.default_pop if pop is None else pop, 2)[0]
        algo = None
    else:
        name = None
        algo = _user_algorithm(algorithm, pop, operators)
    term = _termination(problem, termination, gen, tol)
    seed = _v.integer("seed", seed, 0)
    n_jobs = _n_jobs(n_jobs)
    if checkpoint_every is not None:
        checkpoint_every = int(_v.finite_number("checkpoint_every", checkpoint_every))
        if checkpoint_every < 1:
            raise ValueError(f"checkpoint_every must be a positive integer, got {checkpoint_every}")
        if out is None:
            raise ValueError("checkpoint_every needs an output folder (--out)")
    if algo is None:
        algo = make_algorithm(name, pop, problem.n_obj, **operators)
    else:
        name = type(algo).__name__
        pop = _plain(getattr(algo, "pop_size", None)) if isinstance(getattr(algo, "pop_size", None),
                                                                    numbers.Integral) else None
    algo.setup(problem, termination=term, seed=seed, verbose=False)
    state = {"algorithm": name, "pop": pop, "gen": _max_gen(algo.termination), "seed": seed, "rows": [],
             "elapsed": 0.0, "checkpoint_every": checkpoint_every,
             "options": {"problem": problem.name, "settings": dict(problem.settings), "algorithm": name,
                         "pop": pop, "gen": _max_gen(algo.termination), "seed": seed, "tol": tol,
                         **operators, "checkpoint_every": checkpoint_every}}
    _check_budget(problem, algo)
    if callback is not None and not callable(callback):
        raise ValueError(f"callback must be a pymoo Callback or a function of the algorithm, "
                         f"got {type(callback).__name__}")
    if out is None:
        return _drive(algo, state, n_jobs, client, out, progress, plot, callback=callback)
    out = _io.prepare_out_dir(out)
    with _io.run_in(out, "optimize", _run_key(problem, algo, seed), RUN_OUTPUTS, overwrite) as manifest:
        state["run_id"] = manifest["run_id"]
        return _drive(algo, state, n_jobs, client, out, progress, plot, manifest, callback=callback)


#: the names a run writes into its folder: such files that no manifest of a mechopt run
#: accounts for are refused (:func:`mechopt.run.io.claim_out`)
RUN_OUTPUTS = ("front.csv", "history.csv", "run.json", "front.png", "sweep.csv", "sweep.png", CHECKPOINT)


def _run_key(problem, algo, seed) -> dict:
    """What fixes a run's result: problem, its settings, algorithm, termination, seed."""
    return {"problem": problem.name, "settings": dict(problem.settings), "algorithm": describe_algorithm(algo),
            "termination": describe_termination(algo.termination), "seed": seed}


def _check_budget(problem, algo):
    """Refuse a run that cannot fit in memory or would take years (mechopt.run.budget);
    print a line for one estimated above an hour."""
    import math
    import sys

    from mechopt.run import budget

    term = algo.termination
    max_gen = _max_gen(term)
    max_eval = None
    for t in (term, getattr(term, "max_evals", None)):
        n = getattr(t, "n_max_evals", None)
        if isinstance(n, numbers.Integral) or (isinstance(n, float) and np.isfinite(n)):
            max_eval = int(n)
            break
    pop = getattr(algo, "pop_size", None)
    if not isinstance(pop, numbers.Integral) or (max_gen is None and max_eval is None):
        return None  # a termination by time or a custom algorithm: nothing to estimate from
    n_off = getattr(algo, "n_offsprings", None)
    n_off = int(n_off) if isinstance(n_off, numbers.Integral) and n_off > 0 else int(pop)
    if max_gen is None:
        max_gen = math.ceil(max(max_eval - pop, 0) / n_off) + 1
    # memory first, with no design evaluated: a run that cannot fit is refused at once
    budget.check(budget.estimate(problem, int(pop), n_off, max_gen, max_eval, sample=False))
    line = budget.check(budget.estimate(problem, int(pop), n_off, max_gen, max_eval))
    if line:
        print(line, file=sys.stderr)
    return line


def resume(out, n_jobs: int | None = None, client=None, progress: bool = True, plot: bool = True,
           expect: dict | None = None) -> RunResult:
    """Continue the run whose checkpoint is ``out/checkpoint.pkl`` (see :func:`optimize`).

    The checkpoint is authenticated before it is loaded (:mod:`mechopt.run.checkpoint`)
    and must belong to the run ``out/manifest.json`` records. ``expect`` holds
    options the caller asks for (the keys of the checkpoint's ``options``: problem,
    algorithm, pop, gen, seed, tol, the operator settings, checkpoint_every, and
    ``settings``, the problem's): any that differ from the checkpointed run's are
    refused with the list. A finished run, and one stopped before its first
    checkpoint, say so. Every refusal is a one-line ValueError.

    Parameters
    ----------
    out : str or Path
        The run folder.
    n_jobs : int, optional
        Worker processes (None: chosen by timing).
    client : dask.distributed.Client, optional
        Evaluate on a Dask cluster.
    progress : bool
        Log one line per generation.
    plot : bool
        Draw front.png.
    expect : dict, optional
        Options the caller asks for, refused when they differ from the run's.

    Returns
    -------
    RunResult
        As :func:`optimize` returns for the uninterrupted run.

    Raises
    ------
    ValueError
        One line, for a missing, foreign or unauthenticated checkpoint, a finished
        run, or options that differ from ``expect``.
    """
    from mechopt.run import checkpoint as _ck

    from mechopt.run import keys as _keys

    n_jobs = _n_jobs(n_jobs)
    out = Path(out)
    where = f"--resume {str(out)!r}"
    _keys.load_key(create=True)  # an unsafe key is refused before anything is read
    manifest = _io.read_manifest(out)
    if manifest is not None and not _io.authentic(manifest):
        manifest = None  # vouches for nothing: the authenticated checkpoint decides
    path = out / CHECKPOINT
    if not os.path.lexists(path):
        if manifest is not None and manifest["status"] == "complete":
            raise ValueError(f"{where}: this run is complete (its result is front.csv); nothing to resume")
        if manifest is not None:
            raise ValueError(f"{where}: the run started but stopped before its first checkpoint; "
                             f"run it again without --resume")
        raise ValueError(f"{where} holds no {CHECKPOINT}")
    try:
        header, ck = _ck.read(path)
        algo, state = ck["algorithm_state"], ck["state"]
        _check_state(algo, state)
    except _ck.UnreadableCheckpoint as exc:
        raise ValueError(f"{where}: unreadable {CHECKPOINT} ({exc})") from None
    except OSError as exc:
        raise ValueError(f"{where}: unreadable {CHECKPOINT} ({exc.strerror or type(exc).__name__})") from None
    except (KeyError, TypeError, AttributeError, ValueError) as exc:
        raise ValueError(f"{where}: unreadable {CHECKPOINT} (not a mechopt run state: "
                         f"{type(exc).__name__})") from None
    manifest = _manifest_for(out, where, manifest, header)
    if expect:
        diff = _conflicts(header.get("options") or {}, expect)
        if diff:
            raise ValueError(f"{where}: options differ from the checkpointed run ({diff}); drop them to "
                             f"resume, or start a new run in another folder")
    return _drive(algo, state, n_jobs, client, out, progress, plot, manifest)


def _check_state(algo, state):
    """The loaded checkpoint holds a pymoo algorithm set up on a problem and the
    runner's state with the types it needs (TypeError/KeyError otherwise)."""
    from pymoo.core.algorithm import Algorithm
    from pymoo.core.problem import Problem

    if not isinstance(algo, Algorithm) or not isinstance(getattr(algo, "problem", None), Problem):
        raise TypeError("not a pymoo algorithm")
    if not isinstance(state, dict):
        raise TypeError("state")
    kinds = {"rows": list, "elapsed": float, "algorithm": (str, type(None)), "seed": numbers.Integral,
             "gen": (numbers.Integral, type(None)), "checkpoint_every": (numbers.Integral, type(None))}
    for key, kind in kinds.items():
        if not isinstance(state[key], kind):
            raise TypeError(key)
    if not all(isinstance(r, dict) for r in state["rows"]):
        raise TypeError("rows")


def _manifest_for(out: Path, where: str, manifest, header: dict) -> dict:
    """The run manifest a resumed checkpoint continues: the folder's, if the
    checkpoint is that run's; a new one for a folder without (an older mechopt's),
    unless its run.json names another problem."""
    from mechopt.run.io import MANIFEST

    if manifest is not None:
        if manifest.get("run_id") != header.get("run_id"):
            diff = _io.differences(manifest.get("key", {}), header.get("key") or {})
            raise ValueError(f"{where}: {CHECKPOINT} belongs to another run than {MANIFEST}"
                             f"{f' ({diff})' if diff else ''}; remove the one you do not want")
        if manifest["status"] == "complete":
            raise ValueError(f"{where}: this run is complete (its result is front.csv); nothing to resume")
        return manifest
    try:
        done = _io.read_json(out / "run.json")
    except (OSError, ValueError):
        done = None
    if isinstance(done, dict) and done.get("problem") not in (None, header.get("problem")):
        raise ValueError(f"{where}: {CHECKPOINT} is a run of {header.get('problem')}, run.json one of "
                         f"{done.get('problem')}; remove the one you do not want")
    manifest = {"kind": "optimize", "key": header.get("key") or {}, "status": "running",
                "run_id": header.get("run_id") or os.urandom(16).hex(), "owned": [CHECKPOINT]}
    _io.write_manifest(manifest, out)
    return manifest


def _conflicts(recorded: dict, expect: dict) -> str:
    """``"pop 1 (the run's: 20), seed 4 (the run's: 3)"`` for the asked-for options that
    differ from the recorded ones ("" if none)."""
    out = []
    for key, want in expect.items():
        if want is None:
            continue
        if key == "settings":
            have = recorded.get("settings") or {}
            out += [f"{k} {v!r} (the run's: {have.get(k)!r})" for k, v in want.items() if have.get(k) != v]
        elif recorded.get(key) != want:
            out.append(f"{key} {want!r} (the run's: {recorded.get(key)!r})")
    return ", ".join(out)


def _steppable(algo):
    """A plain callback and a silent display: what the checkpoint stores in place of
    the run's (which hold streams and a progress bar), so that the unpickled
    algorithm can be stepped with ``next()`` as it is."""
    from pymoo.core.callback import Callback
    from pymoo.util.display.display import Display

    return Callback(), Display(getattr(algo, "output", None), verbose=False, progress=False)


def _save_checkpoint(algo, state, out: Path):
    """The algorithm and the runner's state, authenticated (mechopt.run.checkpoint), with a
    header naming the run, so that ``--resume`` can check it before loading it."""
    from mechopt.run import checkpoint as _ck

    header = {"run_id": state.get("run_id"), "problem": algo.problem.name,
              "key": _run_key(algo.problem, algo, state["seed"]), "options": state.get("options"),
              "generation": int(algo.n_gen), "mechopt": __version__}
    callback, display = algo.callback, algo.display
    algo.callback, algo.display = _steppable(algo)
    try:
        _ck.write(out / CHECKPOINT, {"algorithm_state": algo, "state": state}, header)
    finally:
        algo.callback, algo.display = callback, display


def _drive(algo, state, n_jobs, client, out, progress, plot, manifest=None, callback=None) -> RunResult:
    """Advance ``algo`` to its termination, checkpointing on the way; write the outputs.

    ``n_jobs=None`` (without a Dask client): generations 1 and 2 run in this process
    and are timed (CPU time); from generation 3 on, two processes if a generation
    takes :data:`PARALLEL_SECONDS` or more."""
    problem = algo.problem
    auto = n_jobs is None and client is None
    used = 1 if n_jobs is None else n_jobs
    problem.use_parallel(used, client)
    total = state.get("gen")
    label = f"{problem.name} {state['algorithm']}"
    bar = Progress(total if total is not None else 100, label) if progress else None
    hist = _History(problem, bar, total, callback)
    hist.rows = state["rows"]
    algo.callback = hist
    if algo.display is None:
        algo.display = _steppable(algo)[1]
    every = state["checkpoint_every"]
    timed, per_gen = [], None
    t0 = time.perf_counter() - state["elapsed"]
    try:
        while algo.has_next():
            c_gen, n_gen = time.process_time(), algo.evaluator.n_eval
            algo.next()
            state["elapsed"] = time.perf_counter() - t0
            if auto and len(timed) < 2:
                # CPU time of this process (all the evaluation, with one process): a
                # loaded machine does not make a cheap problem look expensive
                timed.append((time.process_time() - c_gen, algo.evaluator.n_eval - n_gen))
                # the cheaper of the two per evaluation (the first may pay for imports
                # and compilation), for a generation's number of evaluations
                per_gen = min(t / max(n, 1) for t, n in timed) * timed[-1][1]
                if len(timed) == 2 and per_gen >= PARALLEL_SECONDS and (os.cpu_count() or 1) >= 2:
                    used = 2
                    problem.use_parallel(used, None)
            if every and algo.n_gen % every == 0 and algo.has_next():
                _save_checkpoint(algo, state, out)
                _io.own(out, manifest, CHECKPOINT)
        res = algo.result()
        best = _optimum(algo)
    finally:
        problem.use_parallel(1, None)
        algo.callback, algo.display = _steppable(algo)
        if bar is not None:
            bar.close()
    wall = time.perf_counter() - t0
    X = best.get("X") if best is not None else np.empty((0, problem.n_var))
    feas = best.get("FEAS")[:, 0] if best is not None else np.zeros(0, bool)
    population = _population_table(problem, res.pop)
    info = _run_info(problem, algo, state, used, client, wall)
    info["n_jobs_auto"] = auto
    if auto and per_gen is not None:
        info["seconds_per_generation"] = round(per_gen, 4)
    info["generations"] = int(hist.rows[-1]["generation"]) if hist.rows else 0
    info["evaluations"] = int(algo.evaluator.n_eval)
    info["feasible"] = int(res.pop.get("FEAS")[:, 0].sum()) if feas.any() else 0
    least = None
    if feas.any():
        front = _front_table(problem, X[feas])
    else:  # nothing feasible: an empty front with its full header, and how far the best design is
        least = _least_violating(problem, population)
        front = least.iloc[:0]
        info.update(_violation_info(problem, least))
    history = pd.DataFrame(hist.rows)
    if out is not None:
        with _io.output_set(out, manifest) as stage:
            _io.write_csv(front, stage / "front.csv")
            _io.write_csv(history, stage / "history.csv")
            _io.write_json(info, stage / "run.json")
            if plot:
                from mechopt.run.plotting import plot_front

                _io.save_figure(plot_front(problem, front, history, population, info), stage / "front.png")
        if os.path.isfile(out / CHECKPOINT) and not os.path.islink(out / CHECKPOINT):
            (out / CHECKPOINT).unlink()  # the run is complete: nothing to resume
    return RunResult(front, history, info, population, least, res)


def _population_table(problem, pop) -> pd.DataFrame:
    """The final population from pymoo's stored values (no re-evaluation)."""
    X, F, CV = pop.get("X"), pop.get("F"), pop.get("CV")
    cols = {name: X[:, i] for i, name in enumerate(problem.var_names)}
    for j, ob in enumerate(problem.objectives):
        cols[ob.name] = ob.sense * F[:, j]
    if problem.n_ieq_constr:
        G = pop.get("G")
        for j, name in enumerate(problem.constr_names):
            cols[f"g_{name}"] = G[:, j]
    cols["violation"] = np.asarray(CV, float).reshape(len(X), -1)[:, 0] if len(X) else np.zeros(0)
    return pd.DataFrame(cols)


def _least_violating(problem, population) -> pd.DataFrame:
    """``describe`` of the design with the smallest total violation (first of ties)."""
    cv = np.where(np.isnan(population["violation"].to_numpy()), np.inf, population["violation"].to_numpy())
    x = population[list(problem.var_names)].to_numpy()[int(np.argmin(cv))]
    return pd.DataFrame(problem.describe(x[None, :]))


def _violation_info(problem, least: pd.DataFrame) -> dict:
    """run.json keys of an infeasible run: the least-violating design, its violation
    per constraint (``g_*``: max(0, g)) and in total (their sum)."""
    row = least.iloc[0]
    per = {f"g_{n}": max(0.0, float(row[f"g_{n}"])) for n in problem.constr_names}
    return {"least_violation": float(sum(per.values())),
            "least_violating_design": {n: float(row[n]) for n in problem.var_names},
            "constraint_violations": per}


def infeasible_line(info: dict) -> str | None:
    """``no feasible design in N evaluations; least violation V at r1=..., r3=...``
    for a run (or a sweep) that found no feasible design, else None.

    Parameters
    ----------
    info : dict
        run.json's content.

    Returns
    -------
    str or None
        The line.
    """
    if info.get("feasible", 1) or "least_violation" not in info:
        return None
    design = ", ".join(f"{k}={v:.6g}" for k, v in info["least_violating_design"].items())
    return (f"no feasible design in {info['evaluations']} evaluations; "
            f"least violation {info['least_violation']:.6g} at {design}")


def _run_info(problem, algo, state, n_jobs, client, wall) -> dict:
    import pymoo

    return {
        "problem": problem.name,
        "summary": problem.summary,
        "settings": dict(problem.settings),
        "single_optimum": problem.single_optimum,
        "algorithm": {"name": state["algorithm"], "pop": state["pop"], "gen": state["gen"]},
        "algorithm_settings": describe_algorithm(algo),
        "termination": describe_termination(algo.termination),
        "seed": state["seed"],
        "n_jobs": n_jobs,
        "backend": "dask" if client is not None else "joblib",
        "versions": {"mechopt": __version__, "pymoo": pymoo.__version__, "numpy": np.__version__},
        "wall_time_s": round(wall, 3),
    }


#: sweep weights are checked where every input is (:func:`mechopt.core.validation.weights`)
parse_weights = _v.weights


def sweep(problem, weights, pop=None, gen=None, seed: int = 1, n_jobs: int | None = None, client=None,
          out=None, progress: bool = True, tol: float | None = None, crossover_prob: float | None = None,
          mutation_prob: float | None = None, crossover_eta: float | None = None,
          mutation_eta: float | None = None, overwrite: bool = False) -> pd.DataFrame:
    """Weighted-sum optima of a 2-objective problem for each weight ``w`` of objective 1.

    The objectives are scaled by the span of the NSGA-II front of the same seed
    (``Z = w f1/s1 + (1 - w) f2/s2`` in minimisation form), unless the problem
    defines ``weighted_sum(w)`` itself (e.g. Stan 2008's ``Z = W1 T + W2 W``).
    Writes ``sweep.csv``, ``sweep.png`` and the front run's ``front.csv``,
    ``history.csv``, ``run.json`` and ``front.png`` when ``out``, as one set with a
    manifest (``overwrite`` as in :func:`optimize`).
    ``tol`` and the operator settings apply to every run (see :func:`optimize`).

    A weight whose GA run finds no feasible design has ``feasible`` False, NaN
    objectives and its least-violating design with its ``violation``; the totals
    (``table.attrs["sweep"]``, also under ``"sweep"`` in ``run.json``) say how many
    weights are feasible and, if none and the front is empty, the least violation.

    Parameters
    ----------
    problem : str or Problem
        A 2-objective problem, by name or instance.
    weights : sequence of float
        Weights of objective 1, each in [0, 1].
    pop, gen : int, optional
        Population size and generations of every run.
    seed : int
        Random seed.
    n_jobs : int, optional
        Worker processes.
    client : dask.distributed.Client, optional
        Evaluate on a Dask cluster.
    out : str or Path, optional
        Output folder.
    progress : bool
        Log the progress.
    tol : float, optional
        pymoo's default termination with ``ftol=tol``.
    crossover_prob, mutation_prob, crossover_eta, mutation_eta : float, optional
        Operator settings (:func:`make_algorithm`).
    overwrite : bool
        Replace another run that ``out`` holds.

    Returns
    -------
    DataFrame
        sweep.csv: one row per weight (``weight``, ``z``, the variables, objectives in
        their natural sign, ``feasible``, ``violation``, ``g_*``); ``attrs["sweep"]``
        holds the totals.

    Raises
    ------
    ValueError
        One line, for a problem without two objectives, invalid weights or options,
        or a folder holding another run.
    """
    if problem.n_obj != 2:
        raise ValueError(f"sweep needs a 2-objective problem, {problem.name} has {problem.n_obj}")
    try:  # every input is checked before the first run writes into out
        weights = [_v.finite_number("weights", w) for w in weights]
    except TypeError:
        raise ValueError(f"weights must be a sequence of numbers in [0, 1], got {_v.show(weights)}") from None
    if not weights or not all(0.0 <= w <= 1.0 for w in weights):
        raise ValueError(f"weights must be numbers in [0, 1], got {_v.show(weights)}")
    if len(weights) > _v.MAX_WEIGHTS:
        raise ValueError(f"a sweep takes at most {_v.MAX_WEIGHTS} weights, got {len(weights)}")
    _check_sizes(problem.default_pop if pop is None else pop, problem.default_gen if gen is None else gen)
    _v.integer("seed", seed, 0)
    _n_jobs(n_jobs)
    run_kw = dict(tol=tol, crossover_prob=crossover_prob, mutation_prob=mutation_prob,
                  crossover_eta=crossover_eta, mutation_eta=mutation_eta)
    make_algorithm("nsga2", 2, 2, **{k: v for k, v in run_kw.items() if k != "tol"})  # checks them
    term = _termination(problem, None, gen, tol)
    _check_sweep_budget(problem, len(weights) + 1, problem.default_pop if pop is None else pop,
                        _max_gen(term))
    if out is None:
        return _sweep(problem, weights, pop, gen, seed, n_jobs, client, None, progress, run_kw, None)
    out = _io.prepare_out_dir(out)
    key = {"problem": problem.name, "settings": dict(problem.settings), "weights": weights,
           "pop": pop, "gen": gen, "seed": seed, **run_kw}
    with _io.run_in(out, "sweep", key, RUN_OUTPUTS, overwrite) as manifest:
        return _sweep(problem, weights, pop, gen, seed, n_jobs, client, out, progress, run_kw, manifest)


def _check_sweep_budget(problem, n_runs: int, pop: int, max_gen: int | None):
    """The sweep's ``n_runs`` runs (the NSGA-II front and one per weight) budgeted as a
    whole (:mod:`mechopt.run.budget`): refused if together they cannot fit in memory or
    would take longer than 30 days; a line printed if above an hour."""
    import sys

    from mechopt.run import budget

    if max_gen is None:
        return None
    one = budget.estimate(problem, int(pop), int(pop), int(max_gen))
    total = budget.Estimate(one.memory_bytes, one.seconds * n_runs, one.evaluations * n_runs,
                            one.seconds_per_evaluation)
    try:
        line = budget.check(total)
    except ValueError as exc:
        raise ValueError(f"the sweep ({n_runs} runs): {exc}") from None
    if line:
        line = f"{line} (the whole sweep: {n_runs} runs)"
        print(line, file=sys.stderr)
    return line


def _sweep(problem, weights, pop, gen, seed, n_jobs, client, out, progress, run_kw, manifest):
    """The runs of :func:`sweep` (its inputs checked) and, with ``out``, its files."""
    from mechopt.run.weighted import WeightedSum  # noqa: F401 (installed sub-package)

    front_run = optimize(problem, "nsga2", pop, gen, seed, n_jobs, client, None, progress, plot=False, **run_kw)
    F = np.column_stack([ob.sense * front_run.front[ob.name].to_numpy(float) for ob in problem.objectives])
    scales = np.ptp(F, axis=0) if len(F) > 1 else np.ones(2)
    scales = np.where(scales > 0, scales, 1.0)
    rows, columns = [], None
    runs = [front_run]
    bar = Progress(len(weights), f"{problem.name} sweep") if progress else None
    for i, w in enumerate(weights):
        single = WeightedSum(problem, float(w), scales)
        r = optimize(single, "ga", pop, gen, seed, n_jobs, client, None, progress=False, plot=False, **run_kw)
        runs.append(r)
        # the sweep's own total violation is the last column; a problem column of that
        # name (Le 2013's, the same value as its g_violation) is not written twice
        columns = columns or [c for c in r.front.columns if c != "violation"]
        if len(r.front):
            rows.append({"weight": float(w), **r.front.iloc[0].to_dict(), "feasible": True, "violation": 0.0})
        else:  # no feasible design for this weight: no optimum, only the least-violating design
            keep = list(problem.var_names) + [f"g_{n}" for n in problem.constr_names]
            rows.append({"weight": float(w), **r.least.iloc[0][keep].to_dict(), "feasible": False,
                         "violation": r.info["least_violation"]})
        if bar is not None:
            bar.update(i + 1, f"w={w:.3g}")
    if bar is not None:
        bar.close()
    table = pd.DataFrame(rows).reindex(columns=["weight", *columns, "feasible", "violation"])
    table.attrs["sweep"] = info = _sweep_info(problem, runs, table)
    if out is not None:
        from mechopt.run.plotting import plot_front, plot_sweep

        keep = [*problem.var_names, "violation"]  # every run's final population, for the figure
        population = pd.concat([r.population[keep] for r in runs], ignore_index=True)
        with _io.output_set(out, manifest) as stage:
            _io.write_csv(front_run.front, stage / "front.csv")
            _io.write_csv(front_run.history, stage / "history.csv")
            _io.write_csv(table, stage / "sweep.csv")
            _io.write_json({**front_run.info, "sweep": info}, stage / "run.json")
            _io.save_figure(plot_sweep(problem, front_run.front, table, population, info), stage / "sweep.png")
            _io.save_figure(plot_front(problem, front_run.front, front_run.history, front_run.population,
                                       front_run.info), stage / "front.png")
    return table


def _sweep_info(problem, runs, table) -> dict:
    """The sweep as a whole: weights, how many have a feasible optimum, evaluations and
    feasible designs (in the final populations) of every run (the NSGA-II front and
    each weight); with no feasible design anywhere, the least-violating design over
    all of them."""
    info = {"weights": [float(w) for w in table["weight"]],
            "feasible_weights": int(table["feasible"].sum()),
            "evaluations": int(sum(r.info["evaluations"] for r in runs)),
            "feasible": int(sum(r.info["feasible"] for r in runs))}
    if info["feasible"] == 0:
        best = min(runs, key=lambda r: r.info["least_violation"])
        info.update({k: best.info[k] for k in ("least_violation", "least_violating_design",
                                              "constraint_violations")})
    return info
