"""Size a mechanism for a task: the optimisation, its certification and its files.

:func:`design` states the problem of :mod:`mechopt.analysis.design_eval` (a
:class:`~mechopt.analysis.task.Task`, :class:`~mechopt.requirements.Requirements`
and objectives from :func:`mechopt.requirements.objectives`) as
:class:`mechopt.problems.design.DesignProblem`, runs it through
:func:`mechopt.run.runner.optimize`, polishes the front, certifies every front design
with a finer sampling (:func:`~mechopt.analysis.design_eval.certify`) and returns a
:class:`DesignResult` (front as a DataFrame, :meth:`DesignResult.pick`,
:meth:`DesignResult.knee`); with ``out`` it writes :data:`DESIGN_OUTPUTS`.
"""
from __future__ import annotations

import math
import weakref
from dataclasses import asdict, dataclass, field, replace

import numpy as np
import pandas as pd

from mechopt.core import validation as _v
from mechopt.core import indices as _ix
from mechopt.core.numerics import golden_section_max
from mechopt.analysis.design_eval import (DesignEvaluator, NoFeasibleDesign, certify, feasible, knee_index,
                                          parse_pick, pick_index, sensitivity)
from mechopt.analysis.sampling import Sampling
from mechopt.requirements import Requirements
from mechopt.requirements import collisions as _collisions
from mechopt.requirements.singular import Singular

__all__ = ["design", "DesignResult", "plot_design", "json_record", "DESIGN_OUTPUTS", "SEARCH"]

#: the sampling of :func:`design`'s search: the default counts, settling the requirements its
#: samples show comfortably met (:attr:`Sampling.settle`: only the sign of their ``g``
#: reaches the search, and every front design is certified afterwards with every minimum
#: refined); the registered problem alone (``mechopt optimize design``) refines everything
SEARCH = Sampling(settle=True)


@dataclass
class DesignResult:
    """The outcome of :func:`design`.

    Parameters
    ----------
    front : DataFrame
        One row per certified Pareto design (front.csv's columns, :doc:`outputs`).
    info : dict
        run.json's content.
    evaluator : mechopt.analysis.design_eval.DesignEvaluator
        Re-evaluates any design.
    run : mechopt.run.runner.RunResult, optional
        The runner's result.
    chosen_index : int
        The row of ``front`` written as design.json.
    error : mechopt.analysis.design_eval.NoFeasibleDesign, optional
        The error of a run without a feasible design (``front`` empty).
    boxes : dict
        With a tolerance, ``{row of front: its tolerance box}``
        (:func:`mechopt.workflows.certificate.tolerance_box`); empty without.
    """

    front: pd.DataFrame
    info: dict
    evaluator: DesignEvaluator
    run: object = None
    chosen_index: int = 0
    #: the :class:`NoFeasibleDesign` of a run without a feasible design (``front`` empty)
    error: object = None
    #: with a tolerance, each front design's tolerance box
    #: (:func:`mechopt.workflows.certificate.tolerance_box`) by its row in ``front``
    boxes: dict = field(default_factory=dict)

    def _F(self):
        ev = self.evaluator
        return np.column_stack([sense * self.front[o].to_numpy(float) for o, sense in ev.senses().items()])

    def knee(self) -> int:
        """The front's knee (:func:`~mechopt.analysis.design_eval.knee_index`).

        Returns
        -------
        int
            A row of :attr:`front`.
        """
        return knee_index(self._F())

    def pick(self, weights=None) -> dict:
        """The chosen design as a dict (variables, objectives, margins, mechanism):
        the knee without ``weights`` (:func:`~mechopt.analysis.design_eval.knee_index`);
        otherwise, on the objectives normalised to [0, 1] over the front, the design
        minimising the weighted sum (``{"size": 1, "min-lci": 2}`` or
        ``"size=1,min-lci=2"``), or with a prefix ``"asf:size=1,min-lci=2"`` the
        achievement scalarizing function ``max_i Z_i / w_i`` (pymoo's ASF: it reaches
        designs on non-convex parts of a front, which no weighted sum does), or
        ``"pseudo:..."`` the design whose pseudo-weights are nearest (pymoo's
        PseudoWeights, Deb 2001).

        Parameters
        ----------
        weights : dict or str, optional
            ``{objective: weight}`` or ``"name=w,..."``, optionally prefixed ``asf:`` or
            ``pseudo:``; None: the knee.

        Returns
        -------
        dict
            The design record: ``variables``, ``task_placement``, ``objectives``,
            ``margins``, ``constraints_g``, ``feasible``, ``values``, ``tolerance`` and
            ``mechanism`` (the mechanism object), re-certified.
        """
        return self.design_at(pick_index(self._F(), self.evaluator.objectives, weights))

    def design_at(self, i) -> dict:
        """The record of one front design, re-certified.

        Parameters
        ----------
        i : int
            A row of :attr:`front`.

        Returns
        -------
        dict
            As :meth:`pick` returns.
        """
        row = self.front.iloc[int(i)].to_dict()
        v = {k: row[k] for k in (*self.evaluator.spec.lengths, "mode", "task_x", "task_y")}
        if "D" in row:
            v["D"] = row["D"]
        res = certify(self.evaluator, v)
        return _design_record(self.evaluator, v, res, int(i))

    def mechanism(self, weights=None):
        """The chosen mechanism.

        Parameters
        ----------
        weights : dict or str, optional
            As for :meth:`pick`.

        Returns
        -------
        PlanarMechanism
            The mechanism object of the picked design, lengths [L].
        """
        return self.pick(weights)["mechanism"]


def _design_record(ev, v, res, index) -> dict:
    rec = {"index": index, "mechanism_name": ev.spec.name, "unit": ev.unit,
           "variables": {k: v[k] for k in (*ev.spec.lengths, "mode")},
           "task_placement": {"task_x": v["task_x"], "task_y": v["task_y"]},
           "objectives": dict(zip(ev.objectives, ev.objective_values(res))),
           "objective_units": ev.units(),
           "margins": dict(res["margin"]), "constraints_g": dict(res["g"]),
           "feasible": res.get("feasible", feasible(res["g"].values())),
           "values": dict(res["values"]), "tolerance": res.get("tolerance", {}),
           "mechanism": res["mechanism"], "repr": repr(res["mechanism"])}
    if "D" in v:
        rec["variables"]["D"] = v["D"]
    rec.update(ev.record(res["derived"]))
    return rec


def json_record(rec) -> dict:
    """design.json's content from a design record (:meth:`DesignResult.pick`): plain JSON
    data (:func:`mechopt.run.io.plain_json`), without the mechanism object.

    Parameters
    ----------
    rec : dict
        A design record.

    Returns
    -------
    dict
        JSON-ready data (NaN and infinities as None).
    """
    from mechopt.run.io import plain_json

    return plain_json({k: val for k, val in rec.items() if k != "mechanism"})


# ------------------------------------------------------------------ polishing
# The genetic search ends near, not at, the corner where the requirements are active.
# The polish walks into it from several front designs (:func:`_polish_front`). With a
# free placement the feasible set is thin along the placement: for given lengths the
# task fits in a short window of heights, which closes at the smallest design. A
# search over lengths and placement together must stay inside that wedge and stalls
# on the face it started from; so for an objective that the placement does not change
# (the size) the placement is solved inside each evaluation instead
# (:func:`_polish_lengths`): the lengths are searched, each candidate gets the
# placement that maximises its smallest margin (:func:`_peak`), and a candidate is
# feasible when some placement is.

#: placement variables (free task placement), searched apart from the lengths
_PLACEMENT_VARS = ("task_x_rel", "task_y_rel")


#: per problem, ``(row bytes, sampling) -> (objective values, constraints)`` of the rows
#: :func:`_evaluated` has evaluated: the polish evaluates some rows again (a start and
#: its placement, the design a round ends on, its certification), and an evaluation
#: is deterministic
_EVALUATED = weakref.WeakKeyDictionary()


def _evaluated(problem, x, sampling):
    """``(objective values, constraints g)`` of the row ``x`` (as the evaluator returns
    them, in ``problem.constr_names`` order) with ``sampling``, evaluated once."""
    seen = _EVALUATED.setdefault(problem, {})
    key = (np.asarray(x, float).tobytes(), sampling)
    if key not in seen:
        ev = problem.evaluator
        res = ev.evaluate(ev.decode(x), sampling)
        seen[key] = (ev.objective_values(res), [res["g"][n] for n in problem.constr_names])
    return seen[key]


def _certified(problem, x, tolerance=None) -> bool:
    """:func:`certify`'s verdict on the row ``x``: every ``g <= 0`` with its sampling;
    with ``tolerance`` [L] also over its tolerance box (:func:`_box_of`)."""
    if not feasible(_evaluated(problem, x, Sampling.fine())[1]):
        return False
    return tolerance is None or _box_of(problem.evaluator, problem.evaluator.decode(x), tolerance)[0]


def _design_key(ev, v) -> tuple:
    """A design's identity (a decoded design's or a front row's): ``(lengths..., mode,
    task_x, task_y)``, the lengths in the spec's order [L]."""
    return (*(float(v[n]) for n in ev.spec.lengths), str(v["mode"]), float(v["task_x"]), float(v["task_y"]))


def _box_of(ev, v, tolerance):
    """``(holds, box)``: the tolerance box of the decoded design ``v``
    (:func:`mechopt.workflows.certificate.tolerance_box`, its corners and the interval
    bounds, no random draws) and whether the design is certified over it
    (:func:`mechopt.workflows.certificate.box_certified`)."""
    from mechopt.workflows.certificate import box_certified, tolerance_box

    box = tolerance_box(ev, v, tolerance, n_samples=0)
    return box_certified(box), box


def _rows_eval(problem, X, j, sampling):
    """Objective ``j`` (minimisation form) and the constraints ``G`` of the rows ``X``
    evaluated with ``sampling`` (the polish uses the certification's, so what it accepts
    is feasible by :func:`certify`, not only by the search's coarser sampling)."""
    ev = problem.evaluator
    sense = ev.senses()[ev.objectives[j]]
    X = np.atleast_2d(np.asarray(X, float))
    f = np.empty(len(X))
    G = np.empty((len(X), len(problem.constr_names)))
    for i, x in enumerate(X):
        values, g = _evaluated(problem, x, sampling)
        f[i] = sense * values[j]
        G[i] = g
    f = np.where(np.isfinite(f), f, 1e300)
    G = np.where(np.isfinite(G), G, 1e3)
    return f, G


def _phi(G):
    """Smallest normalised margin of each row (``>= 0``: feasible)."""
    G = np.atleast_2d(G)
    return -G.max(axis=1) if G.shape[1] else np.zeros(len(G))


def _best_row(f, G):
    """Index of the best row: feasible first; among feasible rows the lowest ``f``, ties
    (equal to 1e-12, e.g. the size, which no placement changes) broken by the largest
    smallest margin; without a feasible row the largest smallest margin."""
    phi = _phi(G)
    ok = phi >= 0
    if not ok.any():
        return int(np.argmax(phi))
    fb = f[ok].min()
    tie = ok & (f <= fb + _v.ROUNDING * max(abs(fb), 1.0))
    return int(np.flatnonzero(tie)[np.argmax(phi[tie])])


class _Evals:
    """``evals(X) -> (f, G)``: :func:`_rows_eval` of one objective and sampling,
    counting the rows evaluated (``n``)."""

    def __init__(self, problem, j, sampling):
        self.problem, self.j, self.sampling, self.n = problem, j, sampling, 0

    def __call__(self, X):
        X = np.atleast_2d(np.asarray(X, float))
        self.n += len(X)
        return _rows_eval(self.problem, X, self.j, self.sampling)


def _size_of(problem, x) -> float:
    """The size of the row ``x`` from its lengths alone, no evaluation (an objective the
    placement does not change, :func:`_placement_free`: bit for bit the evaluation's)."""
    ev = problem.evaluator
    return ev.spec.size_of(ev.decode(x))


def _placement_index(problem):
    return [i for i, name in enumerate(problem.var_names) if name in _PLACEMENT_VARS]


def _placement_free(problem, j) -> bool:
    """Objective ``j`` does not depend on the task placement (the size, for the
    mechanisms whose size is their link lengths)."""
    ev = problem.evaluator
    return ev.objectives[j] == "size" and ev.spec.size_from_lengths


def _place(problem, x, j, sampling, n=33, levels=3):
    """``x`` with its placement variables re-chosen for its lengths: a deterministic
    scan of the placement range (``n`` points; ``n // 3 + 1`` per variable for
    ``free``), then ``levels`` zooms of 5 points per variable, each halving the step,
    keeping the best row by :func:`_best_row` (``x`` itself is a candidate). For an
    objective the placement does not change this centres the task in the window where
    the design covers it (largest smallest margin); for the others it is the design's
    best feasible placement for the objective."""
    idx = _placement_index(problem)
    x = np.asarray(x, float)
    if not idx:
        return x
    lo, hi = problem.xl[idx], problem.xu[idx]
    m = n if len(idx) == 1 else n // 3 + 1
    axes = [np.linspace(a, b, m) for a, b in zip(lo, hi)]
    P = np.array(np.meshgrid(*axes, indexing="ij")).reshape(len(idx), -1).T
    X = np.repeat(x[None, :], len(P) + 1, axis=0)
    X[1:, idx] = P
    f, G = _rows_eval(problem, X, j, sampling)
    k = _best_row(f, G)
    best, fbest, Gbest = X[k].copy(), f[k], G[k]
    h = (hi - lo) / (m - 1)
    off = np.linspace(-1.0, 1.0, 5)
    for _ in range(levels):
        O = np.array(np.meshgrid(*[off] * len(idx), indexing="ij")).reshape(len(idx), -1).T
        O = O[np.any(O != 0, axis=1)]
        C = np.repeat(best[None, :], len(O), axis=0)
        C[:, idx] = np.clip(best[idx] + O * h, lo, hi)
        fc, Gc = _rows_eval(problem, C, j, sampling)
        k = _best_row(np.r_[fbest, fc], np.vstack([Gbest, Gc]))
        if k:
            best, fbest, Gbest = C[k - 1].copy(), fc[k - 1], Gc[k - 1]
        h = 0.5 * h
    return best


def _concave_peak_bound(ts, ps, plateau=-0.5):
    """Upper bound of the peak of a concave function sampled at increasing ``ts``
    (values ``ps``): in each interval next to the best sample the function lies below
    the secants of the two samples on its left and of the two on its right, extended.
    ``inf`` when a side lacks two samples or uses one at or below ``plateau`` (out of
    reach: ``phi`` is flat there, not concave). Used only to stop a 1-D search early
    (a wrong bound loses a candidate, never admits an infeasible one)."""
    n = len(ts)
    i = int(np.argmax(ps))
    if i == 0 or i == n - 1:
        return math.inf
    bound = float(ps[i])
    for k in (i - 1, i):  # the peak in [ts[k], ts[k + 1]]
        a, b, c, d = k - 1, k, k + 1, k + 2
        if a < 0 or d >= n or min(ps[a], ps[b], ps[c], ps[d]) <= plateau:
            return math.inf
        sl = (ps[b] - ps[a]) / (ts[b] - ts[a])
        sr = (ps[d] - ps[c]) / (ts[d] - ts[c])
        left = lambda t: ps[b] + sl * (t - ts[b])  # noqa: E731
        right = lambda t: ps[c] + sr * (t - ts[c])  # noqa: E731
        cand = [min(left(ts[b]), right(ts[b])), min(left(ts[c]), right(ts[c]))]
        if sl != sr:
            t = (ps[c] - ps[b] + sl * ts[b] - sr * ts[c]) / (sl - sr)
            if ts[b] < t < ts[c]:
                cand.append(left(t))
        bound = max(bound, max(cand))
    return bound


def _peak(problem, evals, x, need=False, known=None, h0=0.005, tol=2e-4):
    """Placement of the lengths of ``x`` that maximises the smallest margin ``phi``,
    one placement variable at a time (two sweeps for ``free``), from ``x``'s placement.

    Each 1-D search brackets the peak (steps of ``h0`` of the variable's range, doubled
    while ``phi`` rises) and narrows it by golden section to ``tol``: ``phi`` is the
    minimum of margins that rise and margins that fall with the placement, so it has
    one peak in the window. With ``need`` it ends at the first ``phi >= 0`` (the
    lengths are feasible; that is all a candidate needs) or once the peak is bounded
    below 0 (by the largest slope seen, doubled, over the bracket, or by the secants of
    :func:`_concave_peak_bound`). ``known`` is ``(phi, f)`` at ``x``; ``evals`` is an
    :class:`_Evals`. Returns ``(x, phi, f)`` at the best placement seen."""
    x = np.array(x, float)
    idx = _placement_index(problem)
    if known is None:
        fk, Gk = evals(x[None, :])
        known = (float(_phi(Gk)[0]), float(fk[0]))
    best = (known[0], known[1], x.copy())
    if not idx or (need and best[0] >= 0):
        return best[2], best[0], best[1]
    for i in idx * (1 if len(idx) == 1 else 2):
        lo, hi = float(problem.xl[i]), float(problem.xu[i])
        base = best[2]
        seen = {float(base[i]): best[0]}

        def P(t):
            nonlocal best
            t = float(min(max(t, lo), hi))
            if t not in seen:
                xx = base.copy()
                xx[i] = t
                fz, Gz = evals(xx[None, :])
                seen[t] = float(_phi(Gz)[0])
                if seen[t] > best[0]:
                    best = (seen[t], float(fz[0]), xx)
            return seen[t]

        def stop(L, R):
            if need and best[0] >= 0:
                return True
            if not need or len(seen) < 3:
                return False
            ts = np.array(sorted(seen))
            ps = np.array([seen[t] for t in ts])
            slope = float(np.max(np.abs(np.diff(ps) / np.diff(ts))))
            return best[0] + 2.0 * slope * (R - L) < 0 or _concave_peak_bound(ts, ps) < 0

        h = h0 * (hi - lo)
        t0 = float(base[i])
        p0, pa, pb = seen[t0], P(t0 - h), P(t0 + h)
        if stop(t0 - h, t0 + h):
            if need and best[0] >= 0:
                break
            continue
        if pa <= p0 and pb <= p0:
            if pa == pb == p0:
                continue  # flat here (e.g. out of reach all around): nothing to follow
            L, R = max(t0 - h, lo), min(t0 + h, hi)
        else:
            d = 1.0 if pb > pa else -1.0
            prev, cur, pc = t0, min(max(t0 + d * h, lo), hi), max(pa, pb)
            while True:
                h *= 2.0
                nxt = min(max(cur + d * h, lo), hi)
                pn = P(nxt)
                if pn <= pc or nxt in (lo, hi) or stop(min(prev, nxt), max(prev, nxt)):
                    if pn > pc:
                        prev, cur = cur, nxt
                    break
                prev, cur, pc = cur, nxt, pn
            L, R = min(prev, nxt), max(prev, nxt)
        golden_section_max(P, L, R, tol=tol * (hi - lo), stop=stop)  # P keeps the best seen
        if need and best[0] >= 0:
            break
    return best[2], best[0], best[1]


def _polish_lengths(problem, x0, j, sampling, seed=0, iters=100, step_min=1e-4, max_evals=6000):
    """Direct search over the lengths for the size (an objective the placement does not
    change, :func:`_placement_free`), the placement solved by :func:`_peak` for each
    candidate (the comment above :data:`_PLACEMENT_VARS`).

    Extreme barrier (a candidate is accepted when it is better and some placement makes
    it feasible); polled per step: the last successful direction, the coordinate
    directions and 2 seeded random ones, in that order, the first success taken; the
    step (in units of each variable's range) doubled on success up to 0.2, halved on
    failure, from 0.01 down to ``step_min``. The accepted design is re-centred
    (:func:`_peak` to the peak). Returns ``(x, f)``; ``x0`` must be feasible."""
    idx = set(_placement_index(problem))
    cont = np.array([i for i, n in enumerate(problem.var_names) if n != "mode" and i not in idx], int)
    span = np.where(problem.xu > problem.xl, problem.xu - problem.xl, 1.0)
    rng = np.random.default_rng(seed)
    evals = _Evals(problem, j, sampling)
    x, phi, f = _peak(problem, evals, x0)
    if cont.size == 0 or phi < 0:
        return x, f
    n = cont.size
    step, last = 0.01, None
    z = (x[cont] - problem.xl[cont]) / span[cont]
    for _ in range(iters):
        dirs = np.vstack([np.eye(n), -np.eye(n), rng.normal(size=(2, n))])
        dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
        if last is not None:
            dirs = np.vstack([last, dirs])
        found = None
        for d in dirs:
            zc = np.clip(z + step * d, 0.0, 1.0)
            if np.array_equal(zc, z):
                continue
            xc = x.copy()
            xc[cont] = problem.xl[cont] + zc * span[cont]
            if not _size_of(problem, xc) < f - _v.RESOLUTION * max(abs(f), 1.0):
                continue  # no better whatever the placement
            fc, Gc = evals(xc[None, :])
            if not fc[0] < f - _v.ROUNDING * max(abs(f), 1.0):
                continue
            xc, pc, fcc = _peak(problem, evals, xc, need=True, known=(float(_phi(Gc)[0]), float(fc[0])))
            if pc >= 0:
                found = (xc, fcc, zc, d)
                break
        if found is not None:
            x, f, z, last = found
            x, _, _ = _peak(problem, evals, x)  # centre it: room for the next step
            step = min(2.0 * step, 0.2)
        else:
            last = None
            step *= 0.5
            if step < step_min:
                break
        if evals.n > max_evals:
            break
    return x, f


def _polish(problem, x0, j, iters=40, seed=0, sampling=None, tolerance=None):
    """Local improvement of objective ``j`` from the feasible design ``x0``: SLSQP
    (finite-difference gradients, a quadratic model: it walks along a smooth active
    constraint), COBYLA (linear models of the constraints: it walks along an active
    constraint where gradients jump), each from the best feasible design seen so far,
    then a seeded direct search with extreme barrier (only feasible, better designs are accepted;
    coordinate and 8 random directions per step, the step doubled on success and
    halved on failure, from 1 % of each variable's range down to 1e-7). Active
    constraints make the optimum a corner the genetic search only approaches; this
    walks into it. Evaluations use ``sampling`` (default the certification's,
    :meth:`Sampling.fine`; the direct search, which reads only feasibility and the
    objective, settles the comfortably met requirements: :attr:`Sampling.settle`); the result is re-checked by :func:`certify` (with
    ``tolerance``, over its tolerance box too) and pulled back toward ``x0`` until it
    passes. Returns the new X row or None."""
    sampling = sampling or Sampling.fine()
    span = np.where(problem.xu > problem.xl, problem.xu - problem.xl, 1.0)
    cont = np.array([i for i, n in enumerate(problem.var_names) if n != "mode"])
    if cont.size == 0:
        return None
    rng = np.random.default_rng(seed)
    size_only = _placement_free(problem, j)  # the objective is the size of the lengths
    # the direct search reads only the objective and whether every g <= 0: the requirements
    # the samples show comfortably met need no refinement (Sampling.settle)
    verdicts = replace(sampling, settle=True)

    def full(z):
        x = np.array(x0, float)
        x[cont] = problem.xl[cont] + np.clip(z, 0.0, 1.0) * span[cont]
        return x

    def batch(Z, below=None):
        """``(f, feasible)`` of the rows ``Z``; with ``below`` (a placement-free size)
        a row whose size (from its lengths alone) is not below ``below`` is not
        evaluated (``f = inf``): the direct search could not accept it."""
        X = np.array([full(z) for z in Z])
        f, ok = np.full(len(X), np.inf), np.zeros(len(X), bool)
        if below is None:
            keep = np.arange(len(X))
        else:
            keep = np.flatnonzero([_size_of(problem, x) < below for x in X])
        if keep.size:
            fk, G = _rows_eval(problem, X[keep], j, verdicts)
            f[keep], ok[keep] = fk, np.all(G <= 0, axis=1)
        return f, ok

    z = (np.asarray(x0, float)[cont] - problem.xl[cont]) / span[cont]
    f, ok = batch([z])
    if not ok[0]:
        return None
    f, f0, z0 = f[0], f[0], z.copy()
    import warnings

    from scipy.optimize import minimize

    cache = {}

    def one(zz):
        key = tuple(np.round(np.clip(zz, 0.0, 1.0), 15))
        if key not in cache:
            fz, Gz = _rows_eval(problem, full(zz)[None, :], j, sampling)
            cache[key] = (float(fz[0]), Gz[0])
        return cache[key]

    def best_seen():
        feas = [(v[0], k) for k, v in cache.items() if np.all(v[1] <= 0)]
        return min(feas) if feas else (math.inf, None)

    # SLSQP (finite-difference gradients: where one constraint is active and its level
    # set runs nearly parallel to the objective's, a direct search sees a cone of
    # descent too narrow to hit; a quadratic model walks along it), then COBYLA (linear
    # models of the constraints: walks along an active one where the gradients jump)
    for method, opts, margin in (("SLSQP", {"eps": 1e-5, "maxiter": 50, "ftol": 1e-10}, 1e-7),
                                 ("COBYLA", {"rhobeg": 0.01, "maxiter": 200, "tol": 1e-9}, 1e-9)):
        if method == "SLSQP":
            cons = [{"type": "ineq", "fun": (lambda zz: -one(zz)[1] - margin)}]
        else:
            cons = [{"type": "ineq", "fun": (lambda zz, k=k: -one(zz)[1][k] - margin)}
                    for k in range(problem.n_ieq_constr)]
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                minimize(lambda zz: one(zz)[0] / max(abs(f0), 1e-300), z, method=method,
                         constraints=cons, bounds=[(0.0, 1.0)] * len(z), options=opts)
        except (ValueError, ArithmeticError):
            pass
        fb, kb = best_seen()  # the best feasible design either method evaluated
        if fb < f:
            z, f = np.array(kb), fb
    n = cont.size
    step = 0.01
    for _ in range(iters):
        dirs = np.vstack([np.eye(n), -np.eye(n), rng.normal(size=(8, n))])
        dirs /= np.linalg.norm(dirs, axis=1, keepdims=True)
        cand = np.clip(z + step * dirs, 0.0, 1.0)
        accept = f - _v.ROUNDING * max(abs(f), 1.0)  # a candidate must be below this
        # the size is minimised as +size (sense 1): a candidate of no smaller size is
        # rejected whatever its margins, so it is not evaluated (the same choice)
        fc, okc = batch(cand, below=accept if size_only else None)
        fc = np.where(okc, fc, np.inf)
        k = int(np.argmin(fc))
        if fc[k] < accept:
            z, f = cand[k], fc[k]
            step = min(2.0 * step, 0.2)
        else:
            step *= 0.5
            if step < 1e-7:
                break
    if not f < f0:
        return None
    for _ in range(40):  # the fine check; pull back toward x0 until it passes
        x = full(z)
        if _certified(problem, x, tolerance):
            return x
        z = z0 + 0.5 * (z - z0) if _ % 2 else z0 + 0.9 * (z - z0)
    return None


def _polish_start(item):
    """One start of :func:`_polish_front` (module level: it runs in workers). For an
    objective the placement does not change, with a free placement: the placement scan
    of :func:`_place` (without zoom), then :func:`_polish_lengths`. Otherwise (a fixed
    placement, or an objective that depends on it) up to ``rounds`` rounds of
    :func:`_place` and :func:`_polish`, until a round gains less than 0.1 %.
    Every evaluation uses the certification's sampling. Returns ``(x, f)`` of a
    certified design better than the start, or None."""
    problem, x, j, seed, rounds, tolerance = item
    fine = Sampling.fine()
    x = np.asarray(x, float)
    f, G = _rows_eval(problem, x[None, :], j, fine)
    f0 = float(f[0]) if np.all(G <= 0) else math.inf
    if _placement_free(problem, j) and _placement_index(problem):
        placed = _place(problem, x, j, fine, levels=0)
        fp, Gp = _rows_eval(problem, placed[None, :], j, fine)
        if not np.all(Gp <= 0):
            return None
        cur, f_cur = _polish_lengths(problem, placed, j, fine, seed=seed)
    else:
        cur, f_cur = x, f0
        for r in range(rounds):
            placed = _place(problem, cur, j, fine)
            fp, Gp = _rows_eval(problem, placed[None, :], j, fine)
            if not np.all(Gp <= 0):
                break
            new = _polish(problem, placed, j, seed=seed + 1000 * r, sampling=fine, tolerance=tolerance)
            new = placed if new is None else new
            fn = float(_rows_eval(problem, new[None, :], j, fine)[0][0])
            gain = (f_cur - fn) / max(abs(f_cur), 1e-300) if math.isfinite(f_cur) else math.inf
            if fn < f_cur:
                cur, f_cur = new, fn
            if not gain > 1e-3:
                break
    if not f_cur < f0 or not _certified(problem, cur, tolerance):
        return None
    return cur, float(f_cur)


def _polish_front(problem, X, objectives=None, n_starts=None, rounds=3, seed=0, n_jobs=1, client=None,
                  tolerance=None):
    """Multi-start polish of each objective ``j`` in ``objectives`` (default all): from
    the front's best design for ``j`` and ``n_starts - 1`` more front designs, evenly
    spaced in rank over the better half for ``j`` (the genetic search leaves each on
    whatever face it reached), each by :func:`_polish_start`, all starts of all
    objectives mapped together over ``n_jobs`` workers (seeded per start: the result
    does not depend on ``n_jobs``). ``n_starts`` defaults to 3 for an objective the
    placement does not change when the placement is free (the thin feasible wedge of
    the module comment above: the face a start sits on decides where a local search
    ends; about a thousand evaluations a start) and to 1 otherwise (more starts did
    not improve the fixed-placement size or the LCI extreme on the benchmarks). With
    a fixed placement a start is one round (the rounds re-choose the placement).
    Returns ``{j: improved rows, best first}``."""
    objectives = range(problem.n_obj) if objectives is None else objectives
    items, owner = [], []
    for j in objectives:
        if not len(X):
            break
        wedge = _placement_free(problem, j) and bool(_placement_index(problem))
        m = n_starts if n_starts is not None else (3 if wedge else 1)
        fj, _ = _rows_eval(problem, X, j, problem.sampling)  # the search's own values rank the starts
        order = np.argsort(fj, kind="stable")
        ranks = np.unique(np.round(np.linspace(0, (len(X) - 1) / 2.0, m)).astype(int))
        for k, r in enumerate(ranks):
            items.append((problem, X[order[r]], j, seed + 7919 * k + 104729 * j,
                          rounds if _placement_index(problem) else 1, tolerance))
            owner.append(j)
    # the long starts (placement-dependent objectives) first: the workers end together
    first = sorted(range(len(items)), key=lambda i: _placement_free(problem, owner[i]))
    items, owner = [items[i] for i in first], [owner[i] for i in first]
    from mechopt.run.parallel import parallel_map

    out = {j: [] for j in objectives}
    for j, r in zip(owner, parallel_map(_polish_start, items, n_jobs or 1, client) if items else []):
        if r is not None:
            out[j].append(r)
    return {j: [x for x, _ in sorted(rs, key=lambda r: r[1])] for j, rs in out.items()}


# ------------------------------------------------------------------ design
def design(mechanism, task, requirements: Requirements | None = None, objectives=("size", "min-lci"),
           *, mode=None, place="fixed", min_length=None, max_length=None, shape=None,
           algorithm=None, pop=None, gen=None, seed=1, n_jobs=1, client=None, out=None,
           progress=False, polish=True, pick=None, checkpoint_every=None, plot=True,
           overwrite=False, tolerance=None) -> DesignResult:
    """Size ``mechanism`` (one of :func:`mechopt.analysis.design_eval.mechanisms`) for ``task``.

    Builds :class:`mechopt.problems.design.DesignProblem`, runs it with
    :func:`mechopt.run.runner.optimize` (seeded; ``n_jobs``/``client`` as there), polishes
    each objective locally from the front (``polish``; :func:`_polish_front`, on the
    same workers, with the certification's sampling; with a free placement the size
    is searched over the lengths, each candidate placed where its margins are largest,
    from 3 front designs; the result does not depend on ``n_jobs``; a five-bar of one
    working mode placed freely is also searched below the base line, a second run of
    the same budget and seed, its front merged; ``place="free"`` first runs ``"free-y"``
    with the same budget and seed and starts from its certified front, so it never ends
    worse), certifies every
    front design with :func:`certify` (designs that fail the fine check are dropped and
    counted in ``info["dropped_by_certification"]``) and returns a
    :class:`DesignResult`. With ``out``, writes ``front.csv``, ``design.json`` (the
    knee, or ``pick`` weights), ``certificate.json`` (each front design's requirements,
    margins, how each is known, its digest: :mod:`mechopt.workflows.certificate`),
    ``run.json``, ``history.csv``, ``front.png`` and ``design.png`` as one set (:func:`mechopt.run.io.output_set`, with ``manifest.json``
    written last), so a failed run leaves nothing half-written; a folder holding
    another run is refused unless ``overwrite``.

    Raises :class:`NoFeasibleDesign` (a ValueError) naming the requirement that
    fails most when no design is feasible; with ``out`` the run's files are written
    first (run.json with ``no_design``, history.csv, population.csv, front.png: an
    empty result is a result).

    Parameters
    ----------
    mechanism : str
        A designed mechanism (``"five-bar"``, ``"bipod"``, ...; :func:`mechopt.mechanisms.designed`).
    task : mechopt.analysis.task.Task
        The task, lengths in its unit [L] (base frame).
    requirements : mechopt.requirements.Requirements, optional
        What must hold over the whole task (default: reach and no type-II
        singularity only).
    objectives : sequence of str
        Objective names (:func:`mechopt.requirements.objectives`).
    mode : str, optional
        Working mode, or ``"any"`` (default: the spec's default mode).
    place : {"fixed", "free-y", "free"}
        Whether the search also moves the task (along y, or in x and y).
    min_length, max_length : float, optional
        Bounds of every link length [L] (defaults from the task's size).
    shape : sequence of float, optional
        Fixed link ratios (non-dimensional); the variable is then the scale D [L]
        (Liu 2006 sec. 3.2.3).
    algorithm : str, optional
        ``"ga"``, ``"de"``, ``"nsga2"``, ``"nsga2-mnn"`` or ``"nsga3"`` (default: ga
        for one objective, else nsga2).
    pop, gen : int, optional
        Population size and generations (default 40 and 50).
    seed : int
        Random seed.
    n_jobs : int
        Worker processes (joblib).
    client : dask.distributed.Client, optional
        Evaluate on a Dask cluster instead.
    out : str or Path, optional
        Output folder (nothing is written without it).
    progress : bool
        Log the progress of each generation.
    polish : bool
        Polish each objective's best design locally.
    pick : dict or str, optional
        Weights choosing design.json (:meth:`DesignResult.pick`; default: the knee).
    checkpoint_every : int, optional
        Write a checkpoint every this many generations.
    plot : bool
        Draw front.png and design.png (with ``out``).
    overwrite : bool
        Replace another run that ``out`` holds (only the files that run wrote).
    tolerance : float, optional
        ``T`` [L]: every front design must also hold for every mechanism whose lengths
        lie within ``+- T`` of its own (:func:`mechopt.workflows.certificate.tolerance_box`
        without random draws: the box's corners evaluated, and interval bounds over the
        whole box, which must prove each requirement they bound); the
        polish pulls a design back until it does, and a front design that does not is
        dropped (``info["dropped_by_tolerance"]``). Each front design's box is in
        certificate.json.

    Returns
    -------
    DesignResult
        The certified front and the run.

    Raises
    ------
    mechopt.analysis.design_eval.NoFeasibleDesign
        A ValueError naming the requirement that fails most, when no design is
        feasible.
    ValueError
        One line, for invalid inputs or a folder holding another run.
    """
    from mechopt.run import io as _io
    from mechopt.problems import get as _problem

    # the registered "design" problem (mechopt.problems.design.DesignProblem), built on
    # this module's evaluator: through the registry, so that the two modules do not
    # import each other
    problem = _problem("design", mechanism=mechanism, task=task, requirements=requirements,
                       objectives=objectives, mode=mode, place=place, min_length=min_length,
                       max_length=max_length, shape=shape, sampling=SEARCH)
    ev = problem.evaluator
    if pick is not None:
        parse_pick(pick, ev.objectives)
    if checkpoint_every is not None:
        raise ValueError("design runs are not checkpointed; run mechopt.run.runner.optimize on the "
                         "registered 'design' problem to checkpoint one")
    if tolerance is not None:
        tolerance = _v.positive_length("tolerance", tolerance)
    def sub_front(place_, side, extra):
        """The certified front of the same run with ``place_`` and ``side`` (the same
        budget and seed), ``extra`` designs added, as decoded designs."""
        sub = _problem("design", mechanism=mechanism, task=task, requirements=requirements,
                       objectives=objectives, mode=mode, place=place_, min_length=min_length,
                       max_length=max_length, shape=shape, side=side, sampling=SEARCH)
        res = _design(sub, sub.evaluator, None, algorithm, pop, gen, seed, n_jobs, client, None, progress,
                      polish, None, extra, tolerance=tolerance)
        names = (*ev.spec.lengths, *(("D",) if ev.shape is not None else ()), "mode", "task_x", "task_y")
        return [{k: (str(r[k]) if k == "mode" else float(r[k])) for k in names}
                for r in res.front.to_dict("records")]

    def other_designs():
        """The designs the main search adds to its front: with a placement searched on
        both sides of the base line, the front of the search below it; with
        ``place="free"``, the front of ``"free-y"`` (itself with the designs below);
        and the stage times of those searches (``{"other searches": s}``, empty
        without)."""
        import time

        t0 = time.perf_counter()
        extra = sub_front("free-y", "below", []) if ev.both_sides else []
        if ev.place == "free":
            extra = sub_front("free-y", "above", extra)
        return extra, ({"other searches": time.perf_counter() - t0} if ev.both_sides or ev.place == "free" else {})

    manifest = None
    if out is not None:
        out = _io.prepare_out_dir(out)
        key = {"mechanism": mechanism, "task": _task_digest(task), "requirements": repr(requirements),
               "objectives": list(objectives), "mode": mode, "place": place, "min_length": min_length,
               "max_length": max_length, "shape": shape, "algorithm": repr(algorithm), "pop": pop, "gen": gen,
               "seed": seed, "polish": polish, "pick": pick, "tolerance": tolerance}
        with _io.run_in(out, "design", key, DESIGN_OUTPUTS, overwrite) as manifest:
            result = _design(problem, ev, pick, algorithm, pop, gen, seed, n_jobs, client, out, progress,
                             polish, manifest, *other_designs(), tolerance=tolerance)
    else:
        result = _design(problem, ev, pick, algorithm, pop, gen, seed, n_jobs, client, None, progress, polish,
                         None, *other_designs(), tolerance=tolerance)
    if result.error is not None:  # the files are written: the empty result is reported
        raise result.error
    return result


def _design(problem, ev, pick, algorithm, pop, gen, seed, n_jobs, client, out, progress, polish, manifest,
            extra=(), before=None, tolerance=None):
    """The run, polish and certification of :func:`design`, and its files with ``out``.
    ``extra`` are decoded designs (the front of the search below the base line, the
    ``free-y`` front of a ``free`` run) certified with the front and, those inside this
    search's bounds, added to the polish's starts; ``before`` the stage times [s] of
    the searches that found them. ``info["stage_times_s"]`` gives the wall time [s] of
    each stage (those searches, optimisation, polish, certification, files) and
    ``info["wall_time_s"]`` their sum, the whole call. With ``tolerance`` a front
    design must also hold over its tolerance box (:func:`_box_of`)."""
    import time

    from mechopt.run import io as _io
    from mechopt.run.runner import optimize

    t0 = time.perf_counter()
    run = optimize(problem, algorithm, pop, gen, seed, n_jobs, client, None, progress=progress,
                   plot=False)
    info = dict(run.info)
    stages = {**(before or {}), "optimisation": time.perf_counter() - t0}
    extra = list(extra)
    if ev.place == "free" or ev.both_sides:
        info["other_designs"] = len(extra)
    if not len(run.front) and not extra:
        return _empty_result(problem, ev, run, info, stages, out, manifest, _no_design(problem, run))
    X = run.front[list(problem.var_names)].to_numpy(float).reshape(-1, len(problem.var_names))
    if extra:  # polish starts too, those inside this search's bounds (the others were polished in theirs)
        E = np.array([ev.encode(v) for v in extra])
        X = np.vstack([X, E[np.all((E >= problem.xl) & (E <= problem.xu), axis=1)]])
    polished = []
    t0 = time.perf_counter()
    if polish:
        new = _polish_front(problem, X, seed=seed, n_jobs=info.get("n_jobs") or n_jobs or 1, client=client,
                            tolerance=tolerance)
        for j, rows_j in new.items():
            if rows_j:
                X = np.vstack([X, *rows_j])
                polished.append(ev.objectives[j])
    stages["polish"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    certified = []
    for v in [ev.decode(x) for x in X] + extra:  # the extra designs as given (exactly their placement)
        res = certify(ev, v)
        if res["feasible"]:
            certified.append((v, res))
    dropped, dropped_box, boxes = len(X) + len(extra) - len(certified), 0, {}
    if tolerance is not None:  # each design's boxes, the designs spread over the workers
        from mechopt.run.parallel import parallel_map

        todo = list({_design_key(ev, v): v for v, _ in certified}.items())
        found = parallel_map(_boxes_of, [(ev, v, tolerance) for _, v in todo], info.get("n_jobs") or n_jobs or 1,
                             client) if todo else []
        boxes = {key: b for (key, _), b in zip(todo, found)}
    rows, kept = [], []
    for v, res in certified:
        row = ev.row(v, res)
        if tolerance is not None:
            ok, box, largest = boxes[_design_key(ev, v)]
            if not ok:
                dropped_box += 1
                continue
            row["tolerance_max"] = largest
        rows.append(row)
        kept.append(ev.objective_values(res))
    if not rows and dropped_box:
        return _empty_result(problem, ev, run, info, stages, out, manifest,
                             _no_box(ev, tolerance, [box for _, box, _ in boxes.values()]))
    if not rows:
        return _empty_result(problem, ev, run, info, stages, out, manifest, _no_design(problem, run, certified=True))
    F = np.array(kept) * np.array(list(ev.senses().values()))
    nd = _non_dominated(F)
    front = pd.DataFrame([rows[i] for i in nd])
    keys = list(ev.objectives)
    front = front.sort_values(keys, kind="mergesort").drop_duplicates(
        subset=[c for c in front.columns if c in (*ev.spec.lengths, "mode", "task_x", "task_y")]
    ).reset_index(drop=True)
    info.update(design=ev.settings(), polished=polished, dropped_by_certification=dropped,
                front_size=int(len(front)), problem="design", certification=asdict(Sampling.fine()))
    if tolerance is not None:
        info.update(tolerance=tolerance, dropped_by_tolerance=dropped_box)
    result = DesignResult(front, info, ev, run)
    if tolerance is not None:
        result.boxes = {i: boxes[_design_key(ev, row)][1] for i, row in front.iterrows()}
    chosen = result.pick(pick)
    result.chosen_index = chosen["index"]
    info["chosen"] = {"index": chosen["index"], "by": "knee" if pick is None else f"weights {pick}"}
    stages["certification"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    if out is not None:
        from mechopt.run.plotting import plot_front

        fig_front = plot_front(problem, front, run.history, run.population, info, chosen=chosen["index"])
        fig_design = plot_design(ev, chosen)
        cert = _certificate(result)  # re-certifies every front design: inside the timed stages
        stages["files"] = time.perf_counter() - t0
        info["stage_times_s"] = stages
        info["wall_time_s"] = sum(stages.values())
        with _io.output_set(out, manifest) as stage:
            _io.write_csv(front, stage / "front.csv")
            _io.write_csv(run.history, stage / "history.csv")
            _io.write_json(json_record(chosen), stage / "design.json")
            _io.write_json(cert, stage / "certificate.json")
            _io.write_json(info, stage / "run.json")
            _io.save_figure(fig_front, stage / "front.png")
            _io.save_figure(fig_design, stage / "design.png")
    else:
        info["stage_times_s"] = stages
        info["wall_time_s"] = sum(stages.values())
    return result


def _empty_result(problem, ev, run, info, stages, out, manifest, exc):
    """No feasible design: a result, not an error. With ``out``, writes ``run.json``
    (``no_design``: the message; ``violations``), ``history.csv``, ``population.csv``
    (the final population with its ``g_*`` columns, least violating first) and
    ``front.png`` (the population coloured by its violation); returns an empty
    :class:`DesignResult` whose ``info["no_design"]`` :func:`design` raises as
    :class:`NoFeasibleDesign`."""
    from mechopt.run import io as _io
    from mechopt.run.plotting import plot_front

    info.update(design=ev.settings(), problem="design", front_size=0, no_design=str(exc),
                violations=exc.info.get("violations", {}), fails=exc.info.get("fails", {}),
                sensitivity=exc.info.get("sensitivity", {}))
    info["stage_times_s"] = stages
    info["wall_time_s"] = sum(stages.values())
    pop = run.population
    G = pop[[f"g_{n}" for n in problem.constr_names]].to_numpy(float)
    pop = pop.iloc[np.argsort(np.maximum(G, 0).sum(1), kind="mergesort")].reset_index(drop=True)
    if out is not None:
        fig = plot_front(problem, pd.DataFrame(), run.history, run.population, info)
        with _io.output_set(out, manifest) as stage:
            _io.write_csv(pop, stage / "population.csv")
            _io.write_csv(run.history, stage / "history.csv")
            _io.write_json(info, stage / "run.json")
            _io.save_figure(fig, stage / "front.png")
    result = DesignResult(pd.DataFrame(), info, ev, run)
    result.error = exc
    return result


def _task_digest(task) -> str:
    """sha256 of everything that defines ``task`` (its arrays byte for byte): a run
    manifest's record of the task, whatever its size."""
    import hashlib

    h = hashlib.sha256()
    for part in (task.kind, task.unit, task.center, task.radius):
        h.update(repr(part).encode())
    for arr in (task.vertices, task.pts):
        h.update(b"-" if arr is None else np.ascontiguousarray(arr, dtype="<f8").tobytes())
    return h.hexdigest()


#: the names a design run writes (such files no run manifest accounts for are refused)
DESIGN_OUTPUTS = ("front.csv", "history.csv", "design.json", "certificate.json", "run.json", "front.png",
                  "design.png", "population.csv")


def _certificate(result) -> dict:
    """certificate.json (:func:`mechopt.workflows.certificate.certificate`)."""
    from mechopt.workflows.certificate import certificate

    return certificate(result)


def _non_dominated(F):
    keep = []
    for i in range(len(F)):
        dom = np.all(F <= F[i], axis=1) & np.any(F < F[i], axis=1)
        if not dom.any():
            keep.append(i)
    return keep


#: the tolerances tried beyond a design's own (multiples of it) for ``tolerance_max``
TOLERANCE_LADDER = (2.0, 4.0, 8.0)


def _boxes_of(item):
    """``(holds, box, largest)`` of one certified design (module level: it runs in
    workers): its box at the run's tolerance (:func:`_box_of`) and, when that holds,
    the largest tolerance of ``T x`` :data:`TOLERANCE_LADDER` whose box holds too, each
    tried in turn up to the first that fails (the bounds' excess grows like the square
    of the tolerance, so a larger box is not extrapolated, it is certified), else ``T``:
    a proven lower bound of the largest tolerance the design survives, within a factor
    2 of it up to ``8 T``."""
    ev, v, tolerance = item
    ok, box = _box_of(ev, v, tolerance)
    largest = tolerance
    if ok:
        for k in TOLERANCE_LADDER:
            if not _box_of(ev, v, k * tolerance)[0]:
                break
            largest = k * tolerance
    return ok, box, largest


def _no_box(ev, tolerance, boxes) -> NoFeasibleDesign:
    """``no design holds over its +-T box``: every certified design failed its tolerance
    box; names the requirement that fails in most boxes and the smallest margin found."""
    from mechopt.workflows.certificate import box_failures

    counts = {}
    for box in boxes:
        for name in box_failures(box):
            counts[name] = counts.get(name, 0) + 1
    worst = max(counts, key=counts.get)
    low = min(box["min_margin"][worst] for box in boxes)
    req = next(r for r in ev.active if r.name == worst)
    unit = req.margin_unit.format(L=ev.unit)
    msg = (f"no design holds over its tolerance box +-{tolerance:g} {ev.unit}: {ev.req.describe(worst, ev.unit)} "
           f"fails in {counts[worst]} of the {len(boxes)} certified designs' boxes (smallest margin found "
           f"{low:.4g} {unit}".rstrip(" -") + "); a smaller --tolerance, or looser requirements")
    return NoFeasibleDesign(msg, {"violations": {}, "fails": counts, "miss": -low, "unit": unit})


def _no_design(problem, run, certified=False) -> NoFeasibleDesign:
    """``no design satisfies <requirement>`` from the least-violating design of the final
    population: the requirement it misses most (reach and singular first: without them
    the other margins mean nothing), by how much in the requirement's own unit, how many
    designs fail it."""
    ev = problem.evaluator
    names = problem.constr_names
    pop = run.population
    G = pop[[f"g_{n}" for n in names]].to_numpy(float)
    k = int(np.argmin(np.maximum(G, 0).sum(1)))
    per = {n: max(0.0, float(G[k, i])) for i, n in enumerate(names)}
    worst = next((n for n in ("reach", "singular") if per.get(n, 0.0) > 0), None) or max(per, key=per.get)
    fails = {n: int((pop[f"g_{n}"] > 0).sum()) for n in names}
    # the least-violating design's margin in natural units
    v = ev.decode(pop[list(problem.var_names)].to_numpy(float)[k])
    searched = replace(problem.sampling, settle=False)  # every margin refined, as it is reported
    res = ev.evaluate(v, searched)
    req = next(r for r in ev.active if r.name == worst)
    unit = req.margin_unit.format(L=ev.unit)
    miss = -float(res["margin"][worst])
    by = f"{miss:.4g} {unit}".rstrip(" -") if math.isfinite(miss) else f"{per[worst]:.3g} normalised"
    # the value the requirement bounds, where it names one (reached_key: a key of values)
    reached = res["values"].get(getattr(req, "reached_key", ""))
    if reached is not None:
        by += f", reaching {reached:.4g} {unit}".rstrip(" -")
    sens = sensitivity(ev, v, worst, searched)
    msg = (f"no design satisfies {ev.req.describe(worst, ev.unit)} (of {len(pop)} designs in the final "
           f"population, {fails[worst]} fail it; the least-violating design misses it by {by})"
           f"{' after certification' if certified else ''}; {_what_helps(sens, -miss, unit)}")
    return NoFeasibleDesign(msg, {"violations": per, "fails": fails, "miss": miss, "unit": unit,
                                  "sensitivity": sens})


#: what a designer does for each change :func:`~mechopt.analysis.design_eval.sensitivity` measures
_ACTIONS = {"longer links": "raise --max-length", "shorter links": "lower --min-length",
            "task moved up": "--place free-y or move the task", "task moved down": "--place free-y or move the task",
            "task moved right": "--place free or move the task", "task moved left": "--place free or move the task",
            "faster actuators": "raise --actuator-speed", "stronger actuators": "raise --actuator-torque"}


def _miss_text(margin: float, unit: str) -> str:
    text = f"meets it by {margin:.4g} {unit}" if margin >= 0 else f"misses it by {-margin:.4g} {unit}"
    return text.rstrip(" -")


def _what_helps(sens: dict, margin: float, unit: str) -> str:
    """The measured changes that raise the least-violating design's margin, best first
    (at most three, each with the margin it reaches), or that none of them helps."""
    # a gain under 0.1 % of the miss is no help (rounding and the samples' resolution)
    gains = sorted(((m - margin, k) for k, m in sens.items()
                    if math.isfinite(m) and m - margin > 1e-3 * abs(margin)), reverse=True)
    if not math.isfinite(margin):  # no margin in the requirement's unit to compare
        return "relax it, or change the placement (--place) or the length bounds"
    if not gains:
        return f"measured at that design, none of: {', '.join(sens)} (10 % each) helps: relax the requirement"
    parts = [f"{k} ({_miss_text(sens[k], unit)}; {_ACTIONS[k]})" for _, k in gains[:3]]
    return "what helps, measured at that design (10 % each): " + ", ".join(parts)


# ------------------------------------------------------------------ figure
def plot_design(ev: DesignEvaluator, rec: dict, n: int = 241):
    """The chosen mechanism at the task's reference pose, the task (titled with where it
    was placed), the good-conditioning workspace ``{LCI >= gamma}`` of its
    singularity-free piece (only with a ``min_lci`` requirement), the type-II locus, the
    reachable boundary and the joint ranges, with units; with a collision option
    (:func:`mechopt.requirements.collisions.drawn`) its bodies as capsules, the keep-out
    zone and the worst-clearance pose (:func:`mechopt.run.plotting.draw_collisions`).

    Parameters
    ----------
    ev : mechopt.analysis.design_eval.DesignEvaluator
        The run's evaluator.
    rec : dict
        The design record (:meth:`DesignResult.pick`).
    n : int
        Raster points per side of the drawn fields.

    Returns
    -------
    Figure
        The drawing (not saved).
    """
    from matplotlib.figure import Figure

    mech = rec["mechanism"]
    spec = ev.spec
    v = {**rec["variables"], **rec["task_placement"]}
    task = ev.task.moved_to(v["task_x"], v["task_y"])
    unit = ev.unit
    gamma = ev.req.min_lci  # the good-conditioning zone is drawn only when asked for
    x0, x1, y0, y1 = task.bbox
    bb = mech.bounding_box()
    off = spec.to_mech(mech, 0.0, 0.0)[0]
    bx0, bx1, by0, by1 = bb[0] - off, bb[1] - off, bb[2], bb[3]
    X0, X1 = min(bx0, x0), max(bx1, x1)
    Y0, Y1 = min(by0, y0, 0.0), max(by1, y1)
    pad = 0.05 * max(X1 - X0, Y1 - Y0)
    gx, gy = np.meshgrid(np.linspace(X0 - pad, X1 + pad, n), np.linspace(Y0 - pad, Y1 + pad, n))
    mx, my = spec.to_mech(mech, gx, gy)
    f = mech.type2_function(mx, my)
    rx, ry = task.reference if task.is_region else task.pts[0]
    s0 = Singular.sign(ev.context(v))  # the assembly mode the design was evaluated in
    lci = _ix.lci(mech.jacobian(mx, my))
    good = (np.sign(f) == s0) & (lci >= (gamma if gamma is not None else np.inf))
    from scipy import ndimage

    labels, _ = ndimage.label(np.sign(f) == s0)  # the singularity-free piece holding the task
    i = int(np.clip(np.searchsorted(gy[:, 0], ry), 0, n - 1))
    k = int(np.clip(np.searchsorted(gx[0], rx), 0, n - 1))
    if labels[i, k]:
        good &= labels == labels[i, k]
    fig = Figure(figsize=(7.5, 6.5))
    ax = fig.add_subplot()
    if gamma is not None:
        ax.contourf(gx, gy, good.astype(float), levels=[0.5, 1.5], colors=["#cfe8cf"])
    ax.contour(gx, gy, np.where(np.isfinite(f), f, np.nan), levels=[0.0], colors="tab:red", linewidths=1.0)
    clr = mech.serial_clearance(mx, my)
    ax.contour(gx, gy, clr, levels=[0.0], colors="0.4", linewidths=0.8, linestyles="--")
    ox, oy = task.outline()
    if task.is_region or task.is_path:
        ax.plot(ox, oy, color="tab:blue", lw=2)
    else:
        ax.plot(ox, oy, ".", color="tab:blue", ms=3)
    # the mechanism at the reference pose
    px, py = float(rx), float(ry)
    pmx, pmy = spec.to_mech(mech, np.float64(px), np.float64(py))
    chain, bases = spec.sketch(mech, px, py, pmx, pmy)  # the legs, drawn by the mechanism's spec
    bodies = []  # with a collision option: the capsules, the keep-out zone, the worst-clearance pose
    if _collisions.drawn(ev.req, ev.objectives):
        from mechopt.run.plotting import draw_collisions

        bodies = draw_collisions(ax, ev.context(v, Sampling.fine()), (px, py), unit)
    for (sx0, sy0), (sx1, sy1) in spec.actuator_paths(mech, rec.get("strokes", [])):
        ax.plot([sx0, sx1], [sy0, sy1], color="k", lw=4, alpha=0.3, solid_capstyle="butt")
    for c in chain:
        c = np.array(c)
        ax.plot(c[:, 0], c[:, 1], "-o", color="k", lw=2, ms=4)
    ax.plot(*np.array(bases).T, "s", color="k", ms=7)
    lines = spec.variable_lines(rec["variables"], unit)
    if "joint_ranges_deg" in rec:
        for i, (a, b) in enumerate(rec["joint_ranges_deg"], 1):
            lines.append(f"theta{i} in [{a:.1f}, {b:.1f}] deg over the task")
            rr = spec.joint_arc_radius(mech, i - 1)
            if rr is not None:  # the crank's range, as an arc about its base joint
                base = bases[i - 1]
                t = np.radians(np.linspace(a, b, 60))
                ax.plot(base[0] + rr * np.cos(t), base[1] + rr * np.sin(t), color="tab:purple", lw=1.5)
    if "strokes" in rec:
        for i, (lo, hi) in enumerate(rec["strokes"], 1):
            lines.append(f"q{i} in [{lo:.4g}, {hi:.4g}] {unit} (stroke {hi - lo:.4g} {unit})")
    for k, val in rec["objectives"].items():
        lines.append(f"{k} = {val:.5g} {rec['objective_units'][k]}")
    ax.text(0.01, 0.99, "\n".join(lines), transform=ax.transAxes, va="top", fontsize=7,
            bbox=dict(boxstyle="round", fc="white", alpha=0.8))
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    handles = [Line2D([], [], color="tab:blue", lw=2, label="task")]
    if gamma is not None:
        handles.append(Patch(color="#cfe8cf", label=f"GCW: LCI >= {gamma:g}, same type-II sign"))
    handles += [Line2D([], [], color="tab:red", lw=1, label="type-II singularity"),
                Line2D([], [], color="0.4", lw=0.8, ls="--", label="reachable boundary")]
    if "joint_ranges_deg" in rec:
        handles.append(Line2D([], [], color="tab:purple", lw=1.5, label="crank ranges"))
    if bodies:  # a longer legend: beside the axes
        ax.legend(handles=handles + bodies, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=7)
    else:
        ax.legend(handles=handles, loc="lower right", fontsize=7)
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    # the task as placed (its label names the position it was given at)
    ax.set_title(f"{spec.name} sized for {ev.task.label}\ntask centre placed at ({v['task_x']:.4g}, "
                 f"{v['task_y']:.4g}) {unit}", fontsize=10)
    return fig
