"""Batch kernels for the symmetric five-bar: local indices, disk means and a fast MIC.

They carry the performance atlas (:mod:`mechopt.atlas`, Liu 2006 Fig. 2-8): tens
of thousands of designs, each needing its MIC and about 10^4 local evaluations.

Every kernel exists twice, with the same formulas in the same order:

* a pure-NumPy path (always available), vectorised over points and designs;
* a compiled path (numba, the optional ``fast`` extra), one loop per design and
  per point, used when numba imports (``MECHOPT_NO_NUMBA=1`` forces NumPy).

``tests/test_atlas.py`` checks that both paths agree (local indices to 1e-12,
MIC and disk means to rounding) and that the fast MIC and disk means agree with
the reference :func:`mechopt.workspace.mic` + :func:`mechopt.performance.global_indices`.

Geometry and conventions are those of :mod:`mechopt.mechanisms.five_bar`
(DESIGN.md): ``A1 = (-r3, 0)``, ``A2 = (r3, 0)``, crank ``r1``, distal link ``r2``,
working-mode signs ``s1, s2`` (``+1`` for ``"+"``); elbows by circle intersection
(no trigonometry); ``J = B^-1 A`` with ``theta_dot = J p_dot``. The kernels work
on the design divided by its length scale ``(r1 + r2 + r3)/3`` and rescale.

Fast MIC (:func:`mic_batch`)
----------------------------
The largest singularity-free disk centred at ``(0, yc)`` has the radius
``min(serial(yc), T(yc))``:

* ``serial(yc) = min(r1 + r2 - D, D - |r1 - r2|)``, ``D = hypot(r3, yc)``: the
  closed-form distance to the four circles of Le eq. (19) (both legs see the
  same ``D`` from the y axis). It is positive only for
  ``|r1 - r2| < D < r1 + r2`` and never exceeds ``min(r1, r2)``.
* ``T(yc)``: the distance to the type-II locus of the working mode, generated
  explicitly. ``P``, ``B1``, ``B2`` collinear means either

  - ``P`` is the midpoint of ``B1 B2``, ``|B1 B2| = 2 r2`` (the coupler curve of the
    four-bar ``A1 B1 B2 A2``). It is sampled by the crank angle of leg 1 *and* by
    that of leg 2 (each parametrisation is regular where the other has a dead
    point), both circle-intersection branches, over the angles where the
    coupler closes and the crank tip lies within ``min(r1, r2) + r2`` of the y
    axis (no farther point can be within ``min(r1, r2)`` of a centre), with
    cosine spacing so that the square-root ends are sampled evenly; or
  - ``B1 = B2 = C = (0, +-sqrt(r1^2 - r3^2))`` (the cranks meet) and ``P`` is on the
    circle of radius ``r2`` about ``C``: seen from a point of the y axis its
    nearest point is ``(0, +-h +- r2)``, so four points replace the circle.

  A point is kept only if its elbows are the working mode's
  (``s_i cross(P - A_i, B_i - A_i) >= 0``). Points of the locus are exact, so a
  sampled distance never underestimates ``T``; where a kept arc ends (a dead
  point or a change of elbow) the locus meets a serial circle, and ``serial``
  already bounds the radius there.

The radius is maximised over ``yc`` in the serial-feasible interval: 128 coarse
centres, then for the two best local maxima the locus is re-sampled 16x finer
around the samples nearest to nine centres of the bracketing interval, and a
golden-section search on that dense cloud gives the centre. Against
:func:`mechopt.workspace.mic` (root finding, ~1e-7) the radius agrees to a few
1e-6 (relative) for mode ``"+-"``; where they differ by more, the reference
missed a better centre or a small type-II lobe (see ``tests/test_atlas.py``).

Disk means and the MCI (:func:`disk_stats_batch`)
-------------------------------------------------
GCI is the mean LCI over the MIC disk, GVI/GPI/GSI the means of the extremes
over the concentric half-radius disk (Liu 2006 eq. 4, 11, 14, 19), with the
nodes and weights of :func:`mechopt.quadrature.disk_rule`. The MCI starts at the
best quadrature node; a compass search (as :func:`mechopt.performance.max_lci`),
a golden-section search along the rim, and Newton iterations on the isotropy
conditions (``LCI = 1`` exactly where J is a scaled rotation or reflection, a
cone apex that direct search approaches slowly) refine it.
"""
from __future__ import annotations

import math
import os

import numpy as np

__all__ = [
    "HAVE_NUMBA",
    "use_numba",
    "MIC_SIZES",
    "lci_points",
    "local_points",
    "mic_batch",
    "disk_stats_batch",
    "DISK_STAT_NAMES",
]

try:  # numba is optional (extra "fast")
    if os.environ.get("MECHOPT_NO_NUMBA", "") not in ("", "0"):
        raise ImportError("disabled by MECHOPT_NO_NUMBA")
    import numba as _numba
except ImportError:  # pragma: no cover - depends on the environment
    _numba = None

HAVE_NUMBA = _numba is not None

#: reachability tolerance on ``h^2`` (same as FiveBar.elbows)
_REACH_TOL = 1e-12
#: sizes of the fast MIC: crank-angle samples per coupler-curve sub-branch,
#: coarse centres, dense refinement factor, centres seeding the refinement,
#: golden-section iterations, local maxima refined
MIC_SIZES = dict(n_crank=128, n_y=128, n_sub=16, n_seed_y=9, n_golden=42, n_cand=2)
#: compass search of the MCI (as mechopt.performance.max_lci)
_MCI_ITERS = 40
#: starting nodes of the MCI search (mutually farther apart than R/3)
_MCI_STARTS = 3
_DIRS = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0],
                  [1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]])
_GOLD = (math.sqrt(5.0) - 1.0) / 2.0

#: columns of :func:`disk_stats_batch`
DISK_STAT_NAMES = ("gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min")


def use_numba(flag=None) -> bool:
    """Whether the compiled path is used (``flag=None``: when numba is installed)."""
    if flag is None:
        return HAVE_NUMBA
    if flag and not HAVE_NUMBA:
        raise ValueError("numba is not installed: pip install 'mechopt[fast]'")
    return bool(flag)


def _njit(fn):
    if _numba is None:
        return fn
    return _numba.njit(cache=True, nogil=True, error_model="numpy")(fn)


def _njit_inline(fn):
    if _numba is None:
        return fn
    return _numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")(fn)


# =============================================================================
# Local kinematics
# =============================================================================
# For leg i with base joint A_i = (-+r3, 0) and v = P - A_i = (dx, y), q = |v|^2:
#   B_i - A_i = c v + h w,  w = (-y, dx),  c = (r1^2 - r2^2)/(2 q) + 1/2,
#   h = s_i sqrt(r1^2/q - c^2)            (FiveBar.elbows, Le eq. 13-14)
#   a_i = P - B_i,  k_i = (B_i - A_i) x a_i = r1 (u_i x a_i)
# and J = [a_1 / k_1; a_2 / k_2]. The kernels work on M = k_1 k_2 J = [k_2 a_1; k_1 a_2]
# (no division per entry): LCI(J) = LCI(M), s(J) = s(M) / |k_1 k_2|.
def _mrows_np(r1, r2, r3, s1, s2, x, y):
    """``(m11, m12, m21, m22, k1 k2, reachable)`` at the points (NumPy, broadcasting)."""
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        dx = x + r3
        dsq = dx * dx + y * y
        inv = 1.0 / dsq
        c = half_d * inv + 0.5
        h2 = r1sq * inv - c * c
        h = np.sqrt(np.maximum(h2, 0.0)) * s1
        bx = c * dx - h * y
        by = c * y + h * dx
        a1x = dx - bx
        a1y = y - by
        k1 = bx * a1y - by * a1x
        ok = (h2 >= -_REACH_TOL) & (dsq > 0.0)
        dx = x - r3
        dsq = dx * dx + y * y
        inv = 1.0 / dsq
        c = half_d * inv + 0.5
        h2 = r1sq * inv - c * c
        h = np.sqrt(np.maximum(h2, 0.0)) * s2
        bx = c * dx - h * y
        by = c * y + h * dx
        a2x = dx - bx
        a2y = y - by
        k2 = bx * a2y - by * a2x
        ok = ok & (h2 >= -_REACH_TOL) & (dsq > 0.0)
        return a1x * k2, a1y * k2, a2x * k1, a2y * k1, k1 * k2, ok


def _lci_m_np(a, b, c, d, ok):
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        S = a * a + b * b + c * c + d * d
        disc = np.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
        den = S + disc
        v = 2.0 * np.abs(a * d - b * c) / den
    return np.where(ok & (den > 0.0), v, 0.0)


def _extremes_m_np(a, b, c, d, kk, ok):
    """``(v_max, v_min, tau_max, tau_min, d_max, d_min)`` of J from M = kk J; NaN where
    unreachable."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        S = a * a + b * b + c * c + d * d
        disc = np.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
        sm = np.sqrt(0.5 * (S + disc))
        ak = np.abs(kk)
        s_max = sm / ak
        s_min = np.abs(a * d - b * c) / (sm * ak)
        out = (1.0 / s_min, 1.0 / s_max, s_max, s_min, 1.0 / (s_min * s_min), 1.0 / (s_max * s_max))
    return tuple(np.where(ok, v, np.nan) for v in out)


@_njit_inline
def _mrows_nb(r1sq, half_d, r3, s1, s2, x, y):
    dx = x + r3
    dsq = dx * dx + y * y
    inv = 1.0 / dsq
    c = half_d * inv + 0.5
    h2 = r1sq * inv - c * c
    h = math.sqrt(max(h2, 0.0)) * s1
    bx = c * dx - h * y
    by = c * y + h * dx
    a1x = dx - bx
    a1y = y - by
    k1 = bx * a1y - by * a1x
    ok = (h2 >= -_REACH_TOL) and (dsq > 0.0)
    dx = x - r3
    dsq = dx * dx + y * y
    inv = 1.0 / dsq
    c = half_d * inv + 0.5
    h2 = r1sq * inv - c * c
    h = math.sqrt(max(h2, 0.0)) * s2
    bx = c * dx - h * y
    by = c * y + h * dx
    a2x = dx - bx
    a2y = y - by
    k2 = bx * a2y - by * a2x
    ok = ok and (h2 >= -_REACH_TOL) and (dsq > 0.0)
    return a1x * k2, a1y * k2, a2x * k1, a2y * k1, k1 * k2, ok


@_njit_inline
def _lci_m_nb(a, b, c, d, ok):
    S = a * a + b * b + c * c + d * d
    disc = math.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
    den = S + disc
    v = 2.0 * abs(a * d - b * c) / den
    return v if (ok and den > 0.0) else 0.0


@_njit_inline
def _lci_point_nb(r1sq, half_d, r3, s1, s2, x, y):
    a, b, c, d, kk, ok = _mrows_nb(r1sq, half_d, r3, s1, s2, x, y)
    return _lci_m_nb(a, b, c, d, ok)


@_njit
def _lci_points_nb(r1, r2, r3, s1, s2, x, y, out):
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    for i in range(x.size):
        out[i] = _lci_point_nb(r1sq, half_d, r3, s1, s2, x[i], y[i])


@_njit
def _local_points_nb(r1, r2, r3, s1, s2, x, y, out):
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    nan = np.nan
    for i in range(x.size):
        a, b, c, d, kk, ok = _mrows_nb(r1sq, half_d, r3, s1, s2, x[i], y[i])
        out[0, i] = _lci_m_nb(a, b, c, d, ok)
        S = a * a + b * b + c * c + d * d
        disc = math.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
        sm = math.sqrt(0.5 * (S + disc))
        ak = abs(kk)
        s_max = sm / ak
        s_min = abs(a * d - b * c) / (sm * ak)
        out[1, i] = 1.0 / s_min if ok else nan
        out[2, i] = 1.0 / s_max if ok else nan
        out[3, i] = s_max if ok else nan
        out[4, i] = s_min if ok else nan
        out[5, i] = 1.0 / (s_min * s_min) if ok else nan
        out[6, i] = 1.0 / (s_max * s_max) if ok else nan


def _signs(mode):
    if mode not in ("+-", "-+", "++", "--"):
        raise ValueError(f"mode must be one of '+-', '-+', '++', '--', got {mode!r}")
    return (1.0 if mode[0] == "+" else -1.0), (1.0 if mode[1] == "+" else -1.0)


def _points(x, y, L):
    x = np.ascontiguousarray(x, dtype=float).ravel() / L
    y = np.ascontiguousarray(y, dtype=float).ravel() / L
    if x.shape != y.shape:
        raise ValueError(f"x and y must have the same size, got {x.size} and {y.size}")
    return x, y


def _design(r1, r2, r3):
    r1, r2, r3 = float(r1), float(r2), float(r3)
    L = (r1 + r2 + r3) / 3.0
    return r1 / L, r2 / L, r3 / L, L


def lci_points(r1, r2, r3, x, y, mode="+-", compiled=None):
    """LCI ``1/kappa_J`` of one design at the points ``(x, y)`` (flattened); 0 where
    unreachable or singular. ``compiled=None`` uses numba when it is installed.

    Lengths are divided by ``(r1 + r2 + r3)/3`` first (the LCI is scale-free), so
    nothing over- or underflows in any unit.
    """
    s1, s2 = _signs(mode)
    r1, r2, r3, L = _design(r1, r2, r3)
    x, y = _points(x, y, L)
    if use_numba(compiled):
        out = np.empty_like(x)
        _lci_points_nb(r1, r2, r3, s1, s2, x, y, out)
        return out
    a, b, c, d, _, ok = _mrows_np(r1, r2, r3, s1, s2, x, y)
    return _lci_m_np(a, b, c, d, ok)


def local_points(r1, r2, r3, x, y, mode="+-", compiled=None):
    """``(7, n)`` array of ``lci, v_max, v_min, tau_max, tau_min, d_max, d_min``
    (:data:`mechopt.indices.LOCAL_INDEX_NAMES`, Liu 2006 eq. 3, 10, 13, 18) at the
    points; the extremes are NaN where a point is unreachable."""
    s1, s2 = _signs(mode)
    r1, r2, r3, L = _design(r1, r2, r3)
    x, y = _points(x, y, L)
    if use_numba(compiled):
        out = np.empty((7, x.size))
        _local_points_nb(r1, r2, r3, s1, s2, x, y, out)
    else:
        a, b, c, d, kk, ok = _mrows_np(r1, r2, r3, s1, s2, x, y)
        out = np.stack((_lci_m_np(a, b, c, d, ok),) + _extremes_m_np(a, b, c, d, kk, ok))
    # back to the caller's unit: J scales as 1/L
    out[1:3] *= L
    out[3:5] /= L
    out[5:7] *= L * L
    return out


# =============================================================================
# Type-II locus of the working mode (see the module docstring)
# =============================================================================
# Coupler-curve sub-branches b = 0..7: leg = b // 4 (whose crank angle is the
# parameter), sigma = +1 if (b // 2) % 2 == 0 else -1 (circle-intersection branch),
# half = b % 2 (theta in [0, pi] or [-pi, 0]). On each, theta runs over the
# interval where the coupler closes, cosine-spaced in u in [0, 1] so that the
# square-root behaviour at the dead points is sampled at even arc length.
_N_SUB_BRANCH = 8


@_njit
def _theta_range_nb(r1, r2, r3, leg, rho):
    """``(theta_a, theta_b)`` in [0, pi] (and its mirror in [-pi, 0]) where the
    coupler of length 2 r2 closes (leg 0: crank 1 at theta; leg 1: crank 2) and
    the crank tip lies within ``|x| <= rho`` of the y axis; ``theta_a > theta_b``
    if empty."""
    lo2 = (r1 - 2.0 * r2) ** 2
    hi2 = (r1 + 2.0 * r2) ** 2
    base = 4.0 * r3 * r3 + r1 * r1
    k = 4.0 * r3 * r1
    if k <= 0.0:
        if not (lo2 <= base <= hi2):
            return 1.0, 0.0
        clo = -1.0
        chi = 1.0
    else:
        # leg 0: L^2 = base - k cos(theta); leg 1: L^2 = base + k cos(theta)
        clo = (base - hi2) / k
        chi = (base - lo2) / k
        if leg == 1:
            clo, chi = -chi, -clo
    # crank tip x = -+r3 + r1 cos(theta) within [-rho, rho]
    sx = -r3 if leg == 0 else r3
    clo = max(clo, (-rho - sx) / r1, -1.0)
    chi = min(chi, (rho - sx) / r1, 1.0)
    if clo > chi:
        return 1.0, 0.0
    return math.acos(chi), math.acos(clo)


@_njit
def _theta_of_u_nb(ta, tb, half, u):
    th = ta + (tb - ta) * 0.5 * (1.0 - math.cos(math.pi * u))
    return th if half == 0 else -th


@_njit
def _coupler_point_nb(r1, r2, r3, s1, s2, leg, sigma, th):
    """Midpoint ``P`` of ``B1 B2`` (``|B1 B2| = 2 r2``) with crank ``leg`` at ``th``:
    ``(px, py, valid)``; valid when it closes and its elbows are the working mode's."""
    if leg == 0:
        ax = -r3
    else:
        ax = r3
    ox = -ax
    bx = ax + r1 * math.cos(th)
    by = r1 * math.sin(th)
    vx = ox - bx
    vy = -by
    L2 = vx * vx + vy * vy
    if not L2 > 0.0:
        return 0.0, 0.0, False
    L = math.sqrt(L2)
    cc = 4.0 * r2 * r2
    a = (L2 + cc - r1 * r1) / (2.0 * L)
    hh2 = cc - a * a
    if hh2 < -1e-12 * cc:
        return 0.0, 0.0, False
    hh = sigma * math.sqrt(max(hh2, 0.0))
    cx = bx + (a * vx - hh * vy) / L
    cy = by + (a * vy + hh * vx) / L
    px = 0.5 * (bx + cx)
    py = 0.5 * (by + cy)
    if leg == 0:
        b1x, b1y, b2x, b2y = bx, by, cx, cy
    else:
        b1x, b1y, b2x, b2y = cx, cy, bx, by
    c1 = (px + r3) * b1y - py * (b1x + r3)
    c2 = (px - r3) * b2y - py * (b2x - r3)
    if s1 * c1 < 0.0 or s2 * c2 < 0.0:
        return px, py, False
    return px, py, True


@_njit
def _axis_points_nb(r1, r2, r3, s1, s2, qy):
    """The B1 = B2 = C branch seen from the y axis: for a centre ``(0, y)`` the
    nearest point of the circle ``|P - C| = r2`` is ``(0, hc +- r2)``; the four
    such points that have the working mode's elbows are written to ``qy``
    (NaN otherwise). Returns how many are valid."""
    m = 0
    for i in range(4):
        qy[i] = np.nan
    if not (r3 > 0.0 and r1 > r3):
        return 0
    h = math.sqrt(r1 * r1 - r3 * r3)
    for i in range(4):
        hc = h if i < 2 else -h
        py = hc + r2 if i % 2 == 0 else hc - r2
        # elbows B1 = B2 = (0, hc), P = (0, py)
        c1 = r3 * hc - py * r3
        c2 = -r3 * hc + py * r3
        if s1 * c1 < 0.0 or s2 * c2 < 0.0:
            continue
        qy[i] = py
        m += 1
    return m


@_njit
def _serial_nb(r1, r2, r3, y):
    D = math.sqrt(r3 * r3 + y * y)
    return min(r1 + r2 - D, D - abs(r1 - r2))


@_njit
def _radius_nb(r1, r2, r3, qx, qy, n, ay, y):
    """``min(serial, distance to the n cloud points and the 4 axis points)``."""
    s = _serial_nb(r1, r2, r3, y)
    if s <= 0.0:
        return 0.0
    best = s * s
    for k in range(n):
        dy = qy[k] - y
        d2 = qx[k] * qx[k] + dy * dy
        if d2 < best:
            best = d2
    for i in range(4):
        dy = ay[i] - y  # NaN compares False
        if dy * dy < best:
            best = dy * dy
    return math.sqrt(best)


@_njit
def _mic_one_nb(r1, r2, r3, s1, s2, ugrid, n_y, n_sub, n_seed_y, n_golden, n_cand,
                qx, qy, ys, rs, dqx, dqy, ay, tr):
    """MIC ``(radius, center_y)`` of one design (work arrays passed in)."""
    nu = ugrid.size
    # centres worth trying: the serial clearance is positive for
    # |r1 - r2| < hypot(r3, y) < r1 + r2, and never exceeds min(r1, r2), so only
    # locus points within min(r1, r2) of that axis segment matter, and their
    # crank tips lie within rho = min(r1, r2) + r2 of the y axis.
    ylo2 = (r1 - r2) * (r1 - r2) - r3 * r3
    ylo = math.sqrt(ylo2) if ylo2 > 0.0 else 0.0
    yhi2 = (r1 + r2) * (r1 + r2) - r3 * r3
    yhi = math.sqrt(yhi2) if yhi2 > 0.0 else 0.0
    rho = 1.01 * (min(r1, r2) + r2)
    for leg in range(2):
        ta, tb = _theta_range_nb(r1, r2, r3, leg, rho)
        tr[leg, 0] = ta
        tr[leg, 1] = tb
    for b in range(_N_SUB_BRANCH):
        leg = b // 4
        sigma = 1.0 if (b // 2) % 2 == 0 else -1.0
        half = b % 2
        ta = tr[leg, 0]
        tb = tr[leg, 1]
        for k in range(nu):
            idx = b * nu + k
            qx[idx] = np.inf
            qy[idx] = 0.0
            if ta > tb:
                continue
            th = _theta_of_u_nb(ta, tb, half, ugrid[k])
            px, py, ok = _coupler_point_nb(r1, r2, r3, s1, s2, leg, sigma, th)
            if ok:
                qx[idx] = px
                qy[idx] = py
    n = _N_SUB_BRANCH * nu
    _axis_points_nb(r1, r2, r3, s1, s2, ay)
    for j in range(n_y):
        ys[j] = ylo + (yhi - ylo) * j / (n_y - 1)
        rs[j] = _radius_nb(r1, r2, r3, qx, qy, n, ay, ys[j])
    best_r = 0.0
    best_y = 0.0
    used0 = -10
    du = 1.0 / (nu - 1)
    for cand in range(n_cand):
        # best local maximum of the coarse radii, not next to the previous candidate
        jb = -1
        for j in range(n_y):
            if abs(j - used0) <= 1 or rs[j] <= 0.0:
                continue
            if j > 0 and rs[j - 1] > rs[j]:
                continue
            if j < n_y - 1 and rs[j + 1] > rs[j]:
                continue
            if jb < 0 or rs[j] > rs[jb]:
                jb = j
        if jb < 0:
            break
        used0 = jb
        lo = ys[max(jb - 1, 0)]
        hi = ys[min(jb + 1, n_y - 1)]
        # dense cloud around the samples nearest to n_seed_y centres of [lo, hi]
        m = 0
        for q in range(n_seed_y):
            yq = lo + (hi - lo) * q / (n_seed_y - 1)
            for b in range(_N_SUB_BRANCH):
                kb = -1
                bd = np.inf
                for k in range(b * nu, (b + 1) * nu):
                    dy = qy[k] - yq
                    d2 = qx[k] * qx[k] + dy * dy
                    if d2 < bd:
                        bd = d2
                        kb = k
                if kb < 0:
                    continue
                leg = b // 4
                sigma = 1.0 if (b // 2) % 2 == 0 else -1.0
                half = b % 2
                u0 = ugrid[kb - b * nu]
                for i in range(-n_sub, n_sub + 1):
                    u = u0 + du * i / n_sub
                    if u < 0.0 or u > 1.0:
                        continue
                    th = _theta_of_u_nb(tr[leg, 0], tr[leg, 1], half, u)
                    px, py, ok = _coupler_point_nb(r1, r2, r3, s1, s2, leg, sigma, th)
                    if ok:
                        dqx[m] = px
                        dqy[m] = py
                        m += 1
        # golden-section maximisation of min(serial, T_dense) over [lo, hi]
        yb = ys[jb]
        fb = _radius_nb(r1, r2, r3, dqx, dqy, m, ay, yb)
        a = lo
        c = hi
        x1 = c - _GOLD * (c - a)
        x2 = a + _GOLD * (c - a)
        f1 = _radius_nb(r1, r2, r3, dqx, dqy, m, ay, x1)
        f2 = _radius_nb(r1, r2, r3, dqx, dqy, m, ay, x2)
        for _ in range(n_golden):
            if f1 >= f2:
                if f1 > fb:
                    fb = f1
                    yb = x1
                c = x2
                x2 = x1
                f2 = f1
                x1 = c - _GOLD * (c - a)
                f1 = _radius_nb(r1, r2, r3, dqx, dqy, m, ay, x1)
            else:
                if f2 > fb:
                    fb = f2
                    yb = x2
                a = x1
                x1 = x2
                f1 = f2
                x2 = a + _GOLD * (c - a)
                f2 = _radius_nb(r1, r2, r3, dqx, dqy, m, ay, x2)
        if f1 > fb:
            fb = f1
            yb = x1
        if f2 > fb:
            fb = f2
            yb = x2
        if fb > best_r:
            best_r = fb
            best_y = yb
    return best_r, best_y


@_njit
def _mic_batch_nb(r1, r2, r3, s1, s2, ugrid, n_y, n_sub, n_seed_y, n_golden, n_cand,
                  out_r, out_y):
    n = _N_SUB_BRANCH * ugrid.size
    qx = np.empty(n)
    qy = np.empty(n)
    ys = np.empty(n_y)
    rs = np.empty(n_y)
    md = n_seed_y * _N_SUB_BRANCH * (2 * n_sub + 1)
    dqx = np.empty(md)
    dqy = np.empty(md)
    ay = np.empty(4)
    tr = np.empty((2, 2))
    for i in range(r1.size):
        out_r[i], out_y[i] = _mic_one_nb(r1[i], r2[i], r3[i], s1, s2, ugrid, n_y, n_sub,
                                         n_seed_y, n_golden, n_cand,
                                         qx, qy, ys, rs, dqx, dqy, ay, tr)


# --- the same algorithm in NumPy, vectorised over a block of designs ----------
def _theta_range_np(r1, r2, r3, leg, rho):
    lo2 = (r1 - 2.0 * r2) ** 2
    hi2 = (r1 + 2.0 * r2) ** 2
    base = 4.0 * r3 * r3 + r1 * r1
    k = 4.0 * r3 * r1
    pos = k > 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        clo = np.where(pos, (base - hi2) / k, -1.0)
        chi = np.where(pos, (base - lo2) / k, 1.0)
    if leg == 1:
        clo, chi = -chi, -clo
    closes = pos | ((lo2 <= base) & (base <= hi2))
    sx = -r3 if leg == 0 else r3
    clo = np.maximum(np.maximum(clo, (-rho - sx) / r1), -1.0)
    chi = np.minimum(np.minimum(chi, (rho - sx) / r1), 1.0)
    ok = closes & (clo <= chi)
    ta = np.where(ok, np.arccos(np.clip(chi, -1.0, 1.0)), 1.0)
    tb = np.where(ok, np.arccos(np.clip(clo, -1.0, 1.0)), 0.0)
    return ta, tb


def _theta_of_u_np(ta, tb, half, u):
    th = ta + (tb - ta) * 0.5 * (1.0 - np.cos(np.pi * u))
    return np.where(half == 0, th, -th)


def _coupler_point_np(r1, r2, r3, s1, s2, leg, sigma, th):
    """Vectorised :func:`_coupler_point_nb` (``leg``, ``sigma`` arrays broadcast)."""
    ax = np.where(leg == 0, -r3, r3)
    ox = -ax
    bx = ax + r1 * np.cos(th)
    by = r1 * np.sin(th)
    vx = ox - bx
    vy = -by
    L2 = vx * vx + vy * vy
    L = np.sqrt(L2)
    cc = 4.0 * r2 * r2
    with np.errstate(divide="ignore", invalid="ignore"):
        a = (L2 + cc - r1 * r1) / (2.0 * L)
        hh2 = cc - a * a
        hh = sigma * np.sqrt(np.maximum(hh2, 0.0))
        cx = bx + (a * vx - hh * vy) / L
        cy = by + (a * vy + hh * vx) / L
    px = 0.5 * (bx + cx)
    py = 0.5 * (by + cy)
    first = leg == 0
    b1x = np.where(first, bx, cx)
    b1y = np.where(first, by, cy)
    b2x = np.where(first, cx, bx)
    b2y = np.where(first, cy, by)
    c1 = (px + r3) * b1y - py * (b1x + r3)
    c2 = (px - r3) * b2y - py * (b2x - r3)
    ok = (L2 > 0.0) & (hh2 >= -1e-12 * cc) & ~(s1 * c1 < 0.0) & ~(s2 * c2 < 0.0)
    return px, py, ok


def _axis_points_np(r1, r2, r3, s1, s2):
    exists = (r3 > 0.0) & (r1 > r3)
    h = np.sqrt(np.maximum(r1 * r1 - r3 * r3, 0.0))
    cols = []
    for i in range(4):
        hc = h if i < 2 else -h
        py = hc + r2 if i % 2 == 0 else hc - r2
        c1 = r3 * hc - py * r3
        c2 = -r3 * hc + py * r3
        ok = exists & ~(s1 * c1 < 0.0) & ~(s2 * c2 < 0.0)
        cols.append(np.where(ok, py, np.nan))
    return np.stack(cols, -1)


def _radius_np(r1, r2, r3, qx, qy, ay, y):
    """``y`` shape ``(B, ...)``; cloud ``qx, qy`` shape ``(B, [1...,] n)``; ``ay`` ``(B, 4)``."""
    D = np.sqrt(r3 * r3 + y * y)
    s = np.minimum(r1 + r2 - D, D - np.abs(r1 - r2))
    dy = qy - y[..., None]
    best = np.minimum(s * s, np.min(qx * qx + dy * dy, axis=-1, initial=np.inf))
    ay = ay.reshape(ay.shape[:1] + (1,) * (y.ndim - 1) + (4,))
    da = ay - y[..., None]
    da2 = np.where(np.isnan(da), np.inf, da * da)
    best = np.minimum(best, da2.min(axis=-1))
    return np.where(s <= 0.0, 0.0, np.sqrt(best))


def _mic_block_np(r1, r2, r3, s1, s2, ugrid, cfg):
    B = r1.size
    nu = ugrid.size
    n_y, n_sub, n_seed_y = cfg["n_y"], cfg["n_sub"], cfg["n_seed_y"]
    c1 = lambda v: v[:, None]  # noqa: E731
    ylo = np.sqrt(np.maximum((r1 - r2) ** 2 - r3 * r3, 0.0))
    yhi = np.sqrt(np.maximum((r1 + r2) ** 2 - r3 * r3, 0.0))
    rho = 1.01 * (np.minimum(r1, r2) + r2)
    tr = [_theta_range_np(r1, r2, r3, leg, rho) for leg in (0, 1)]
    b = np.arange(_N_SUB_BRANCH)
    leg_b = b // 4
    sigma_b = np.where((b // 2) % 2 == 0, 1.0, -1.0)
    half_b = b % 2
    ta = np.stack([tr[leg][0] for leg in leg_b], -1)  # (B, 8)
    tb = np.stack([tr[leg][1] for leg in leg_b], -1)
    rr = [v[:, None, None] for v in (r1, r2, r3)]
    th = _theta_of_u_np(ta[..., None], tb[..., None], half_b[None, :, None], ugrid[None, None, :])
    qx, qy, ok = _coupler_point_np(*rr, s1, s2, leg_b[None, :, None], sigma_b[None, :, None], th)
    ok &= (ta <= tb)[..., None]
    qx = np.where(ok, qx, np.inf).reshape(B, -1)
    qy = np.where(ok, qy, 0.0).reshape(B, -1)
    ay = _axis_points_np(r1, r2, r3, s1, s2)
    ys = c1(ylo) + c1(yhi - ylo) * (np.arange(n_y) / (n_y - 1))[None, :]
    rs = _radius_np(c1(r1), c1(r2), c1(r3), qx[:, None, :], qy[:, None, :], ay, ys)
    jj = np.arange(n_y)
    left = np.concatenate([np.full((B, 1), -np.inf), rs[:, :-1]], 1)
    right = np.concatenate([rs[:, 1:], np.full((B, 1), -np.inf)], 1)
    is_max = (rs > 0.0) & ~(left > rs) & ~(right > rs)
    best_r = np.zeros(B)
    best_y = np.zeros(B)
    used = np.full(B, -10)
    du = 1.0 / (nu - 1)
    rows = np.arange(B)
    for _ in range(cfg["n_cand"]):
        cand = is_max & (np.abs(jj[None, :] - used[:, None]) > 1)
        have = cand.any(axis=1)
        jb = np.argmax(np.where(cand, rs, -np.inf), axis=1)
        used = np.where(have, jb, used)
        lo = ys[rows, np.maximum(jb - 1, 0)]
        hi = ys[rows, np.minimum(jb + 1, n_y - 1)]
        yq = c1(lo) + c1(hi - lo) * (np.arange(n_seed_y) / (n_seed_y - 1))[None, :]  # (B, Q)
        qxb = qx.reshape(B, 1, _N_SUB_BRANCH, nu)
        qyb = qy.reshape(B, 1, _N_SUB_BRANCH, nu)
        d2 = qxb * qxb + (qyb - yq[:, :, None, None]) ** 2  # (B, Q, 8, nu)
        kb = np.argmin(d2, axis=-1)  # (B, Q, 8)
        seen = np.isfinite(np.min(d2, axis=-1))
        off = np.arange(-n_sub, n_sub + 1) / n_sub
        u = ugrid[kb][..., None] + du * off  # (B, Q, 8, 2 n_sub + 1)
        thd = _theta_of_u_np(ta[:, None, :, None], tb[:, None, :, None], half_b[None, None, :, None], u)
        px, py, okd = _coupler_point_np(*(v[..., None] for v in rr), s1, s2,
                                        leg_b[None, None, :, None], sigma_b[None, None, :, None], thd)
        okd &= (u >= 0.0) & (u <= 1.0) & seen[..., None]
        dqx = np.where(okd, px, np.inf).reshape(B, -1)
        dqy = np.where(okd, py, 0.0).reshape(B, -1)
        rad = lambda y: _radius_np(r1, r2, r3, dqx, dqy, ay, y)  # noqa: E731
        yb = ys[rows, jb]
        fb = rad(yb)
        a, c = lo.copy(), hi.copy()
        x1 = c - _GOLD * (c - a)
        x2 = a + _GOLD * (c - a)
        f1, f2 = rad(x1), rad(x2)
        for _ in range(cfg["n_golden"]):
            left_ = f1 >= f2
            up1 = left_ & (f1 > fb)
            up2 = ~left_ & (f2 > fb)
            fb = np.where(up1, f1, np.where(up2, f2, fb))
            yb = np.where(up1, x1, np.where(up2, x2, yb))
            # f1 >= f2: c = x2, x2 = x1 (f2 = f1), new x1;  else a = x1, x1 = x2, new x2
            c = np.where(left_, x2, c)
            a = np.where(left_, a, x1)
            nx2 = np.where(left_, x1, a + _GOLD * (c - a))
            nx1 = np.where(left_, c - _GOLD * (c - a), x2)
            nf1 = np.where(left_, np.nan, f2)
            nf2 = np.where(left_, f1, np.nan)
            fnew = rad(np.where(left_, nx1, nx2))
            f1 = np.where(left_, fnew, nf1)
            f2 = np.where(left_, nf2, fnew)
            x1, x2 = nx1, nx2
        for xv, fv in ((x1, f1), (x2, f2)):
            up = fv > fb
            fb = np.where(up, fv, fb)
            yb = np.where(up, xv, yb)
        better = have & (fb > best_r)
        best_r = np.where(better, fb, best_r)
        best_y = np.where(better, yb, best_y)
        if not have.any():
            break
    return best_r, best_y


def mic_batch(r1, r2, r3, mode="+-", compiled=None, **sizes):
    """Fast MIC of many designs: ``(radius, center_y)`` arrays (see the module docstring)."""
    s1, s2 = _signs(mode)
    cfg = dict(MIC_SIZES, **sizes)
    r1, r2, r3 = (np.ascontiguousarray(v, dtype=float).ravel() for v in np.broadcast_arrays(r1, r2, r3))
    L = (r1 + r2 + r3) / 3.0
    r1, r2, r3 = r1 / L, r2 / L, r3 / L
    ugrid = np.linspace(0.0, 1.0, cfg["n_crank"])
    out_r = np.empty(r1.size)
    out_y = np.empty(r1.size)
    if use_numba(compiled):
        _mic_batch_nb(r1, r2, r3, s1, s2, ugrid, cfg["n_y"], cfg["n_sub"], cfg["n_seed_y"],
                      cfg["n_golden"], cfg["n_cand"], out_r, out_y)
    else:
        block = max(1, int(2_000_000 // (cfg["n_y"] * _N_SUB_BRANCH * ugrid.size)))
        for i in range(0, r1.size, block):
            sl = slice(i, i + block)
            out_r[sl], out_y[sl] = _mic_block_np(r1[sl], r2[sl], r3[sl], s1, s2, ugrid, cfg)
    if s1 == s2:  # r3 = 0 in mode ++ or --: the two legs coincide, every pose is type-II singular
        out_r[r3 == 0.0] = 0.0
    return out_r * L, out_y * L


# =============================================================================
# Disk means and the MCI
# =============================================================================
@_njit
def _iso_residual_nb(r1sq, half_d, r3, s1, s2, x, y, which):
    """Residual of isotropy of M = k1 k2 J: ``(a - d, b + c)`` (a scaled rotation,
    which = 0) or ``(a + d, b - c)`` (a scaled reflection, which = 1), divided by the
    Frobenius norm (scale-free)."""
    a, b, c, d, kk, ok = _mrows_nb(r1sq, half_d, r3, s1, s2, x, y)
    if not ok:
        return np.nan, np.nan
    S = a * a + b * b + c * c + d * d
    n = math.sqrt(S)
    if which == 0:
        return (a - d) / n, (b + c) / n
    return (a + d) / n, (b - c) / n


@_njit
def _compass_nb(r1sq, half_d, r3, s1, s2, cy, R, bx, by, best, step, n_iter, dirs):
    """Compass search (8 directions, step halved on failure, kept in the disk)."""
    for _ in range(n_iter):
        jb = -1
        vb = -1.0
        for j in range(dirs.shape[0]):
            px = bx + step * dirs[j, 0]
            py = by + step * dirs[j, 1]
            if math.hypot(px, py) > R:
                continue
            v = _lci_point_nb(r1sq, half_d, r3, s1, s2, px, cy + py)
            if jb < 0 or v > vb:
                jb = j
                vb = v
        if jb >= 0 and vb > best:
            best = vb
            bx = bx + step * dirs[jb, 0]
            by = by + step * dirs[jb, 1]
        else:
            step *= 0.5
    return bx, by, best


@_njit
def _newton_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, px, py, which, n_iter):
    """Damped Newton on an isotropy residual from ``(px, py)``: a step is halved
    until it stays in the disk and lowers the residual (else the search stops).
    Returns the best LCI visited (-1 if no step was taken)."""
    h = 1e-7 * R
    best = -1.0
    f0, g0 = _iso_residual_nb(r1sq, half_d, r3, s1, s2, px, cy + py, which)
    n0 = f0 * f0 + g0 * g0
    for _ in range(n_iter):
        if not math.isfinite(n0):
            break
        fx, gx = _iso_residual_nb(r1sq, half_d, r3, s1, s2, px + h, cy + py, which)
        fy, gy = _iso_residual_nb(r1sq, half_d, r3, s1, s2, px, cy + py + h, which)
        j11 = (fx - f0) / h
        j12 = (fy - f0) / h
        j21 = (gx - g0) / h
        j22 = (gy - g0) / h
        det = j11 * j22 - j12 * j21
        if not (det != 0.0 and math.isfinite(det)):
            break
        dx = -(j22 * f0 - j12 * g0) / det
        dy = -(-j21 * f0 + j11 * g0) / det
        t = 1.0
        ok = False
        qx = px
        qy = py
        f1 = f0
        g1 = g0
        n1 = n0
        for _ in range(8):
            qx = px + t * dx
            qy = py + t * dy
            if math.hypot(qx, qy) <= R:
                f1, g1 = _iso_residual_nb(r1sq, half_d, r3, s1, s2, qx, cy + qy, which)
                n1 = f1 * f1 + g1 * g1
                if n1 < n0:
                    ok = True
                    break
            t *= 0.5
        if not ok:
            break
        px = qx
        py = qy
        f0 = f1
        g0 = g1
        n0 = n1
        v = _lci_point_nb(r1sq, half_d, r3, s1, s2, px, cy + py)
        if v > best:
            best = v
    return best


@_njit
def _rim_nb(r1sq, half_d, r3, s1, s2, cy, R, n_rim):
    """Best LCI on the rim: best of ``n_rim`` samples, then golden section in the angle."""
    kb = 0
    vk = -1.0
    for k in range(n_rim):
        ph = 2.0 * math.pi * k / n_rim
        v = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * math.cos(ph), cy + R * math.sin(ph))
        if v > vk:
            vk = v
            kb = k
    dph = 2.0 * math.pi / n_rim
    a = dph * (kb - 1)
    c = dph * (kb + 1)
    x1 = c - _GOLD * (c - a)
    x2 = a + _GOLD * (c - a)
    f1 = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * math.cos(x1), cy + R * math.sin(x1))
    f2 = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * math.cos(x2), cy + R * math.sin(x2))
    for _ in range(40):
        if f1 >= f2:
            c = x2
            x2 = x1
            f2 = f1
            x1 = c - _GOLD * (c - a)
            f1 = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * math.cos(x1), cy + R * math.sin(x1))
        else:
            a = x1
            x1 = x2
            f1 = f2
            x2 = a + _GOLD * (c - a)
            f2 = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * math.cos(x2), cy + R * math.sin(x2))
    return max(vk, f1, f2)


@_njit
def _mci_nb(r1sq, half_d, r3, s1, s2, cy, R, ux, uy, lv, step0, n_iter, dirs, n_rim, n_start,
            starts):
    """Maximum LCI over the disk of radius R about (0, cy), given the LCI ``lv`` at
    the unit nodes ``(ux, uy)``:

    * from each of ``n_start`` nodes (the best one, then the best one farther
      than R/3 from the nodes already used) a compass search
      (:func:`mechopt.performance.max_lci`), then damped Newton iterations on
      both isotropy conditions (LCI = 1 exactly where J is a scaled rotation or
      reflection: a cone apex that direct search approaches only slowly);
    * a golden-section search along the rim.
    """
    best = -1.0
    m = 0
    for _ in range(n_start):
        kb = -1
        vb = -np.inf
        for k in range(ux.size):
            far = True
            for q in range(m):
                ex = ux[k] - ux[starts[q]]
                ey = uy[k] - uy[starts[q]]
                far = far and (ex * ex + ey * ey > 1.0 / 9.0)
            if far and lv[k] > vb:
                kb = k
                vb = lv[k]
        if kb < 0:
            break
        starts[m] = kb
        m += 1
        bx, by, b = _compass_nb(r1sq, half_d, r3, s1, s2, cy, R, R * ux[kb], R * uy[kb], lv[kb],
                                R * step0, n_iter, dirs)
        best = max(best, b)
        for which in range(2):
            best = max(best, _newton_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, bx, by, which, 12))
    return max(best, _rim_nb(r1sq, half_d, r3, s1, s2, cy, R, n_rim))


@_njit
def _disk_stats_one_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, dirs, n_rim, lv,
                       starts, out):
    """Mean LCI over the MIC disk, its maximum (best node, then
    :func:`_mci_nb`), and the means of the velocity, payload and
    stiffness extremes over the concentric half-radius disk."""
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    nan = np.nan
    if not (R > 0.0 and math.isfinite(R)):
        for q in range(out.size):
            out[q] = nan
        return
    acc = 0.0
    for k in range(ux.size):
        v = _lci_point_nb(r1sq, half_d, r3, s1, s2, R * ux[k], cy + R * uy[k])
        lv[k] = v
        acc += w[k] * v
    out[0] = acc
    out[1] = _mci_nb(r1sq, half_d, r3, s1, s2, cy, R, ux, uy, lv, step0, n_iter, dirs, n_rim,
                     starts.size, starts)
    h = 0.5 * R
    a_vmax = 0.0
    a_vmin = 0.0
    a_tmax = 0.0
    a_tmin = 0.0
    a_dmax = 0.0
    a_dmin = 0.0
    n_bad = 0
    for k in range(ux.size):
        a, b, c, d, kk, ok = _mrows_nb(r1sq, half_d, r3, s1, s2, h * ux[k], cy + h * uy[k])
        S = a * a + b * b + c * c + d * d
        disc = math.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
        sm = math.sqrt(0.5 * (S + disc))
        ak = abs(kk)
        s_max = sm / ak
        s_min = abs(a * d - b * c) / (sm * ak)
        wk = w[k]
        a_vmax += wk / s_min
        a_vmin += wk / s_max
        a_tmax += wk * s_max
        a_tmin += wk * s_min
        a_dmax += wk / (s_min * s_min)
        a_dmin += wk / (s_max * s_max)
        n_bad += 0 if ok else 1
    out[2] = a_vmax
    out[3] = a_vmin
    out[4] = a_tmax
    out[5] = a_tmin
    out[6] = a_dmax
    out[7] = a_dmin
    if n_bad > 0:
        for q in range(2, 8):
            out[q] = nan


@_njit
def _disk_stats_batch_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, dirs, n_rim,
                         n_start, out):
    lv = np.empty(ux.size)
    starts = np.empty(n_start, np.int64)
    for i in range(r1.size):
        _disk_stats_one_nb(r1[i], r2[i], r3[i], s1, s2, cy[i], R[i], ux, uy, w, step0, n_iter,
                           dirs, n_rim, lv, starts, out[i])


def _lci_at_np(rr, s1, s2, x, y):
    a, b, c, d, _, ok = _mrows_np(*rr, s1, s2, x, y)
    return _lci_m_np(a, b, c, d, ok)


def _iso_residual_np(rr, s1, s2, x, y, which):
    a, b, c, d, _, ok = _mrows_np(*rr, s1, s2, x, y)
    n = np.where(ok, np.sqrt(a * a + b * b + c * c + d * d), np.nan)
    if which == 0:
        return (a - d) / n, (b + c) / n
    return (a + d) / n, (b - c) / n


def _golden_rim_np(rr, s1, s2, cy, R, a, c, n):
    f = lambda ph: _lci_at_np(rr, s1, s2, (R * np.cos(ph))[:, None], (cy + R * np.sin(ph))[:, None])[:, 0]  # noqa: E731
    x1 = c - _GOLD * (c - a)
    x2 = a + _GOLD * (c - a)
    f1, f2 = f(x1), f(x2)
    for _ in range(n):
        left = f1 >= f2
        c = np.where(left, x2, c)
        a = np.where(left, a, x1)
        nx1 = np.where(left, c - _GOLD * (c - a), x2)
        nx2 = np.where(left, x1, a + _GOLD * (c - a))
        fn = f(np.where(left, nx1, nx2))
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
        x1, x2 = nx1, nx2
    return np.maximum(f1, f2)


def _compass_np(rr, s1, s2, cy, R, bx, by, best, step, n_iter):
    c1 = lambda v: v[:, None]  # noqa: E731
    rows = np.arange(R.size)
    for _ in range(n_iter):
        px = c1(bx) + c1(step) * _DIRS[None, :, 0]
        py = c1(by) + c1(step) * _DIRS[None, :, 1]
        inside = ~(np.hypot(px, py) > c1(R))
        v = np.where(inside, _lci_at_np(rr, s1, s2, px, c1(cy) + py), -np.inf)
        jb = np.argmax(v, axis=1)
        vb = v[rows, jb]
        up = inside.any(axis=1) & (vb > best)
        best = np.where(up, vb, best)
        bx = np.where(up, bx + step * _DIRS[jb, 0], bx)
        by = np.where(up, by + step * _DIRS[jb, 1], by)
        step = np.where(up, step, 0.5 * step)
    return bx, by, best


def _newton_iso_np(rr, s1, s2, cy, R, px, py, which, n_iter):
    c1 = lambda v: v[:, None]  # noqa: E731
    res = lambda x, y: tuple(v[:, 0] for v in _iso_residual_np(rr, s1, s2, c1(x), c1(cy + y), which))  # noqa: E731
    h = 1e-7 * R
    best = np.full(R.size, -1.0)
    f0, g0 = res(px, py)
    n0 = f0 * f0 + g0 * g0
    live = np.ones(R.size, bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        for _ in range(n_iter):
            live &= np.isfinite(n0)
            if not live.any():
                break
            fx, gx = res(px + h, py)
            fy, gy = res(px, py + h)
            j11, j12 = (fx - f0) / h, (fy - f0) / h
            j21, j22 = (gx - g0) / h, (gy - g0) / h
            det = j11 * j22 - j12 * j21
            live &= (det != 0.0) & np.isfinite(det)
            dx = -(j22 * f0 - j12 * g0) / det
            dy = -(-j21 * f0 + j11 * g0) / det
            t = np.ones(R.size)
            ok = np.zeros(R.size, bool)
            qx, qy, f1, g1, n1 = px.copy(), py.copy(), f0.copy(), g0.copy(), n0.copy()
            for _ in range(8):
                if not (live & ~ok).any():
                    break
                tx = px + t * dx
                ty = py + t * dy
                inside = np.hypot(tx, ty) <= R
                ff, gg = res(tx, ty)
                nn = ff * ff + gg * gg
                acc = live & ~ok & inside & (nn < n0)
                qx, qy = np.where(acc, tx, qx), np.where(acc, ty, qy)
                f1, g1, n1 = np.where(acc, ff, f1), np.where(acc, gg, g1), np.where(acc, nn, n1)
                ok |= acc
                t = np.where(ok, t, 0.5 * t)
            live &= ok
            px, py = np.where(live, qx, px), np.where(live, qy, py)
            f0, g0, n0 = np.where(live, f1, f0), np.where(live, g1, g0), np.where(live, n1, n0)
            v = _lci_at_np(rr, s1, s2, c1(px), c1(cy + py))[:, 0]
            best = np.where(live & (v > best), v, best)
    return best


def _mci_starts_np(ux, uy, lv, n_start):
    """Starting nodes of :func:`_mci_nb`: ``(k, have)`` arrays of shape (B, n_start)."""
    c1 = lambda v: v[:, None]  # noqa: E731
    far = np.ones(lv.shape, bool)
    ks, haves = [], []
    for _ in range(n_start):
        haves.append(far.any(axis=1))
        kb = np.argmax(np.where(far, lv, -np.inf), axis=1)
        ks.append(kb)
        far &= (ux[None, :] - c1(ux[kb])) ** 2 + (uy[None, :] - c1(uy[kb])) ** 2 > 1.0 / 9.0
    return np.stack(ks, 1), np.stack(haves, 1)


def _mci_search_np(rr, s1, s2, cy, R, ux, uy, ks, haves, lvs, step0, n_iter, n_rim):
    """Vectorised :func:`_mci_nb` from the starts of :func:`_mci_starts_np` (``lvs``:
    LCI at those nodes); rr: (B, 1) columns, the rest (B,) or (B, n_start)."""
    c1 = lambda v: v[:, None]  # noqa: E731
    B = R.size
    rows = np.arange(B)
    best = np.full(B, -1.0)
    for j in range(ks.shape[1]):
        kb, have = ks[:, j], haves[:, j]
        bx, by, b = _compass_np(rr, s1, s2, cy, R, R * ux[kb], R * uy[kb], lvs[:, j],
                                R * step0, n_iter)
        cand = b
        for which in (0, 1):
            cand = np.maximum(cand, _newton_iso_np(rr, s1, s2, cy, R, bx, by, which, 12))
        best = np.where(have, np.maximum(best, cand), best)
    ph = 2.0 * np.pi * np.arange(n_rim) / n_rim
    v = _lci_at_np(rr, s1, s2, c1(R) * np.cos(ph), c1(cy) + c1(R) * np.sin(ph))
    kr = np.argmax(v, axis=1)
    dph = 2.0 * np.pi / n_rim
    fr = _golden_rim_np(rr, s1, s2, cy, R, dph * (kr - 1), dph * (kr + 1), 40)
    return np.maximum(best, np.maximum(v[rows, kr], fr))


def _disk_stats_block_np(r1, r2, r3, s1, s2, cy, R, ux, uy, w, n_start):
    """Quadrature part for a block of designs with R > 0: ``(stats (B, 8) with the
    MCI column left NaN, starting nodes, their flags and LCI)``."""
    c1 = lambda v: v[:, None]  # noqa: E731
    rr = (c1(r1), c1(r2), c1(r3))
    lci = _lci_at_np(rr, s1, s2, c1(R) * ux[None, :], c1(cy) + c1(R) * uy[None, :])
    gci = np.sum(w * lci, axis=1)
    ks, haves = _mci_starts_np(ux, uy, lci, n_start)
    lvs = np.take_along_axis(lci, ks, axis=1)
    h = 0.5 * c1(R)
    a, b, c, d, kk, ok = _mrows_np(*rr, s1, s2, h * ux[None, :], c1(cy) + h * uy[None, :])
    ext = _extremes_m_np(a, b, c, d, kk, ok)
    means = [np.sum(w * v, axis=1) for v in ext]
    res = np.stack([gci, np.full(r1.size, np.nan)] + means, -1)
    res[~ok.all(axis=1), 2:] = np.nan
    return res, ks, haves, lvs


def _disk_stats_np(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, n_rim, n_start):
    out = np.full((r1.size, 8), np.nan)
    live = (R > 0.0) & np.isfinite(R)
    if not live.any():
        return out
    r1, r2, r3, cy, R = (v[live] for v in (r1, r2, r3, cy, R))
    n = r1.size
    res = np.empty((n, 8))
    ks = np.empty((n, n_start), np.int64)
    haves = np.empty((n, n_start), bool)
    lvs = np.empty((n, n_start))
    block = max(1, 400_000 // ux.size)
    for i in range(0, n, block):
        sl = slice(i, i + block)
        res[sl], ks[sl], haves[sl], lvs[sl] = _disk_stats_block_np(
            r1[sl], r2[sl], r3[sl], s1, s2, cy[sl], R[sl], ux, uy, w, n_start)
    # the searches of the MCI touch a few points per design: vectorise over all
    rr = (r1[:, None], r2[:, None], r3[:, None])
    res[:, 1] = _mci_search_np(rr, s1, s2, cy, R, ux, uy, ks, haves, lvs, step0, n_iter, n_rim)
    out[live] = res
    return out


def disk_stats_batch(r1, r2, r3, center_y, radius, mode="+-", quadrature="area", n_r=None,
                     n_theta=None, compiled=None):
    """``(n, 8)`` array of :data:`DISK_STAT_NAMES` for designs with a known MIC.

    GCI is the mean LCI over the MIC disk and MCI its maximum (best quadrature
    node, then the compass search of :func:`mechopt.performance.max_lci`); the
    velocity, payload and stiffness means are over the concentric disk of half
    radius (Liu 2006 eq. 4, 11, 14, 19). The rule is
    :func:`mechopt.quadrature.disk_rule` (``area`` or ``polar``). NaN rows for a
    radius <= 0 (no singularity-free disk).
    """
    from mechopt.quadrature import DEFAULT_N_R, DEFAULT_N_THETA, disk_rule

    s1, s2 = _signs(mode)
    n_r = DEFAULT_N_R if n_r is None else int(n_r)
    n_theta = DEFAULT_N_THETA if n_theta is None else int(n_theta)
    ux, uy, w = (np.ascontiguousarray(v) for v in disk_rule(1.0, quadrature, n_r=n_r, n_theta=n_theta))
    r1, r2, r3, cy, R = (np.ascontiguousarray(v, dtype=float).ravel()
                         for v in np.broadcast_arrays(r1, r2, r3, center_y, radius))
    # work on the normalised design (length scale 1), rescale the extremes
    L = (r1 + r2 + r3) / 3.0
    r1, r2, r3, cy, R = r1 / L, r2 / L, r3 / L, cy / L, R / L
    step0 = 1.0 / n_r
    out = np.empty((r1.size, 8))
    if use_numba(compiled):
        _disk_stats_batch_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, _MCI_ITERS, _DIRS,
                             n_theta, _MCI_STARTS, out)
    else:
        out[:] = _disk_stats_np(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, _MCI_ITERS, n_theta,
                                _MCI_STARTS)
    out[:, 2:4] *= L[:, None]
    out[:, 4:6] /= L[:, None]
    out[:, 6:8] *= (L * L)[:, None]
    return out
