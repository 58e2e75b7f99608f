"""The zoom of :mod:`mechopt.analysis.sampling` compiled: one design's minimum over a
polygon (or path) task of one pointwise function, refined by zooming, in one call.

:func:`mechopt.analysis.sampling.region_mins` refines a minimum by zooming around the
lowest samples (boundary: levels of ``n`` arc-length offsets around each start;
interior: levels of ``n x n`` points kept inside the task). Written with NumPy, each
level costs a few dozen small array operations and a call of the function through the
mechanism's methods: three quarters of a design evaluation's time. Here the same
search runs as one compiled loop over levels, starts and points, calling a compiled
point kernel ``f(p, x, y)`` of the mechanism (:meth:`PlanarMechanism.zoom_kernel
<mechopt.core.protocol.PlanarMechanism.zoom_kernel>`).

It gives the NumPy search's minimum bit for bit: each point's coordinates, the
kernel's value (the operations of the NumPy path, :class:`mechopt.core.jit.Twin`) and
each choice are those of :func:`~mechopt.analysis.sampling._boundary_search` and
:func:`~mechopt.analysis.sampling._interior_search` (``np.argmin``: the first lowest
value, the first NaN if any; ``min`` over a level: NaN if any value is NaN; a level's
minimum replaces the best only when lower). The starts (the lowest samples) are chosen
by the caller, with NumPy, as there. Tests compare the two searches bit for bit
(tests/test_zoom.py).

The polygon's boundary points and its inside test are the per-point formulas of
:meth:`mechopt.analysis.task.Task.boundary_at` and :meth:`~mechopt.analysis.task.Task.contains`
(:func:`polygon_points`, :func:`contains_points`), which that module's compiled twins
call too. A circle's boundary needs ``cos`` and ``sin`` (NumPy's and the C library's
differ in the last bit), so a circle task keeps the NumPy search.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mechopt.core import jit
from mechopt.core.jit import jitable
from mechopt.core.protocol import POINT_MAX

__all__ = ["ZoomKernel", "point_in_reach", "polygon_points", "contains_points", "arc_params", "polygon_grid",
           "zoom_minimum", "zoom_ranges"]


@dataclass(frozen=True)
class ZoomKernel:
    """A mechanism's compiled zoom for one quantity: ``entry`` (a
    :class:`mechopt.core.jit.Twin` whose loop calls :func:`zoom_minimum` with the
    quantity's point kernel) and the kernel's parameters ``params`` (a float array).

    Parameters
    ----------
    entry : mechopt.core.jit.Twin
        The compiled search, called as ``entry(params, search)`` (``search`` the tuple of
        the remaining arguments of :func:`zoom_minimum` or :func:`zoom_ranges`).
    params : ndarray
        The point kernel's parameters (lengths and signs).
    """

    entry: object
    params: np.ndarray

    def run(self, *search):
        """The compiled search with this kernel's parameters: :func:`zoom_minimum`'s or
        :func:`zoom_ranges`' result (the quantity's, :meth:`PlanarMechanism.zoom_kernel
        <mechopt.core.protocol.PlanarMechanism.zoom_kernel>`); the entry receives the
        arguments as one tuple.

        Parameters
        ----------
        *search
            The arguments of :func:`zoom_minimum` or :func:`zoom_ranges` after ``p``.

        Returns
        -------
        tuple of float or ndarray
            The search's minima.
        """
        return self.entry(self.params, search)

    def with_row(self, row):
        """The same kernel for row ``row`` of a quantity of several rows (which takes the
        row in its last parameter).

        Parameters
        ----------
        row : int
            The row.

        Returns
        -------
        ZoomKernel
            The kernel of that row.
        """
        params = self.params.copy()
        params[-1] = row
        return ZoomKernel(self.entry, params)


@jitable
def point_in_reach(v):
    """A coordinate as :func:`mechopt.core.protocol.as_points` keeps it (compiled
    kernels): NaN beyond :data:`~mechopt.core.protocol.POINT_MAX`.

    Parameters
    ----------
    v : float
        A coordinate [L].

    Returns
    -------
    float
        ``v``, or NaN.
    """
    return np.nan if abs(v) > POINT_MAX else v


# The polygon's per-point formulas are written once each, inside loops over a batch of
# points (polygon_points, contains_points): a compiled helper called per point with the
# edge arrays pays numba's reference counting of each array argument at every call
# (about 8 ns an array, ten times the arithmetic of a boundary point).
@jitable
def polygon_points(t, is_path, vx, vy, ex, ey, L, cum, bx, by):
    """The points at the arc-length fractions ``t`` of a polygon's boundary (mod 1) or
    of a path (clipped to [0, 1]), into ``bx, by``:
    :meth:`mechopt.analysis.task.Task.boundary_at` point by point.

    Parameters
    ----------
    t : ndarray
        The arc-length fractions.
    is_path : bool
        A path (two ends) rather than a closed polygon.
    vx, vy, ex, ey, L, cum : ndarray
        The edges (:attr:`mechopt.analysis.task.Task.edges`): start points, vectors
        [unit], lengths [unit] and the vertices' arc-length fractions.
    bx, by : ndarray
        The points [unit], ``t.size`` each (written).
    """
    last = vx.size - 1
    for i in range(t.size):
        # t mod 1 as np.mod computes it (fmod is exact, so t - floor(t) is the same float)
        ti = min(max(t[i], 0.0), 1.0) if is_path else t[i] - np.floor(t[i])
        # np.searchsorted(cum, ti, side="right") - 1: the last vertex at or before ti (a
        # NaN ti gives a NaN point whatever the edge)
        lo, hi = 0, cum.size
        while lo < hi:
            mid = (lo + hi) // 2
            if cum[mid] <= ti:
                lo = mid + 1
            else:
                hi = mid
        k = min(max(lo - 1, 0), last)
        s = (ti - cum[k]) / ((cum[k + 1] - cum[k]) if L[k] > 0 else 1.0)
        bx[i], by[i] = vx[k] + s * ex[k], vy[k] + s * ey[k]


@jitable
def arc_params(n, is_path, L, cum, total):
    """:meth:`mechopt.analysis.task.Task.boundary_params` of a polygon or path: ``m_i =
    max(1, ceil(n L_i / total))`` samples on edge ``i`` at the fractions ``cum_i +
    (cum_{i+1} - cum_i) k / m_i``, ``k < m_i`` (a path's last point too), and the largest
    gap ``max(L_i / m_i)``; NumPy's operations on each element, so the same floats.

    Parameters
    ----------
    n : int
        Requested number of samples (at least 8).
    is_path : bool
        A path (two ends) rather than a closed polygon.
    L, cum : ndarray
        The edges' lengths [unit] and the vertices' arc-length fractions
        (:attr:`mechopt.analysis.task.Task.edges`).
    total : float
        ``L.sum()`` (NumPy's pairwise sum) [unit].

    Returns
    -------
    t : ndarray
        The arc-length fractions.
    gap : float
        The largest distance between neighbouring samples [unit] (0 if NaN).
    """
    m = np.empty(L.size, dtype=np.int64)
    size = 1 if is_path else 0
    for i in range(L.size):
        m[i] = max(1, np.int64(np.ceil(n * L[i] / total)))
        size += m[i]
    t = np.empty(size)
    j = 0
    gap, nan = -np.inf, False
    for i in range(L.size):
        d = cum[i + 1] - cum[i]
        for k in range(m[i]):
            t[j] = cum[i] + d * k / m[i]
            j += 1
        g = L[i] / m[i]
        nan = nan or g != g
        gap = g if g > gap else gap
    if is_path:
        t[j] = 1.0
    return t, (gap if gap > 0.0 and not nan else 0.0)


@jitable
def _linspace(start, stop, n, out):
    """``np.linspace(start, stop, n)`` into ``out``: NumPy 2's floats (``i * step +
    start``, the last one ``stop``; ``i / div * delta + start`` where the step is 0)."""
    div = n - 1
    delta = stop - start
    if div > 0:
        step = delta / div
        for i in range(n):
            out[i] = ((i / div) * delta if step == 0 else i * step) + start
        out[n - 1] = stop
    else:
        for i in range(n):
            out[i] = i * delta + start


@jitable
def polygon_grid(x0, x1, y0, y1, n, vx, vy, wy, ex, ey, L2, tol):
    """The nodes of the ``n x n`` grid over ``[x0, x1] x [y0, y1]`` (``np.linspace`` each
    way, in ``np.meshgrid``'s order: row after row of constant ordinate) that
    :func:`contains_points` keeps: :meth:`mechopt.analysis.task.Task.grid` of a polygon.

    Parameters
    ----------
    x0, x1, y0, y1 : float
        The bounding box [unit].
    n : int
        Nodes per side.
    vx, vy, wy, ex, ey, L2 : ndarray
        The edges (:attr:`mechopt.analysis.task.Task.edges`).
    tol : float
        :attr:`mechopt.analysis.task.Task.inside_tolerance` [unit].

    Returns
    -------
    x, y : ndarray
        The nodes kept [unit].
    """
    xs, ys = np.empty(n), np.empty(n)
    _linspace(x0, x1, n, xs)
    _linspace(y0, y1, n, ys)
    gx, gy = np.empty(n * n), np.empty(n * n)
    for r in range(n):
        for c in range(n):
            gx[r * n + c], gy[r * n + c] = xs[c], ys[r]
    keep = np.empty(n * n, dtype=np.bool_)
    contains_points(gx, gy, vx, vy, wy, ex, ey, L2, tol, keep)
    m = 0
    for i in range(n * n):
        if keep[i]:
            gx[m], gy[m] = gx[i], gy[i]
            m += 1
    return gx[:m].copy(), gy[:m].copy()


@jitable
def contains_points(x, y, vx, vy, wy, ex, ey, L2, tol, out):
    """Whether each point ``(x[i], y[i])`` lies inside a polygon or within ``tol`` of its
    boundary, into ``out``: :meth:`mechopt.analysis.task.Task.contains` point by point.

    The even-odd rule first: the crossing abscissae ``ex (y - vy) / ey + vx`` of the
    edges with one end above the point's line, computed again only when the ordinate
    changes (a grid's row shares them: the same floats, so the same parity); then, for a
    point outside, the distance to the edges (:meth:`Task._distance
    <mechopt.analysis.task.Task._distance>`; NaN propagating as in NumPy's clip, hypot
    and min). Where no NaN can arise (a finite point, edges of positive length) the
    first edge within ``tol`` decides, as the minimum over all would, and an edge whose
    box, widened by 2 tol and by 1e-14 times the magnitudes involved (~45 ulps: more
    than the rounding of the distance computed below and of the box's corner v + e),
    does not hold the point is farther than ``tol`` in computed distance too, so it
    cannot decide.

    Parameters
    ----------
    x, y : ndarray
        The points [unit].
    vx, vy, wy, ex, ey, L2 : ndarray
        The edges (:attr:`mechopt.analysis.task.Task.edges`): start points, the next
        vertex's ordinate, vectors and squared lengths [unit, unit^2].
    tol : float
        :attr:`mechopt.analysis.task.Task.inside_tolerance` [unit].
    out : ndarray
        Booleans, ``x.size`` (written).
    """
    edges_ok = True
    for j in range(L2.size):
        edges_ok = edges_ok and L2[j] > 0.0
    xc = np.empty(vx.size)
    k, row_y = 0, np.nan
    for i in range(x.size):
        px, py = x[i], y[i]
        if not py == row_y:  # a new row (a NaN ordinate: every time)
            k, row_y = 0, py
            for j in range(vx.size):
                if (vy[j] > py) != (wy[j] > py):
                    xc[k] = ex[j] * (py - vy[j]) / ey[j] + vx[j]
                    k += 1
        n = 0
        for q in range(k):
            if px < xc[q]:
                n += 1
        if n % 2 == 1:
            out[i] = True
            continue
        early = edges_ok and np.isfinite(px) and np.isfinite(py)
        best, near = np.inf, False
        for j in range(vx.size):
            if early:
                wx = vx[j] + ex[j]
                m = 2.0 * tol + 1e-14 * (abs(px) + abs(py) + abs(vx[j]) + abs(vy[j]) + abs(ex[j]) + abs(ey[j]))
                if (px < min(vx[j], wx) - m or px > max(vx[j], wx) + m
                        or py < min(vy[j], wy[j]) - m or py > max(vy[j], wy[j]) + m):
                    continue
            dx, dy = px - vx[j], py - vy[j]
            s = (dx * ex[j] + dy * ey[j]) / L2[j]
            if s < 0.0:
                s = 0.0
            elif s > 1.0:
                s = 1.0
            d = np.hypot(dx - s * ex[j], dy - s * ey[j])
            if early and d <= tol:
                near = True
                break
            best = np.minimum(best, d)
        out[i] = near or best <= tol


@jitable
def _offset_points(t, offsets, is_path, vx, vy, ex, ey, L, cum, ts, bx, by):
    """The boundary points at the fractions ``t + offsets`` (a zoom level around one
    start) into ``bx, by`` (:func:`polygon_points`; ``ts`` holds the fractions)."""
    for j in range(offsets.size):
        ts[j] = t + offsets[j]
    polygon_points(ts, is_path, vx, vy, ex, ey, L, cum, bx, by)


@jitable
def _value(f, p, scale, bad, x, y):
    """``scale * f(p, x, y)``, ``bad`` where that is not finite (``bad_to``)."""
    v = scale * f(p, x, y)
    return v if np.isfinite(v) else bad


@jitable
def _lower(best, v):
    """``v`` where ``v < best`` (a NaN ``v`` never replaces ``best``)."""
    return v if v < best else best


@jitable
def _first_min(v, j, amin, imin, seen_nan):
    """One step of ``np.argmin``/``np.min`` over a row: the first lowest value, the
    first NaN once one is seen. Returns ``(amin, imin, seen_nan)``."""
    if seen_nan:
        return amin, imin, True
    if np.isnan(v):
        return v, j, True
    if j == 0 or v < amin:
        return v, j, False
    return amin, imin, False


@jitable
def _level(level_min, level_nan, amin, seen_nan):
    """A level's ``min`` over its starts' rows (NaN if any value is NaN): with one
    start's ``(amin, seen_nan)`` of :func:`_first_min`. Returns ``(level_min, level_nan)``."""
    if seen_nan:
        return level_min, True
    return (amin if amin < level_min else level_min), level_nan


@jitable
def zoom_minimum(f, p, scale, bad, tb_best, t0, offsets, is_path, vx, vy, wy, ex, ey, L, L2, cum, tol,
                 in_best, px0, py0, h0, gx, gy, in_levels):
    """``(boundary minimum, interior minimum)`` of ``scale * f(p, x, y)`` (non-finite
    values replaced by ``bad``) over a polygon or path task, refined by zooming: the
    searches of :mod:`mechopt.analysis.sampling` for one function (module doc).

    Boundary: from the arc-length fractions ``t0`` of the starts, one level per row of
    ``offsets`` (each start's ``t + offsets[level]``, the start moved to its lowest
    point), from ``tb_best`` (the samples' minimum). Interior: from ``(px0, py0)``,
    ``in_levels`` levels of the points ``p + h gx, p + h gy`` kept inside (``tol``),
    ``h`` from ``h0`` divided by ``(sqrt(gx.size) - 1) / 2`` a level, from ``in_best``.

    Parameters
    ----------
    f : callable
        The compiled point kernel ``f(p, x, y)``.
    p : ndarray
        Its parameters.
    scale, bad : float
        The factor of its value and the replacement of a non-finite one.
    tb_best : float
        The boundary samples' minimum.
    t0 : ndarray
        The boundary starts' arc-length fractions.
    offsets : ndarray
        The boundary zoom's offsets, one level per row.
    is_path : bool
        A path (two ends) rather than a closed polygon.
    vx, vy, wy, ex, ey, L, L2, cum : ndarray
        The edges (:attr:`mechopt.analysis.task.Task.edges`).
    tol : float
        :attr:`mechopt.analysis.task.Task.inside_tolerance` [unit].
    in_best : float
        The interior samples' minimum.
    px0, py0 : ndarray
        The interior starts [unit].
    h0 : float
        The interior grid's step [unit].
    gx, gy : ndarray
        The interior zoom's offsets (in steps), an ``n x n`` grid ravelled.
    in_levels : int
        Interior levels.

    Returns
    -------
    tuple of float
        ``(boundary minimum, interior minimum)``.
    """
    # boundary
    t = t0.copy()
    best_b = tb_best
    ts, bx, by = np.empty(offsets.shape[1]), np.empty(offsets.shape[1]), np.empty(offsets.shape[1])
    for lev in range(offsets.shape[0]):
        level_min, level_nan = np.inf, False
        for r in range(t.size):
            _offset_points(t[r], offsets[lev], is_path, vx, vy, ex, ey, L, cum, ts, bx, by)
            amin, imin, seen_nan = np.inf, 0, False
            for j in range(offsets.shape[1]):
                v = _value(f, p, scale, bad, bx[j], by[j])
                amin, imin, seen_nan = _first_min(v, j, amin, imin, seen_nan)
            level_min, level_nan = _level(level_min, level_nan, amin, seen_nan)
            t[r] = t[r] + offsets[lev, imin]
        best_b = _lower(best_b, np.nan if level_nan else level_min)
    # interior
    n = int(round(np.sqrt(gx.size)))
    px, py = px0.copy(), py0.copy()
    h = h0
    best_i = in_best
    xs, ys, inside = np.empty(gx.size), np.empty(gx.size), np.empty(gx.size, dtype=np.bool_)
    for _ in range(in_levels):
        level_min, level_nan = np.inf, False
        for r in range(px.size):
            for j in range(gx.size):
                xs[j], ys[j] = px[r] + h * gx[j], py[r] + h * gy[j]
            contains_points(xs, ys, vx, vy, wy, ex, ey, L2, tol, inside)
            amin, imin, seen_nan = np.inf, 0, False
            for j in range(gx.size):
                v = _value(f, p, scale, bad, xs[j], ys[j]) if inside[j] else np.inf
                amin, imin, seen_nan = _first_min(v, j, amin, imin, seen_nan)
            level_min, level_nan = _level(level_min, level_nan, amin, seen_nan)
            px[r], py[r] = px[r] + h * gx[imin], py[r] + h * gy[imin]
        best_i = _lower(best_i, np.nan if level_nan else level_min)
        h = 2.0 * h / (n - 1)
    return best_b, best_i


@jitable
def zoom_ranges(arguments, angles, p, bad_lo, bad_hi, best, t0, offsets, is_path, vx, vy, ex, ey, L, cum):
    """The boundary minima of ``q1, -q1, q2, -q2`` (rows 0 to 3; NaN replaced by
    ``bad_lo`` in the minima of ``q_i``, ``bad_hi`` in those of ``-q_i``), ``q_i`` two
    angles whose formulas need NumPy's ``arccos`` and ``arctan2``, refined by zooming:
    :func:`mechopt.analysis.sampling.leg_ranges`' search bit for bit (module doc).

    Each level's points are computed here, ``arguments(p, x, y) -> (k1, k2, y1, x1, y2,
    x2, ok)`` at each of them, then NumPy's ``arccos(k_i)`` and ``arctan2(y_i, x_i)`` of
    all of them in one block run by the interpreter (:func:`mechopt.core.jit.objmode`;
    NumPy's value at a point does not depend on the array around it), then
    ``angles(p, alpha1, alpha2, beta1, beta2, ok) -> (q1, q2)``.

    Parameters
    ----------
    arguments, angles : callable
        The compiled point kernels (above).
    p : ndarray
        Their parameters.
    bad_lo, bad_hi : float
        Replacements of NaN in the minima of ``q_i`` and of ``-q_i``.
    best : ndarray
        The four rows' minima over the boundary samples.
    t0 : ndarray
        The starts' arc-length fractions, the same number per row, row after row.
    offsets : ndarray
        The boundary zoom's offsets, one level per row.
    is_path : bool
        A path (two ends) rather than a closed polygon.
    vx, vy, ex, ey, L, cum : ndarray
        The edges (:attr:`mechopt.analysis.task.Task.edges`).

    Returns
    -------
    ndarray
        The four minima.
    """
    t = t0.copy()
    best = best.copy()
    k = t.size // 4
    n = offsets.shape[1]
    m = t.size * n
    k1, k2, y1, x1, y2, x2 = np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m), np.empty(m)
    ok = np.empty(m, dtype=np.bool_)
    ts, bx, by = np.empty(n), np.empty(n), np.empty(n)
    for lev in range(offsets.shape[0]):
        for s in range(t.size):
            _offset_points(t[s], offsets[lev], is_path, vx, vy, ex, ey, L, cum, ts, bx, by)
            for j in range(n):
                i = s * n + j
                k1[i], k2[i], y1[i], x1[i], y2[i], x2[i], ok[i] = arguments(p, bx[j], by[j])
        with jit.objmode(a1="float64[:]", a2="float64[:]", b1="float64[:]", b2="float64[:]"):
            a1, a2, b1, b2 = np.arccos(k1), np.arccos(k2), np.arctan2(y1, x1), np.arctan2(y2, x2)
        for r in range(4):
            level_min, level_nan = np.inf, False
            for s in range(r * k, (r + 1) * k):
                amin, imin, seen_nan = np.inf, 0, False
                for j in range(n):
                    i = s * n + j
                    q1, q2 = angles(p, a1[i], a2[i], b1[i], b2[i], ok[i])
                    q = q1 if r < 2 else q2
                    v = (q if r % 2 == 0 else -q)
                    v = v if np.isfinite(v) else (bad_lo if r % 2 == 0 else bad_hi)
                    amin, imin, seen_nan = _first_min(v, j, amin, imin, seen_nan)
                level_min, level_nan = _level(level_min, level_nan, amin, seen_nan)
                t[s] = t[s] + offsets[lev, imin]
            best[r] = _lower(best[r], np.nan if level_nan else level_min)
    return best
