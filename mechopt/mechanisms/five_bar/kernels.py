"""Batch kernels for the symmetric five-bar: local indices, disk means and a fast MIC.

They carry the performance atlas (:mod:`mechopt.run.atlas`, Liu 2006 Fig. 2-8): tens
of thousands of designs, each needing its MIC and about 10^4 local evaluations.

Every kernel has two paths, with the same formulas in the same order:

* a pure-NumPy path (always available), vectorised over points and designs;
* a compiled path (numba, the optional ``fast`` extra), one loop per design and
  per point, used when numba is available (:mod:`mechopt.core.jit`;
  ``MECHOPT_NO_NUMBA=1`` forces NumPy).

A formula is written once, as a plain Python function marked
:func:`~mechopt.core.jit.jitable` (``_mrows``, ``_lci_m``, ``_sv_m``, ``_iso_r``,
``_tr_step``, ...): the compiled loops call it on scalars, the NumPy path on arrays
(under ``np.errstate``). What stays twice is the control flow around the formulas:
the compiled loops stop each search where it ends, the NumPy path carries masks of
the searches still running.

``tests/test_atlas.py`` checks that both paths agree (local indices to 1e-12,
MIC and disk means to rounding) and that the fast MIC and disk means agree with
the reference :func:`mechopt.analysis.workspace.mic` + :func:`mechopt.analysis.performance.global_indices`.

Geometry and conventions are those of :mod:`mechopt.mechanisms.five_bar.model`
(Le 2013 eq. 13-19): ``A1 = (-r3, 0)``, ``A2 = (r3, 0)``, crank ``r1``, distal link ``r2``,
working-mode signs ``s1, s2`` (``+1`` for ``"+"``); elbows by circle intersection
(no trigonometry); ``J = B^-1 A`` with ``theta_dot = J p_dot``. The kernels work
on the design divided by its length scale ``(r1 + r2 + r3)/3`` and rescale.

Fast MIC (:func:`mic_batch`)
----------------------------
The algorithm and its formulas are those of :mod:`mechopt.mechanisms.five_bar.mic`
(closed-form serial clearance, explicit type-II locus, Le eq. 19): its compiled
kernel here, and a NumPy path vectorised over blocks of designs. Against
:func:`mechopt.analysis.workspace.mic` (root finding, ~1e-7) the radius agrees to a few
1e-6 (relative) for mode ``"+-"``; where they differ by more, the reference
missed a better centre or a small type-II lobe (see ``tests/test_atlas.py``).

Disk means and the MCI (:func:`disk_stats_batch`)
-------------------------------------------------
GCI is the mean LCI over the MIC disk, GVI/GPI/GSI the means of the extremes
over the concentric half-radius disk (Liu 2006 eq. 4, 11, 14, 19), with the
nodes and weights of :func:`mechopt.core.quadrature.disk_rule`. The MCI
(:func:`_mci_nb`) works on the isotropy residual ``r = (G11 - G22, 2 G12) / tr G``
of ``G = J^T J`` (``r = 0`` exactly where ``LCI = 1``; ``|r|^2`` is smooth where
LCI has a cone apex), as :func:`mechopt.analysis.performance.max_lci`:

1. isotropic points. For the mirror-symmetric modes (``"+-"``, ``"-+"``) ``r_2 =
   0`` exactly on the y axis, so an isotropic point there is a sign change of
   ``r_1`` along the diameter: 64 samples, then the Illinois method. Isotropic
   points need not lie on the axis (off it they come in mirror pairs, e.g. inside
   the MIC of (0.9085, 1.5937, 0.4978)), so otherwise, and for every mode, plain
   Newton on ``r = 0`` from a 16 x 32 polar grid of starts (its half ``x > 0`` for
   the symmetric modes, whose iteration commutes with the mirror), no descent
   test, the worse half dropped every 4 iterations: it crosses the long curved
   valleys of near-isotropy of the designs with nearly coincident base joints,
   where a damped Newton stalls. The first isotropic point (``|r|^2 < 1e-26``)
   ends the search.
2. otherwise interior maxima: from the best quadrature node and two more
   (mutually farther apart than R/3) a compass search, then the trust-region
   Newton of ``max_lci`` on ``|r|^2`` and damped Newton on the isotropy
   conditions;
3. the rim: golden section in the angle around the best of ``n_theta`` samples.

On 1500 random designs of Liu's space it equals ``global_indices(...)["mci"]``
to 1e-6 on both paths (``tests/test_mci.py``); the two paths agree to rounding.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core.indices import GLOBAL_INDEX_NAMES, lci_of_entries, two_smax_squared
from mechopt.core.jit import HAVE_NUMBA, jitable, njit, select, use_numba
from mechopt.core.validation import ROUNDING, STEP_FLOOR
from mechopt.mechanisms.five_bar import mic as _mic
from mechopt.mechanisms.five_bar.model import MODES

__all__ = [
    "HAVE_NUMBA",
    "use_numba",
    "MIC_SIZES",
    "lci_points",
    "local_points",
    "mic_batch",
    "disk_stats_batch",
    "DISK_STAT_NAMES",
    "compile_all",
    "KERNEL_GROUPS",
]

#: reachability tolerance on ``h^2`` (same as FiveBar.elbows)
_REACH_TOL = ROUNDING
#: sizes of the fast MIC (:data:`mechopt.mechanisms.five_bar.mic.MIC_SIZES`)
MIC_SIZES = _mic.MIC_SIZES
#: iterations of the compass search and of the trust-region polish of the MCI
_MCI_ITERS = 40
#: starting nodes of the MCI search (mutually farther apart than R/3)
_MCI_STARTS = 3
_DIRS = np.array([[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0],
                  [1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]])
#: the ratio of the golden-section searches (:data:`mechopt.core.numerics.INV_PHI`)
_GOLD = _mic._GOLD
#: isotropy search of the MCI (as mechopt.analysis.performance.max_lci): ``g = |r|^2`` below
#: which a point counts as isotropic, most Newton iterations, the polar grid of
#: its starts (a quarter of max_lci's 64 x 128 grid in each direction)
_G_ISO = 1e-26
_ISO_ITERS = 16
_ISO_N_R = 16
_ISO_N_THETA = 32
#: intervals of the sign-change scan of the isotropy residual along the y axis
#: (mirror-symmetric modes), most iterations of its bracketed root search
_AXIS_N = 64
_AXIS_ITERS = 100

#: columns of :func:`disk_stats_batch`
DISK_STAT_NAMES = GLOBAL_INDEX_NAMES


# =============================================================================
# Local kinematics
# =============================================================================
# For leg i with base joint A_i = (-+r3, 0) and v = P - A_i = (dx, y), q = |v|^2:
#   B_i - A_i = c v + h w,  w = (-y, dx),  c = (r1^2 - r2^2)/(2 q) + 1/2,
#   h = s_i sqrt(r1^2/q - c^2)            (FiveBar.elbows, Le eq. 13-14)
#   a_i = P - B_i,  k_i = (B_i - A_i) x a_i = r1 (u_i x a_i)
# and J = [a_1 / k_1; a_2 / k_2]. The kernels work on M = k_1 k_2 J = [k_2 a_1; k_1 a_2]
# (no division per entry): LCI(J) = LCI(M), s(J) = s(M) / |k_1 k_2|.
@jitable
def _leg(r1sq, half_d, ax, s, x, y):
    """``(a_x, a_y, k, reachable)`` of the leg with base joint ``(ax, 0)`` and elbow sign
    ``s`` (``half_d = (r1^2 - r2^2)/2``)."""
    dx = x - ax
    dsq = dx * dx + y * y
    inv = 1.0 / dsq
    c = half_d * inv + 0.5
    h2 = r1sq * inv - c * c
    h = np.sqrt(np.maximum(h2, 0.0)) * s
    bx = c * dx - h * y
    by = c * y + h * dx
    a_x = dx - bx
    a_y = y - by
    return a_x, a_y, bx * a_y - by * a_x, (h2 >= -_REACH_TOL) & (dsq > 0.0)


@jitable
def _mrows(r1sq, half_d, r3, s1, s2, x, y):
    """``(m11, m12, m21, m22, k1 k2, reachable)`` at ``(x, y)``; scalars or arrays."""
    a1x, a1y, k1, ok1 = _leg(r1sq, half_d, -r3, s1, x, y)
    a2x, a2y, k2, ok2 = _leg(r1sq, half_d, r3, s2, x, y)
    return a1x * k2, a1y * k2, a2x * k1, a2y * k1, k1 * k2, ok1 & ok2


@jitable
def _lci_m(a, b, c, d, ok):
    """LCI of ``M`` (:func:`mechopt.core.indices.lci_of_entries`); 0 where not ``ok``, for
    ``M = 0`` and where the entries overflowed (NaN fails ``v >= 0``)."""
    v = lci_of_entries(a, b, c, d)
    return select(ok & (v >= 0.0), v, 0.0)


@jitable
def _sv_m(a, b, c, d, kk):
    """``(s_max, s_min)`` of J from ``M = kk J``."""
    sm = np.sqrt(0.5 * two_smax_squared(a, b, c, d))
    ak = abs(kk)
    return sm / ak, abs(a * d - b * c) / (sm * ak)


@jitable
def _extremes(s_max, s_min):
    """``(v_max, v_min, tau_max, tau_min, d_max, d_min)`` of J from its singular values
    (Liu 2006 eq. 10, 13, 18)."""
    return 1.0 / s_min, 1.0 / s_max, s_max, s_min, 1.0 / (s_min * s_min), 1.0 / (s_max * s_max)


@jitable
def _lci_point(r1sq, half_d, r3, s1, s2, x, y):
    a, b, c, d, kk, ok = _mrows(r1sq, half_d, r3, s1, s2, x, y)
    return _lci_m(a, b, c, d, ok)


def _on_arrays(formula, r1, r2, r3, *args):
    """``formula(r1^2, (r1^2 - r2^2)/2, r3, *args)`` on arrays, NumPy's warnings off
    (unreachable points and ``P`` on a base joint give inf or NaN, then masked)."""
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return formula(r1sq, half_d, r3, *args)


def _mrows_np(r1, r2, r3, s1, s2, x, y):
    """``(m11, m12, m21, m22, k1 k2, reachable)`` at the points (NumPy, broadcasting)."""
    return _on_arrays(_mrows, r1, r2, r3, s1, s2, x, y)


def _lci_m_np(a, b, c, d, ok):
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return _lci_m(a, b, c, d, ok)


def _extremes_m_np(a, b, c, d, kk, ok):
    """``(v_max, v_min, tau_max, tau_min, d_max, d_min)`` of J from M = kk J; NaN where
    unreachable."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        out = _extremes(*_sv_m(a, b, c, d, kk))
    return tuple(np.where(ok, v, np.nan) for v in out)


@njit
def _lci_points_nb(r1, r2, r3, s1, s2, x, y, out):
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    for i in range(x.size):
        out[i] = _lci_point(r1sq, half_d, r3, s1, s2, x[i], y[i])


@njit
def _local_points_nb(r1, r2, r3, s1, s2, x, y, out):
    r1sq = r1 * r1
    half_d = 0.5 * (r1sq - r2 * r2)
    nan = np.nan
    for i in range(x.size):
        a, b, c, d, kk, ok = _mrows(r1sq, half_d, r3, s1, s2, x[i], y[i])
        out[0, i] = _lci_m(a, b, c, d, ok)
        s_max, s_min = _sv_m(a, b, c, d, kk)
        ext = _extremes(s_max, s_min)
        for q in range(6):
            out[q + 1, i] = ext[q] if ok else nan


def _signs(mode):
    if mode not in MODES:
        raise ValueError(f"mode must be one of {', '.join(map(repr, MODES))}, got {mode!r}")
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

    Parameters
    ----------
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    x, y : array_like
        Points [L].
    mode : str
        Working mode.
    compiled : bool, optional
        Use the numba kernels (None: when installed).

    Returns
    -------
    ndarray
        The LCI at each point (flattened).
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
    (:data:`mechopt.core.indices.LOCAL_INDEX_NAMES`, Liu 2006 eq. 3, 10, 13, 18) at the
    points; the extremes are NaN where a point is unreachable.

    Parameters
    ----------
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    x, y : array_like
        Points [L].
    mode : str
        Working mode.
    compiled : bool, optional
        Use the numba kernels (None: when installed).

    Returns
    -------
    ndarray
        Shape ``(7, n)``.
    """
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
# Type-II locus of the working mode: the MIC (formulas in mechopt.mechanisms.five_bar.mic)
# =============================================================================
_N_SUB_BRANCH = _mic._N_SUB_BRANCH
#: the compiled kernel of :func:`mic_batch` (:func:`mechopt.mechanisms.five_bar.mic._mic_batch_loop`)
_mic_batch_nb = _mic._compiled_batch()
#: compiled for direct calls (tests): sorting the locus cloud and the distance to it
_sort_cloud_nb = njit(_mic._sort_cloud)
_radius_nb = njit(_mic._radius)
_radius_sorted_nb = njit(_mic._radius_sorted)


# --- the NumPy path, vectorised over a block of designs ----------------------
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


def _locus_np(rr, s1, s2, leg, sigma, ta, tb, half, u):
    """:func:`mechopt.mechanisms.five_bar.mic._coupler_point` at ``u`` of sub-branches
    (arrays, broadcasting), with NumPy's trigonometry."""
    th = _mic._theta_of_u(ta, tb, half, np.cos(np.pi * u))
    with np.errstate(divide="ignore", invalid="ignore"):  # L2 = 0: not valid
        return _mic._coupler_point(*rr, s1, s2, leg, sigma, np.cos(th), np.sin(th))


def _axis_points_np(r1, r2, r3, s1, s2):
    """:func:`mechopt.mechanisms.five_bar.mic._axis_points` of every design: ``(B, 4)``, NaN
    where none."""
    ay = np.empty((r1.size, 4))
    for i in range(r1.size):
        _mic._axis_points(r1[i], r2[i], r3[i], s1, s2, ay[i])
    return ay


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
    qx, qy, ok = _locus_np(rr, s1, s2, leg_b[None, :, None], sigma_b[None, :, None], ta[..., None],
                           tb[..., None], half_b[None, :, None], ugrid[None, None, :])
    ok &= (ta <= tb)[..., None]
    qx = np.where(ok, qx, np.inf).reshape(B, -1)
    qy = np.where(ok, qy, 0.0).reshape(B, -1)
    ay = _axis_points_np(r1, r2, r3, s1, s2)
    ys = c1(ylo) + c1(yhi - ylo) * (np.arange(n_y) / (n_y - 1))[None, :]
    qxa, qya = _mic._with_axis_points(qx, qy, ay)
    rs = _mic._cloud_radius(c1(r1), c1(r2), c1(r3), qxa[:, None, :], qya[:, None, :], ys)
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
        px, py, okd = _locus_np(tuple(v[..., None] for v in rr), s1, s2, leg_b[None, None, :, None],
                                sigma_b[None, None, :, None], ta[:, None, :, None], tb[:, None, :, None],
                                half_b[None, None, :, None], u)
        okd &= (u >= 0.0) & (u <= 1.0) & seen[..., None]
        dqx = np.where(okd, px, np.inf).reshape(B, -1)
        dqy = np.where(okd, py, 0.0).reshape(B, -1)
        dqx, dqy = _mic._with_axis_points(dqx, dqy, ay)
        rad = lambda y: _mic._cloud_radius(r1, r2, r3, dqx, dqy, y)  # noqa: E731
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
    """Fast MIC of many designs: ``(radius, center_y)`` arrays (see the module docstring).

    Parameters
    ----------
    r1, r2, r3 : array_like
        Crank, distal link and half base [L] of each design.
    mode : str
        Working mode.
    compiled : bool, optional
        Use the numba kernels (None: when installed).
    **sizes : 
        Sizes of the search (:data:`mechopt.mechanisms.five_bar.mic.MIC_SIZES`).

    Returns
    -------
    radius, center_y : ndarray
        [L], per design.
    """
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
@jitable
def _iso_r(r1sq, half_d, r3, s1, s2, x, y):
    """Isotropy residual ``r = (G11 - G22, 2 G12) / tr G`` of ``G = M^T M`` (that of
    ``J^T J``: r is scale-free), as :func:`mechopt.analysis.performance._iso_residual`:
    ``r = 0`` exactly where LCI = 1, ``g = |r|^2`` smooth and decreasing in LCI.
    NaN where unreachable or M = 0."""
    a, b, c, d, kk, ok = _mrows(r1sq, half_d, r3, s1, s2, x, y)
    g11 = a * a + c * c
    g22 = b * b + d * d
    t = g11 + g22
    t = select(ok & (t > 0.0), t, np.nan)
    return (g11 - g22) / t, 2.0 * (a * b + c * d) / t


@jitable
def _iso_residual(r1sq, half_d, r3, s1, s2, x, y, which):
    """Residual of isotropy of M = k1 k2 J: ``(a - d, b + c)`` (a scaled rotation,
    which = 0) or ``(a + d, b - c)`` (a scaled reflection, which = 1), divided by the
    Frobenius norm (scale-free); NaN where unreachable."""
    a, b, c, d, kk, ok = _mrows(r1sq, half_d, r3, s1, s2, x, y)
    n = select(ok, np.sqrt(a * a + b * b + c * c + d * d), np.nan)
    if which == 0:
        return (a - d) / n, (b + c) / n
    return (a + d) / n, (b - c) / n


@jitable
def _fd_step(f0, g0, fx, gx, fy, gy, h):
    """Newton step on ``(f, g) = 0`` from forward differences (steps ``h`` in x and y):
    ``(det, dx, dy)``."""
    j11 = (fx - f0) / h
    j12 = (fy - f0) / h
    j21 = (gx - g0) / h
    j22 = (gy - g0) / h
    det = j11 * j22 - j12 * j21
    return det, -(j22 * f0 - j12 * g0) / det, -(-j21 * f0 + j11 * g0) / det


@jitable
def _cd_step(f0, q0, f1, q1, f2, q2, f3, q3, f4, q4, h):
    """Newton step on ``(f, q) = 0`` from central differences (``1, 2``: ``x +- h``;
    ``3, 4``: ``y +- h``): ``(dx, dy)``."""
    j11 = (f1 - f2) / (2.0 * h)
    j12 = (f3 - f4) / (2.0 * h)
    j21 = (q1 - q2) / (2.0 * h)
    j22 = (q3 - q4) / (2.0 * h)
    det = j11 * j22 - j12 * j21
    return -(j22 * f0 - j12 * q0) / det, -(j11 * q0 - j21 * f0) / det


@jitable
def _g_model(a1, a2, u1, u2, v1, v2, w1, w2, z1, z2, c1, c2, h, h2):
    """Gradient and Hessian of ``g = |r|^2`` from the residual ``r = (a1, a2)`` at a point
    and at its 6-point stencil (``u``: x + h, ``v``: x - h, ``w``: y + h, ``z``: y - h,
    ``c``: both + h; ``h2 = h^2``): ``(gx, gy, hxx, hxy, hyy)``."""
    r1x = (u1 - v1) / (2.0 * h)
    r1y = (w1 - z1) / (2.0 * h)
    r2x = (u2 - v2) / (2.0 * h)
    r2y = (w2 - z2) / (2.0 * h)
    r1xx = (u1 - 2.0 * a1 + v1) / h2
    r2xx = (u2 - 2.0 * a2 + v2) / h2
    r1yy = (w1 - 2.0 * a1 + z1) / h2
    r2yy = (w2 - 2.0 * a2 + z2) / h2
    r1xy = (c1 - u1 - w1 + a1) / h2
    r2xy = (c2 - u2 - w2 + a2) / h2
    gx = 2.0 * (r1x * a1 + r2x * a2)
    gy = 2.0 * (r1y * a1 + r2y * a2)
    hxx = 2.0 * (r1x * r1x + r2x * r2x + a1 * r1xx + a2 * r2xx)
    hyy = 2.0 * (r1y * r1y + r2y * r2y + a1 * r1yy + a2 * r2yy)
    hxy = 2.0 * (r1x * r1y + r2x * r2y + a1 * r1xy + a2 * r2xy)
    return gx, gy, hxx, hxy, hyy


@jitable
def _tr_step(gx, gy, hxx, hxy, hyy, delta):
    """Minimiser of the model ``grad.d + d.H.d/2`` over ``|d| <= delta`` (the exact
    2x2 trust-region subproblem of :func:`mechopt.analysis.performance._trust_region_step`):
    ``(dx, dy, predicted decrease)``; scalars or arrays."""
    disc = np.hypot(0.5 * (hxx - hyy), hxy)
    l1 = 0.5 * (hxx + hyy) - disc  # smaller eigenvalue
    l2 = 0.5 * (hxx + hyy) + disc
    big = hxx >= hyy  # eigenvector e of l2 from the better-conditioned row
    ax = select(big, l2 - hyy, hxy)
    ay = select(big, hxy, l2 - hxx)
    n = np.hypot(ax, ay)
    ex = select(n > 0.0, ax / n, 1.0)
    ey = select(n > 0.0, ay / n, 0.0)
    ge = gx * ex + gy * ey  # gradient in the eigenbasis (e, f = e turned by +90 deg)
    gf = gy * ex - gx * ey
    newton = (l1 > 0.0) & (np.hypot(ge / l2, gf / l1) <= delta)
    mu_lo = select(-l1 > 0.0, -l1, 0.0)
    mu = mu_lo + ROUNDING * (abs(l1) + abs(l2)) + 1e-300
    for _ in range(12):  # More-Sorensen: Newton on 1/|d(mu)| - 1/delta
        de = -ge / (l2 + mu)
        df = -gf / (l1 + mu)
        nrm = np.hypot(de, df)
        q = de * de / (l2 + mu) + df * df / (l1 + mu)
        new = mu + (nrm * nrm / q) * (nrm - delta) / delta
        lo = mu_lo + 0.5 * (mu - mu_lo)  # stays right of the pole
        mu = select(new > lo, new, lo)
    mu = select(newton, 0.0, mu)
    de = -ge / (l2 + mu)
    df = -gf / (l1 + mu)
    nrm = np.hypot(de, df)
    short = select(newton, False, nrm < delta)  # hard case: reach the boundary along f
    d2 = delta * delta - nrm * nrm
    tau = np.sqrt(select(d2 > 0.0, d2, 0.0))
    df = select(short, select(gf > 0.0, df - tau, df + tau), df)
    nrm = select(short, np.hypot(de, df), nrm)
    sc = select(nrm > delta, delta / nrm, 1.0)
    de = select(nrm > delta, de * sc, de)
    df = select(nrm > delta, df * sc, df)
    pred = -(ge * de + gf * df + 0.5 * (l2 * de * de + l1 * df * df))
    return de * ex - df * ey, de * ey + df * ex, pred


@njit
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
            v = _lci_point(r1sq, half_d, r3, s1, s2, px, cy + py)
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


@njit
def _newton_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, px, py, which, n_iter):
    """Damped Newton on an isotropy residual from ``(px, py)``: a step is halved
    until it stays in the disk and lowers the residual (else the search stops).
    Returns the best LCI visited (-1 if no step was taken)."""
    h = 1e-7 * R
    best = -1.0
    f0, g0 = _iso_residual(r1sq, half_d, r3, s1, s2, px, cy + py, which)
    n0 = f0 * f0 + g0 * g0
    for _ in range(n_iter):
        if not math.isfinite(n0):
            break
        fx, gx = _iso_residual(r1sq, half_d, r3, s1, s2, px + h, cy + py, which)
        fy, gy = _iso_residual(r1sq, half_d, r3, s1, s2, px, cy + py + h, which)
        det, dx, dy = _fd_step(f0, g0, fx, gx, fy, gy, h)
        if not (det != 0.0 and math.isfinite(det)):
            break
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
                f1, g1 = _iso_residual(r1sq, half_d, r3, s1, s2, qx, cy + qy, which)
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
        v = _lci_point(r1sq, half_d, r3, s1, s2, px, cy + py)
        if v > best:
            best = v
    return best


@njit
def _tr_polish_nb(r1sq, half_d, r3, s1, s2, cy, R, px, py, delta, n_iter):
    """Trust-region Newton minimising ``g = |r|^2`` (maximising LCI) from ``(px,
    py)``, as :func:`mechopt.analysis.performance._trust_region`: gradient and Hessian from
    central differences of ``r`` (6-point stencil), trial points projected into
    the disk, a step kept only if it lowers ``g``. Returns the LCI at the end."""
    h = max(1e-5 * R, ROUNDING * (abs(cy) + R))
    h2 = h * h
    for _ in range(n_iter):
        a1, a2 = _iso_r(r1sq, half_d, r3, s1, s2, px, cy + py)
        g0 = a1 * a1 + a2 * a2
        if not (math.isfinite(g0) and g0 > _G_ISO):
            break
        u1, u2 = _iso_r(r1sq, half_d, r3, s1, s2, px + h, cy + py)
        v1, v2 = _iso_r(r1sq, half_d, r3, s1, s2, px - h, cy + py)
        w1, w2 = _iso_r(r1sq, half_d, r3, s1, s2, px, cy + (py + h))
        z1, z2 = _iso_r(r1sq, half_d, r3, s1, s2, px, cy + (py - h))
        c1, c2 = _iso_r(r1sq, half_d, r3, s1, s2, px + h, cy + (py + h))
        gx, gy, hxx, hxy, hyy = _g_model(a1, a2, u1, u2, v1, v2, w1, w2, z1, z2, c1, c2, h, h2)
        dx, dy, pred = _tr_step(gx, gy, hxx, hxy, hyy, delta)
        step = math.hypot(dx, dy)
        tx = px + dx
        ty = py + dy
        rad = math.hypot(tx, ty)
        if rad > R:
            sc = R / rad
            tx = tx * sc
            ty = ty * sc
        q1, q2 = _iso_r(r1sq, half_d, r3, s1, s2, tx, cy + ty)
        gt = q1 * q1 + q2 * q2
        rho = (g0 - gt) / pred
        if gt < g0:
            px = tx
            py = ty
        if rho > 0.25:
            if rho > 0.75 and step > 0.99 * delta:
                delta = 2.0 * delta if 2.0 * delta < R else R
        else:
            delta = 0.25 * step
        # converged: nothing left to gain above rounding, or the region has collapsed
        if not (math.isfinite(delta) and delta > ROUNDING * R) or pred <= STEP_FLOOR * g0:
            break
    return _lci_point(r1sq, half_d, r3, s1, s2, px, cy + py)


@njit
def _rim_nb(r1sq, half_d, r3, s1, s2, cy, R, n_rim):
    """Best LCI on the rim: best of ``n_rim`` samples, then golden section in the angle."""
    kb = 0
    vk = -1.0
    for k in range(n_rim):
        ph = 2.0 * math.pi * k / n_rim
        v = _lci_point(r1sq, half_d, r3, s1, s2, R * math.cos(ph), cy + R * math.sin(ph))
        if v > vk:
            vk = v
            kb = k
    dph = 2.0 * math.pi / n_rim
    a = dph * (kb - 1)
    c = dph * (kb + 1)
    x1 = c - _GOLD * (c - a)
    x2 = a + _GOLD * (c - a)
    f1 = _lci_point(r1sq, half_d, r3, s1, s2, R * math.cos(x1), cy + R * math.sin(x1))
    f2 = _lci_point(r1sq, half_d, r3, s1, s2, R * math.cos(x2), cy + R * math.sin(x2))
    for _ in range(40):
        if f1 >= f2:
            c = x2
            x2 = x1
            f2 = f1
            x1 = c - _GOLD * (c - a)
            f1 = _lci_point(r1sq, half_d, r3, s1, s2, R * math.cos(x1), cy + R * math.sin(x1))
        else:
            a = x1
            x1 = x2
            f1 = f2
            x2 = a + _GOLD * (c - a)
            f2 = _lci_point(r1sq, half_d, r3, s1, s2, R * math.cos(x2), cy + R * math.sin(x2))
    return max(vk, f1, f2)


@njit
def _axis_root_nb(r1sq, half_d, r3, s1, s2, cy, a, fa, b, fb, n_iter):
    """Illinois (modified regula falsi) on ``r_1(0, cy + t)`` bracketed by
    ``a < b``, ``fa fb < 0``, until ``g < _G_ISO``: the LCI there, or -1 (no such
    point: the bracket collapsed, a NaN inside, or ``n_iter`` exhausted)."""
    side = 0
    for _ in range(n_iter):
        t = 0.5 * (a + b) if fb == fa else (a * fb - b * fa) / (fb - fa)
        if not (t > a and t < b):
            t = 0.5 * (a + b)
        if t == a or t == b:
            return -1.0
        f, q = _iso_r(r1sq, half_d, r3, s1, s2, 0.0, cy + t)
        if not math.isfinite(f):
            return -1.0
        if f * f + q * q < _G_ISO:
            return _lci_point(r1sq, half_d, r3, s1, s2, 0.0, cy + t)
        if f * fb > 0.0:
            b = t
            fb = f
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a = t
            fa = f
            if side == 1:
                fb *= 0.5
            side = 1
    return -1.0


@njit
def _axis_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, n_ax, n_iter):
    """Isotropic point on the y axis within the disk, for the mirror-symmetric modes
    (``s1 = -s2``: there ``G12 = 0`` exactly on the axis, so it is a root of ``r_1``
    alone). ``r`` at ``n_ax + 1`` equally spaced points of the diameter; the first
    (from ``cy - R`` up) sample with ``g < _G_ISO`` or sign change of ``r_1``
    whose :func:`_axis_root_nb` succeeds gives the LCI there. -1 if none."""
    ta = -R
    fa, qa = _iso_r(r1sq, half_d, r3, s1, s2, 0.0, cy + ta)
    if fa * fa + qa * qa < _G_ISO:
        return _lci_point(r1sq, half_d, r3, s1, s2, 0.0, cy + ta)
    for k in range(1, n_ax + 1):
        tb = -R + (2.0 * R) * k / n_ax
        fb, qb = _iso_r(r1sq, half_d, r3, s1, s2, 0.0, cy + tb)
        if fa * fb < 0.0:
            v = _axis_root_nb(r1sq, half_d, r3, s1, s2, cy, ta, fa, tb, fb, n_iter)
            if v >= 0.0:
                return v
        if fb * fb + qb * qb < _G_ISO:
            return _lci_point(r1sq, half_d, r3, s1, s2, 0.0, cy + tb)
        ta = tb
        fa = fb
    return -1.0


@njit
def _iso_newton_nb(r1sq, half_d, r3, s1, s2, cy, R, sx, sy, n_iter, n_min, wk):
    """Isotropic points as :func:`mechopt.analysis.performance._newton_isotropy`: plain
    Newton on ``r = 0`` (central differences, no descent test: it crosses the long
    curved valleys of near-isotropy that a monotone method does not) from the
    starts ``R (sx, sy)`` at once, steps capped at R/2, iterates projected into
    the disk; every 4 iterations the worse half of the starts (by ``g``) is
    dropped while more than ``n_min`` remain; stops at the first point with ``g <
    _G_ISO``. ``wk``: (6, sx.size) work space. Returns ``(g, LCI)`` of the best
    point visited (``(inf, -1)`` if none)."""
    px = wk[0]
    py = wk[1]
    gk = wk[2]
    ddx = wk[3]
    ddy = wk[4]
    n = sx.size
    for k in range(n):
        px[k] = R * sx[k]
        py[k] = R * sy[k]
    h = max(1e-5 * R, ROUNDING * (abs(cy) + R))
    bx = 0.0
    by = 0.0
    bg = np.inf
    for it in range(n_iter):
        kb = -1
        gmin = np.inf
        for k in range(n):
            x = px[k]
            y = py[k]
            f0, q0 = _iso_r(r1sq, half_d, r3, s1, s2, x, cy + y)
            f1, q1 = _iso_r(r1sq, half_d, r3, s1, s2, x + h, cy + y)
            f2, q2 = _iso_r(r1sq, half_d, r3, s1, s2, x - h, cy + y)
            f3, q3 = _iso_r(r1sq, half_d, r3, s1, s2, x, cy + (y + h))
            f4, q4 = _iso_r(r1sq, half_d, r3, s1, s2, x, cy + (y - h))
            g = f0 * f0 + q0 * q0
            gk[k] = g
            if g < gmin:
                gmin = g
                kb = k
            ddx[k], ddy[k] = _cd_step(f0, q0, f1, q1, f2, q2, f3, q3, f4, q4, h)
        if kb >= 0 and gmin < bg:
            bx = px[kb]
            by = py[kb]
            bg = gmin
        if bg < _G_ISO:
            break
        m = 0
        for k in range(n):
            st = math.hypot(ddx[k], ddy[k])
            if math.isfinite(st) and st > STEP_FLOOR * R and math.isfinite(gk[k]):
                wk[5, m] = gk[k]
                m += 1
        if m == 0:
            break
        med = np.inf
        if it % 4 == 3 and m > n_min:  # keep the better half
            med = np.median(wk[5, :m])
        j = 0
        for k in range(n):
            st = math.hypot(ddx[k], ddy[k])
            if math.isfinite(st) and st > STEP_FLOOR * R and math.isfinite(gk[k]) and gk[k] <= med:
                cap = 0.5 * R / st if st > 0.5 * R else 1.0
                qx = px[k] + cap * ddx[k]
                qy = py[k] + cap * ddy[k]
                rr = math.hypot(qx, qy)
                if rr > R:
                    sc = R / rr
                    qx = qx * sc
                    qy = qy * sc
                px[j] = qx
                py[j] = qy
                j += 1
        n = j
    if not bg < np.inf:
        return np.inf, -1.0
    return bg, _lci_point(r1sq, half_d, r3, s1, s2, bx, cy + by)


@njit
def _mci_nb(r1sq, half_d, r3, s1, s2, cy, R, ux, uy, lv, step0, n_iter, dirs, n_rim, n_start,
            starts, sx, sy, n_min, wk):
    """Maximum LCI over the disk of radius R about (0, cy), given the LCI ``lv`` at
    the unit nodes ``(ux, uy)``:

    1. isotropic points (LCI = 1, nothing is larger): for the mirror-symmetric
       modes a root of the isotropy residual on the y axis
       (:func:`_axis_iso_nb`), else (all modes) plain Newton on the residual
       from the starts ``R (sx, sy)`` (:func:`_iso_newton_nb`, the search of
       :func:`mechopt.analysis.performance.max_lci`); the first found ends the search;
    2. otherwise, from each of ``n_start`` nodes (the best one, then the best one
       farther than R/3 from the nodes already used) a compass search, then
       damped Newton iterations on both isotropy conditions (J a scaled rotation
       or reflection);
    3. a golden-section search along the rim.

    The largest LCI evaluated (never below the best node), capped at 1.
    """
    best = -1.0
    for k in range(lv.size):
        best = max(best, lv[k])
    if s1 != s2:
        v = _axis_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, _AXIS_N, _AXIS_ITERS)
        if v >= 0.0:
            return min(max(best, v), 1.0)
    g, v = _iso_newton_nb(r1sq, half_d, r3, s1, s2, cy, R, sx, sy, _ISO_ITERS, n_min, wk)
    if g < _G_ISO:
        return min(max(best, v), 1.0)
    best = max(best, v)
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
        best = max(best, _tr_polish_nb(r1sq, half_d, r3, s1, s2, cy, R, bx, by, R * step0,
                                       n_iter))
        for which in range(2):
            best = max(best, _newton_iso_nb(r1sq, half_d, r3, s1, s2, cy, R, bx, by, which, 12))
    return min(max(best, _rim_nb(r1sq, half_d, r3, s1, s2, cy, R, n_rim)), 1.0)


@njit
def _disk_stats_one_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, dirs, n_rim, lv,
                       starts, sx, sy, n_min, wk, out):
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
        v = _lci_point(r1sq, half_d, r3, s1, s2, R * ux[k], cy + R * uy[k])
        lv[k] = v
        acc += w[k] * v
    out[0] = acc
    out[1] = _mci_nb(r1sq, half_d, r3, s1, s2, cy, R, ux, uy, lv, step0, n_iter, dirs, n_rim,
                     starts.size, starts, sx, sy, n_min, wk)
    h = 0.5 * R
    a_vmax = 0.0
    a_vmin = 0.0
    a_tmax = 0.0
    a_tmin = 0.0
    a_dmax = 0.0
    a_dmin = 0.0
    n_bad = 0
    for k in range(ux.size):
        a, b, c, d, kk, ok = _mrows(r1sq, half_d, r3, s1, s2, h * ux[k], cy + h * uy[k])
        s_max, s_min = _sv_m(a, b, c, d, kk)
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


@njit
def _disk_stats_batch_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, dirs, n_rim,
                         n_start, sx, sy, n_min, out):
    lv = np.empty(ux.size)
    starts = np.empty(n_start, np.int64)
    wk = np.empty((6, sx.size))
    for i in range(r1.size):
        _disk_stats_one_nb(r1[i], r2[i], r3[i], s1, s2, cy[i], R[i], ux, uy, w, step0, n_iter,
                           dirs, n_rim, lv, starts, sx, sy, n_min, wk, out[i])


def _lci_at_np(rr, s1, s2, x, y):
    return _on_arrays(_lci_point, *rr, s1, s2, x, y)


def _iso_residual_np(rr, s1, s2, x, y, which):
    return _on_arrays(_iso_residual, *rr, s1, s2, x, y, which)


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


def _tr_polish_np(rr, s1, s2, cy, R, px, py, delta, n_iter):
    """:func:`_tr_polish_nb` for arrays of designs (rr: (B, 1) columns, the rest (B,))."""
    c1 = lambda v: v[:, None]  # noqa: E731
    res = lambda x, y: tuple(v[:, 0] for v in _iso_r_np(rr, s1, s2, c1(x), c1(cy + y)))  # noqa: E731
    h = np.maximum(1e-5 * R, ROUNDING * (np.abs(cy) + R))
    h2 = h * h
    live = np.ones(R.size, bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(n_iter):
            a1, a2 = res(px, py)
            g0 = a1 * a1 + a2 * a2
            live &= np.isfinite(g0) & (g0 > _G_ISO)
            if not live.any():
                break
            u1, u2 = res(px + h, py)
            v1, v2 = res(px - h, py)
            w1, w2 = res(px, py + h)
            z1, z2 = res(px, py - h)
            k1, k2 = res(px + h, py + h)
            gx, gy, hxx, hxy, hyy = _g_model(a1, a2, u1, u2, v1, v2, w1, w2, z1, z2, k1, k2, h, h2)
            dx, dy, pred = _tr_step(gx, gy, hxx, hxy, hyy, delta)
            step = np.hypot(dx, dy)
            tx, ty = px + dx, py + dy
            rad = np.hypot(tx, ty)
            sc = np.where(rad > R, R / rad, 1.0)
            tx, ty = np.where(rad > R, tx * sc, tx), np.where(rad > R, ty * sc, ty)
            q1, q2 = res(tx, ty)
            gt = q1 * q1 + q2 * q2
            rho = (g0 - gt) / pred
            acc = live & (gt < g0)
            px, py = np.where(acc, tx, px), np.where(acc, ty, py)
            grow = (rho > 0.75) & (step > 0.99 * delta)
            nd = np.where(rho > 0.25, np.where(grow, np.where(2.0 * delta < R, 2.0 * delta, R),
                                               delta), 0.25 * step)
            delta = np.where(live, nd, delta)
            live &= np.isfinite(delta) & (delta > ROUNDING * R) & ~(pred <= STEP_FLOOR * g0)
    return _lci_at_np(rr, s1, s2, c1(px), c1(cy + py))[:, 0]


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
            det, dx, dy = _fd_step(f0, g0, fx, gx, fy, gy, h)
            live &= (det != 0.0) & np.isfinite(det)
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


def _iso_r_np(rr, s1, s2, x, y):
    """:func:`_iso_r` (broadcasting)."""
    return _on_arrays(_iso_r, *rr, s1, s2, x, y)


def _axis_root_np(rr, s1, s2, cy, a, fa, b, fb, n_iter):
    """:func:`_axis_root_nb` for arrays of brackets (rr: (B, 1) columns, the rest (B,))."""
    c1 = lambda v: v[:, None]  # noqa: E731
    out = np.full(cy.size, -1.0)
    side = np.zeros(cy.size, np.int64)
    live = np.ones(cy.size, bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for _ in range(n_iter):
            if not live.any():
                break
            t = np.where(fb == fa, 0.5 * (a + b), (a * fb - b * fa) / (fb - fa))
            t = np.where((t > a) & (t < b), t, 0.5 * (a + b))
            live &= (t != a) & (t != b)
            f, q = (v[:, 0] for v in _iso_r_np(rr, s1, s2, 0.0, c1(cy + t)))
            live &= np.isfinite(f)
            hit = live & (f * f + q * q < _G_ISO)
            if hit.any():
                v = _lci_at_np(rr, s1, s2, 0.0, c1(cy + t))[:, 0]
                out = np.where(hit, v, out)
                live &= ~hit
            right = f * fb > 0.0
            upb, upa = live & right, live & ~right
            b, fb = np.where(upb, t, b), np.where(upb, f, fb)
            fa = np.where(upb & (side == -1), 0.5 * fa, fa)
            a, fa = np.where(upa, t, a), np.where(upa, f, fa)
            fb = np.where(upa & (side == 1), 0.5 * fb, fb)
            side = np.where(upb, -1, np.where(upa, 1, side))
    return out


def _axis_iso_np(rr, s1, s2, cy, R, n_ax, n_iter):
    """:func:`_axis_iso_nb` for arrays of designs (rr: (B, 1) columns, the rest (B,))."""
    c1 = lambda v: v[:, None]  # noqa: E731
    B = R.size
    t = -c1(R) + (2.0 * c1(R)) * np.arange(1, n_ax + 1) / n_ax
    t = np.concatenate([-c1(R), t], axis=1)
    f, q = _iso_r_np(rr, s1, s2, 0.0, c1(cy) + t)
    with np.errstate(invalid="ignore", over="ignore"):
        # events in the order of _axis_iso_nb: sample k at 2k, the bracket (k, k + 1) at 2k + 1
        samp = f * f + q * q < _G_ISO
        sign = f[:, :-1] * f[:, 1:] < 0.0
    never = 2 * n_ax + 2
    pos_s = np.where(samp.any(axis=1), 2 * np.argmax(samp, axis=1), never)
    pos_r = np.full(B, never)
    val_r = np.full(B, -1.0)
    todo = sign.copy()
    while True:
        k = np.argmax(todo, axis=1)
        rows = np.flatnonzero(todo.any(axis=1) & (pos_r == never) & (2 * k + 1 < pos_s))
        if rows.size == 0:
            break
        k = k[rows]
        todo[rows, k] = False
        sub = tuple(v[rows] for v in rr)
        v = _axis_root_np(sub, s1, s2, cy[rows], t[rows, k], f[rows, k], t[rows, k + 1],
                          f[rows, k + 1], n_iter)
        good = v >= 0.0
        pos_r[rows[good]] = 2 * k[good] + 1
        val_r[rows[good]] = v[good]
    ks = np.minimum(pos_s // 2, n_ax)
    v_s = _lci_at_np(rr, s1, s2, 0.0, c1(cy) + np.take_along_axis(t, ks[:, None], 1))[:, 0]
    return np.where(pos_s < pos_r, v_s, val_r)


def _iso_newton_np(rr, s1, s2, cy, R, sx, sy, n_iter, n_min):
    """:func:`_iso_newton_nb` for arrays of designs (rr: (B, 1) columns, the rest
    (B,)): ``(g, LCI)``. The live starts of each design are kept in their order at
    the front of its row."""
    c1 = lambda v: v[:, None]  # noqa: E731
    B = R.size
    bx, by = np.zeros(B), np.zeros(B)
    bg = np.full(B, np.inf)
    h = np.maximum(1e-5 * R, ROUNDING * (np.abs(cy) + R))
    idx = np.arange(B)  # designs still searching
    px, py = c1(R) * sx[None, :], c1(R) * sy[None, :]
    alive = np.ones(px.shape, bool)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        for it in range(n_iter):
            if idx.size == 0:
                break
            sub = tuple(v[idx] for v in rr)
            cyc, hh, Rc = c1(cy[idx]), c1(h[idx]), c1(R[idx])
            f0, q0 = _iso_r_np(sub, s1, s2, px, cyc + py)
            f1, q1 = _iso_r_np(sub, s1, s2, px + hh, cyc + py)
            f2, q2 = _iso_r_np(sub, s1, s2, px - hh, cyc + py)
            f3, q3 = _iso_r_np(sub, s1, s2, px, cyc + (py + hh))
            f4, q4 = _iso_r_np(sub, s1, s2, px, cyc + (py - hh))
            g = np.where(alive, f0 * f0 + q0 * q0, np.nan)
            gm = np.where(g < np.inf, g, np.inf)
            kb = np.argmin(gm, axis=1)
            gmin = gm[np.arange(idx.size), kb]
            up = gmin < bg[idx]
            bx[idx[up]] = px[up, kb[up]]
            by[idx[up]] = py[up, kb[up]]
            bg[idx[up]] = gmin[up]
            dx, dy = _cd_step(f0, q0, f1, q1, f2, q2, f3, q3, f4, q4, hh)
            st = np.hypot(dx, dy)
            keep = alive & np.isfinite(st) & (st > STEP_FLOOR * Rc) & np.isfinite(g)
            m = keep.sum(axis=1)
            if it % 4 == 3:  # keep the better half
                half = m > n_min
                if half.any():
                    med = np.nanmedian(np.where(keep[half], g[half], np.nan), axis=1)
                    keep[half] &= g[half] <= med[:, None]
            go = ~(bg[idx] < _G_ISO) & (m > 0)
            cap = np.where(st > 0.5 * Rc, 0.5 * Rc / st, 1.0)
            qx, qy = px + cap * dx, py + cap * dy
            rad = np.hypot(qx, qy)
            sc = np.where(rad > Rc, Rc / rad, 1.0)
            px, py, alive = qx * sc, qy * sc, keep
            # drop the finished designs, move the live starts to the front
            px, py, alive = px[go], py[go], alive[go]
            idx = idx[go]
            order = np.argsort(~alive, axis=1, kind="stable")
            px, py, alive = (np.take_along_axis(v, order, 1) for v in (px, py, alive))
            ncol = int(alive.sum(axis=1).max()) if idx.size else 0
            px, py, alive = px[:, :ncol], py[:, :ncol], alive[:, :ncol]
    v = _lci_at_np(rr, s1, s2, c1(bx), c1(cy + by))[:, 0]
    found = bg < np.inf
    return np.where(found, bg, np.inf), np.where(found, v, -1.0)


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


def _mci_search_np(rr, s1, s2, cy, R, ux, uy, ks, haves, lvs, step0, n_iter, n_rim, sx, sy,
                   n_min):
    """Vectorised :func:`_mci_nb` from the starts of :func:`_mci_starts_np` (``lvs``:
    LCI at those nodes, the first the best node); rr: (B, 1) columns, the rest (B,)
    or (B, n_start)."""
    c1 = lambda v: v[:, None]  # noqa: E731
    B = R.size
    out = np.full(B, np.nan)
    best = lvs[:, 0].copy()
    todo = np.ones(B, bool)
    # 1. isotropic points: on the axis (mirror-symmetric modes), then from the grid of starts
    if s1 != s2:
        v = _axis_iso_np(rr, s1, s2, cy, R, _AXIS_N, _AXIS_ITERS)
        hit = v >= 0.0
        out[hit] = np.minimum(np.maximum(best[hit], v[hit]), 1.0)
        todo &= ~hit
    block = max(1, 200_000 // sx.size)
    for i0 in range(0, B, block):
        q = np.flatnonzero(todo[i0:i0 + block]) + i0
        if q.size == 0:
            continue
        g, v = _iso_newton_np(tuple(a[q] for a in rr), s1, s2, cy[q], R[q], sx, sy, _ISO_ITERS,
                              n_min)
        hit = g < _G_ISO
        out[q[hit]] = np.minimum(np.maximum(best[q[hit]], v[hit]), 1.0)
        todo[q[hit]] = False
        best[q] = np.maximum(best[q], v)
    q = np.flatnonzero(todo)
    if q.size == 0:
        return out
    # 2. compass search and damped Newton from the starting nodes, 3. the rim
    rr, cy, R, ks, haves, lvs, best = (tuple(a[q] for a in rr), cy[q], R[q], ks[q], haves[q],
                                       lvs[q], best[q])
    rows = np.arange(q.size)
    for j in range(ks.shape[1]):
        kb, have = ks[:, j], haves[:, j]
        bx, by, b = _compass_np(rr, s1, s2, cy, R, R * ux[kb], R * uy[kb], lvs[:, j],
                                R * step0, n_iter)
        cand = np.maximum(b, _tr_polish_np(rr, s1, s2, cy, R, bx, by, R * step0, n_iter))
        for which in (0, 1):
            cand = np.maximum(cand, _newton_iso_np(rr, s1, s2, cy, R, bx, by, which, 12))
        best = np.where(have, np.maximum(best, cand), best)
    ph = 2.0 * np.pi * np.arange(n_rim) / n_rim
    v = _lci_at_np(rr, s1, s2, c1(R) * np.cos(ph), c1(cy) + c1(R) * np.sin(ph))
    kr = np.argmax(v, axis=1)
    dph = 2.0 * np.pi / n_rim
    fr = _golden_rim_np(rr, s1, s2, cy, R, dph * (kr - 1), dph * (kr + 1), 40)
    out[q] = np.minimum(np.maximum(best, np.maximum(v[rows, kr], fr)), 1.0)
    return out


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


def _disk_stats_np(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, n_iter, n_rim, n_start, sx, sy,
                   n_min):
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
    res[:, 1] = _mci_search_np(rr, s1, s2, cy, R, ux, uy, ks, haves, lvs, step0, n_iter, n_rim,
                               sx, sy, n_min)
    out[live] = res
    return out


def _iso_starts(s1, s2):
    """Unit-disk starts of the isotropy Newton (:func:`_iso_newton_nb`) and the
    count of starts above which the worse half is dropped: the nodes of the polar
    ``_ISO_N_R x _ISO_N_THETA`` grid, as in :func:`mechopt.analysis.performance.max_lci`. For
    the mirror-symmetric modes only the nodes with ``x > 0`` (none is on the axis):
    there ``r(-x, y) = (r_1, -r_2)(x, y)`` holds exactly, so the mirrored start runs
    the mirrored iteration with the same ``g``, and the half grid does what the
    whole grid does (with 4 instead of 8 starts as the floor of the halving)."""
    from mechopt.core.quadrature import disk_rule

    sx, sy, _ = disk_rule(1.0, "polar", n_r=_ISO_N_R, n_theta=_ISO_N_THETA)
    if s1 != s2:
        keep = sx > 0.0
        return np.ascontiguousarray(sx[keep]), np.ascontiguousarray(sy[keep]), 4
    return np.ascontiguousarray(sx), np.ascontiguousarray(sy), 8


def disk_stats_batch(r1, r2, r3, center_y, radius, mode="+-", quadrature="area", n_r=None,
                     n_theta=None, compiled=None):
    """``(n, 8)`` array of :data:`DISK_STAT_NAMES` for designs with a known MIC.

    GCI is the mean LCI over the MIC disk and MCI its maximum (the search of
    :func:`_mci_nb`, which follows :func:`mechopt.analysis.performance.max_lci`); the
    velocity, payload and stiffness means are over the concentric disk of half
    radius (Liu 2006 eq. 4, 11, 14, 19). The rule is
    :func:`mechopt.core.quadrature.disk_rule` (``area`` or ``polar``). NaN rows for a
    radius <= 0 (no singularity-free disk).

    Parameters
    ----------
    r1, r2, r3 : array_like
        Crank, distal link and half base [L] of each design.
    center_y, radius : array_like
        The MIC of each design [L].
    mode : str
        Working mode.
    quadrature : str
        ``"area"`` or ``"polar"``.
    n_r, n_theta : int, optional
        Quadrature nodes.
    compiled : bool, optional
        Use the numba kernels (None: when installed).

    Returns
    -------
    ndarray
        Shape ``(n, 8)``, columns :data:`DISK_STAT_NAMES`.
    """
    from mechopt.core.quadrature import DEFAULT_N_R, DEFAULT_N_THETA, disk_rule

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
    sx, sy, n_min = _iso_starts(s1, s2)
    out = np.empty((r1.size, 8))
    if use_numba(compiled):
        _disk_stats_batch_nb(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, _MCI_ITERS, _DIRS,
                             n_theta, _MCI_STARTS, sx, sy, n_min, out)
    else:
        out[:] = _disk_stats_np(r1, r2, r3, s1, s2, cy, R, ux, uy, w, step0, _MCI_ITERS, n_theta,
                                _MCI_STARTS, sx, sy, n_min)
    out[:, 2:4] *= L[:, None]
    out[:, 4:6] /= L[:, None]
    out[:, 6:8] *= (L * L)[:, None]
    return out


# =============================================================================
# Compiling ahead of use
# =============================================================================
#: the groups of :func:`compile_all`, by the entry points that run them
KERNEL_GROUPS = ("disk", "mic", "points")


def compile_all(groups=KERNEL_GROUPS) -> bool:
    """Compile the five-bar's compiled kernels now, for the argument types the package
    passes them, into numba's on-disk cache (:func:`mechopt.core.jit.cache_dir`):
    ``"disk"`` the disk means and the MCI (:func:`disk_stats_batch`), ``"mic"`` the
    explicit MIC (:func:`mic_batch`, :mod:`~mechopt.mechanisms.five_bar.mic`),
    ``"points"`` the local indices (:func:`lci_points`, :func:`local_points`, the fused
    LCI of :mod:`~mechopt.mechanisms.five_bar.lci`).

    A process that finds them there loads them in about 0.4 s instead of compiling
    them (about 11 s for all; two processes starting at once would both compile). The
    test suite calls this before its worker processes start, the groups in two
    processes; a user may call it after installing. Returns False (and does nothing)
    without numba.

    Parameters
    ----------
    groups : tuple of str
        Kernel groups of :data:`KERNEL_GROUPS`.

    Returns
    -------
    bool
        False without numba (nothing compiled), else True.

    Raises
    ------
    ValueError
        For an unknown group.
    """
    groups = tuple(groups)
    for g in groups:
        if g not in KERNEL_GROUPS:
            raise ValueError(f"kernel group must be one of {', '.join(map(repr, KERNEL_GROUPS))}, got {g!r}")
    if not HAVE_NUMBA:
        return False
    one = np.array([0.85]), np.array([1.6]), np.array([0.55])
    x, y = np.array([0.0, 0.3]), np.array([1.2, 1.5])
    if "disk" in groups:
        for mode in ("+-", "++"):  # the mirror-symmetric modes and the others take other branches
            for quadrature in ("area", "polar"):
                disk_stats_batch(*one, np.array([1.5]), np.array([0.5]), mode=mode,
                                 quadrature=quadrature, compiled=True)
    if "mic" in groups:
        mic_batch(*one, compiled=True)
        _mic._compiled_one(0.85, 1.6, 0.55, 1.0, -1.0)
        qx, qy = np.array([0.1, -0.2]), np.array([1.0, 1.1])
        sx, sy = np.empty(2), np.empty(2)
        m = _sort_cloud_nb(qx, qy, 2, sx, sy)
        ay = np.array([np.nan, 1.3, np.nan, -0.2])
        _radius_nb(1.1, 1.4, 0.3, qx, qy, 2, ay, 1.0)
        _radius_sorted_nb(1.1, 1.4, 0.3, sx, sy, m, ay, 1.0, -1)
    if "points" in groups:
        from mechopt.mechanisms.five_bar import lci as _lci

        lci_points(0.85, 1.6, 0.55, x, y, compiled=True)
        local_points(0.85, 1.6, 0.55, x, y, compiled=True)
        _lci.five_bar_lci_numba(x, y, 0.85, 1.6, 0.55, 1.0, -1.0)
    return True
