"""The symmetric five-bar's explicit MIC and the workspace geometry it rests on.

:class:`FiveBarWorkspace` is what :meth:`mechopt.mechanisms.five_bar.model.FiveBar.explicit_workspace`
returns to :mod:`mechopt.analysis.workspace` (the hook
:meth:`mechopt.core.protocol.PlanarMechanism.explicit_workspace`): the maximal inscribed circle
(MIC, Liu 2006 footnote 2; Le 2013 sec. III) of one design, the legs' reach that bounds
where :meth:`~mechopt.mechanisms.five_bar.model.FiveBar.type2_function` can be finite, and
why a design has no MIC, in terms of its lengths.

The MIC algorithm. The largest singularity-free disk centred at ``(0, yc)`` has the radius
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
golden-section search on that dense cloud gives the centre (sizes:
:data:`MIC_SIZES`).

Three implementations, one set of formulas. The formulas (``_theta_range``,
``_theta_of_u``, ``_coupler_point``, ``_axis_points``, ``_serial``, ...) are plain
Python, marked :func:`~mechopt.core.jit.jitable`:

* the compiled kernel (``_mic_batch_loop``, compiled by ``_compiled_batch``; the
  atlas's :func:`mechopt.mechanisms.five_bar.kernels.mic_batch`) calls them on scalars;
* the one-design NumPy port (:func:`five_bar_mic` before numba is loaded: a few ms, no
  numba start-up) calls them on arrays, with the C library's trigonometric functions
  (``math``; NumPy's vectorised ``cos``/``arccos`` may differ from them in the last bit)
  and its operations in the kernel's order, so that it gives the compiled kernel's
  values bit for bit (``tests/test_workspace.py``, 1600 designs, every mode);
* the NumPy batch path of :func:`~mechopt.mechanisms.five_bar.kernels.mic_batch` calls the
  vectorised ones with NumPy's trigonometric functions (equal to rounding).

Importing this module imports neither numba nor the kernels.
"""
from __future__ import annotations

import math
import time

import numpy as np

from mechopt.core.jit import HAVE_NUMBA, jitable, njit, select
from mechopt.core.numerics import INV_PHI, golden_section_max
from mechopt.core.validation import RESOLUTION, ROUNDING

__all__ = ["FiveBarWorkspace", "five_bar_mic", "MIC_SIZES", "MIC_NUMBA_AFTER_SECONDS"]

#: sizes of the MIC search: crank-angle samples per coupler-curve sub-branch, coarse
#: centres, dense refinement factor, centres seeding the refinement, golden-section
#: iterations, local maxima refined
MIC_SIZES = dict(n_crank=128, n_y=128, n_sub=16, n_seed_y=9, n_golden=42, n_cand=2)
#: the ratio of the golden-section searches
_GOLD = INV_PHI
#: coupler-curve sub-branches b = 0..7: leg = b // 4 (whose crank angle is the
#: parameter), sigma = +1 if (b // 2) % 2 == 0 else -1 (circle-intersection branch),
#: half = b % 2 (theta in [0, pi] or [-pi, 0]). On each, theta runs over the
#: interval where the coupler closes, cosine-spaced in u in [0, 1] so that the
#: square-root behaviour at the dead points is sampled at even arc length.
_N_SUB_BRANCH = 8
#: seconds spent in the NumPy port after which :func:`five_bar_mic` uses the compiled
#: kernel (its first load costs about 0.5 s per process; see
#: :mod:`mechopt.mechanisms.five_bar.lci`)
MIC_NUMBA_AFTER_SECONDS = 0.5
_port_seconds = 0.0
_batch = None  # the compiled mic_batch_loop, once made


def _signs(mode):
    """The elbow signs ``(s1, s2)`` of a working mode (``+1`` for ``"+"``, Le eq. 17-18)."""
    return (1.0 if mode[0] == "+" else -1.0), (1.0 if mode[1] == "+" else -1.0)


# =============================================================================
# Formulas (scalars in the compiled kernel; see the module docstring)
# =============================================================================
@jitable
def _theta_range(r1, r2, r3, leg, rho):
    """``(theta_a, theta_b)`` in [0, pi] (and its mirror in [-pi, 0]) where the
    coupler of length 2 r2 closes (leg 0: crank 1 at theta; leg 1: crank 2) and
    the crank tip lies within ``|x| <= rho`` of the y axis; ``theta_a > theta_b``
    if empty. Scalars."""
    # t * t, not t ** 2: Python's ** calls the C library's pow, compiled code multiplies
    t = r1 - 2.0 * r2
    lo2 = t * t
    t = r1 + 2.0 * r2
    hi2 = t * t
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


@jitable
def _theta_of_u(ta, tb, half, cos_pu):
    """The crank angle at ``u`` of a sub-branch, cosine-spaced over ``[ta, tb]`` (``half``
    0) or its mirror (``half`` 1), given ``cos_pu = cos(pi u)``."""
    th = ta + (tb - ta) * 0.5 * (1.0 - cos_pu)
    return select(half == 0, th, -th)


@jitable
def _coupler_point(r1, r2, r3, s1, s2, leg, sigma, cos_th, sin_th):
    """Midpoint ``P`` of ``B1 B2`` (``|B1 B2| = 2 r2``) with the crank ``leg`` at the angle
    ``th`` (given as ``cos th``, ``sin th``) and the circle-intersection branch ``sigma``:
    ``(px, py, valid)``, valid when the coupler closes and the elbows are the working
    mode's (``px``, ``py`` are meaningless otherwise). Scalars or arrays (broadcast)."""
    ax = select(leg == 0, -r3, r3)
    ox = -ax
    bx = ax + r1 * cos_th
    by = r1 * sin_th
    vx = ox - bx
    vy = -by
    L2 = vx * vx + vy * vy
    L = np.sqrt(L2)
    cc = 4.0 * r2 * r2
    a = (L2 + cc - r1 * r1) / (2.0 * L)
    hh2 = cc - a * a
    hh = sigma * np.sqrt(np.maximum(hh2, 0.0))
    cx = bx + (a * vx - hh * vy) / L
    cy = by + (a * vy + hh * vx) / L
    px = 0.5 * (bx + cx)
    py = 0.5 * (by + cy)
    first = leg == 0
    b1x = select(first, bx, cx)
    b1y = select(first, by, cy)
    b2x = select(first, cx, bx)
    b2y = select(first, cy, by)
    c1 = (px + r3) * b1y - py * (b1x + r3)
    c2 = (px - r3) * b2y - py * (b2x - r3)
    ok = (L2 > 0.0) & (hh2 >= -ROUNDING * cc) & (s1 * c1 >= 0.0) & (s2 * c2 >= 0.0)
    return px, py, ok


@jitable
def _axis_points(r1, r2, r3, s1, s2, qy):
    """The B1 = B2 = C branch seen from the y axis: for a centre ``(0, y)`` the
    nearest point of the circle ``|P - C| = r2`` is ``(0, hc +- r2)``; the four
    such points that have the working mode's elbows are written to ``qy``
    (NaN otherwise). Returns how many are valid. Scalars."""
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


@jitable
def _serial(r1, r2, r3, y):
    """Distance from ``(0, y)`` to the nearest serial circle (Le eq. 19); scalars or arrays."""
    D = np.sqrt(r3 * r3 + y * y)
    return np.minimum(r1 + r2 - D, D - abs(r1 - r2))


@jitable
def _centre_range(r1, r2, r3):
    """``(ylo, yhi, rho)``: the centres worth trying and the reach of the useful locus.

    The serial clearance is positive for ``|r1 - r2| < hypot(r3, y) < r1 + r2`` and
    never exceeds ``min(r1, r2)``, so only locus points within ``min(r1, r2)`` of that
    axis segment matter, and their crank tips lie within ``rho = min(r1, r2) + r2`` of
    the y axis (1 % margin). Scalars."""
    ylo2 = (r1 - r2) * (r1 - r2) - r3 * r3
    ylo = math.sqrt(ylo2) if ylo2 > 0.0 else 0.0
    yhi2 = (r1 + r2) * (r1 + r2) - r3 * r3
    yhi = math.sqrt(yhi2) if yhi2 > 0.0 else 0.0
    return ylo, yhi, 1.01 * (min(r1, r2) + r2)


@jitable
def _best_local_max(rs, n_y, used):
    """Index of the best local maximum of the coarse radii ``rs[:n_y]`` (positive, not
    next to the previous candidate ``used``), -1 if none."""
    jb = -1
    for j in range(n_y):
        if abs(j - used) <= 1 or rs[j] <= 0.0:
            continue
        if j > 0 and rs[j - 1] > rs[j]:
            continue
        if j < n_y - 1 and rs[j + 1] > rs[j]:
            continue
        if jb < 0 or rs[j] > rs[jb]:
            jb = j
    return jb


@jitable
def _axis_d2(ay, y, best):
    """``min(best, distance^2 to the axis points ay)`` (NaN entries are none)."""
    for i in range(4):
        dy = ay[i] - y  # NaN compares False
        if dy * dy < best:
            best = dy * dy
    return best


@jitable
def _radius(r1, r2, r3, qx, qy, n, ay, y):
    """``min(serial, distance to the n cloud points and the 4 axis points)``: the
    reference of :func:`_radius_sorted` (a plain scan)."""
    s = _serial(r1, r2, r3, y)
    if s <= 0.0:
        return 0.0
    best = s * s
    for k in range(n):
        dy = qy[k] - y
        d2 = qx[k] * qx[k] + dy * dy
        if d2 < best:
            best = d2
    return math.sqrt(_axis_d2(ay, y, best))


@jitable
def _sort_cloud(qx, qy, n, sx2, sy):
    """The first ``n`` points of ``(qx, qy)`` that can be nearest (finite), ordered by
    y: their ``x * x`` in ``sx2`` and their y in ``sy``; returns how many. A point with
    an infinite or NaN coordinate never passes ``d2 < best`` in :func:`_radius`."""
    m = 0
    for k in range(n):
        if qx[k] < np.inf and qx[k] > -np.inf and qy[k] < np.inf and qy[k] > -np.inf:
            sy[m] = qy[k]
            sx2[m] = qx[k]
            m += 1
    if m == 0:
        return 0
    order = np.argsort(sy[:m])
    ys_ = sy[:m].copy()
    xs_ = sx2[:m].copy()
    for i in range(m):
        j = order[i]
        sy[i] = ys_[j]
        sx2[i] = xs_[j] * xs_[j]
    return m


@jitable
def _scan(sx2, sy, y, start, stop, step, best, kb):
    """The sorted points ``start, start + step, ...`` (before ``stop``), outwards from
    ``y``, until ``dy * dy`` alone reaches ``best``: ``(best, index of the best)``."""
    for k in range(start, stop, step):
        dy = sy[k] - y
        dd = dy * dy
        if not dd < best:
            break
        d2 = sx2[k] + dd
        if d2 < best:
            best = d2
            kb = k
    return best, kb


@jitable
def _radius_sorted(r1, r2, r3, sx2, sy, m, ay, y, hint):
    """:func:`_radius` of a cloud sorted by :func:`_sort_cloud`, the same value
    bit for bit, and the index of a nearest cloud point (-1 if none is nearer than
    the serial clearance). Each point's ``d2 = x * x + dy * dy`` is computed as
    there; the point ``hint`` (the nearest one of a centre nearby) is tried first,
    then the points outwards from ``y`` until ``dy * dy`` alone reaches the smallest
    ``d2`` so far (``d2 >= dy * dy`` in floating point, and ``dy * dy`` only grows
    outwards), so that no point that could lower the minimum is skipped; a minimum
    does not depend on the order of its terms."""
    s = _serial(r1, r2, r3, y)
    if s <= 0.0:
        return 0.0, hint
    best = s * s
    kb = -1
    if 0 <= hint < m:
        dy = sy[hint] - y
        d2 = sx2[hint] + dy * dy
        if d2 < best:
            best = d2
            kb = hint
    j = np.searchsorted(sy[:m], y)
    best, kb = _scan(sx2, sy, y, j, m, 1, best, kb)
    best, kb = _scan(sx2, sy, y, j - 1, -1, -1, best, kb)
    return math.sqrt(_axis_d2(ay, y, best)), kb


@jitable
def _locus_point(r1, r2, r3, s1, s2, b, ta, tb, u):
    """:func:`_coupler_point` at ``u`` of the sub-branch ``b`` (crank interval ``[ta, tb]``)."""
    leg = b // 4
    sigma = 1.0 if (b // 2) % 2 == 0 else -1.0
    th = _theta_of_u(ta, tb, b % 2, math.cos(math.pi * u))
    return _coupler_point(r1, r2, r3, s1, s2, leg, sigma, math.cos(th), math.sin(th))


@jitable
def _mic_one_loop(r1, r2, r3, s1, s2, ugrid, n_y, n_sub, n_seed_y, n_golden, n_cand,
            qx, qy, ys, rs, dqx, dqy, ay, tr, sx2, sy, dsx2, dsy):
    """MIC ``(radius, center_y)`` of one design in units of its length scale (the
    compiled kernel; work arrays passed in)."""
    nu = ugrid.size
    ylo, yhi, rho = _centre_range(r1, r2, r3)
    for leg in range(2):
        ta, tb = _theta_range(r1, r2, r3, leg, rho)
        tr[leg, 0] = ta
        tr[leg, 1] = tb
    for b in range(_N_SUB_BRANCH):
        ta = tr[b // 4, 0]
        tb = tr[b // 4, 1]
        for k in range(nu):
            idx = b * nu + k
            qx[idx] = np.inf
            qy[idx] = 0.0
            if ta > tb:
                continue
            px, py, ok = _locus_point(r1, r2, r3, s1, s2, b, ta, tb, ugrid[k])
            if ok:
                qx[idx] = px
                qy[idx] = py
    n = _N_SUB_BRANCH * nu
    _axis_points(r1, r2, r3, s1, s2, ay)
    ns = _sort_cloud(qx, qy, n, sx2, sy)
    hint = -1
    for j in range(n_y):
        ys[j] = ylo + (yhi - ylo) * j / (n_y - 1)
        rs[j], hint = _radius_sorted(r1, r2, r3, sx2, sy, ns, ay, ys[j], hint)
    best_r = 0.0
    best_y = 0.0
    used0 = -10
    du = 1.0 / (nu - 1)
    for cand in range(n_cand):
        jb = _best_local_max(rs, n_y, used0)
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
                u0 = ugrid[kb - b * nu]
                for i in range(-n_sub, n_sub + 1):
                    u = u0 + du * i / n_sub
                    if u < 0.0 or u > 1.0:
                        continue
                    px, py, ok = _locus_point(r1, r2, r3, s1, s2, b, tr[b // 4, 0], tr[b // 4, 1], u)
                    if ok:
                        dqx[m] = px
                        dqy[m] = py
                        m += 1
        # golden-section maximisation of min(serial, T_dense) over [lo, hi]
        md = _sort_cloud(dqx, dqy, m, dsx2, dsy)
        yb = ys[jb]
        fb, h0 = _radius_sorted(r1, r2, r3, dsx2, dsy, md, ay, yb, -1)
        a = lo
        c = hi
        x1 = c - _GOLD * (c - a)
        x2 = a + _GOLD * (c - a)
        f1, h1 = _radius_sorted(r1, r2, r3, dsx2, dsy, md, ay, x1, h0)
        f2, h2 = _radius_sorted(r1, r2, r3, dsx2, dsy, md, ay, x2, h0)
        for _ in range(n_golden):
            if f1 >= f2:
                if f1 > fb:
                    fb = f1
                    yb = x1
                c = x2
                x2 = x1
                f2 = f1
                x1 = c - _GOLD * (c - a)
                h2 = h1
                f1, h1 = _radius_sorted(r1, r2, r3, dsx2, dsy, md, ay, x1, h1)
            else:
                if f2 > fb:
                    fb = f2
                    yb = x2
                a = x1
                x1 = x2
                f1 = f2
                x2 = a + _GOLD * (c - a)
                h1 = h2
                f2, h2 = _radius_sorted(r1, r2, r3, dsx2, dsy, md, ay, x2, h2)
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


def _mic_batch_loop(r1, r2, r3, s1, s2, ugrid, n_y, n_sub, n_seed_y, n_golden, n_cand, out_r, out_y):
    """:func:`_mic_one_loop` of every design (normalised lengths) into ``out_r``, ``out_y``."""
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
    sx2 = np.empty(n)
    sy = np.empty(n)
    dsx2 = np.empty(md)
    dsy = np.empty(md)
    for i in range(r1.size):
        out_r[i], out_y[i] = _mic_one_loop(r1[i], r2[i], r3[i], s1, s2, ugrid, n_y, n_sub, n_seed_y,
                                     n_golden, n_cand, qx, qy, ys, rs, dqx, dqy, ay, tr, sx2, sy,
                                     dsx2, dsy)


def _compiled_batch():
    """:func:`_mic_batch_loop` compiled (made once per process; loads numba), or the plain
    function without numba."""
    global _batch
    if _batch is None:
        _batch = njit(_mic_batch_loop)
    return _batch


# =============================================================================
# Vectorised formulas (the NumPy paths)
# =============================================================================
def _with_axis_points(qx, qy, ay):
    """The cloud ``(qx, qy)`` (last axis: its points) with the axis points ``ay`` (last axis
    4, NaN: none) appended as the points ``(0, ay)``: their ``0 * 0 + dy * dy`` is the
    ``dy * dy`` of :func:`_radius` exactly; a missing one gets an infinite ``qx``."""
    none = np.isnan(ay)
    return (np.concatenate([qx, np.where(none, np.inf, 0.0)], axis=-1),
            np.concatenate([qy, np.where(none, 0.0, ay)], axis=-1))


def _cloud_radius(r1, r2, r3, qx, qy, y):
    """``min(serial, distance to the cloud)`` at the centres ``y`` (any shape ``S``; ``qx``,
    ``qy`` broadcast against ``S + (n,)``, an infinite ``qx`` is no point): the minimum of
    the terms of :func:`_radius` for a cloud from :func:`_with_axis_points` (a minimum
    does not depend on the order of its terms)."""
    s = _serial(r1, r2, r3, y)
    dy = qy - y[..., None]
    best = np.minimum(s * s, np.min(qx * qx + dy * dy, axis=-1, initial=np.inf))
    return np.where(s <= 0.0, 0.0, np.sqrt(best))


def _libm(f, a):
    """The scalar function ``f`` of :mod:`math` at every element of ``a``."""
    a = np.asarray(a, dtype=float)
    return np.fromiter(map(f, a.ravel().tolist()), float, a.size).reshape(a.shape)


def _locus_points(r1, r2, r3, s1, s2, leg, sigma, ta, tb, half, u):
    """:func:`_coupler_point` at ``u`` of sub-branches (arrays), the C library's
    trigonometry (the compiled kernel's values)."""
    th = _theta_of_u(ta, tb, half, _libm(math.cos, math.pi * u))
    with np.errstate(divide="ignore", invalid="ignore"):  # L2 = 0: not valid
        return _coupler_point(r1, r2, r3, s1, s2, leg, sigma, _libm(math.cos, th), _libm(math.sin, th))


def _mic_one(r1, r2, r3, s1, s2):
    """:func:`_mic_one_loop` of one design in units of its length scale, vectorised in NumPy
    (over the samples of the locus and the coarse centres) with the kernel's values."""
    n_y, n_sub = MIC_SIZES["n_y"], MIC_SIZES["n_sub"]
    n_seed_y, n_golden = MIC_SIZES["n_seed_y"], MIC_SIZES["n_golden"]
    ugrid = np.linspace(0.0, 1.0, MIC_SIZES["n_crank"])
    nu = ugrid.size
    ylo, yhi, rho = _centre_range(r1, r2, r3)
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
        lv = live[:, None]
        px, py, ok = _locus_points(r1, r2, r3, s1, s2, leg_b[lv], sigma_b[lv], ta_b[lv], tb_b[lv],
                                   half_b[lv], ugrid[None, :])
        qx[live] = np.where(ok, px, np.inf)
        qy[live] = np.where(ok, py, 0.0)
    ay = np.empty(4)
    _axis_points(r1, r2, r3, s1, s2, ay)
    ys = ylo + (yhi - ylo) * np.arange(n_y) / (n_y - 1)
    rs = _cloud_radius(r1, r2, r3, *_with_axis_points(qx.ravel(), qy.ravel(), ay), ys).tolist()
    best_r, best_y = 0.0, 0.0
    used = -10
    du = 1.0 / (nu - 1)
    off = np.arange(-n_sub, n_sub + 1)
    for _ in range(MIC_SIZES["n_cand"]):
        jb = _best_local_max(rs, n_y, used)
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
        px, py, ok = _locus_points(r1, r2, r3, s1, s2, leg_b[bb], sigma_b[bb], ta_b[bb], tb_b[bb],
                                   half_b[bb], u)
        ok &= (u >= 0.0) & (u <= 1.0)
        dqx, dqy = _with_axis_points(px[ok], py[ok], ay)

        def rad(y):
            return float(_cloud_radius(r1, r2, r3, dqx, dqy, np.array([y]))[0])

        # golden-section maximisation of min(serial, T_dense) over [lo, hi], the best
        # point seen (from the coarse one) kept
        yb = float(ys[jb])
        g = golden_section_max(rad, lo, hi, max_iter=n_golden, start=(yb, rad(yb)))
        yb, fb = g.x_best, g.f_best
        if fb > best_r:
            best_r, best_y = fb, yb
    return best_r, best_y


def _compiled_one(r1, r2, r3, s1, s2):
    """:func:`_mic_one_loop` of one design by the compiled kernel."""
    out_r, out_y = np.empty(1), np.empty(1)
    _compiled_batch()(np.array([r1]), np.array([r2]), np.array([r3]), s1, s2,
                     np.linspace(0.0, 1.0, MIC_SIZES["n_crank"]), MIC_SIZES["n_y"],
                     MIC_SIZES["n_sub"], MIC_SIZES["n_seed_y"], MIC_SIZES["n_golden"],
                     MIC_SIZES["n_cand"], out_r, out_y)
    return float(out_r[0]), float(out_y[0])


def _in_unit(r1, r2, r3, mode, solve):
    """``solve`` on the design divided by its length scale ``(r1 + r2 + r3)/3``, the
    result scaled back (as :func:`mechopt.mechanisms.five_bar.kernels.mic_batch` does)."""
    s1, s2 = _signs(mode)
    L = (r1 + r2 + r3) / 3.0
    r3n = r3 / L
    r, y = solve(r1 / L, r2 / L, r3n, s1, s2)
    if s1 == s2 and r3n == 0.0:  # r3 = 0 in mode ++ or --: every pose is type-II singular
        r = 0.0
    return r * L, y * L


def _mic_one_port(r1, r2, r3, mode):
    """The NumPy port's ``(radius, center_y)`` of one design."""
    return _in_unit(r1, r2, r3, mode, _mic_one)


def five_bar_mic(r1, r2, r3, mode="+-"):
    """``(radius, center_y)`` of the five-bar's explicit MIC: the values of
    ``kernels.mic_batch(r1, r2, r3, mode, compiled=True)``, by the NumPy port for the
    first :data:`MIC_NUMBA_AFTER_SECONDS` of a process, by the compiled kernel after
    (if numba is available).

    Parameters
    ----------
    r1, r2, r3 : float
        Crank, distal link and half base [L].
    mode : str
        Working mode.

    Returns
    -------
    radius, center_y : float
        [L].
    """
    global _port_seconds
    if HAVE_NUMBA and _port_seconds >= MIC_NUMBA_AFTER_SECONDS:
        return _in_unit(r1, r2, r3, mode, _compiled_one)
    t0 = time.perf_counter()
    out = _mic_one_port(r1, r2, r3, mode)
    _port_seconds += time.perf_counter() - t0
    return out


# =============================================================================
# The hook of the protocol
# =============================================================================
class FiveBarWorkspace:
    """The explicit workspace geometry of a :class:`~mechopt.mechanisms.five_bar.model.FiveBar`
    (the contract of :meth:`mechopt.core.protocol.PlanarMechanism.explicit_workspace`).

    Parameters
    ----------
    fb : FiveBar
        The design.
    """

    #: the default raster step of :func:`mechopt.analysis.workspace.usable_region`
    #: (``length_scale/400``) in the design's lengths
    step_text = "(r1 + r2 + r3)/1200"

    def __init__(self, fb):
        self.fb = fb

    def mic(self):
        """``(radius, center_y)`` of the MIC (:func:`five_bar_mic`).

        Returns
        -------
        radius, center_y : float
            [L].
        """
        fb = self.fb
        return five_bar_mic(fb.r1, fb.r2, fb.r3, fb.mode)

    def reach_filter(self):
        """``near(x, y)``: False only where :meth:`FiveBar.type2_function` is certainly NaN
        (a leg cannot assemble), i.e. where ``|P - A_i|`` lies outside
        ``[|r1 - r2| - m, r1 + r2 + m]`` for a leg. The elbows accept a pose while
        ``h^2 = -(q - lo^2)(q - hi^2) / (4 q^2) >= -1e-12`` (``q = |P - A_i|^2``); beyond the
        margin ``m = 1e-3 L + 1e-9 (r1 + r2)^3 / (r1 r2)`` it is below ``-1e-9`` in exact
        arithmetic (``|h^2|`` grows monotonically away from the annulus and is at least
        ``2 m r1 r2 / (r1 + r2)^3`` there), far beyond rounding.

        Returns
        -------
        callable
            ``near(x, y)`` -> boolean array.
        """
        fb = self.fb
        r1, r2, r3 = fb.r1, fb.r2, fb.r3
        hi = r1 + r2
        m = 1e-3 * fb.length_scale + RESOLUTION * hi ** 3 / (r1 * r2)
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

    def no_mic_reason(self) -> str:
        """Why the design has no MIC: the first of the conditions below that fails, else
        the bare finding.

        * ``r3 < r1 + r2``: otherwise no point of the y axis is reachable by both legs;
        * not ``r3 = 0`` in the modes ``"++"``/``"--"`` (both elbows on one point:
          singular everywhere);
        * ``min(r1, r2) >= 1e-9 (r1 + r2 + r3)/3``: the MIC radius never exceeds
          ``min(r1, r2)`` and a radius below 1e-9 of the length scale is not resolved
          in double precision (the test of :func:`mechopt.analysis.workspace.mic`).

        Returns
        -------
        str
            One clause.
        """
        fb = self.fb
        r1, r2, r3 = fb.r1, fb.r2, fb.r3
        scale = (r1 + r2 + r3) / 3.0
        if not r3 < r1 + r2:
            return f"no point of the y axis is reachable by both legs: r3 must be less than r1 + r2 = {r1 + r2:g}"
        if fb.mode in ("++", "--") and r3 <= ROUNDING * scale:
            return (f"with r3 = {r3:g} the working mode {fb.mode!r} puts both elbows on (nearly) one point, "
                    f"singular everywhere: use r3 > {ROUNDING:g} (r1 + r2 + r3)/3 or the mode '+-' or '-+'")
        if min(r1, r2) < RESOLUTION * scale:
            return (f"the MIC radius is at most min(r1, r2) = {min(r1, r2):g}, below {RESOLUTION:g} (r1 + r2 + r3)/3 "
                    f"= {RESOLUTION * scale:g}, the smallest radius double precision resolves here: "
                    "min(r1, r2) must be at least that")
        return "every point of the y axis near the workspace is singular or unreachable in this working mode"

    def radius_bound(self, step, given_step: bool) -> str:
        """The bound on the MIC radius that a raster step ``step`` needs, as a clause of
        :func:`mechopt.analysis.workspace.unusable_message`.

        Parameters
        ----------
        step : float
            The raster step [L].
        given_step : bool
            Whether the caller chose the step.

        Returns
        -------
        str
            The clause, starting ``"; "``.
        """
        fb = self.fb
        need = "" if given_step else " (r1 + r2 + r3)/800 ="
        return (f"; the MIC radius is at most min(r1, r2) = {min(fb.r1, fb.r2):.6g}, so min(r1, r2) "
                f"must be at least about{need} {1.5 * step:.6g}")
