"""Global performance indices: means of local indices over a region.

Liu 2006 defines every global index as an area mean over a workspace W
(eq. 4, 11, 14, 19):

* GCI ``eta_J`` (mean LCI) and MCI (maximum LCI) over the maximal inscribed
  workspace (the MIC disk);
* GVI ``eta_Vmax/min``, GPI ``eta_Fmax/min`` and GSI ``eta_Dmax/min`` over the
  concentric disk of radius ``r_MIC/2`` (Liu 3.2.2: the extremes blow up near
  the singular loci);
* over the good-conditioning workspace (sec. 3.2.3): GCI and GSI.

The quadrature is named (``area`` or ``polar``, see :mod:`mechopt.core.quadrature`)
and is reported with every result.
"""
from __future__ import annotations

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v
from mechopt.core.numerics import golden_section_max
from mechopt.core.quadrature import QUADRATURES, disk_rule
from mechopt.analysis.workspace import MIC, Region, _blocks, mic as _mic

__all__ = ["disk_mean", "global_indices", "region_indices", "max_lci"]
# local index behind each global mean over the half-radius disk
_HALF_DISK = {
    "gvi_max": "v_max", "gvi_min": "v_min",
    "gpi_max": "tau_max", "gpi_min": "tau_min",
    "gsi_max": "d_max", "gsi_min": "d_min",
}


def disk_mean(mech, center_y, radius, quadrature="area", n_r=None, n_theta=None):
    """Means of every local index over the disk of ``radius`` centred at ``(0, center_y)``.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    center_y : float
        Ordinate of the disk's centre [L].
    radius : float
        The disk's radius [L], >= 0.
    quadrature : {"area", "polar"}
        The rule of :func:`mechopt.core.quadrature.disk_rule` ("polar": Liu 2006's
        mean over radius and angle; "area": the area mean).
    n_r, n_theta : int, optional
        Nodes in radius and angle (default: the rule's).

    Returns
    -------
    dict
        ``{name: float}`` keyed by :data:`mechopt.core.indices.LOCAL_INDEX_NAMES`, in
        the indices' units.

    Raises
    ------
    ValueError
        For an unknown quadrature, a negative radius or a non-finite centre.
    """
    kw = {k: v for k, v in (("n_r", n_r), ("n_theta", n_theta)) if v is not None}
    center_y = _v.position("center_y", center_y)
    dx, dy, w = disk_rule(radius, quadrature, **kw)
    loc = mech.local_indices(dx, center_y + dy)
    return {k: float(np.sum(w * v)) for k, v in loc.items()}


#: ``g`` below which a point counts as isotropic (``1 - LCI ~ sqrt(g) ~ 1e-13``)
_G_ISO = 1e-26
#: most Newton iterations of the isotropy search (it converges quadratically or not at all)
_NEWTON_MAX = 16


def _iso_residual(mech, x, y):
    """Isotropy residual ``r = (G11 - G22, 2 G12) / tr G`` of ``G = J^T J`` at the
    points ``(x, y)`` (1-D arrays): ``r = 0`` exactly where ``LCI = 1``, and
    ``|r|^2 = g = ((1 - LCI^2) / (1 + LCI^2))^2``, a smooth function decreasing
    in LCI (no cone at the isotropic points). NaN where J is not finite or zero."""
    J = np.asarray(mech.jacobian(x, y), dtype=float)
    a, b, c, d = J[..., 0, 0], J[..., 0, 1], J[..., 1, 0], J[..., 1, 1]
    g11 = a * a + c * c
    g22 = b * b + d * d
    t = g11 + g22
    t = np.where(t > 0, t, np.nan)
    return (g11 - g22) / t, 2.0 * (a * b + c * d) / t


def _into_disk(px, py, radius):
    """Points radially projected onto the closed disk of ``radius`` about 0."""
    rr = np.hypot(px, py)
    s = np.where(rr > radius, radius / np.where(rr > 0, rr, 1.0), 1.0)
    return px * s, py * s


def _stencil_residuals(mech, px, py, cy, h, n):
    """``r`` at ``p`` and at ``p + h`` times the first ``n`` offsets of
    (0,0), (+x), (-x), (+y), (-y), (+x+y): arrays of shape (K, n)."""
    ox = np.array([0.0, h, -h, 0.0, 0.0, h])[:n]
    oy = np.array([0.0, 0.0, 0.0, h, -h, h])[:n]
    X = (px[:, None] + ox).ravel()
    Y = (py[:, None] + oy).ravel()
    r1, r2 = _iso_residual(mech, X, cy + Y)
    return r1.reshape(-1, n), r2.reshape(-1, n)


def _jac_r(r1, r2, h):
    """Central-difference Jacobian ``dr/dp`` from :func:`_stencil_residuals`."""
    return ((r1[:, 1] - r1[:, 2]) / (2 * h), (r1[:, 3] - r1[:, 4]) / (2 * h),
            (r2[:, 1] - r2[:, 2]) / (2 * h), (r2[:, 3] - r2[:, 4]) / (2 * h))


def _newton_isotropy(mech, px, py, cy, radius, h, n_iter):
    """Plain Newton on ``r(p) = 0`` from every start at once (steps capped at
    ``radius/2``, iterates projected into the disk). No descent test: near an
    almost degenerate isotropic point ``g`` is a long curved valley (the five-bar
    with nearly coincident base joints, whose isotropic points form a circle when
    ``r3 = 0``), where monotone methods crawl but Newton jumps. Every 4
    iterations the worse half of the starts (by ``g``) is dropped. Stops at the
    first isotropic point (``g < _G_ISO``). Returns the best point visited and
    its ``g``."""
    bx, by, bg = px[:1].copy(), py[:1].copy(), np.full(1, np.inf)
    for it in range(n_iter):
        r1, r2 = _stencil_residuals(mech, px, py, cy, h, 5)
        g = r1[:, 0] ** 2 + r2[:, 0] ** 2
        k = int(np.argmin(np.where(np.isfinite(g), g, np.inf)))
        if g[k] < bg[0]:
            bx, by, bg = px[k:k + 1].copy(), py[k:k + 1].copy(), g[k:k + 1].copy()
        if bg[0] < _G_ISO:
            break
        j11, j12, j21, j22 = _jac_r(r1, r2, h)
        det = j11 * j22 - j12 * j21
        dx = -(j22 * r1[:, 0] - j12 * r2[:, 0]) / det
        dy = -(j11 * r2[:, 0] - j21 * r1[:, 0]) / det
        step = np.hypot(dx, dy)
        keep = np.isfinite(step) & (step > _v.STEP_FLOOR * radius) & np.isfinite(g)
        if it % 4 == 3 and keep.sum() > 8:  # keep the better half
            keep &= g <= np.median(g[keep])
        if not keep.any():
            break
        px, py, dx, dy, step = px[keep], py[keep], dx[keep], dy[keep], step[keep]
        cap = np.where(step > 0.5 * radius, 0.5 * radius / step, 1.0)
        px, py = _into_disk(px + cap * dx, py + cap * dy, radius)
    return bx[0], by[0], bg[0]


def _trust_region_step(gx, gy, hxx, hxy, hyy, delta, n_sec=12):
    """Minimiser of the model ``grad.d + d.H.d/2`` over ``|d| <= delta`` for K 2x2
    problems at once: in the eigenbasis of H, ``d(mu) = -(H + mu I)^-1 grad`` with
    ``mu = 0`` if H is positive definite and the Newton step fits, else the ``mu >
    max(0, -lambda_min)`` with ``|d(mu)| = delta`` (More-Sorensen: Newton on
    ``1/|d| - 1/delta``), plus a move along the bottom eigenvector in the "hard
    case". Returns ``(dx, dy, predicted decrease of the model)``."""
    disc = np.hypot(0.5 * (hxx - hyy), hxy)
    l1 = 0.5 * (hxx + hyy) - disc  # smaller eigenvalue
    l2 = 0.5 * (hxx + hyy) + disc
    big = hxx >= hyy  # eigenvector e of l2 from the better-conditioned row
    ax, ay = np.where(big, l2 - hyy, hxy), np.where(big, hxy, l2 - hxx)
    n = np.hypot(ax, ay)
    ok = n > 0
    n = np.where(ok, n, 1.0)
    ex, ey = np.where(ok, ax / n, 1.0), np.where(ok, ay / n, 0.0)
    ge = gx * ex + gy * ey  # gradient in the eigenbasis (e, f = e turned by +90 deg)
    gf = gy * ex - gx * ey
    newton = (l1 > 0) & (np.hypot(ge / l2, gf / l1) <= delta)
    mu_lo = np.maximum(0.0, -l1)
    mu = mu_lo + _v.ROUNDING * (np.abs(l1) + np.abs(l2)) + 1e-300
    for _ in range(n_sec):
        de, df = -ge / (l2 + mu), -gf / (l1 + mu)
        nrm = np.hypot(de, df)
        q = de * de / (l2 + mu) + df * df / (l1 + mu)  # -d|d|^2/dmu / 2
        new = mu + (nrm * nrm / q) * (nrm - delta) / delta
        mu = np.maximum(new, mu_lo + 0.5 * (mu - mu_lo))  # stays right of the pole
    mu = np.where(newton, 0.0, mu)
    de, df = -ge / (l2 + mu), -gf / (l1 + mu)
    nrm = np.hypot(de, df)
    short = ~newton & (nrm < delta)  # hard case: reach the boundary along f
    tau = np.sqrt(np.maximum(delta * delta - nrm * nrm, 0.0))
    df = np.where(short, df + np.where(gf > 0, -tau, tau), df)
    nrm = np.hypot(de, df)
    s = np.where(nrm > delta, delta / nrm, 1.0)
    de, df = de * s, df * s
    pred = -(ge * de + gf * df + 0.5 * (l2 * de * de + l1 * df * df))
    return de * ex - df * ey, de * ey + df * ex, pred


def _trust_region(mech, px, py, cy, radius, h, delta0, n_iter):
    """Trust-region Newton minimising ``g`` (i.e. maximising LCI) from K starts at
    once; gradient and Hessian of ``g = |r|^2`` from central differences of ``r``
    (a 6-point stencil), trial points projected into the disk, a step kept only
    if it lowers ``g``. Converges to interior local maxima whether isotropic or
    not. Returns the final points."""
    delta = np.full(px.shape, float(delta0))
    live = np.ones(px.shape, bool)
    for _ in range(n_iter):
        r1, r2 = _stencil_residuals(mech, px, py, cy, h, 6)
        a1, a2 = r1[:, 0], r2[:, 0]
        g0 = a1 * a1 + a2 * a2
        live &= np.isfinite(g0) & (g0 > _G_ISO)
        if not live.any():
            break
        r1x, r1y, r2x, r2y = _jac_r(r1, r2, h)
        h2 = h * h
        r1xx, r2xx = (r1[:, 1] - 2 * a1 + r1[:, 2]) / h2, (r2[:, 1] - 2 * a2 + r2[:, 2]) / h2
        r1yy, r2yy = (r1[:, 3] - 2 * a1 + r1[:, 4]) / h2, (r2[:, 3] - 2 * a2 + r2[:, 4]) / h2
        r1xy = (r1[:, 5] - r1[:, 1] - r1[:, 3] + a1) / h2
        r2xy = (r2[:, 5] - r2[:, 1] - r2[:, 3] + a2) / h2
        gx, gy = 2 * (r1x * a1 + r2x * a2), 2 * (r1y * a1 + r2y * a2)
        hxx = 2 * (r1x * r1x + r2x * r2x + a1 * r1xx + a2 * r2xx)
        hyy = 2 * (r1y * r1y + r2y * r2y + a1 * r1yy + a2 * r2yy)
        hxy = 2 * (r1x * r1y + r2x * r2y + a1 * r1xy + a2 * r2xy)
        dx, dy, pred = _trust_region_step(gx, gy, hxx, hxy, hyy, delta)
        step = np.hypot(dx, dy)
        tx, ty = _into_disk(px + dx, py + dy, radius)
        q1, q2 = _iso_residual(mech, tx, cy + ty)
        gt = q1 * q1 + q2 * q2
        rho = (g0 - gt) / pred
        acc = live & (gt < g0)
        px, py = np.where(acc, tx, px), np.where(acc, ty, py)
        delta = np.where(rho > 0.25, np.where((rho > 0.75) & (step > 0.99 * delta),
                                              np.minimum(2.0 * delta, radius), delta), 0.25 * step)
        # converged: nothing left to gain above rounding, or the region has collapsed
        live &= np.isfinite(delta) & (delta > _v.ROUNDING * radius) & ~(pred <= _v.STEP_FLOOR * g0)
    return px, py


def _rim_search(mech, cy, radius, n_rim, n_best, n_iter):
    """Best LCI on the rim: ``n_rim`` samples, then a golden-section search in the
    angle (all at once) around each of the ``n_best`` best sampled local maxima."""
    def f(t):
        return np.asarray(mech.lci(radius * np.cos(t), cy + radius * np.sin(t)), float)

    ph = 2.0 * np.pi * np.arange(n_rim) / n_rim
    v = f(ph)
    best = float(np.max(v))
    if n_iter <= 0 or n_rim < 3:
        return best
    k = np.flatnonzero((v >= np.roll(v, 1)) & (v >= np.roll(v, -1)))
    k = k[np.argsort(-v[k], kind="stable")][:n_best]
    dph = 2.0 * np.pi / n_rim
    g = golden_section_max(f, ph[k] - dph, ph[k] + dph, max_iter=n_iter)
    return max(best, float(np.max(g.f1)), float(np.max(g.f2)))


def _grid_local_maxima(v, n_r, n_theta):
    """Flat indices of the nodes of a polar grid (``disk_rule`` order, ring-major)
    not below any of their four neighbours (the innermost ring's inward
    neighbour is the node opposite it)."""
    V = v.reshape(n_r, n_theta)
    inner = np.empty_like(V)
    inner[1:] = V[:-1]
    inner[0] = np.roll(V[0], n_theta // 2)
    outer = np.full_like(V, -np.inf)
    outer[:-1] = V[1:]
    loc = (V >= np.roll(V, 1, 1)) & (V >= np.roll(V, -1, 1)) & (V >= inner) & (V >= outer)
    return np.flatnonzero(loc.ravel())


def max_lci(mech, center_y, radius, n_r=64, n_theta=128, iters=40, n_seeds=6):
    """Maximum LCI over a disk: the MCI of Liu 2006 sec. 2.1.

    What is maximised: ``LCI = s_min / s_max`` of ``mech.jacobian`` (1 at an
    isotropic point), over the closed disk of ``radius`` centred at
    ``(0, center_y)`` (the MIC for the MCI). Only ``mech.lci`` and
    ``mech.jacobian`` are used, so any mechanism of the protocol works.

    Algorithm. LCI has a cone apex where it reaches 1, so the searches work on
    the isotropy residual ``r = (G11 - G22, 2 G12) / tr G`` of ``G = J^T J``
    instead: ``r = 0`` exactly where ``LCI = 1`` and ``g = |r|^2 =
    ((1 - LCI^2)/(1 + LCI^2))^2`` is smooth and decreases as LCI grows.

    1. LCI on a polar grid of ``n_r x n_theta`` nodes (:func:`disk_rule`).
    2. Isotropic points: plain Newton on ``r = 0`` (central differences, no
       descent test, so that it crosses the long curved valleys of nearly
       degenerate designs) from the nodes of a ``n_r/4 x n_theta/4`` polar grid,
       all at once, at most ``min(iters, 16)`` iterations, the worse half of the
       starts dropped every 4. As soon as a point with ``g < 1e-26`` is found in
       the disk, its LCI (1 to about 1e-13) is the answer: nothing is larger.
    3. Otherwise interior maxima: trust-region Newton on ``g`` (exact 2x2
       subproblem, at most ``iters`` iterations) from the ``n_seeds`` best local
       maxima of the grid.
    4. Maxima on the rim: ``2 n_theta`` samples, then a golden-section search in
       the angle (``iters + 20`` iterations) around the ``n_seeds`` best local
       maxima of the samples.

    Returns the largest LCI evaluated (with ``mech.lci``) at a point of the
    disk, capped at 1: always attained, so never above the true maximum, and
    never below the best grid node. Tolerance: ``|MCI - 1| < 1e-12`` when an
    isotropic point is found; at a non-isotropic interior or rim maximum the
    location converges to ~1e-10 ``radius`` and the value to rounding
    (~1e-14). A maximum whose basin none of the grids resolves (narrower than
    about ``radius / n_r``) can be missed. Checked against the atlas kernel and
    independent maximisers in ``tests/test_mci.py``. Deterministic; about 1 ms
    (isotropic point found) to 10 ms for a five-bar at the defaults.
    ``iters = 0`` returns the best grid node or rim sample.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    center_y : float
        Ordinate of the disk's centre [L].
    radius : float
        The disk's radius [L].
    n_r, n_theta : int
        The polar grid of step 1.
    iters : int
        Most iterations of the local searches (0: the grid and rim samples alone).
    n_seeds : int
        Local maxima of the grid (and of the rim samples) the searches start from.

    Returns
    -------
    float
        The MCI (dimensionless, in [0, 1]).
    """
    center_y = _v.position("center_y", center_y)
    iters = _v.integer("iters", iters, 0)
    n_seeds = _v.integer("n_seeds", n_seeds, 1)
    n_r = _v.integer("n_r", n_r, 1)
    dx, dy, _ = disk_rule(radius, "polar", n_r=n_r, n_theta=n_theta)
    n_theta = dx.size // n_r
    cy = center_y
    R = float(radius)  # a finite number >= 0 (disk_rule)
    if R == 0.0:
        return min(float(np.asarray(mech.lci(0.0, cy), float)), 1.0)
    lci = lambda x, y: np.asarray(mech.lci(x, cy + y), float)  # noqa: E731
    v = lci(dx, dy)
    best = float(np.max(v))
    if iters == 0:
        return min(max(best, _rim_search(mech, cy, R, 2 * n_theta, n_seeds, 0)), 1.0)
    h = max(1e-5 * R, _v.ROUNDING * (abs(cy) + R))  # finite-difference step
    with np.errstate(all="ignore"):  # NaN (unreachable) points are simply never accepted
        # 2. isotropic points
        sx, sy, _ = disk_rule(R, "polar", n_r=max(1, n_r // 4), n_theta=max(1, n_theta // 4))
        bx, by, bg = _newton_isotropy(mech, sx, sy, cy, R, h, min(iters, _NEWTON_MAX))
        best = max(best, float(lci(np.array([bx]), np.array([by]))[0]))
        if bg < _G_ISO:
            return min(best, 1.0)
        # 3. interior local maxima
        seeds = _grid_local_maxima(v, n_r, n_theta)
        seeds = seeds[np.argsort(-v[seeds], kind="stable")][:n_seeds]
        if seeds.size == 0:  # only with NaN values from a foreign ``lci``
            seeds = np.array([int(np.argmax(v))])
        px, py = _trust_region(mech, dx[seeds], dy[seeds], cy, R, h, R / n_r, iters)
        best = max(best, float(np.max(lci(px, py))))
        # 4. the rim
        best = max(best, _rim_search(mech, cy, R, 2 * n_theta, n_seeds, iters + 20))
    return min(best, 1.0)


def global_indices(mech, quadrature: str = "area", mic: MIC | None = None, **rule) -> dict:
    """Liu 2006 global indices of ``mech`` (eq. 4, 11, 14, 19) with the named quadrature.

    Returns a dict with ``r_mic``, ``mic_center_y`` and :data:`mechopt.core.indices.GLOBAL_INDEX_NAMES`.
    Lengths are those of ``mech`` [L]; GVI scales as L, GPI as 1/L, GSI as L^2.
    ``mci`` is the maximum LCI over the MIC by :func:`max_lci` (at its defaults; a
    maximum, so it depends on neither ``quadrature`` nor ``rule``). The atlas
    kernel computes it by another algorithm (``tests/test_mci.py`` compares them).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``disk_indices`` (symmetric about the y axis).
    quadrature : {"area", "polar"}
        The rule of the disk means (:func:`disk_mean`).
    mic : mechopt.analysis.workspace.MIC, optional
        The MIC when already computed (default: :func:`mechopt.analysis.workspace.mic`).
    **rule
        ``n_r``, ``n_theta`` of the quadrature.

    Returns
    -------
    dict
        ``r_mic`` and ``mic_center_y`` [L], ``gci`` and ``mci`` (dimensionless),
        ``gvi_*`` [L per rad], ``gpi_*`` [per L], ``gsi_*`` [L^2] (GVI, GPI, GSI over
        the half-radius disk, Liu 2006 sec. 2).

    Raises
    ------
    ValueError
        For an unknown quadrature, or a design without a MIC.
    """
    _v.choice("quadrature", quadrature, QUADRATURES)
    m = _mic(mech) if mic is None else mic
    full = disk_mean(mech, m.center_y, m.radius, quadrature, **rule)
    half = disk_mean(mech, m.center_y, 0.5 * m.radius, quadrature, **rule)
    out = {"r_mic": m.radius, "mic_center_y": m.center_y, "gci": full["lci"],
           "mci": max_lci(mech, m.center_y, m.radius)}
    out.update({name: half[loc] for name, loc in _HALF_DISK.items()})
    return out


def region_indices(mech, region: Region) -> dict:
    """Area means over a raster region (e.g. the GCW).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    region : mechopt.core.quadrature.Region
        A raster region (cells and mask).

    Returns
    -------
    dict
        ``gci`` (dimensionless), ``gsi_max`` and ``gsi_min`` [L^2 for cranks]; NaN for
        an empty region (no mean exists).
    """
    if not region.mask.any():
        return {"gci": np.nan, "gsi_max": np.nan, "gsi_min": np.nan}
    x, y = region.points()
    # the local indices are pointwise: computed in blocks (bounded temporaries), then
    # each mean over the whole array at once (the same sum as without blocks)
    loc = {k: np.empty(x.size) for k in ("lci", "d_max", "d_min")}
    for sl in _blocks(x.size):
        part = _ix.local_indices(mech.jacobian(x[sl], y[sl]))
        for k, v in loc.items():
            v[sl] = part[k]
    return {"gci": float(np.mean(loc["lci"])),
            "gsi_max": float(np.mean(loc["d_max"])),
            "gsi_min": float(np.mean(loc["d_min"]))}
