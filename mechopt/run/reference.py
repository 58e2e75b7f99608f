"""Brute-force reference fronts of problems with one or two design variables.

A lattice over the bounds, refined around the edges of its Pareto set, then the
feasible non-dominated designs of every evaluation (details in
:func:`reference_front`). :meth:`mechopt.run.problem.MechoptProblem.pareto_front`
returns its ``F`` (computed on demand, kept by the problem instance), and
``benchmarks/bench_fronts.py`` measures every default run against it
(:func:`compare`: IGD+ and the hypervolume ratio in objectives normalised by the
reference front).
"""
from __future__ import annotations

import itertools
import time

import numpy as np

from mechopt.run.parallel import chunks, parallel_map

__all__ = ["reference_front", "nondominated", "normalisation", "compare", "FULL", "QUICK",
           "SO_TOP", "SO_REFINE", "SO_LEVELS", "MAX_CENTRES"]

#: full and quick lattices by number of variables: (points per variable, refinement
#: factor, levels of refinement)
FULL = {1: (2001, 10, 1), 2: (161, 6, 2)}
QUICK = {1: (201, 8, 1), 2: (41, 4, 1)}
#: one objective: zoom levels around the best ``SO_TOP`` designs, each ``SO_REFINE``
#: times finer (the optimum to ``step / SO_REFINE ** SO_LEVELS``)
SO_TOP, SO_REFINE, SO_LEVELS = 10, 4, 6
#: most refinement centres per level (taken evenly from the front, sorted)
MAX_CENTRES = 400


def _eval_chunk(args):
    problem, X = args
    res = problem.evaluate_designs(X)
    G = res.get("G")
    feasible = np.all(G <= 0, axis=1) if G is not None and G.shape[1] else np.ones(len(X), bool)
    return res["F"], feasible


def _evaluate(problem, X, n_jobs):
    """``(F, feasible)`` of designs ``X`` (minimisation form), in ``n_jobs`` processes."""
    if len(X) == 0:
        return np.empty((0, problem.n_obj)), np.zeros(0, bool)
    parts = parallel_map(_eval_chunk, [(problem, c) for c in chunks(X, max(1, 8 * n_jobs))],
                         n_jobs=n_jobs)
    return np.concatenate([p[0] for p in parts]), np.concatenate([p[1] for p in parts])


def nondominated(F) -> np.ndarray:
    """Mask of the rows of ``F`` (minimisation form) that no other row dominates
    (duplicates: the first kept), by ``moocore.is_nondominated`` (a pymoo dependency).

    Parameters
    ----------
    F : array_like, shape (n, n_obj)
        Objective vectors.

    Returns
    -------
    numpy.ndarray of bool, shape (n,)
    """
    import moocore

    F = np.asarray(F, float)
    if len(F) == 0:
        return np.zeros(0, bool)
    return np.asarray(moocore.is_nondominated(F, keep_weakly=False), bool)


def _lattice(xl, xu, n):
    return [np.linspace(a, b, n) for a, b in zip(xl, xu)]


def _front_mask(F, feasible, n_obj, top=1):
    """Designs on the front: non-dominated feasible ones (the ``top`` best for one objective)."""
    mask = np.zeros(len(F), bool)
    idx = np.flatnonzero(feasible)
    if not len(idx):
        return mask
    if n_obj == 1:
        order = idx[np.argsort(F[idx, 0], kind="stable")]
        mask[order[:top]] = True
    else:
        mask[idx[nondominated(F[idx])]] = True
    return mask


def _edge_points(X, front, h):
    """Of the front designs ``X[front]``, those with a lattice neighbour (spacing ``h``,
    among the evaluated designs) that is off the front; with none evaluated, kept."""
    keys = {tuple(k): bool(f) for k, f in zip(np.round(X / h).astype(np.int64), front)}
    d = X.shape[1]
    offs = [o for o in itertools.product((-1, 0, 1), repeat=d) if any(o)]
    out = []
    for x in X[front]:
        k = np.round(x / h).astype(np.int64)
        out.append(any(not keys.get(tuple(k + o), True) for o in offs))
    return np.array(out, bool)


def reference_front(problem, grid=None, refine=None, levels=None, n_jobs: int = 1, quick: bool = False,
                    log=None) -> dict:
    """Brute-force reference front of ``problem`` (a :class:`~mechopt.run.problem.MechoptProblem`
    with at most two variables), from its own ``evaluate_designs``:

    1. a lattice over the bounds: 2001 points for one variable, 161 x 161 for two
       (``quick``: 201, 41 x 41);
    2. refinement: a lattice 10 (two variables: 6; quick: 8, 4) times finer in the
       cells around every non-dominated feasible lattice point that has a neighbour
       off the front (the edges of the Pareto set in design space), at most
       :data:`MAX_CENTRES` of them, evenly; once for one variable, twice for two
       (quick: once);
    3. the feasible non-dominated designs of all evaluations, one per objective vector.

    A single-objective problem's "front" is its best feasible design; the refinement
    zooms :data:`SO_LEVELS` times, :data:`SO_REFINE` times finer each, around the best
    :data:`SO_TOP` designs instead.

    Parameters
    ----------
    problem : MechoptProblem
        The problem (picklable: with ``n_jobs > 1`` it travels to the workers).
    grid, refine, levels : int, optional
        Points per variable, refinement factor and levels (defaults above).
    n_jobs : int
        Worker processes (:func:`mechopt.run.parallel.parallel_map`).
    quick : bool
        The coarse defaults.
    log : callable, optional
        ``log(message)`` for each refinement level.

    Returns
    -------
    dict
        ``X`` (designs), ``F`` (their objectives, minimisation form), ``evaluations``
        and ``seconds``.

    Raises
    ------
    ValueError
        For a problem with more than two variables.
    """
    p = problem
    d = p.n_var
    if d > 2:
        raise ValueError(f"{p.name} has {d} design variables; the brute force covers at most 2")
    g0, k0, l0 = (QUICK if quick else FULL)[d]
    if p.n_obj == 1:
        k0, l0 = SO_REFINE, SO_LEVELS
    grid, refine, levels = grid or g0, refine or k0, l0 if levels is None else levels
    t0 = time.perf_counter()
    axes = _lattice(p.xl, p.xu, grid)
    step = (p.xu - p.xl) / (grid - 1)
    X = np.array(list(itertools.product(*axes)), float)
    F, feas = _evaluate(p, X, n_jobs)
    seen = {tuple(np.round((x - p.xl) / step * refine ** levels).astype(np.int64)) for x in X}
    for level in range(1, levels + 1):
        front = _front_mask(F, feas, p.n_obj, top=SO_TOP)
        centres = X[front]
        if p.n_obj > 1:  # only the edges of the Pareto set: a front point with a neighbour off it
            centres = centres[_edge_points(X, front, step / refine ** (level - 1))]
            if len(centres) > MAX_CENTRES:
                order = np.lexsort(centres.T[::-1])
                centres = centres[order[np.linspace(0, len(centres) - 1, MAX_CENTRES).round().astype(int)]]
        fine = step / refine ** level
        offs = np.array(list(itertools.product(range(-refine, refine + 1), repeat=d)), float) * fine
        cand = (centres[:, None, :] + offs[None, :, :]).reshape(-1, d)
        cand = np.clip(cand, p.xl, p.xu)
        keys = np.round((cand - p.xl) / step * refine ** levels).astype(np.int64)
        new = []
        for x, key in zip(cand, map(tuple, keys)):
            if key not in seen:
                seen.add(key)
                new.append(x)
        if log:
            log(f"  {p.name}: level {level}: {len(centres)} centres, {len(new)} new designs")
        if not new:
            break
        Xn = np.array(new)
        Fn, fn = _evaluate(p, Xn, n_jobs)
        X, F, feas = np.vstack([X, Xn]), np.vstack([F, Fn]), np.concatenate([feas, fn])
    front = _front_mask(F, feas, p.n_obj, top=1)
    Xf, Ff = X[front], F[front]
    if p.n_obj > 1:  # one design per objective vector
        _, first = np.unique(np.round(Ff, 12), axis=0, return_index=True)
        Xf, Ff = Xf[np.sort(first)], Ff[np.sort(first)]
    return {"X": Xf, "F": Ff, "evaluations": len(X), "seconds": time.perf_counter() - t0}


def normalisation(problem, F_ref):
    """``(ideal, span)`` of the reference front ``F_ref`` (minimisation form); a zero
    span (a single-design front) by the objective's declared range
    (:attr:`mechopt.run.problem.Objective.bounds`, 1 without one).

    Parameters
    ----------
    problem : MechoptProblem
    F_ref : numpy.ndarray, shape (n, n_obj)

    Returns
    -------
    (ideal, span) : tuple of numpy.ndarray
    """
    ideal, nadir = F_ref.min(axis=0), F_ref.max(axis=0)
    span = nadir - ideal
    declared = np.array([1.0 if ob.bounds is None else ob.bounds[1] - ob.bounds[0]
                         for ob in problem.objectives], float)
    span = np.where(span > 1e-12 * np.maximum(1.0, declared), span, declared)
    return ideal, span


def compare(problem, F_ref, F_run) -> dict:
    """IGD+ and the hypervolume ratio (several objectives) or the relative gap (one) of
    ``F_run`` against ``F_ref``, both in minimisation form, normalised by
    :func:`normalisation` (HV reference point 1.1 in every direction).

    Parameters
    ----------
    problem : MechoptProblem
    F_ref, F_run : numpy.ndarray, shape (n, n_obj)

    Returns
    -------
    dict
        ``{"igd_plus", "hv_ratio"}``, or ``{"gap"}`` (``(f_run - f_ref) / |f_ref|``, > 0:
        the run is worse) for one objective.
    """
    if problem.n_obj == 1:
        best, got = float(F_ref[:, 0].min()), float(F_run[:, 0].min()) if len(F_run) else np.inf
        return {"gap": (got - best) / abs(best) if best else got - best}
    from pymoo.indicators.hv import HV
    from pymoo.indicators.igd_plus import IGDPlus

    if not len(F_run):
        return {"igd_plus": np.inf, "hv_ratio": 0.0}
    ideal, span = normalisation(problem, F_ref)
    R, A = (F_ref - ideal) / span, (F_run - ideal) / span
    hv = HV(ref_point=np.full(problem.n_obj, 1.1))
    return {"igd_plus": float(IGDPlus(R)(A)), "hv_ratio": float(hv(A) / hv(R))}
