"""One seeded runner for every Problem: ``optimize`` and weighted-sum ``sweep``.

Population evaluation goes through the Problem's chunked
:func:`mechopt.parallel.parallel_map` (joblib or Dask), so the same seed gives
the same front for any ``n_jobs`` and either backend. Outputs go through
:mod:`mechopt.io` (atomic writes):

``front.csv``    one row per non-dominated feasible design (variables, objectives
                 with their natural sign, constraint values, derived indices)
``history.csv``  per generation: evaluations, best objective values, hypervolume
``run.json``     problem, algorithm and parameters, seed, versions, wall time,
                 ``feasible`` (feasible designs in the final population) and
                 ``evaluations``
``front.png``    the front (or the convergence curve of a single objective)

A run may end without any feasible design (a small budget, a demanding
requirement). That is an answer, not an error: ``front.csv`` keeps its header
and has no rows, ``run.json`` has ``"feasible": 0`` and the least-violating
design of the final population (``least_violating_design``, its
``least_violation`` = sum of max(0, g) and ``constraint_violations`` per
``g_*`` column), and ``front.png`` shows the population coloured by constraint
violation; :func:`infeasible_line` is the one-line summary the CLI prints.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd

from . import __version__
from . import io as _io
from . import validation as _v
from .progress import Progress

__all__ = ["ALGORITHMS", "make_algorithm", "optimize", "resume", "sweep", "parse_weights", "RunResult",
           "infeasible_line"]

ALGORITHMS = ("ga", "nsga2", "nsga3")


def make_algorithm(name: str, pop: int, n_obj: int):
    """A pymoo algorithm by name with population ``pop`` (NSGA-III: Das-Dennis
    reference directions, as many partitions as fit in ``pop``)."""
    _v.choice("algorithm", name, ALGORITHMS)
    pop = _v.integer("pop", pop, 2, MAX_POP)
    if name == "nsga3" and n_obj < 2:
        raise ValueError(f"algorithm 'nsga3' needs at least 2 objectives, the problem has {n_obj}")
    if name == "ga":
        if n_obj != 1:
            raise ValueError(f"algorithm 'ga' needs a single objective, the problem has {n_obj}")
        from pymoo.algorithms.soo.nonconvex.ga import GA

        return GA(pop_size=pop, eliminate_duplicates=True)
    if name == "nsga2":
        from pymoo.algorithms.moo.nsga2 import NSGA2

        return NSGA2(pop_size=pop)
    from pymoo.algorithms.moo.nsga3 import NSGA3
    from pymoo.util.ref_dirs import get_reference_directions

    from math import comb

    p = 1
    while comb(p + 1 + n_obj - 1, n_obj - 1) <= pop:
        p += 1
    ref = get_reference_directions("das-dennis", n_obj, n_partitions=p)
    return NSGA3(ref_dirs=ref, pop_size=pop)


@dataclass
class RunResult:
    front: pd.DataFrame
    history: pd.DataFrame
    info: dict
    #: the final population: variables, objectives (natural sign), ``g_*`` and
    #: ``violation`` (sum of max(0, g), pymoo's CV)
    population: pd.DataFrame | None = None
    #: ``describe`` row (one-row table) of the least-violating design when no
    #: design is feasible, else None
    least: pd.DataFrame | None = None


#: largest population and number of generations accepted (a typo such as
#: ``--pop 100000000000`` would otherwise exhaust memory or never end)
MAX_POP = MAX_GEN = 1_000_000


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


class _History:
    """pymoo callback: one history row per generation, and the progress line."""

    def __init__(self, problem, progress: Progress | None):
        self.problem, self.progress, self.rows, self.ref = problem, progress, [], None

    def __call__(self, algorithm):
        F = algorithm.opt.get("F")
        feas = algorithm.opt.get("FEAS")[:, 0]
        row = {"generation": algorithm.n_gen, "evaluations": algorithm.evaluator.n_eval,
               "n_front": int(len(F))}
        sense = np.array([ob.sense for ob in self.problem.objectives])
        info = ""
        for j, ob in enumerate(self.problem.objectives):
            best = (F[:, j].min() if len(F) else np.nan) * ob.sense
            row[f"best_{ob.name}"] = float(best) if feas.any() else np.nan
        if 2 <= F.shape[1] <= 3:
            if self.ref is None:
                pf = algorithm.pop.get("F")
                lo, hi = pf.min(axis=0), pf.max(axis=0)
                self.ref = hi + 0.1 * np.maximum(hi - lo, 1e-12)
            from pymoo.indicators.hv import HV

            row["hypervolume"] = float(HV(ref_point=self.ref)(F[feas])) if feas.any() else 0.0
            info = f"hv {row['hypervolume']:.5g}"
        elif F.shape[1] == 1:
            info = f"best {self.problem.objectives[0].name} {row[f'best_{self.problem.objectives[0].name}']:.6g}"
        self.rows.append(row)
        if self.progress is not None:
            self.progress.update(algorithm.n_gen, info)


def _front_table(problem, X) -> pd.DataFrame:
    df = pd.DataFrame(problem.describe(X))
    keys = [ob.name for ob in problem.objectives] + list(problem.var_names)
    return df.sort_values(keys, kind="mergesort").reset_index(drop=True)


CHECKPOINT = "checkpoint.pkl"


def optimize(problem, algorithm: str | None = None, pop: int | None = None, gen: int | None = None,
             seed: int = 1, n_jobs: int = 2, client=None, out=None, progress: bool = True,
             plot: bool = True, checkpoint_every: int | None = None) -> RunResult:
    """Run ``problem`` with a seeded pymoo algorithm; write the run folder if ``out``.

    With ``checkpoint_every=K`` (needs ``out``) the whole algorithm state (population,
    random generator, history) is pickled atomically to ``out/checkpoint.pkl`` every
    K generations; :func:`resume` continues from it and ends with the same
    ``front.csv``, byte for byte, as an uninterrupted run.
    """
    algorithm = algorithm or problem.default_algorithm
    pop, gen = _check_sizes(problem.default_pop if pop is None else pop,
                            problem.default_gen if gen is None else gen)
    seed = _v.integer("seed", seed, 0)
    n_jobs = _v.integer("n_jobs", n_jobs, 1)
    if checkpoint_every is not None:
        checkpoint_every = int(_v.finite_number("checkpoint_every", checkpoint_every))
        if checkpoint_every < 1:
            raise ValueError(f"checkpoint_every must be a positive integer, got {checkpoint_every}")
        if out is None:
            raise ValueError("checkpoint_every needs an output folder (--out)")
    algo = make_algorithm(algorithm, pop, problem.n_obj)
    out = _io.prepare_out_dir(out) if out is not None else None
    algo.setup(problem, termination=("n_gen", gen), seed=seed, verbose=False)
    state = {"algorithm": algorithm, "pop": pop, "gen": gen, "seed": seed, "rows": [], "ref": None,
             "elapsed": 0.0, "checkpoint_every": checkpoint_every}
    return _drive(algo, state, n_jobs, client, out, progress, plot)


def resume(out, n_jobs: int = 2, client=None, progress: bool = True, plot: bool = True) -> RunResult:
    """Continue the run whose checkpoint is ``out/checkpoint.pkl`` (see :func:`optimize`)."""
    import pickle

    path = Path(out) / CHECKPOINT
    try:
        with open(path, "rb") as fh:
            ck = pickle.load(fh)
        algo, state = ck["algorithm_state"], ck["state"]
        if not (hasattr(algo, "has_next") and hasattr(algo, "problem") and isinstance(state, dict)):
            raise TypeError("not a mechopt checkpoint")
    except FileNotFoundError:
        raise ValueError(f"--resume {str(out)!r} holds no {CHECKPOINT}") from None
    except (OSError, pickle.UnpicklingError, EOFError, KeyError, AttributeError, TypeError,
            ValueError, ImportError, IndexError) as exc:  # ImportError: written by another version
        raise ValueError(f"--resume {str(out)!r}: unreadable {CHECKPOINT} ({type(exc).__name__})") from None
    return _drive(algo, state, n_jobs, client, Path(out), progress, plot)


def _save_checkpoint(algo, state, out: Path):
    import pickle

    # cloudpickle (a joblib dependency) because pymoo's algorithms hold local
    # functions (its random-state decorator) that plain pickle refuses; the file
    # loads with plain pickle
    import cloudpickle

    callback, display = algo.callback, algo.display
    algo.callback, algo.display = None, None  # hold streams and a progress bar
    try:
        with _io.atomic_path(out / CHECKPOINT) as tmp, open(tmp, "wb") as fh:
            cloudpickle.dump({"algorithm_state": algo, "state": state}, fh, protocol=pickle.HIGHEST_PROTOCOL)
    finally:
        algo.callback, algo.display = callback, display


def _drive(algo, state, n_jobs, client, out, progress, plot) -> RunResult:
    """Advance ``algo`` to its termination, checkpointing on the way; write the outputs."""
    from pymoo.core.callback import Callback
    from pymoo.util.display.display import Display

    problem = algo.problem
    problem.use_parallel(n_jobs, client)
    bar = Progress(state["gen"], f"{problem.name} {state['algorithm']}") if progress else None
    hist = _History(problem, bar)
    hist.rows, hist.ref = state["rows"], state["ref"]
    algo.callback = hist
    if algo.display is None:
        algo.display = Display(algo.output, verbose=False, progress=False)
    every = state["checkpoint_every"]
    t0 = time.perf_counter() - state["elapsed"]
    try:
        while algo.has_next():
            algo.next()
            state["ref"], state["elapsed"] = hist.ref, time.perf_counter() - t0
            if every and algo.n_gen % every == 0 and algo.has_next():
                _save_checkpoint(algo, state, out)
        res = algo.result()
    finally:
        problem.use_parallel(1, None)
        algo.callback = Callback()
        if bar is not None:
            bar.close()
    wall = time.perf_counter() - t0
    X = res.opt.get("X") if res.opt is not None else np.empty((0, problem.n_var))
    feas = res.opt.get("FEAS")[:, 0] if res.opt is not None else np.zeros(0, bool)
    population = _population_table(problem, res.pop)
    info = _run_info(problem, state["algorithm"], state["pop"], state["gen"], state["seed"], n_jobs,
                     client, wall)
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
        _io.write_csv(front, out / "front.csv")
        _io.write_csv(history, out / "history.csv")
        _io.write_json(info, out / "run.json")
        if plot:
            from .plotting import plot_front

            _io.save_figure(plot_front(problem, front, history, population, info), out / "front.png")
        if (out / CHECKPOINT).exists():
            (out / CHECKPOINT).unlink()  # the run is complete: nothing to resume
    return RunResult(front, history, info, population, least)


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
    for a run (or a sweep) that found no feasible design, else None."""
    if info.get("feasible", 1) or "least_violation" not in info:
        return None
    design = ", ".join(f"{k}={v:.6g}" for k, v in info["least_violating_design"].items())
    return (f"no feasible design in {info['evaluations']} evaluations; "
            f"least violation {info['least_violation']:.6g} at {design}")


def _run_info(problem, algorithm, pop, gen, seed, n_jobs, client, wall) -> dict:
    import pymoo

    return {
        "problem": problem.name,
        "summary": problem.summary,
        "settings": dict(problem.settings),
        "single_optimum": problem.single_optimum,
        "algorithm": {"name": algorithm, "pop": pop, "gen": gen},
        "seed": seed,
        "n_jobs": n_jobs,
        "backend": "dask" if client is not None else "joblib",
        "versions": {"mechopt": __version__, "pymoo": pymoo.__version__, "numpy": np.__version__},
        "wall_time_s": round(wall, 3),
    }


#: sweep weights are checked where every input is (:func:`mechopt.validation.weights`)
parse_weights = _v.weights


def sweep(problem, weights, pop=None, gen=None, seed: int = 1, n_jobs: int = 2, client=None,
          out=None, progress: bool = True) -> pd.DataFrame:
    """Weighted-sum optima of a 2-objective problem for each weight ``w`` of objective 1.

    The objectives are scaled by the span of the NSGA-II front of the same seed
    (``Z = w f1/s1 + (1 - w) f2/s2`` in minimisation form), unless the problem
    defines ``weighted_sum(w)`` itself (e.g. Stan 2008's ``Z = W1 T + W2 W``).
    Writes ``sweep.csv``, the front run's files and ``sweep.png`` when ``out``.

    A weight whose GA run finds no feasible design has ``feasible`` False, NaN
    objectives and its least-violating design with its ``violation``; the totals
    (``table.attrs["sweep"]``, also under ``"sweep"`` in ``run.json``) say how many
    weights are feasible and, if none and the front is empty, the least violation.
    """
    from .problems.weighted import WeightedSum  # noqa: F401 (installed sub-package)

    if problem.n_obj != 2:
        raise ValueError(f"sweep needs a 2-objective problem, {problem.name} has {problem.n_obj}")
    try:  # every input is checked before the first run writes into out
        weights = [_v.finite_number("weights", w) for w in weights]
    except TypeError:
        raise ValueError(f"weights must be a sequence of numbers in [0, 1], got {_v.show(weights)}") from None
    if not weights or not all(0.0 <= w <= 1.0 for w in weights):
        raise ValueError(f"weights must be numbers in [0, 1], got {_v.show(weights)}")
    _check_sizes(problem.default_pop if pop is None else pop, problem.default_gen if gen is None else gen)
    _v.integer("seed", seed, 0)
    _v.integer("n_jobs", n_jobs, 1)
    out = _io.prepare_out_dir(out) if out is not None else None
    front_run = optimize(problem, "nsga2", pop, gen, seed, n_jobs, client, out, progress, plot=False)
    F = np.column_stack([ob.sense * front_run.front[ob.name].to_numpy(float) for ob in problem.objectives])
    scales = np.ptp(F, axis=0) if len(F) > 1 else np.ones(2)
    scales = np.where(scales > 0, scales, 1.0)
    rows, columns = [], None
    runs = [front_run]
    bar = Progress(len(weights), f"{problem.name} sweep") if progress else None
    for i, w in enumerate(weights):
        single = WeightedSum(problem, float(w), scales)
        r = optimize(single, "ga", pop, gen, seed, n_jobs, client, None, progress=False, plot=False)
        runs.append(r)
        columns = columns or list(r.front.columns)
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
        from .plotting import plot_sweep

        _io.write_csv(table, out / "sweep.csv")
        _io.write_json({**front_run.info, "sweep": info}, out / "run.json")
        keep = [*problem.var_names, "violation"]  # every run's final population, for the figure
        population = pd.concat([r.population[keep] for r in runs], ignore_index=True)
        _io.save_figure(plot_sweep(problem, front_run.front, table, population, info), out / "sweep.png")
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
