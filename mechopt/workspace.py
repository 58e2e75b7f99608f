"""Workspace geometry for any mechanism of the protocol.

* :func:`mic` - the maximal inscribed circle (MIC, Liu 2006 footnote 2; Le 2013
  sec. III): the largest disk centred on the y axis (centre ``y > 0``) that
  contains no singular point of the working mode. Its clearance to the type-I
  loci is closed form (``serial_clearance``); its clearance to the type-II locus
  is found by root finding of ``type2_function`` along rays (bracketing on a
  radial grid, then bisection), refined in angle; the best centre is found by a
  grid over ``y`` refined by golden-section search.
* :func:`usable_region` - the connected singularity-free region above the base
  that contains the MIC centre (Liu 2006 sec. 3.2.1), as a mask on a raster.
* :func:`gcw` - the good-conditioning workspace ``{LCI >= gamma}`` inside it.
* :func:`largest_square` - the largest square centred on the y axis inside a region.
* :func:`joint_ranges` - actuator ranges over a region.
"""
from __future__ import annotations

import math

from dataclasses import dataclass

import numpy as np

from . import validation as _v
from .quadrature import Grid, grid_over

__all__ = [
    "MIC",
    "mic",
    "type2_clearance",
    "Region",
    "usable_region",
    "gcw",
    "largest_square",
    "joint_ranges",
]

_GOLDEN = (np.sqrt(5.0) - 1.0) / 2.0


@dataclass(frozen=True)
class MIC:
    """Maximal inscribed circle: ``radius`` and centre ``(0, center_y)`` [L]."""

    radius: float
    center_y: float


def _first_sign_change(mech, cx, cy, phi, radius, n_r, n_bisect=36):
    """Radius of the first zero (or loss of reachability) of ``type2_function``
    along rays ``(cx, cy) + r (cos phi, sin phi)``, ``0 < r <= radius``.

    ``cx``, ``cy``, ``radius`` have shape ``(m,)`` (centres), ``phi`` shape
    ``(m, k)`` or ``(k,)``; returns ``(m, k)``, equal to ``radius`` where no zero
    is found and to 0 where the centre itself is singular or unreachable.
    """
    cx, cy, radius = (np.asarray(v, float)[:, None, None] for v in (cx, cy, radius))
    phi = np.broadcast_to(np.asarray(phi, float), (cx.shape[0], np.shape(phi)[-1]))[:, :, None]
    f0 = mech.type2_function(cx, cy)
    s0 = np.sign(f0)
    c, s = np.cos(phi), np.sin(phi)
    r = radius * (np.arange(1, n_r + 1) / n_r)
    f = mech.type2_function(cx + r * c, cy + r * s)
    bad = ~(np.sign(f) == s0)  # sign change, zero or NaN (unreachable)
    hit = bad.any(axis=2)
    k = np.where(hit, bad.argmax(axis=2), n_r - 1)
    step = radius[:, :, 0] / n_r
    lo, hi = k * step, (k + 1) * step
    c, s, cx, cy, s0 = c[..., 0], s[..., 0], cx[..., 0], cy[..., 0], s0[..., 0]
    for _ in range(n_bisect):
        mid = 0.5 * (lo + hi)
        same = np.sign(mech.type2_function(cx + mid * c, cy + mid * s)) == s0
        lo = np.where(same, mid, lo)
        hi = np.where(same, hi, mid)
    out = np.where(hit, 0.5 * (lo + hi), radius[:, :, 0])
    return np.where(np.isfinite(f0[..., 0]) & (s0 != 0), out, 0.0)


def type2_clearance(mech, cx, cy, radius, n_phi=128, n_r=96, n_refine=64):
    """Distance from centres ``(cx, cy)`` to the type-II locus, searched up to ``radius``.

    Vectorised over centres (arrays of shape ``(m,)``; scalars give a float).
    Rays on a uniform angle grid bracket the first sign change of
    ``type2_function`` on a radial grid and bisect it; the angle of the closest
    hit is then refined on ``n_refine`` rays spanning the neighbouring grid
    cells. At the closest point the locus is tangent to the circle, so the ray
    there crosses it transversally and the bracketing cannot miss it.
    """
    from .mechanisms.base import as_points

    scalar = np.ndim(cx) == 0 and np.ndim(cy) == 0 and np.ndim(radius) == 0
    cx, cy = as_points(cx, cy)
    radius, _ = as_points(radius, 0.0)
    cx, cy, radius = (np.atleast_1d(v) for v in np.broadcast_arrays(cx, cy, radius))
    out = np.zeros(cx.shape)
    live = radius > 0
    if live.any():
        cxl, cyl, rl = cx[live], cy[live], radius[live]
        phi = np.arange(n_phi) * (2 * np.pi / n_phi)
        r = _first_sign_change(mech, cxl, cyl, phi, rl, n_r)
        j = np.argmin(r, axis=1)
        best = r[np.arange(r.shape[0]), j]
        dphi = 2 * np.pi / n_phi
        phi2 = phi[j][:, None] + np.linspace(-dphi, dphi, n_refine)[None, :]
        r2 = _first_sign_change(mech, cxl, cyl, phi2, np.minimum(rl, best * 1.05 + 1e-12), 2 * n_r)
        out[live] = np.minimum(best, r2.min(axis=1))
    return float(out[0]) if scalar else out


def _mic_radius_at(mech, cy):
    cy = np.atleast_1d(np.asarray(cy, float))
    serial = np.maximum(mech.serial_clearance(0.0, cy), 0.0)
    return np.minimum(serial, type2_clearance(mech, np.zeros_like(cy), cy, serial))


def mic(mech, method: str = "auto", n_y: int = 48, tol: float = 1e-6) -> MIC:
    """Maximal inscribed circle of ``mech`` (centre on the y axis, ``y > 0``).

    ``method="explicit"`` (the default for a :class:`~mechopt.FiveBar`, ``"auto"``)
    uses :func:`mechopt.kernels.mic_batch`: the five-bar's type-II locus is
    generated explicitly (B1, P, B2 collinear) and filtered by working mode, then
    a dense search over centres with golden-section refinement (about 2.5e-6
    relative against a converged reference, ``tests/test_atlas.py``).

    ``method="rays"`` works for any mechanism of the protocol: a grid of ``n_y``
    centres over ``(0, ymax]`` locates the best centre (type-II clearance by
    root finding along rays, :func:`type2_clearance`), and a golden-section
    search between its neighbours refines it to ``tol`` relative to the
    mechanism's length scale. Its coarse centre grid can pick the lower of two
    nearly equal peaks; the explicit method does not.

    Raises ValueError when no centre on the positive y axis is a regular
    reachable point (``radius`` would be 0).
    """
    from .mechanisms.five_bar import FiveBar

    _v.choice("method", method, ("auto", "explicit", "rays"))
    n_y = _v.integer("n_y", n_y, 1)
    tol = _v.finite_number("tol", tol)
    if not tol > 0.0:
        raise ValueError(f"tol must be a positive relative tolerance, got {_v.show(tol)}")
    if method == "auto":
        method = "explicit" if isinstance(mech, FiveBar) else "rays"
    if method == "explicit":
        if not isinstance(mech, FiveBar):
            raise ValueError(f"method 'explicit' needs a FiveBar, got {type(mech).__name__}")
        from .kernels import mic_batch

        r, y = mic_batch(mech.r1, mech.r2, mech.r3, mode=mech.mode)
        if not r[0] > 1e-9 * mech.length_scale:
            raise ValueError(f"{mech!r} has no singularity-free disk centred on the y axis (MIC radius 0)")
        return MIC(radius=float(r[0]), center_y=float(y[0]))
    ymax = mech.bounding_box()[3]
    ys = ymax * np.arange(1, n_y + 1) / (n_y + 1)
    rs = _mic_radius_at(mech, ys)
    j = int(np.argmax(rs))
    if rs[j] <= 0:
        raise ValueError(f"{mech!r} has no singularity-free disk centred on the y axis (MIC radius 0)")
    a = ys[j - 1] if j > 0 else 0.0
    b = ys[j + 1] if j + 1 < n_y else ymax
    # golden-section maximisation of the (locally unimodal) radius over [a, b]
    x1 = b - _GOLDEN * (b - a)
    x2 = a + _GOLDEN * (b - a)
    f1, f2 = _mic_radius_at(mech, [x1, x2])
    for _ in range(200):  # 0.618^200: below any tol in double precision
        if not b - a > tol * mech.length_scale:
            break
        if f1 >= f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - _GOLDEN * (b - a)
            f1 = float(_mic_radius_at(mech, x1)[0])
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + _GOLDEN * (b - a)
            f2 = float(_mic_radius_at(mech, x2)[0])
    best = max((rs[j], ys[j]), (f1, x1), (f2, x2))
    return MIC(radius=float(best[0]), center_y=float(best[1]))


@dataclass(frozen=True)
class Region:
    """A region as a boolean ``mask`` on a :class:`~mechopt.quadrature.Grid`."""

    grid: Grid
    mask: np.ndarray

    @property
    def area(self) -> float:
        return self.grid.area(self.mask)

    def points(self):
        """``(x, y)`` of the cell centres inside the region (1-D arrays)."""
        X, Y = self.grid.points()
        return X[self.mask], Y[self.mask]

    def mean(self, values) -> float:
        return self.grid.mean(values, self.mask)


def _default_step(mech):
    return mech.length_scale / 400.0


def usable_region(mech, step=None, center=None) -> Region:
    """The connected singularity-free region above the base containing the MIC centre.

    Cells are kept where the pose is reachable, ``y > 0`` and ``type2_function``
    has the sign it has at the MIC centre; the connected component (4-neighbour)
    of the cell holding the centre is returned. The area converges at first
    order in ``step`` (default ``length_scale/400``).
    """
    from scipy import ndimage

    step = _default_step(mech) if step is None else _v.positive_length("step", step)
    if center is None:
        center = (0.0, mic(mech).center_y)
    center = _v.finite_numbers("center", center, 2, "a point (x, y)")
    xmin, xmax, _, ymax = mech.bounding_box()
    grid = grid_over((xmin, xmax, 0.0, ymax), step)
    X, Y = grid.points()
    f = mech.type2_function(X, Y)
    s0 = np.sign(mech.type2_function(*center))
    free = np.sign(f) == s0
    labels, _ = ndimage.label(free)
    i = int(np.clip(np.searchsorted(grid.y, center[1]) , 0, grid.y.size - 1))
    j = int(np.clip(np.searchsorted(grid.x, center[0]), 0, grid.x.size - 1))
    lab = labels[i, j]
    if lab == 0:
        raise ValueError(f"{mech!r}: the MIC centre is not inside a singularity-free region")
    return Region(grid, labels == lab)


def gcw(mech, gamma: float = 0.5, usable: Region | None = None) -> Region:
    """Good-conditioning workspace ``{LCI >= gamma}`` inside the usable workspace.

    Liu 2006 sec. 3.2.3 step 1 (Fig. 25). It may be empty (``area == 0``): Liu's
    design (0.4, 2.33, 0.27) has no GCW at ``gamma = 0.5``, a result, not an error.
    """
    gamma = _v.open_unit_interval("gamma", gamma)
    usable = usable_region(mech) if usable is None else usable
    X, Y = usable.grid.points()
    mask = usable.mask & (mech.lci(X, Y) >= gamma)
    return Region(usable.grid, mask)


def largest_square(region: Region):
    """Largest axis-aligned square centred on the y axis inside ``region``.

    For a centre ``(0, yc)`` the half side is the Chebyshev distance to the
    nearest cell outside the region, ``min max(|x|, |y - yc|)`` (only boundary
    cells matter). Returns ``(side, center_y)``; accurate to about one cell.
    A region that does not meet the y axis (an empty one included) holds no such
    square: ``(0.0, nan)``.
    """
    from scipy import ndimage

    mask = region.mask
    grid = region.grid
    outside = ~mask
    # outside cells that touch the region, plus the raster frame
    edge = outside & ndimage.binary_dilation(mask)
    X, Y = grid.points()
    ox, oy = np.abs(X[edge]), Y[edge]
    half = 0.5 * grid.step
    # frame of the raster counts as outside
    x0, x1 = grid.x[0] - half, grid.x[-1] + half
    y0, y1 = grid.y[0] - half, grid.y[-1] + half
    rows = np.flatnonzero(mask[:, np.argmin(np.abs(grid.x))])
    if rows.size == 0:
        return 0.0, math.nan
    best = (0.0, float(grid.y[rows[0]]))
    for chunk in np.array_split(grid.y[rows], max(1, rows.size // 256)):
        # cell edges: a square reaching an outside cell's centre minus half a cell
        d = np.maximum(ox[None, :], np.abs(oy[None, :] - chunk[:, None])) - half
        h = d.min(axis=1) if d.size else np.full(chunk.size, np.inf)
        h = np.minimum.reduce([h, min(-x0, x1) + 0 * chunk, chunk - y0, y1 - chunk])
        k = int(np.argmax(h))
        if h[k] > best[0]:
            best = (float(h[k]), float(chunk[k]))
    return 2.0 * best[0], best[1]


def joint_ranges(mech, region: Region):
    """``((q1_lo, q1_hi), (q2_lo, q2_hi))`` of the actuator coordinates over a region
    (rad for angular joints). For the five-bar the angles follow Le eq. (17)-(18)
    without wrapping, so the ranges are continuous. NaN bounds for an empty region."""
    if not region.mask.any():
        return (math.nan, math.nan), (math.nan, math.nan)
    x, y = region.points()
    q1, q2, _ = mech.ik(x, y)
    return (float(np.nanmin(q1)), float(np.nanmax(q1))), (float(np.nanmin(q2)), float(np.nanmax(q2)))


def largest_square_at(predicate, center_y: float, half_max: float, n_inner: int = 33,
                      n_edge: int = 257, tol: float = 1e-6) -> float:
    """Side of the largest square centred at ``(0, center_y)`` on which
    ``predicate(x, y)`` holds at every sample point, ``side <= 2 half_max``.

    Le 2013 sec. III (Fig. 4) shrinks the square inscribed in the MIC until the
    constraints hold; since concentric squares are nested, feasibility is
    monotone in the side and bisection finds the largest one (to ``tol`` relative
    to ``half_max``). Each candidate is checked on ``n_edge`` points per edge and
    an ``n_inner`` x ``n_inner`` interior grid.
    """
    u = np.linspace(-1.0, 1.0, n_edge)
    one = np.ones_like(u)
    g = np.linspace(-1.0, 1.0, n_inner)
    GX, GY = np.meshgrid(g, g)
    sx = np.concatenate([u, u, -one, one, GX.ravel()])
    sy = np.concatenate([-one, one, u, u, GY.ravel()])

    def ok(h):
        return bool(np.all(predicate(h * sx, center_y + h * sy)))

    if ok(half_max):
        return 2.0 * half_max
    lo, hi = 0.0, half_max
    while hi - lo > tol * half_max:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if ok(mid) else (lo, mid)
    return 2.0 * lo
