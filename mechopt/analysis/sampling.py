"""How a task is sampled for one evaluation of a design, and the searches that refine a
minimum over it.

Samples (:func:`samples`): ``n_boundary`` points along the task's boundary ``dT`` at
uniform arc length (every polygon vertex included; largest gap ``h_b``) and an
``n_interior`` x ``n_interior`` grid over its box, kept inside ``T``; a path's samples
run along the polyline in the same way (every way-point included), with no interior;
a point task's samples are its points.

Minima (:func:`region_mins`): the minimum of a continuous function over ``T`` is
attained on ``dT`` or at an interior critical point: both are located on the samples
and refined by zooming (boundary: 4 levels of 17 points around the 3 lowest boundary
samples, interior: 3 levels of 9 x 9 points around the 3 lowest grid samples, each
level 4x (interior) or 8x (boundary) finer), which places the minimiser to ``h/64``
(interior) and ``h_b/2048`` (boundary). Stated tolerance: the grid resolves the
basins of the minimum (no dip narrower than a grid cell); the value is then exact to
the zoom resolution (about 1e-5 relative for LCI on the examples; the tests check
every front design on a 200 x 200 grid). Ranges over the boundary
(:func:`leg_ranges`) use the boundary zoom alone.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from mechopt.core.jit import Twin
from mechopt.core.protocol import mark_in_reach

__all__ = ["Sampling", "samples", "bad_to", "region_mins", "leg_ranges", "minimise", "compiled_region_min"]


#: the zoom (module doc): starts per search, and per search its levels and points per
#: level (the boundary's along the arc, the interior's per side of its square)
ZOOM_STARTS = 3
BOUNDARY_LEVELS, BOUNDARY_POINTS = 4, 17
INTERIOR_LEVELS, INTERIOR_POINTS = 3, 9


@dataclass(frozen=True)
class Sampling:
    """Sample counts of one evaluation: boundary points, interior grid per side.

    Parameters
    ----------
    n_boundary : int
        Boundary points.
    n_interior : int
        Interior grid nodes per side.
    refine : bool
        Refine minima by zooming.
    settle : bool
        Leave unrefined the minima of the requirements the samples show comfortably
        met (:meth:`mechopt.requirements.base.Requirement.settled`): the sampling of
        ``mechopt design``'s search (:data:`mechopt.workflows.design.SEARCH`), where only
        the sign of such a requirement's ``g`` reaches the search (pymoo's constraint
        violation counts ``max(0, g)``); never the certification's.
    """

    n_boundary: int = 192
    n_interior: int = 13
    refine: bool = True
    settle: bool = False

    @classmethod
    def fine(cls):
        """The certification of :func:`certify` (front designs, design.json).

        Returns
        -------
        Sampling
            2048 boundary points, a 61 x 61 grid, refinement.
        """
        return cls(2048, 61, True)


def bad_to(v, bad):
    """NaN (unreachable) replaced by ``bad``.

    Parameters
    ----------
    v : ndarray
        Values.
    bad : float
        The replacement of NaN.

    Returns
    -------
    ndarray
        The values.
    """
    return np.where(np.isfinite(v), v, bad)


def _readonly(*arrays):
    """``arrays``, made read-only (kept samples are shared by many evaluations)."""
    for a in arrays:
        a.setflags(write=False)
    return arrays


def samples(task, s: Sampling) -> dict:
    """The samples of one evaluation of ``task`` (module doc): boundary parameters
    ``tb`` and points ``bx, by`` (largest gap ``gap``), interior grid ``ix, iy`` (step
    ``step``), and both together, ``allx, ally``. A point task's points are its
    boundary samples (contiguous copies: every sample set is a contiguous array).

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The (placed) task.
    s : Sampling
        The counts.

    Returns
    -------
    dict
        The arrays named above [L].
    """
    if task.is_region:
        tb, gap = task.boundary_params(s.n_boundary)
        bx, by = task.boundary_at(tb)
        ix, iy, step = task.grid(s.n_interior)
    elif task.is_path:  # along the polyline, as a boundary; no interior
        tb, gap = task.boundary_params(s.n_boundary)
        bx, by = task.boundary_at(tb)
        ix, iy, step = np.zeros(0), np.zeros(0), 0.0
    else:
        tb, gap = np.zeros(0), 0.0
        bx, by = task.pts[:, 0].copy(), task.pts[:, 1].copy()
        ix, iy, step = np.zeros(0), np.zeros(0), 0.0
    allx, ally = np.concatenate([bx, ix]), np.concatenate([by, iy])
    mark_in_reach(*_readonly(tb, bx, by, ix, iy, allx, ally))  # every evaluation's kinematics read them
    return dict(task=task, tb=tb, gap=gap, bx=bx, by=by, ix=ix, iy=iy, step=step, allx=allx, ally=ally)


@lru_cache(maxsize=None)
def _boundary_offsets(size, levels, n):
    """Parameter offsets of each level of the boundary zoom over ``size`` samples:
    ``n`` points over +-1.5 sample spacings, each level ``(n - 1) / 2`` times finer."""
    dt = 1.0 / size * 1.5
    out = []
    for _ in range(levels):
        out.append(np.linspace(-dt, dt, n))
        dt = 2.0 * dt / (n - 1)
    return _readonly(*out)


@lru_cache(maxsize=None)
def _interior_offsets(n):
    """The ``n x n`` offsets (in steps) of the interior zoom, ravelled: ``(GX, GY)``."""
    g = np.linspace(-1.0, 1.0, n)
    return _readonly(*(a.ravel() for a in np.meshgrid(g, g)))


def _lowest(vals, k):
    """The indices of the ``k`` lowest values, the set of ``np.argsort(vals)[:k]``,
    without sorting them all: by a partition (compiled: one pass keeping the ``k + 1``
    lowest, :func:`_lowest_loop`) when the ``k``-th lowest value is below the
    ``(k + 1)``-th (the set is then unique; ties inside it leave its order to the partial
    sort, which no search depends on: each start zooms on its own and the searches take
    the minimum over all); when a tie straddles the ``k``-th place (or with NaN) by the
    full sort, whose choice among equal values the zoom has always started from."""
    if vals.size > k + 1:
        if Twin.compiled():  # one pass, no sort (about 1 us instead of 7 for the fine samples)
            out = np.empty(k, dtype=np.intp)
            if _LOWEST_TWIN(vals, k, out):
                return out
        else:
            part = np.argpartition(vals, k)[:k + 1]  # the k + 1 lowest, in no order
            o = np.argsort(vals[part])
            low = vals[part][o]
            if low[k - 1] < low[k]:  # False with NaN
                return part[o[:k]]
    return np.argsort(vals)[:k]


def _lowest_loop(vals, k, out):
    """:func:`_lowest`'s partition in one pass (compiled, :class:`mechopt.core.jit.Twin`):
    the ``k + 1`` lowest values kept in order (an equal value after them does not enter);
    when the ``k``-th is below the ``(k + 1)``-th, their indices into ``out`` and True
    (the set is then unique), else False (a NaN among the values, a tie across the
    ``k``-th place: the caller sorts). ``vals`` has more than ``k + 1`` values."""
    m = k + 1
    bv, bi = np.empty(m), np.empty(m, dtype=np.intp)
    c = 0
    for i in range(vals.size):
        v = vals[i]
        if v != v:
            return False
        if c < m:
            j = c
            c += 1
        elif v < bv[m - 1]:
            j = m - 1
        else:
            continue
        while j > 0 and bv[j - 1] > v:
            bv[j], bi[j] = bv[j - 1], bi[j - 1]
            j -= 1
        bv[j], bi[j] = v, i
    if not bv[k - 1] < bv[k]:
        return False
    for j in range(k):
        out[j] = bi[j]
    return True


_LOWEST_TWIN = Twin(_lowest_loop)


def _keep_lower(best, v):
    """Python's ``min(best, v)`` row by row: ``v`` where ``v < best`` (so a NaN ``v``
    never replaces ``best``, and a NaN ``best`` stays)."""
    return np.where(v < best, v, best)


def _own_blocks(V, m):
    """Each row's values at its own points: row ``r`` of ``V`` (shape ``(m, m * P)``,
    ``F`` at the points of every row, row ``r``'s ``P`` points in the ``r``-th block),
    as one array of shape ``(m * P,)``."""
    if m == 1:
        return V[0]
    return V.reshape(m, m, -1)[np.arange(m), np.arange(m)].ravel()


def _boundary_search(ctx, vals, refine, k=ZOOM_STARTS, levels=BOUNDARY_LEVELS, n=BOUNDARY_POINTS):
    """Minimum over the task's boundary of each row of ``vals`` (a function's values at
    the boundary samples, one function per row), refined by zooming (module doc) around
    each row's ``k`` lowest samples. A generator run by :func:`minimise`: it yields the
    boundary parameters of each zoom level (every row's, row after row) and is sent the
    values there (``F``'s rows at all of them); it returns the minima, one per row.
    The rows zoom independently: each reads only its own function at its own points,
    so the minima are those of one search per row."""
    m = vals.shape[0]
    if vals.shape[1] == 0:
        return [math.inf] * m
    best = vals.min(axis=1)
    if not refine or ctx["tb"].size == 0:
        return [float(b) for b in best]
    t = ctx["tb"][np.concatenate([_lowest(v, k) for v in vals])]  # k starts per row, row after row
    rows = np.arange(t.size)
    for off in _boundary_offsets(ctx["tb"].size, levels, n):
        ts = t[:, None] + off
        vv = _own_blocks((yield ts.ravel()), m).reshape(ts.shape)
        t = ts[rows, np.argmin(vv, axis=1)]
        best = _keep_lower(best, vv.reshape(m, -1).min(axis=1))
    return [float(b) for b in best]


def _interior_search(ctx, vals, refine, k=ZOOM_STARTS, levels=INTERIOR_LEVELS, n=INTERIOR_POINTS):
    """Minimum over the task's interior grid of each row of ``vals`` (a function's
    values there, one function per row), refined by zooming (module doc) around each
    row's ``k`` lowest grid points; a generator run by :func:`minimise`, as
    :func:`_boundary_search`, that yields points ``(x, y)``."""
    m = vals.shape[0]
    if ctx["ix"].size == 0:
        return [math.inf] * m
    best = vals.min(axis=1)
    if not refine:
        return [float(b) for b in best]
    order = np.concatenate([_lowest(v, k) for v in vals])  # k starts per row, row after row
    px, py = ctx["ix"][order], ctx["iy"][order]
    rows = np.arange(order.size)
    h = ctx["step"]
    task = ctx["task"]
    GX, GY = _interior_offsets(n)
    for _ in range(levels):
        X = px[:, None] + h * GX
        Y = py[:, None] + h * GY
        inside = task.contains(X, Y)
        vv = np.where(inside, _own_blocks((yield X.ravel(), Y.ravel()), m).reshape(X.shape), np.inf)
        j = np.argmin(vv, axis=1)
        px, py = X[rows, j], Y[rows, j]
        best = _keep_lower(best, vv.reshape(m, -1).min(axis=1))
        h = 2.0 * h / (n - 1)
    return [float(b) for b in best]


def minimise(F, searches, task):
    """Run the zoom ``searches`` (generators of :func:`_boundary_search` and
    :func:`_interior_search` on ``task``) together and return their minima: each
    round maps the boundary parameters they ask for to points in one call and passes
    all the points to ``F`` in one call (``F(x, y)``: the values of the searched
    functions as rows, shape ``(m, N)``), then sends each search its columns. A call of
    a mechanism's method on 50 points costs mostly its overhead: batching the searches
    of one evaluation saves most of its time.

    Parameters
    ----------
    F : callable
        ``F(x, y)`` -> the searches' values.
    searches : list
        Generators of the boundary and interior searches.
    task : mechopt.analysis.task.Task
        The (placed) task.

    Returns
    -------
    list of float
        The minima, one per search.
    """
    out = [None] * len(searches)
    asks = {}

    def advance(i, values=None):
        try:
            asks[i] = searches[i].send(values)
        except StopIteration as stop:
            out[i] = stop.value

    for i in range(len(searches)):
        advance(i)
    while asks:
        ids, reqs = list(asks), list(asks.values())
        asks.clear()
        ts = [r for r in reqs if not isinstance(r, tuple)]  # boundary parameters
        bx, by = task.boundary_at(np.concatenate(ts)) if ts else (None, None)
        xs, ys, at = [], [], 0
        for r in reqs:
            if isinstance(r, tuple):
                xs.append(r[0])
                ys.append(r[1])
            else:
                xs.append(bx[at:at + r.size])
                ys.append(by[at:at + r.size])
                at += r.size
        V = F(np.concatenate(xs), np.concatenate(ys))
        at = 0
        for i, x in zip(ids, xs):
            advance(i, V[:, at:at + x.size])
            at += x.size
    return out


def region_mins(ctx, F, refine, vals):
    """Minimum over the task of each row of ``F(x, y)`` (functions evaluated by one
    call, shape ``(m, N)``): the boundary and interior searches of every row
    (:func:`_boundary_search`, :func:`_interior_search`) run together; ``vals`` is
    ``F`` at ``ctx["allx"], ctx["ally"]`` (the boundary samples, then the grid).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's context (samples, task).
    F : callable
        ``F(x, y)`` -> shape ``(m, N)``.
    refine : bool
        Refine by zooming.
    vals : ndarray
        ``F`` at the samples.

    Returns
    -------
    list of float
        The minimum of each row.
    """
    nb = ctx["bx"].size
    vals = np.asarray(vals)
    on_boundary, inside = minimise(F, [_boundary_search(ctx, vals[:, :nb], refine),
                                       _interior_search(ctx, vals[:, nb:], refine)], ctx["task"])
    return [min(b, i) for b, i in zip(on_boundary, inside)]


@lru_cache(maxsize=None)
def _boundary_offset_rows(size, levels, n):
    """:func:`_boundary_offsets` as one array, a level per row (the compiled zoom's)."""
    return _readonly(np.stack(_boundary_offsets(size, levels, n)))[0]


def compiled_region_min(ctx, kernel, scale, bad, vals, k=ZOOM_STARTS):
    """The minima over the boundary and over the interior of one function,
    ``scale * f`` with ``NaN -> bad``, by the compiled zoom
    (:func:`mechopt.core.zoom.zoom_minimum`) of a mechanism's point kernel ``f``
    (:class:`mechopt.core.zoom.ZoomKernel`), refined: those of :func:`_boundary_search`
    and :func:`_interior_search` bit for bit (the starts are chosen here, by
    :func:`_lowest`, as there), whose smaller one :func:`region_mins` returns. None for
    a circle task (its boundary needs ``cos`` and ``sin``: the NumPy search).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's context (samples, task).
    kernel : mechopt.core.zoom.ZoomKernel
        The compiled search.
    scale, bad : float
        The factor of the kernel's value and the replacement of a non-finite one.
    vals : ndarray
        The function at ``ctx["allx"], ctx["ally"]``, shape ``(N,)``.
    k : int
        Starts per search.

    Returns
    -------
    tuple of float or None
        ``(boundary minimum, interior minimum)`` (inf where there is none).
    """
    task = ctx["task"]
    if task.kind == "circle":
        return None
    nb = ctx["bx"].size
    vb, vi = vals[:nb], vals[nb:]
    tb_best = float(vb.min()) if vb.size else math.inf
    in_best = float(vi.min()) if ctx["ix"].size else math.inf
    if (vb.size == 0 or ctx["tb"].size == 0) and ctx["ix"].size == 0:
        return tb_best, in_best  # a point task: no zoom
    vx, vy, wy, ex, ey, L2, L, cum = task.edges
    if vb.size and ctx["tb"].size:
        t0 = ctx["tb"][_lowest(vb, k)]
        offsets = _boundary_offset_rows(ctx["tb"].size, BOUNDARY_LEVELS, BOUNDARY_POINTS)
    else:
        t0, offsets = np.zeros(0), np.zeros((0, BOUNDARY_POINTS))
    GX, GY = _interior_offsets(INTERIOR_POINTS)
    if ctx["ix"].size:
        order = _lowest(vi, k)
        px0, py0, levels = ctx["ix"][order], ctx["iy"][order], INTERIOR_LEVELS
    else:
        px0, py0, levels = np.zeros(0), np.zeros(0), 0
    return kernel.run(float(scale), float(bad), tb_best, t0, offsets, task.is_path, vx, vy, wy, ex, ey, L, L2, cum,
                      task.inside_tolerance, in_best, px0, py0, float(ctx["step"]), GX, GY, levels)


def leg_ranges(ctx, legs, refine, bad=(np.inf, np.inf), kernel=None):
    """``[(lo1, hi1), (lo2, hi2)]``: the range over the task's boundary of each of the
    two values ``legs(x, y)`` returns (one per leg: actuator or link angle), NaN
    replaced by ``bad[0]`` for the minimum and ``bad[1]`` for the maximum: the
    boundary minima (:func:`_boundary_search`) of ``q1, -q1, q2, -q2``, searched
    together (:func:`minimise`: one call of ``legs`` per round, not four); with
    ``kernel`` (the mechanism's compiled zoom of the same two values,
    :class:`mechopt.core.zoom.ZoomKernel`) the refinement runs compiled
    (:func:`mechopt.core.zoom.zoom_ranges`, the same minima bit for bit) on a polygon or
    path task.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's context (samples, task).
    legs : callable
        ``legs(x, y) -> (v1, v2)``.
    refine : bool
        Refine by zooming.
    bad : tuple of float
        Replacements of NaN.
    kernel : mechopt.core.zoom.ZoomKernel, optional
        The compiled zoom of ``legs``.

    Returns
    -------
    list of tuple
        ``[(lo1, hi1), (lo2, hi2)]``.
    """
    def rows(x, y):
        q1, q2 = legs(x, y)[:2]
        return np.stack([bad_to(q1, bad[0]), bad_to(-q1, bad[1]), bad_to(q2, bad[0]), bad_to(-q2, bad[1])])

    vals = rows(ctx["bx"], ctx["by"])
    task = ctx["task"]
    if kernel is not None and refine and ctx["tb"].size and vals.shape[1] and task.kind != "circle":
        vx, vy, _, ex, ey, _, L, cum = task.edges
        t0 = ctx["tb"][np.concatenate([_lowest(v, ZOOM_STARTS) for v in vals])]  # as _boundary_search
        m = [float(v) for v in kernel.run(float(bad[0]), float(bad[1]), vals.min(axis=1), t0,
                                          _boundary_offset_rows(ctx["tb"].size, BOUNDARY_LEVELS, BOUNDARY_POINTS),
                                          task.is_path,
                                          vx, vy, ex, ey, L, cum)]
    else:
        m = minimise(rows, [_boundary_search(ctx, vals, refine)], task)[0]
    return [(m[0], -m[1]), (m[2], -m[3])]
