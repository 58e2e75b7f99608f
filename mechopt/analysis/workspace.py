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

Cost of one design. Nothing here imports scipy or numba: the five-bar's MIC is
the atlas kernel's algorithm (:func:`mechopt.mechanisms.five_bar.kernels.mic_batch`) ported to NumPy for
one design, with the same values bit for bit (``tests/test_workspace.py``), and the
connected component of the usable region is found on runs of cells. The raster
is evaluated in blocks of rows (:data:`RASTER_BLOCK` cells), so its memory stays
bounded whatever its size.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.numerics import INV_PHI, golden_section_max
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
]

#: cells per block of a raster evaluation (the kinematics' temporaries stay small)
RASTER_BLOCK = 1 << 15


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
    is the algorithm of :func:`mechopt.mechanisms.five_bar.kernels.mic_batch`: the five-bar's type-II
    locus is generated explicitly (B1, P, B2 collinear) and filtered by working
    mode, then a dense search over centres with golden-section refinement (about
    2.5e-6 relative against a converged reference, ``tests/test_atlas.py``). One
    design is computed by a NumPy port of the compiled kernel (same values bit for
    bit, a few ms, no numba start-up); after :data:`MIC_NUMBA_AFTER_SECONDS` of
    such work in a process (a long optimisation), the compiled kernel takes over.

    ``method="rays"`` works for any mechanism of the protocol: a grid of ``n_y``
    centres over ``(0, ymax]`` locates the best centre (type-II clearance by
    root finding along rays, :func:`type2_clearance`), and a golden-section
    search between its neighbours refines it to ``tol`` relative to the
    mechanism's length scale. Its coarse centre grid can pick the lower of two
    nearly equal peaks; the explicit method does not.

    Raises ValueError when no centre on the positive y axis is a regular
    reachable point (``radius`` would be 0); the message names the inputs and,
    for the five-bar, which condition on them fails.
    """
    _v.choice("method", method, ("auto", "explicit", "rays"))
    n_y = _v.integer("n_y", n_y, 1)
    tol = _v.finite_number("tol", tol)
    if not tol > 0.0:
        raise ValueError(f"tol must be a positive relative tolerance, got {_v.show(tol)}")
    if method == "auto":
        method = "explicit" if mech.explicit_mic else "rays"
    if method == "explicit" and not mech.explicit_mic:
        raise ValueError(f"method 'explicit' needs a FiveBar (a mechanism with explicit_mic), "
                         f"got {type(mech).__name__}")
    out = _mic(mech, method, n_y, tol)
    if out is None:
        raise ValueError(no_mic_message(mech))
    return out


def _mic(mech, method="explicit", n_y=48, tol=1e-6):
    """:func:`mic` without its argument checks; None instead of the error."""
    if method == "explicit":
        r, y = five_bar_mic(mech.r1, mech.r2, mech.r3, mech.mode)
        if not r > 1e-9 * mech.length_scale:
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
    """Why ``mech`` has no MIC, in terms of its inputs (one line): for a five-bar,
    the first of the conditions below that fails, else the bare finding.

    * ``r3 < r1 + r2``: otherwise no point of the y axis is reachable by both legs;
    * not ``r3 = 0`` in the modes ``"++"``/``"--"`` (both elbows on one point:
      singular everywhere);
    * ``min(r1, r2) >= 1e-9 (r1 + r2 + r3)/3``: the MIC radius never exceeds
      ``min(r1, r2)`` and a radius below 1e-9 of the length scale is not resolved
      in double precision (the test of :func:`mic`).
    """
    head = f"{mech!r} has no singularity-free disk centred on the y axis (MIC radius 0)"
    if not mech.explicit_mic:
        return head
    r1, r2, r3 = mech.r1, mech.r2, mech.r3
    scale = (r1 + r2 + r3) / 3.0
    if not r3 < r1 + r2:
        why = f"no point of the y axis is reachable by both legs: r3 must be less than r1 + r2 = {r1 + r2:g}"
    elif mech.mode in ("++", "--") and r3 <= 1e-12 * scale:
        why = (f"with r3 = {r3:g} the working mode {mech.mode!r} puts both elbows on (nearly) one point, "
               "singular everywhere: use r3 > 1e-12 (r1 + r2 + r3)/3 or the mode '+-' or '-+'")
    elif min(r1, r2) < 1e-9 * scale:
        why = (f"the MIC radius is at most min(r1, r2) = {min(r1, r2):g}, below 1e-9 (r1 + r2 + r3)/3 "
               f"= {1e-9 * scale:g}, the smallest radius double precision resolves here: "
               "min(r1, r2) must be at least that")
    else:
        why = "every point of the y axis near the workspace is singular or unreachable in this working mode"
    return f"{head}: {why}"


# --- the five-bar's explicit MIC for one design ---------------------------------------------
# A NumPy port of ``mechopt.mechanisms.five_bar.kernels._mic_one_nb`` with its operations in the same order
# and the C library's trigonometric functions (``math``; NumPy's vectorised arccos
# differs from it in the last bit), so that it gives the compiled kernel's values bit
# for bit (tests/test_workspace.py checks it on 1600 designs, every mode). Its sizes are
# ``kernels.MIC_SIZES`` (the same test checks that they are equal).
_MIC_SIZES = dict(n_crank=128, n_y=128, n_sub=16, n_seed_y=9, n_golden=42, n_cand=2)
#: the ratio of the port's golden-section search (:data:`mechopt.mechanisms.five_bar.kernels._GOLD`)
_GOLD = INV_PHI
_N_SUB_BRANCH = 8
#: seconds spent in the NumPy port after which :func:`five_bar_mic` loads the compiled
#: kernel (its first load costs about 0.5 s per process; see :mod:`mechopt.mechanisms.five_bar.lci`)
MIC_NUMBA_AFTER_SECONDS = 0.5
_port_seconds = 0.0
_compiled_mic = None  # mechopt.mechanisms.five_bar.kernels.mic_batch once the compiled kernel is used


def _libm(f, a):
    """The scalar function ``f`` of :mod:`math` at every element of ``a``."""
    a = np.asarray(a, dtype=float)
    return np.fromiter(map(f, a.ravel().tolist()), float, a.size).reshape(a.shape)


def _theta_range(r1, r2, r3, leg, rho):
    t = r1 - 2.0 * r2
    lo2 = t * t
    t = r1 + 2.0 * r2
    hi2 = t * t
    base = 4.0 * r3 * r3 + r1 * r1
    k = 4.0 * r3 * r1
    if k <= 0.0:
        if not (lo2 <= base <= hi2):
            return 1.0, 0.0
        clo, chi = -1.0, 1.0
    else:
        clo = (base - hi2) / k
        chi = (base - lo2) / k
        if leg == 1:
            clo, chi = -chi, -clo
    sx = -r3 if leg == 0 else r3
    clo = max(clo, (-rho - sx) / r1, -1.0)
    chi = min(chi, (rho - sx) / r1, 1.0)
    if clo > chi:
        return 1.0, 0.0
    return math.acos(chi), math.acos(clo)


def _theta_of_u(ta, tb, half, u):
    th = ta + (tb - ta) * 0.5 * (1.0 - _libm(math.cos, math.pi * u))
    return np.where(half == 0, th, -th)


def _coupler_points(r1, r2, r3, s1, s2, leg, sigma, th):
    """Midpoints ``P`` of ``B1 B2`` with the crank ``leg`` at ``th``: ``(px, py, ok)``."""
    ax = np.where(leg == 0, -r3, r3)
    ox = -ax
    bx = ax + r1 * _libm(math.cos, th)
    by = r1 * _libm(math.sin, th)
    vx = ox - bx
    vy = -by
    L2 = vx * vx + vy * vy
    cc = 4.0 * r2 * r2
    with np.errstate(divide="ignore", invalid="ignore"):  # L2 = 0: not ok
        L = np.sqrt(L2)
        a = (L2 + cc - r1 * r1) / (2.0 * L)
        hh2 = cc - a * a
        hh = sigma * np.sqrt(np.maximum(hh2, 0.0))
        cx = bx + (a * vx - hh * vy) / L
        cy = by + (a * vy + hh * vx) / L
        px = 0.5 * (bx + cx)
        py = 0.5 * (by + cy)
        first = leg == 0
        b1x, b1y = np.where(first, bx, cx), np.where(first, by, cy)
        b2x, b2y = np.where(first, cx, bx), np.where(first, cy, by)
        c1 = (px + r3) * b1y - py * (b1x + r3)
        c2 = (px - r3) * b2y - py * (b2x - r3)
        ok = (L2 > 0.0) & ~(hh2 < -1e-12 * cc) & ~(s1 * c1 < 0.0) & ~(s2 * c2 < 0.0)
    return px, py, ok


def _axis_points(r1, r2, r3, s1, s2):
    qy = [math.nan] * 4
    if r3 > 0.0 and r1 > r3:
        h = math.sqrt(r1 * r1 - r3 * r3)
        for i in range(4):
            hc = h if i < 2 else -h
            py = hc + r2 if i % 2 == 0 else hc - r2
            c1 = r3 * hc - py * r3
            c2 = -r3 * hc + py * r3
            if not (s1 * c1 < 0.0 or s2 * c2 < 0.0):
                qy[i] = py
    return [v for v in qy if v == v]


def _cloud_radius(r1, r2, r3, qx, qy, ay, y):
    """``min(serial, distance to the cloud and the axis points)`` at the centres ``y``."""
    D = np.sqrt(r3 * r3 + y * y)
    s = np.minimum(r1 + r2 - D, D - abs(r1 - r2))
    best = s * s
    if qx.size:
        dy = qy[None, :] - y[:, None]
        best = np.minimum(best, np.min(qx * qx + dy * dy, axis=1))
    for v in ay:
        d = v - y
        best = np.minimum(best, d * d)
    return np.where(s <= 0.0, 0.0, np.sqrt(best))


def _mic_one(r1, r2, r3, s1, s2):
    """``kernels._mic_one_nb`` of one design in units of its length scale."""
    n_y, n_sub = _MIC_SIZES["n_y"], _MIC_SIZES["n_sub"]
    n_seed_y, n_golden = _MIC_SIZES["n_seed_y"], _MIC_SIZES["n_golden"]
    ugrid = np.linspace(0.0, 1.0, _MIC_SIZES["n_crank"])
    nu = ugrid.size
    ylo2 = (r1 - r2) * (r1 - r2) - r3 * r3
    ylo = math.sqrt(ylo2) if ylo2 > 0.0 else 0.0
    yhi2 = (r1 + r2) * (r1 + r2) - r3 * r3
    yhi = math.sqrt(yhi2) if yhi2 > 0.0 else 0.0
    rho = 1.01 * (min(r1, r2) + r2)
    tr = [_theta_range(r1, r2, r3, leg, rho) for leg in (0, 1)]
    b = np.arange(_N_SUB_BRANCH)
    leg_b = b // 4
    sigma_b = np.where((b // 2) % 2 == 0, 1.0, -1.0)
    half_b = b % 2
    ta_b = np.array([tr[leg][0] for leg in leg_b])
    tb_b = np.array([tr[leg][1] for leg in leg_b])
    # the locus sampled on every sub-branch whose crank-angle interval is not empty
    qx = np.full((_N_SUB_BRANCH, nu), np.inf)
    qy = np.zeros((_N_SUB_BRANCH, nu))
    live = np.flatnonzero(ta_b <= tb_b)
    if live.size:
        th = _theta_of_u(ta_b[live, None], tb_b[live, None], half_b[live, None], ugrid[None, :])
        px, py, ok = _coupler_points(r1, r2, r3, s1, s2, leg_b[live, None], sigma_b[live, None], th)
        qx[live] = np.where(ok, px, np.inf)
        qy[live] = np.where(ok, py, 0.0)
    ay = _axis_points(r1, r2, r3, s1, s2)
    ys = ylo + (yhi - ylo) * np.arange(n_y) / (n_y - 1)
    rs = _cloud_radius(r1, r2, r3, qx.ravel(), qy.ravel(), ay, ys).tolist()
    best_r, best_y = 0.0, 0.0
    used = -10
    du = 1.0 / (nu - 1)
    off = np.arange(-n_sub, n_sub + 1)
    for _ in range(_MIC_SIZES["n_cand"]):
        # best local maximum of the coarse radii, not next to the previous candidate
        jb = -1
        for j in range(n_y):
            if abs(j - used) <= 1 or rs[j] <= 0.0:
                continue
            if (j > 0 and rs[j - 1] > rs[j]) or (j < n_y - 1 and rs[j + 1] > rs[j]):
                continue
            if jb < 0 or rs[j] > rs[jb]:
                jb = j
        if jb < 0:
            break
        used = jb
        lo, hi = float(ys[max(jb - 1, 0)]), float(ys[min(jb + 1, n_y - 1)])
        # dense cloud around the samples nearest to n_seed_y centres of [lo, hi]
        yq = lo + (hi - lo) * np.arange(n_seed_y) / (n_seed_y - 1)
        d2 = qx[None] * qx[None] + (qy[None] - yq[:, None, None]) ** 2  # (seed, branch, u)
        seen_q, seen_b = np.nonzero(np.isfinite(np.min(d2, axis=2)))
        k = np.argmin(d2, axis=2)[seen_q, seen_b]
        u = ugrid[k][:, None] + du * off[None, :] / n_sub
        bb = seen_b[:, None]
        th = _theta_of_u(ta_b[bb], tb_b[bb], half_b[bb], u)
        px, py, ok = _coupler_points(r1, r2, r3, s1, s2, leg_b[bb], sigma_b[bb], th)
        ok &= (u >= 0.0) & (u <= 1.0)
        dqx, dqy = px[ok], py[ok]

        def rad(y):
            return float(_cloud_radius(r1, r2, r3, dqx, dqy, ay, np.array([y]))[0])

        # golden-section maximisation of min(serial, T_dense) over [lo, hi], the best
        # point seen (from the coarse one) kept
        yb = float(ys[jb])
        g = golden_section_max(rad, lo, hi, max_iter=n_golden, start=(yb, rad(yb)))
        yb, fb = g.x_best, g.f_best
        if fb > best_r:
            best_r, best_y = fb, yb
    return best_r, best_y


def _compiled():
    """:func:`mechopt.mechanisms.five_bar.kernels.mic_batch` if its compiled path exists, else False."""
    global _compiled_mic
    if _compiled_mic is None:
        from mechopt.mechanisms.five_bar import kernels

        _compiled_mic = kernels.mic_batch if kernels.HAVE_NUMBA else False
    return _compiled_mic


def five_bar_mic(r1, r2, r3, mode="+-"):
    """``(radius, center_y)`` of the five-bar's explicit MIC: the values of
    ``kernels.mic_batch(r1, r2, r3, mode, compiled=True)``, by the NumPy port for the
    first :data:`MIC_NUMBA_AFTER_SECONDS` of a process, by the compiled kernel after
    (if numba is available)."""
    global _port_seconds
    from mechopt.mechanisms.five_bar.lci import HAVE_NUMBA

    if HAVE_NUMBA and _port_seconds >= MIC_NUMBA_AFTER_SECONDS and _compiled():
        r, y = _compiled()(r1, r2, r3, mode=mode, compiled=True)
        return float(r[0]), float(y[0])
    t0 = time.perf_counter()
    out = _mic_one_port(r1, r2, r3, mode)
    _port_seconds += time.perf_counter() - t0
    return out


def _mic_one_port(r1, r2, r3, mode):
    """The NumPy port's ``(radius, center_y)``, as ``kernels.mic_batch`` scales it."""
    s1 = 1.0 if mode[0] == "+" else -1.0
    s2 = 1.0 if mode[1] == "+" else -1.0
    L = (r1 + r2 + r3) / 3.0
    r3n = r3 / L
    r, y = _mic_one(r1 / L, r2 / L, r3n, s1, s2)
    if s1 == s2 and r3n == 0.0:  # r3 = 0 in mode ++ or --: every pose is type-II singular
        r = 0.0
    return r * L, y * L


@dataclass(frozen=True)
class Region:
    """A region as a boolean ``mask`` on a :class:`~mechopt.core.quadrature.Grid`."""

    grid: Grid
    mask: np.ndarray

    @property
    def area(self) -> float:
        return self.grid.area(self.mask)

    def points(self):
        """``(x, y)`` of the cell centres inside the region (1-D arrays, row-major
        order: those of ``X[mask], Y[mask]`` for ``X, Y = grid.points()``)."""
        return self._points

    @cached_property
    def _points(self):
        rows, cols = np.nonzero(self.mask)
        x, y = self.grid.x[cols], self.grid.y[rows]
        x.setflags(write=False)
        y.setflags(write=False)
        return x, y

    def mean(self, values) -> float:
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

    Raises ValueError naming the inputs when the centre is singular or
    unreachable, or when the raster is too coarse for the region (its cell next
    to the centre lies outside it: a usable workspace thinner than about a cell).
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
    near = _five_bar_reach_filter(mech) if mech.explicit_mic else None
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


def _five_bar_reach_filter(fb):
    """``near(x, y)``: False only where :meth:`FiveBar.type2_function` is certainly NaN
    (a leg cannot assemble), i.e. where ``|P - A_i|`` lies outside
    ``[|r1 - r2| - m, r1 + r2 + m]`` for a leg. The elbows accept a pose while
    ``h^2 = -(q - lo^2)(q - hi^2) / (4 q^2) >= -1e-12`` (``q = |P - A_i|^2``); beyond the
    margin ``m = 1e-3 L + 1e-9 (r1 + r2)^3 / (r1 r2)`` it is below ``-1e-9`` in exact
    arithmetic (``|h^2|`` grows monotonically away from the annulus and is at least
    ``2 m r1 r2 / (r1 + r2)^3`` there), far beyond rounding."""
    r1, r2, r3 = fb.r1, fb.r2, fb.r3
    hi = r1 + r2
    m = 1e-3 * fb.length_scale + 1e-9 * hi ** 3 / (r1 * r2)
    lo2 = max(abs(r1 - r2) - m, 0.0) ** 2
    hi2 = (hi + m) ** 2

    def near(x, y):
        y2 = y * y
        ok = None
        for ax in (-r3, r3):
            q = x - ax
            q *= q
            q += y2
            leg = (q >= lo2) & (q <= hi2)
            ok = leg if ok is None else ok & leg
        return ok

    return near


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
    """Why :func:`usable_region` found no region, in terms of the inputs (one line)."""
    s0 = np.sign(mech.type2_function(*center))
    if not (np.isfinite(s0) and s0 != 0):
        return (f"{mech!r}: the centre {_v.show(tuple(center))} is singular or unreachable, so it lies "
                "in no singularity-free region")
    five_bar = mech.explicit_mic
    scale = "(r1 + r2 + r3)/1200" if five_bar else "its length scale/400"
    what = f"the raster step {step:.6g}" if given_step else f"the raster step {scale} = {step:.6g}"
    bound = ""
    if five_bar:
        need = "" if given_step else " (r1 + r2 + r3)/800 ="
        bound = (f"; the MIC radius is at most min(r1, r2) = {min(mech.r1, mech.r2):.6g}, so min(r1, r2) "
                 f"must be at least about{need} {1.5 * step:.6g}")
    radius = "" if r_mic is None else f" (radius {r_mic:.6g})"
    return (f"{mech!r}: its usable workspace is too thin for {what}: the raster cell next to the "
            f"MIC centre{radius} lies outside it; the MIC radius must be at least about 1.5 raster "
            f"steps{bound}")


def gcw(mech, gamma: float = 0.5, usable: Region | None = None) -> Region:
    """Good-conditioning workspace ``{LCI >= gamma}`` inside the usable workspace.

    Liu 2006 sec. 3.2.3 step 1 (Fig. 25). It may be empty (``area == 0``): Liu's
    design (0.4, 2.33, 0.27) has no GCW at ``gamma = 0.5``, a result, not an error.
    The LCI is evaluated at the usable cells only.
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
    without wrapping, so the ranges are continuous. NaN bounds for an empty region."""
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
