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

Mechanism-specific geometry comes through the protocol's hook
:meth:`~mechopt.core.protocol.PlanarMechanism.explicit_workspace`: a mechanism that
has one (the symmetric five-bar, :class:`mechopt.mechanisms.five_bar.mic.FiveBarWorkspace`)
gives its MIC explicitly, the reach of its legs (the raster skips the cells no leg
reaches) and the conditions on its inputs that the error messages name; without one,
everything here is the generic method above.

Cost of one design. Nothing here imports scipy or numba (the five-bar's explicit
MIC runs a NumPy port of the atlas kernel for one design, a few ms), and the
connected component of the usable region is found on runs of cells. The raster
is evaluated in blocks of rows (:data:`RASTER_BLOCK` cells), so its memory stays
bounded whatever its size.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.numerics import golden_section_max
from mechopt.core.quadrature import Grid, grid_over

__all__ = [
    "MIC",
    "mic",
    "type2_clearance",
    "Region",
    "usable_region",
    "gcw",
    "largest_square",
    "joint_ranges",
    "largest_square_at",
    "no_mic_message",
    "unusable_message",
]

#: cells per block of a raster evaluation (the kinematics' temporaries stay small)
RASTER_BLOCK = 1 << 15


@dataclass(frozen=True)
class MIC:
    """Maximal inscribed circle: ``radius`` and centre ``(0, center_y)`` [L].

    Parameters
    ----------
    radius : float
        The radius [L].
    center_y : float
        Ordinate of the centre [L] (the centre is on the y axis).
    """

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

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    cx, cy : array_like
        The centres [L], shape ``(m,)`` or scalars.
    radius : float
        The search radius [L].
    n_phi : int
        Rays of the angle grid.
    n_r : int
        Radial grid nodes per ray.
    n_refine : int
        Rays of the angle refinement.

    Returns
    -------
    float or ndarray
        The distance [L] from each centre to the locus (or to the loss of
        reachability); ``radius`` where none is found within it, 0 where the centre
        itself is singular or unreachable.
    """
    from mechopt.core.protocol import as_points

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
        r2 = _first_sign_change(mech, cxl, cyl, phi2, np.minimum(rl, best * 1.05 + _v.ROUNDING), 2 * n_r)
        out[live] = np.minimum(best, r2.min(axis=1))
    return float(out[0]) if scalar else out


def _mic_radius_at(mech, cy):
    cy = np.atleast_1d(np.asarray(cy, float))
    serial = np.maximum(mech.serial_clearance(0.0, cy), 0.0)
    return np.minimum(serial, type2_clearance(mech, np.zeros_like(cy), cy, serial))


def mic(mech, method: str = "auto", n_y: int = 48, tol: float = 1e-6) -> MIC:
    """Maximal inscribed circle of ``mech`` (centre on the y axis, ``y > 0``).

    ``method="explicit"`` (the default, ``"auto"``, for a mechanism whose
    :meth:`~mechopt.core.protocol.PlanarMechanism.explicit_workspace` is not None) is
    the mechanism's own algorithm. For a :class:`~mechopt.FiveBar` it is that of
    :mod:`mechopt.mechanisms.five_bar.mic`: the type-II locus is generated explicitly
    (B1, P, B2 collinear) and filtered by working mode, then a dense search over
    centres with golden-section refinement (about 2.5e-6 relative against a converged
    reference, ``tests/test_atlas.py``); one design is computed by a NumPy port of the
    atlas's compiled kernel (same values bit for bit, a few ms, no numba start-up),
    and after :data:`mechopt.mechanisms.five_bar.mic.MIC_NUMBA_AFTER_SECONDS` of such
    work in a process (a long optimisation) by the compiled kernel.

    ``method="rays"`` works for any mechanism of the protocol: a grid of ``n_y``
    centres over ``(0, ymax]`` locates the best centre (type-II clearance by
    root finding along rays, :func:`type2_clearance`), and a golden-section
    search between its neighbours refines it to ``tol`` relative to the
    mechanism's length scale. Its coarse centre grid can pick the lower of two
    nearly equal peaks; the explicit method does not.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    method : {"auto", "explicit", "rays"}
        The algorithm (above).
    n_y : int
        Centres of the rays method's grid.
    tol : float
        Tolerance of the rays method's refinement, relative to the length scale.

    Returns
    -------
    MIC
        ``radius`` and ``center_y`` [L].

    Raises
    ------
    ValueError
        When no centre on the positive y axis is a regular reachable point
        (``radius`` would be 0); the message names the inputs and, for a mechanism
        with an explicit workspace, which condition on them fails.
    """
    _v.choice("method", method, ("auto", "explicit", "rays"))
    n_y = _v.integer("n_y", n_y, 1)
    tol = _v.finite_number("tol", tol)
    if not tol > 0.0:
        raise ValueError(f"tol must be a positive relative tolerance, got {_v.show(tol)}")
    if method == "explicit" and mech.explicit_workspace() is None:
        raise ValueError(f"method 'explicit' needs a FiveBar (a mechanism with explicit_mic), "
                         f"got {type(mech).__name__}")
    out = _mic(mech, method, n_y, tol)
    if out is None:
        raise ValueError(no_mic_message(mech))
    return out


def _mic(mech, method="auto", n_y=48, tol=1e-6):
    """:func:`mic` without its argument checks; None instead of the error."""
    explicit = mech.explicit_workspace() if method != "rays" else None
    if explicit is not None:
        r, y = explicit.mic()
        if not r > _v.RESOLUTION * mech.length_scale:
            return None
        return MIC(radius=r, center_y=y)
    ymax = mech.bounding_box()[3]
    ys = ymax * np.arange(1, n_y + 1) / (n_y + 1)
    rs = _mic_radius_at(mech, ys)
    j = int(np.argmax(rs))
    if rs[j] <= 0:
        return None
    a = ys[j - 1] if j > 0 else 0.0
    b = ys[j + 1] if j + 1 < n_y else ymax
    # golden-section maximisation of the (locally unimodal) radius over [a, b]
    # (0.618^200: below any tol in double precision)
    g = golden_section_max(lambda y: float(_mic_radius_at(mech, y)[0]), a, b,
                           tol=tol * mech.length_scale, max_iter=200)
    best = max((rs[j], ys[j]), (g.f1, g.x1), (g.f2, g.x2))
    return MIC(radius=float(best[0]), center_y=float(best[1]))


def no_mic_message(mech) -> str:
    """Why ``mech`` has no MIC, in terms of its inputs (one line): for a mechanism with
    an explicit workspace its ``no_mic_reason()`` (for the five-bar, the first condition
    on ``r1, r2, r3`` and the mode that fails), else the bare finding.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.

    Returns
    -------
    str
        The message.
    """
    head = f"{mech!r} has no singularity-free disk centred on the y axis (MIC radius 0)"
    explicit = mech.explicit_workspace()
    if explicit is None:
        return head
    return f"{head}: {explicit.no_mic_reason()}"


@dataclass(frozen=True)
class Region:
    """A region as a boolean ``mask`` on a :class:`~mechopt.core.quadrature.Grid`.

    Parameters
    ----------
    grid : mechopt.core.quadrature.Grid
        The raster (cell centres and step [L]).
    mask : ndarray of bool
        The cells inside the region, shape of the grid.
    """

    grid: Grid
    mask: np.ndarray

    @property
    def area(self) -> float:
        return self.grid.area(self.mask)

    def points(self):
        """``(x, y)`` of the cell centres inside the region (1-D arrays, row-major
        order: those of ``X[mask], Y[mask]`` for ``X, Y = grid.points()``).

        Returns
        -------
        x, y : ndarray
            Read-only arrays [L].
        """
        return self._points

    @cached_property
    def _points(self):
        rows, cols = np.nonzero(self.mask)
        x, y = self.grid.x[cols], self.grid.y[rows]
        x.setflags(write=False)
        y.setflags(write=False)
        return x, y

    def mean(self, values) -> float:
        """The area mean of a field over the region.

        Parameters
        ----------
        values : ndarray
            The field at every cell of the grid (its shape).

        Returns
        -------
        float
            The mean over the region's cells (mid-point rule).

        Raises
        ------
        ValueError
            For an empty region (no mean exists).
        """
        return self.grid.mean(values, self.mask)


def _default_step(mech):
    return mech.length_scale / 400.0


def _blocks(n, size=RASTER_BLOCK):
    """Slices of ``range(n)`` of at most ``size`` elements."""
    return [slice(i, min(i + size, n)) for i in range(0, n, max(1, size))]


def usable_region(mech, step=None, center=None) -> Region:
    """The connected singularity-free region above the base containing the MIC centre.

    Cells are kept where the pose is reachable, ``y > 0`` and ``type2_function``
    has the sign it has at the MIC centre; the connected component (4-neighbour)
    of the cell holding the centre is returned. The area converges at first
    order in ``step`` (default ``length_scale/400``).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    step : float, optional
        The raster step [L] (default ``length_scale/400``).
    center : float, optional
        Ordinate of the MIC centre [L] (default: :func:`mic`'s).

    Returns
    -------
    Region
        The usable workspace.

    Raises
    ------
    ValueError
        Naming the inputs, when the centre is singular or unreachable, or when the
        raster is too coarse for the region (its cell next to the centre lies
        outside it: a usable workspace thinner than about a cell).
    """
    given = step is not None
    step = _v.positive_size("step", step) if given else _default_step(mech)
    if center is None:
        center = (0.0, mic(mech).center_y)
    center = _v.finite_numbers("center", center, 2, "a point (x, y)")
    region = _usable_region(mech, step, center)
    if region is None:
        raise ValueError(unusable_message(mech, step, center, given_step=given))
    return region


def _usable_region(mech, step, center):
    """:func:`usable_region` without its argument checks; None instead of the error."""
    xmin, xmax, _, ymax = mech.bounding_box()
    grid = grid_over((xmin, xmax, 0.0, ymax), step)
    s0 = np.sign(mech.type2_function(*center))
    free = np.zeros(grid.shape, dtype=bool)
    ny, nx = grid.shape
    rows = max(1, RASTER_BLOCK // nx)
    explicit = mech.explicit_workspace()
    near = None if explicit is None else explicit.reach_filter()
    for r0 in range(0, ny, rows):
        r1 = min(r0 + rows, ny)
        X = np.broadcast_to(grid.x, (r1 - r0, nx))
        Y = np.broadcast_to(grid.y[r0:r1, None], (r1 - r0, nx))
        if near is None:
            free[r0:r1] = np.sign(mech.type2_function(X, Y)) == s0
        else:  # type2_function (pointwise) only where it can be finite
            keep = near(X, Y)
            free[r0:r1][keep] = np.sign(mech.type2_function(X[keep], Y[keep])) == s0
    i = int(np.clip(np.searchsorted(grid.y, center[1]), 0, grid.y.size - 1))
    j = int(np.clip(np.searchsorted(grid.x, center[0]), 0, grid.x.size - 1))
    if not free[i, j]:
        return None
    return Region(grid, _component(free, i, j))


def _component(free, i, j):
    """Mask of the 4-connected component of ``free`` (2-D boolean) holding the cell
    ``(i, j)`` (which must be free): what ``scipy.ndimage.label`` labels it, found on
    the runs of free cells of each row (two runs of adjacent rows touch when they
    share a column)."""
    ny, nx = free.shape
    # runs: the transitions of the rows padded with a False column on each side
    w = nx + 2
    padded = np.zeros((ny, w), dtype=bool)
    padded[:, 1:-1] = free
    flat = padded.ravel()
    t = np.flatnonzero(flat[1:] != flat[:-1]) + 1  # start, end, start, end, ... (row-major)
    run_row, run_start = np.divmod(t[0::2], w)
    run_end = t[1::2] - run_row * w  # exclusive
    run_start -= 1
    run_end -= 1
    key_start = run_row * w + run_start
    key_end = run_row * w + run_end
    # runs of the next row sharing a column with run a: start < end_a and end > start_a
    nxt = (run_row + 1) * w
    lo = np.searchsorted(key_end, nxt + run_start, side="right")
    hi = np.searchsorted(key_start, nxt + run_end, side="left")
    count = np.maximum(hi - lo, 0)
    a = np.repeat(np.arange(run_row.size), count)
    b = np.repeat(lo - np.cumsum(count) + count, count) + np.arange(a.size)
    # adjacency of the run graph (both directions), as CSR
    src = np.concatenate([a, b])
    dst = np.concatenate([b, a])
    order = np.argsort(src, kind="stable")
    ptr = np.searchsorted(src[order], np.arange(run_row.size + 1)).tolist()
    dst = dst[order].tolist()
    seed = int(np.searchsorted(key_start, i * w + j, side="right")) - 1
    seen = bytearray(run_row.size)
    seen[seed] = 1
    stack = [seed]
    while stack:
        k = stack.pop()
        for n in dst[ptr[k]:ptr[k + 1]]:
            if not seen[n]:
                seen[n] = 1
                stack.append(n)
    mask = np.zeros((ny, nx), dtype=bool)
    keep = np.flatnonzero(np.frombuffer(bytes(seen), dtype=np.uint8))
    for r, c0, c1 in zip(run_row[keep].tolist(), run_start[keep].tolist(), run_end[keep].tolist()):
        mask[r, c0:c1] = True
    return mask


def unusable_message(mech, step, center, given_step=False, r_mic=None) -> str:
    """Why :func:`usable_region` found no region, in terms of the inputs (one line).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    step : float
        The raster step used [L].
    center : float
        Ordinate of the MIC centre [L].
    given_step : bool
        Whether the caller chose the step (the message then names a finer one).
    r_mic : float, optional
        The MIC radius [L], for the bound on the step.

    Returns
    -------
    str
        The message.
    """
    s0 = np.sign(mech.type2_function(*center))
    if not (np.isfinite(s0) and s0 != 0):
        return (f"{mech!r}: the centre {_v.show(tuple(center))} is singular or unreachable, so it lies "
                "in no singularity-free region")
    explicit = mech.explicit_workspace()
    scale = "its length scale/400" if explicit is None else explicit.step_text
    what = f"the raster step {step:.6g}" if given_step else f"the raster step {scale} = {step:.6g}"
    bound = "" if explicit is None else explicit.radius_bound(step, given_step)
    radius = "" if r_mic is None else f" (radius {r_mic:.6g})"
    return (f"{mech!r}: its usable workspace is too thin for {what}: the raster cell next to the "
            f"MIC centre{radius} lies outside it; the MIC radius must be at least about 1.5 raster "
            f"steps{bound}")


def gcw(mech, gamma: float = 0.5, usable: Region | None = None) -> Region:
    """Good-conditioning workspace ``{LCI >= gamma}`` inside the usable workspace.

    Liu 2006 sec. 3.2.3 step 1 (Fig. 25). It may be empty (``area == 0``): Liu's
    design (0.4, 2.33, 0.27) has no GCW at ``gamma = 0.5``, a result, not an error.
    The LCI is evaluated at the usable cells only.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    gamma : float
        The LCI level, in (0, 1).
    usable : Region, optional
        The usable workspace (default: :func:`usable_region` at its defaults).

    Returns
    -------
    Region
        The GCW (possibly empty).
    """
    gamma = _v.open_unit_interval("gamma", gamma)
    usable = usable_region(mech) if usable is None else usable
    grid = usable.grid
    mask = np.zeros(grid.shape, dtype=bool)
    ny, nx = grid.shape
    rows = max(1, RASTER_BLOCK // nx)
    for r0 in range(0, ny, rows):  # by blocks of rows: the LCI is pointwise
        part = mask[r0:r0 + rows]
        i, j = np.nonzero(usable.mask[r0:r0 + rows])
        if i.size:
            part[i, j] = mech.lci(grid.x[j], grid.y[r0 + i]) >= gamma
    return Region(grid, mask)


def largest_square(region: Region):
    """Largest axis-aligned square centred on the y axis inside ``region``.

    For a centre ``(0, yc)`` the half side is the Chebyshev distance to the
    nearest cell outside the region, ``min max(|x|, |y - yc|)`` (only boundary
    cells matter). Returns ``(side, center_y)``; accurate to about one cell.
    A region that does not meet the y axis (an empty one included) holds no such
    square: ``(0.0, nan)``.

    Parameters
    ----------
    region : Region
        A raster region.

    Returns
    -------
    side : float
        The square's side [L].
    center_y : float
        Ordinate of its centre [L].
    """
    mask = region.mask
    grid = region.grid
    # outside cells that touch the region (a 4-neighbour dilation), plus the raster frame
    near = mask.copy()
    near[1:] |= mask[:-1]
    near[:-1] |= mask[1:]
    near[:, 1:] |= mask[:, :-1]
    near[:, :-1] |= mask[:, 1:]
    rows_e, cols_e = np.nonzero(near & ~mask)
    ox, oy = np.abs(grid.x[cols_e]), grid.y[rows_e]
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
    without wrapping, so the ranges are continuous. NaN bounds for an empty region.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    region : Region
        A raster region.

    Returns
    -------
    tuple
        ``((q1_lo, q1_hi), (q2_lo, q2_hi))`` [rad or L].
    """
    if not region.mask.any():
        return (math.nan, math.nan), (math.nan, math.nan)
    x, y = region.points()
    lo1 = lo2 = math.inf
    hi1 = hi2 = -math.inf
    for sl in _blocks(x.size):
        q1, q2, _ = mech.ik(x[sl], y[sl])
        with np.errstate(invalid="ignore"):
            lo1, hi1 = np.fmin(lo1, np.nanmin(q1, initial=np.inf)), np.fmax(hi1, np.nanmax(q1, initial=-np.inf))
            lo2, hi2 = np.fmin(lo2, np.nanmin(q2, initial=np.inf)), np.fmax(hi2, np.nanmax(q2, initial=-np.inf))
    return _finite_or_nan(lo1, hi1), _finite_or_nan(lo2, hi2)


def _finite_or_nan(lo, hi):
    """``(lo, hi)`` as floats; NaN bounds where no finite value was seen."""
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return math.nan, math.nan
    return float(lo), float(hi)


def largest_square_at(predicate, center_y: float, half_max: float, n_inner: int = 33,
                      n_edge: int = 257, tol: float = 1e-6) -> float:
    """Side of the largest square centred at ``(0, center_y)`` on which
    ``predicate(x, y)`` holds at every sample point, ``side <= 2 half_max``.

    Le 2013 sec. III (Fig. 4) shrinks the square inscribed in the MIC until the
    constraints hold; since concentric squares are nested, feasibility is
    monotone in the side and bisection finds the largest one (to ``tol`` relative
    to ``half_max``). Each candidate is checked on ``n_edge`` points per edge and
    an ``n_inner`` x ``n_inner`` interior grid.

    Parameters
    ----------
    predicate : callable
        ``predicate(x, y)`` -> boolean array, True where the constraints hold.
    center_y : float
        Ordinate of the centre [L].
    half_max : float
        The largest half side [L].
    n_inner : int
        Interior grid nodes per side.
    n_edge : int
        Points per edge.
    tol : float
        Tolerance of the bisection, relative to ``half_max``.

    Returns
    -------
    float
        The side [L] (0 when no square holds).
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
