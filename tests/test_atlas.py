"""Five-bar performance atlas (issue 6): fast kernels, accuracy, parallel backends, CLI.

The accuracy reference is built from the library's reference machinery at fine
resolution: the type-II clearance of :func:`mechopt.analysis.workspace.type2_clearance`
(root finding along rays) plus the closed-form serial clearance, maximised over
the centre: a 200-point profile ranks the local maxima and every one of the three
best is refined to 1e-8 of the radius, all designs at once (``_reference_mics``;
``mechopt.analysis.workspace.mic`` refines only the best grid point, and its
48-point grid misses the better of two nearly equal peaks, e.g. (2.2812,
0.4778, 0.241), see :func:`test_fast_mic_finds_the_better_of_two_peaks`); the
disk means of :func:`mechopt.analysis.performance.global_indices` at 96 x 192 nodes; and
for the MCI the best of :func:`mechopt.analysis.performance.max_lci` and a Nelder-Mead
polish of a smooth surrogate from the best node of a 128 x 256 grid
(``max_lci``'s compass search can stall short of a cone apex at LCI = 1).
"""
import json
import os
import socket
import subprocess
import sys
import time

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import minimize

from mechopt import FiveBar
from mechopt.core import indices as ix
from mechopt.mechanisms.five_bar import kernels as K
from mechopt.mechanisms.five_bar.batch import RESULT_COLUMNS, evaluate_designs
from mechopt.run.atlas import compute_atlas, design_grid, index_columns, plane_coordinates, run_atlas
from mechopt.cli import main
from mechopt.analysis.performance import global_indices, max_lci
from mechopt.core.quadrature import disk_rule
from mechopt.analysis.workspace import MIC, mic, type2_clearance

numba_only = pytest.mark.skipif(not K.HAVE_NUMBA, reason="numba not installed")
MODES = ("+-", "-+", "++", "--")


def _random_designs(n, seed, lo=0.0):
    rng = np.random.default_rng(seed)
    r3 = rng.uniform(0.0, 1.5, n)
    r1 = lo + rng.uniform(0.0, 1.0, n) * (3.0 - r3 - 2 * lo)
    return r1, 3.0 - r1 - r3, r3


def _disk_is_free(fb, cy, radius, n_r=300, n_theta=2000):
    dx, dy, _ = disk_rule(radius, "polar", n_r=n_r, n_theta=n_theta)
    f = fb.type2_function(dx, cy + dy)
    f0 = fb.type2_function(0.0, cy)
    return bool(fb.reachable(dx, cy + dy).all() and (np.sign(f) == np.sign(f0)).all())


# --- the design space ---------------------------------------------------------
def test_design_grid_is_liu_space():
    g = design_grid(0.01)
    assert len(g) == 33824
    assert np.allclose(g.r1 + g.r2 + g.r3, 3.0)
    assert (g.r1 > 0).all() and (g.r2 > 0).all() and g.r3.between(0, 1.5).all()
    assert g.r3.max() == 1.5 and g.r3.min() == 0.0
    assert len(design_grid(0.1)) == 344 and len(design_grid(0.5)) == 14
    # any step (3/step not an integer) still keeps r1, r2 > 0 and r3 <= 1.5
    g = design_grid(0.07)
    assert (g.r2 > 0).all() and g.r3.max() <= 1.5 and np.allclose(g.r1 + g.r2 + g.r3, 3.0)


def test_plane_coordinates_are_isometric():
    a = np.array([[0.4, 1.9, 0.7], [1.5, 1.5, 0.0], [2.2, 0.3, 0.5], [0.1, 1.4, 1.5]])
    s, t = plane_coordinates(*a.T)
    d_plane = np.hypot(s[:, None] - s[None, :], t[:, None] - t[None, :])
    d_space = np.linalg.norm(a[:, None, :] - a[None, :, :], axis=-1)
    assert np.allclose(d_plane, d_space, atol=1e-12)
    assert s[1] == 0.0 and t[1] == 0.0  # r1 = r2 on the axis, r3 = 0 at t = 0


# --- local kernels: NumPy vs numba vs the generic path ---------------------------
def _points(n=200_000, seed=3):
    rng = np.random.default_rng(seed)
    x = rng.uniform(-3, 3, n)
    y = rng.uniform(-1, 3, n)
    # add exact type-I poses (on the outer circle of leg 1) and base joints
    ph = rng.uniform(0, np.pi, 50)
    x = np.concatenate([x, -0.55 + 2.45 * np.cos(ph), [-0.55, 0.55]])
    y = np.concatenate([y, 2.45 * np.sin(ph), [0.0, 0.0]])
    return x, y


@pytest.mark.parametrize("mode", MODES)
def test_lci_points_matches_generic_path(mode):
    x, y = _points(20_000)
    fb = FiveBar(0.85, 1.6, 0.55, mode=mode)
    with np.errstate(invalid="ignore"):
        ref = ix.lci(fb.jacobian(x, y))
    # on a type-I locus the LCI ~ sqrt(h^2) amplifies rounding of h^2 ~ 1e-16 to 1e-8
    edge = np.abs(fb.serial_clearance(x, y)) < 1e-6
    assert edge.sum() > 10
    for compiled in (False, True) if K.HAVE_NUMBA else (False,):
        got = K.lci_points(0.85, 1.6, 0.55, x, y, mode=mode, compiled=compiled)
        assert np.max(np.abs(got - ref)[~edge]) < 1e-9
        assert np.max(np.abs(got - ref)[edge]) < 1e-6


@numba_only
@pytest.mark.parametrize("mode", MODES)
def test_lci_numba_equals_numpy_to_1e12(mode):
    x, y = _points()
    for r in [(0.85, 1.6, 0.55), (1.5, 1.2, 0.3), (2.9, 0.05, 0.05), (1.0, 1.0, 0.0)]:
        a = K.lci_points(*r, x, y, mode=mode, compiled=True)
        b = K.lci_points(*r, x, y, mode=mode, compiled=False)
        assert np.max(np.abs(a - b)) <= 1e-12


def test_local_points_match_generic_path_and_numba():
    fb = FiveBar(0.85, 1.6, 0.55)
    dx, dy, _ = disk_rule(0.8, "area", n_r=40, n_theta=80)
    x, y = dx, 1.5025 + dy
    ref = fb.local_indices(x, y)
    ref = np.stack([ref[k] for k in ix.LOCAL_INDEX_NAMES])
    got = K.local_points(0.85, 1.6, 0.55, x, y, compiled=False)
    assert np.allclose(got, ref, rtol=1e-9, atol=1e-12)
    # scale: J ~ 1/L, so |V| ~ L, |tau| ~ 1/L, |D| ~ L^2
    big = K.local_points(8.5, 16.0, 5.5, 10 * x, 10 * y, compiled=False)
    assert np.allclose(big, got * np.array([1, 10, 10, 0.1, 0.1, 100, 100])[:, None], rtol=1e-12)
    if K.HAVE_NUMBA:
        xx, yy = _points(50_000)
        a = K.local_points(0.85, 1.6, 0.55, xx, yy, compiled=True)
        b = K.local_points(0.85, 1.6, 0.55, xx, yy, compiled=False)
        assert np.array_equal(np.isnan(a), np.isnan(b))
        ok = np.isfinite(a) & np.isfinite(b)
        assert np.all(np.abs(a[ok] - b[ok]) <= 1e-12 * np.maximum(1.0, np.abs(b[ok])))


# --- fast MIC ----------------------------------------------------------------
@numba_only
@pytest.mark.parametrize("mode", MODES)
def test_mic_and_disk_stats_numba_equal_numpy(mode):
    r1, r2, r3 = _random_designs(40, seed=5)
    r1, r2, r3 = (np.append(v, w) for v, w in zip((r1, r2, r3), ([1.5, 1.0, 0.75], [1.5, 0.5, 0.75], [0.0, 1.5, 1.5])))
    Ra, Ya = K.mic_batch(r1, r2, r3, mode=mode, compiled=True)
    Rb, Yb = K.mic_batch(r1, r2, r3, mode=mode, compiled=False)
    assert np.allclose(Ra, Rb, rtol=0, atol=1e-12) and np.allclose(Ya, Yb, rtol=0, atol=1e-12)
    for q in ("area", "polar"):
        Sa = K.disk_stats_batch(r1, r2, r3, Ya, Ra, mode=mode, quadrature=q, compiled=True)
        Sb = K.disk_stats_batch(r1, r2, r3, Ya, Ra, mode=mode, quadrature=q, compiled=False)
        assert np.array_equal(np.isnan(Sa), np.isnan(Sb))
        ok = np.isfinite(Sa)
        ok[:, 1] = False
        assert np.allclose(Sa[ok], Sb[ok], rtol=1e-11, atol=1e-13)
        # the MCI ends an iterative search (finite-difference Newton steps): near
        # r3 = 0, where the isotropic points nearly form a curve, rounding moves
        # its last digits
        mci = np.isfinite(Sa[:, 1])
        assert np.allclose(Sa[mci, 1], Sb[mci, 1], rtol=1e-7, atol=0)


@pytest.mark.parametrize("r", [(1.5, 1.2, 0.3), (1.17, 1.45, 0.38), (0.85, 1.6, 0.55),
                               (0.7, 1.7, 0.6), (1.1, 1.65, 0.25), (0.3402, 1.365, 1.2948),
                               (2.7306, 0.0297, 0.2397), (0.729, 1.03, 1.241)])
def test_fast_mic_matches_workspace_mic(r):
    """Designs where the type-II locus limits the MIC, a thin annulus, a centre at y -> 0.
    (The reference's 200 centres find the same peak as 400 on each of these designs, and
    its golden-section refinement ends at the same ``tol``: the two references differ by
    at most 5e-7 relative in the radius, beside the 1e-5 checked.)"""
    fb = FiveBar(*r)
    R, yc = K.mic_batch(*r)
    m = mic(fb, method="rays", n_y=200)
    assert R[0] == pytest.approx(m.radius, rel=1e-5)
    assert yc[0] == pytest.approx(m.center_y, abs=1e-4)


def test_fast_mic_finds_the_better_of_two_peaks():
    """Two centres give nearly the same radius; workspace.mic refines the wrong one."""
    r = (2.2812, 0.4778, 3 - 2.2812 - 0.4778)
    fb = FiveBar(*r)
    R, yc = K.mic_batch(*r)
    m = mic(fb, method="rays", n_y=400)
    assert m.center_y == pytest.approx(2.0298, abs=1e-3)
    assert yc[0] == pytest.approx(2.5082, abs=1e-3) and R[0] > m.radius * (1 + 5e-4)
    # the reference's own clearance at the fast centre confirms the larger radius
    serial = float(fb.serial_clearance(0.0, yc[0]))
    assert min(serial, type2_clearance(fb, 0.0, yc[0], serial)) == pytest.approx(R[0], rel=1e-5)
    assert _disk_is_free(fb, yc[0], R[0] * (1 - 1e-4))
    assert not _disk_is_free(fb, yc[0], R[0] * (1 + 1e-2))


def test_degenerate_designs_get_nan_not_an_error():
    # r3 = 1.5 means r1 + r2 = r3: the only reachable point of the y axis is the origin
    out = evaluate_designs([0.75, 0.1, 1.0], [0.75, 1.4, 1.5], [1.5, 1.5, 0.5])
    assert (out[:2, 0] == 0.0).all() and np.isnan(out[:2, 1:]).all()
    assert np.isfinite(out[2]).all() and out[2, 0] > 0


def test_evaluate_designs_scales_like_global_indices():
    a = evaluate_designs([0.85], [1.6], [0.55])[0]
    b = evaluate_designs([8.5], [16.0], [5.5])[0]
    f = dict(r_mic=10, mic_center_y=10, gci=1, mci=1, gvi_max=10, gvi_min=10, gpi_max=0.1,
             gpi_min=0.1, gsi_max=100, gsi_min=100)
    assert np.allclose(b, a * np.array([f[c] for c in RESULT_COLUMNS]), rtol=1e-9)


# --- accuracy on a random sample against a converged reference ------------------
class _Lengths:
    """Five-bars with per-point lengths (arrays that broadcast against the points),
    for the model's own elementwise formulas: ``FiveBar.serial_clearance`` and
    ``FiveBar.type2_function`` read nothing but ``r1, r2, r3`` and the mode's signs."""

    elbows, _legs = FiveBar.elbows, FiveBar._legs
    serial_clearance, type2_function = FiveBar.serial_clearance, FiveBar.type2_function

    def __init__(self, r1, r2, r3, s1, s2):
        self.r1, self.r2, self.r3, self._s1, self._s2 = r1, r2, r3, s1, s2


class _Designs:
    """Several five-bars as one mechanism for :func:`type2_clearance`: centre ``i``
    (its leading axis) belongs to design ``rows[i]``, so that one call serves the
    centres of every design (the call, not the points, costs most in the refinement)."""

    def __init__(self, fbs, rows):
        self.p = [np.array([getattr(fbs[k], n) for k in rows], float)
                  for n in ("r1", "r2", "r3", "_s1", "_s2")]

    def type2_function(self, x, y):
        shape = (-1,) + (1,) * (np.ndim(x) - 1)
        return _Lengths(*(v.reshape(shape) for v in self.p)).type2_function(x, y)


def _radius_at(fbs, rows, ys, **rays):
    """The MIC radius at the centres ``(0, ys[i])`` of the designs ``fbs[rows[i]]``: the
    serial clearance capped by :func:`type2_clearance` (at its defaults unless ``rays``)."""
    ys = np.asarray(ys, float)
    serial = np.maximum(_Lengths(*_Designs(fbs, rows).p).serial_clearance(0.0, ys), 0.0)
    out = np.zeros_like(ys)
    ok = serial > 0  # (type2_clearance drops centres of radius 0: keep the rows aligned)
    if ok.any():
        out[ok] = np.minimum(serial[ok], type2_clearance(_Designs(fbs, rows[ok]), np.zeros(ok.sum()),
                                                         ys[ok], serial[ok], **rays))
    return out


def _reference_mics(fbs, n_y=200, n_peaks=3, max_rounds=40):
    """For each design the largest ``_radius_at`` over ``0 <= y <= ymax`` (and where).

    1. A profile on ``n_y + 1`` centres with few rays (32 instead of 128): it only
       ranks the profile's local maxima, every value returned comes from
       ``_radius_at`` at the defaults. The ``n_peaks`` best are refined, each over
       its two neighbouring grid cells.
    2. The peaks of all designs are refined at once (one ``type2_clearance`` call
       a round). The radius is a distance to the singular set, a minimum of smooth
       branches, so a peak is a kink where a rising and a falling branch meet (so
       on every one of the 50 designs) or a smooth top. Each peak keeps a bracket
       ``[a, b]``, ``a`` on the rising side and ``b`` on the falling side (signs of
       one-sided slopes over a step ``eps``). The next centre is where the tangents
       at ``a`` and ``b`` meet: exact for a V of straight branches, so its error is
       of second order in the bracket (``w^2 / L`` for branches curved on a length
       ``L``). It is kept 1 % of the bracket away from both ends, so that a bracket
       shrinks at least 100 times every other round even when the tangents are
       noisy (slopes to about 1e-4). The new centre replaces the end on its side; a
       centre falling behind and rising ahead is a top within ``eps``. When the
       same end was replaced twice running (the tangent of a convex branch keeps
       landing on the near side) the next centre is moved past the estimate
       towards the stale end, so that both ends close in. A bracket whose ends
       have slopes of the wrong signs (not unimodal, or a top on the border of
       ``[0, ymax]``) is bisected. A peak stops when its bracket is below ``tol``
       or when it cannot beat the best value of its design: the radius is
       1-Lipschitz in the centre, so over ``[a, b]`` it stays below
       ``(f(a) + f(b) + b - a) / 2``.

    Returns the best value evaluated for each design: with ``tol = 1e-8`` of the
    radius, the value to about 1e-8 relative (the centre to ``tol`` where the V's
    slopes are of order 1).
    """
    D = len(fbs)
    ymax = np.array([fb.bounding_box()[3] for fb in fbs])
    ys = ymax[:, None] * np.arange(n_y + 1) / n_y
    rows, a, b, scale = [], [], [], np.empty(D)
    for d, fb in enumerate(fbs):
        rs = _radius_at(fbs, np.full(n_y + 1, d), ys[d], n_phi=32, n_r=24, n_refine=8)
        peaks = [j for j in range(n_y + 1) if rs[j] > 0 and (j == 0 or rs[j] >= rs[j - 1])
                 and (j == n_y or rs[j] >= rs[j + 1])]
        scale[d] = max(float(rs.max()), 1e-3 * ymax[d])  # for the tolerances
        for j in sorted(peaks, key=lambda j: -rs[j])[:n_peaks]:
            rows.append(d)
            a.append(ys[d, max(j - 1, 0)])
            b.append(ys[d, min(j + 1, n_y)])
    rows, a, b = np.array(rows, int), np.array(a), np.array(b)
    best_r, best_y = np.zeros(D), np.full(D, np.nan)
    if rows.size == 0:
        return [MIC(radius=0.0, center_y=np.nan)] * D
    eps, tol, top = 1e-9 * scale[rows], 1e-8 * scale[rows], ymax[rows]

    def evaluate(k, y, sides):
        """Radius at the centres ``y`` of the peaks ``k`` and the slopes towards
        ``y + s eps`` for each ``s`` of ``sides`` (towards ``y - s eps`` where that
        leaves ``[0, ymax]``: the same slope)."""
        pts = [y]
        for s in sides:
            z = y + s * eps[k]
            pts.append(np.where((z < 0) | (z > top[k]), y - s * eps[k], z))
        P = np.stack(pts)
        R = _radius_at(fbs, np.tile(rows[k], len(pts)), P.ravel()).reshape(P.shape)
        for d, r, z in zip(np.tile(rows[k], len(pts)), R.ravel(), P.ravel()):
            if r > best_r[d]:
                best_r[d], best_y[d] = r, z
        return [R[0]] + [(R[i] - R[0]) / (P[i] - P[0]) for i in range(1, len(pts))]

    every = np.arange(rows.size)
    fa, sa = evaluate(every, a, [-1])
    fb_, sb = evaluate(every, b, [+1])
    stale = np.zeros(rows.size, int)  # 1 / 2: a replaced once / twice running; -1 / -2: b
    live = np.ones(rows.size, bool)
    for _ in range(max_rounds):
        w = b - a
        live &= (w > tol) & (0.5 * (fa + fb_ + w) > best_r[rows])
        if not live.any():
            break
        unimodal = (sa > 0) & (sb < 0)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = (fb_ - fa + sa * a - sb * b) / (sa - sb)  # where the two tangents meet
        past = 2 * np.where(stale > 0, c - a, b - c)
        c = np.where(stale == 2, c + past, np.where(stale == -2, c - past, c))
        c = np.where(unimodal & np.isfinite(c), c, 0.5 * (a + b))
        i = np.flatnonzero(live)
        c = np.clip(c, a + 0.01 * w, b - 0.01 * w)[i]
        fc, behind, ahead = evaluate(i, c, [-1, +1])
        rising = (behind > 0) & (ahead > 0)
        at_top = (behind >= 0) & (ahead <= 0) & ~rising
        falling = ~rising & ~at_top  # (also a local minimum: taken as the new b)
        a[i[rising]], fa[i[rising]], sa[i[rising]] = c[rising], fc[rising], ahead[rising]
        b[i[falling]], fb_[i[falling]], sb[i[falling]] = c[falling], fc[falling], behind[falling]
        stale[i[rising]] = np.where(stale[i[rising]] > 0, 2, 1)
        stale[i[falling]] = np.where(stale[i[falling]] < 0, -2, -1)
        live[i[at_top]] = False
    assert not live.any(), "the reference MIC search did not converge"
    return [MIC(radius=float(r), center_y=float(y)) for r, y in zip(best_r, best_y)]


def _reference_mci(fb, m):
    cy, R = m.center_y, m.radius
    dx, dy, _ = disk_rule(R, "polar", n_r=128, n_theta=256)
    v = fb.lci(dx, cy + dy)
    k = int(np.argmax(v))

    def proj(p):
        r = np.hypot(*p)
        return p if r <= R else p * (R / r)

    def f(p):  # smooth in p: (1 - LCI^2)^2 = P Q / s_max^4 (no cone at LCI = 1)
        c = float(fb.lci(*(proj(p) + [0.0, cy])))
        return (1 - c * c) ** 2 + max(np.hypot(*p) - R, 0.0)

    res = minimize(f, np.array([dx[k], dy[k]]), method="Nelder-Mead",
                   options={"xatol": 1e-12, "fatol": 1e-16, "maxiter": 4000})
    p = proj(res.x)
    return max(float(v[k]), float(fb.lci(p[0], cy + p[1])), max_lci(fb, cy, R))


def _reference(designs):
    """Reference rows (area, polar) of each design of ``designs`` (one MIC search for all)."""
    fbs = [FiveBar(*r) for r in designs]
    out = []
    for fb, m in zip(fbs, _reference_mics(fbs)):
        mci = _reference_mci(fb, m)
        rows = []
        for q in ("area", "polar"):
            g = global_indices(fb, q, mic=m, n_r=96, n_theta=192)
            g["mci"] = mci
            rows.append(g)
        out.append(rows)
    return out


def test_atlas_indices_within_1e3_of_converged_reference_on_50_random_designs():
    from joblib import Parallel, delayed

    r1, r2, r3 = _random_designs(50, seed=0)
    designs = list(zip(r1, r2, r3))
    # one half of the designs a worker (every other one: the halves cost the same), so
    # that the MIC search batches the designs of a half; then back in the designs' order
    even, odd = Parallel(n_jobs=2)(delayed(_reference)(designs[k::2]) for k in range(2))
    refs = [r for pair in zip(even, odd) for r in pair]
    worst = {}
    for qi, q in enumerate(("area", "polar")):
        fast = pd.DataFrame(evaluate_designs(r1, r2, r3, quadrature=q), columns=RESULT_COLUMNS)
        ref = pd.DataFrame([r[qi] for r in refs])
        assert np.allclose(fast.mic_center_y, ref.mic_center_y, rtol=0, atol=1e-3)
        for c in RESULT_COLUMNS:
            if c == "mic_center_y":
                continue
            err = np.abs(fast[c] / ref[c] - 1.0)
            worst[(q, c)] = float(err.max())
    bad = {k: v for k, v in worst.items() if not v <= 1e-3}
    assert not bad, bad


# --- parallel backends and the command line ---------------------------------------
def test_cli_atlas_with_region(tmp_path, capsys):
    out = tmp_path / "atlas"
    assert main(["atlas", "five-bar", "--step", "0.1", "--out", str(out), "--n-jobs", "2",
                 "--where", "r_mic > 0.8 and (gci > 0.6 or mci >= 0.99)"]) == 0
    table = pd.read_csv(out / "atlas.csv")
    assert list(table.columns) == ["r1", "r2", "r3", "s", "t"] + list(index_columns("gci,mci,gvi,gpi,gsi,r_mic"))
    assert len(table) == 344
    nan_rows = table.gci.isna()
    assert (table.r3[nan_rows] == 1.5).all() and nan_rows.sum() == 14
    region = pd.read_csv(out / "region.csv")
    sel = (table.r_mic > 0.8) & ((table.gci > 0.6) | (table.mci >= 0.99))
    assert len(region) == sel.sum() > 0
    assert np.allclose(region[["r1", "r2", "r3"]].to_numpy(), table.loc[sel, ["r1", "r2", "r3"]].to_numpy())
    for c in ("r_mic", "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min"):
        png = out / f"atlas_{c}.png"
        assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"
    assert "344 designs" in capsys.readouterr().out


def test_index_selection_and_polar(tmp_path):
    man = run_atlas(tmp_path, step=0.25, indices="gsi,gci", quadrature="polar", n_jobs=1,
                    figures=False, verbose=False)
    table = pd.read_csv(tmp_path / "atlas.csv")
    assert list(table.columns)[5:] == ["r_mic", "mic_center_y", "gsi_max", "gsi_min", "gci"]
    assert man["quadrature"] == "polar" and man["n_designs"] == len(table)
    direct = evaluate_designs(table.r1, table.r2, table.r3, quadrature="polar")
    assert np.allclose(table.gci, direct[:, RESULT_COLUMNS.index("gci")], equal_nan=True, rtol=1e-9)


def test_joblib_result_does_not_depend_on_workers_or_chunks():
    a = compute_atlas(step=0.2, n_jobs=1)
    b = compute_atlas(step=0.2, n_jobs=2, chunk_size=7)
    pd.testing.assert_frame_equal(a, b, check_exact=True)


def test_dask_localcluster_equals_joblib(tmp_path):
    # equality does not depend on the grid's size: 84 designs (--step 0.2; was 0.1, 344
    # designs in one chunk of 512), in chunks of 16 so that both workers compute some
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster:
        assert main(["atlas", "five-bar", "--step", "0.2", "--chunk-size", "16", "--no-figures", "--out",
                     str(tmp_path / "dask"), "--dask", cluster.scheduler_address]) == 0
    assert main(["atlas", "five-bar", "--step", "0.2", "--no-figures", "--out",
                 str(tmp_path / "joblib"), "--n-jobs", "2"]) == 0
    a = pd.read_csv(tmp_path / "dask" / "atlas.csv")
    b = pd.read_csv(tmp_path / "joblib" / "atlas.csv")
    pd.testing.assert_frame_equal(a, b, check_exact=True)


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.parametrize("argv, message", [
    (["--step", "0"], "step must lie in (0, 0.5]"),
    (["--step", "-0.1"], "step must lie in (0, 0.5]"),
    (["--step", "0.6"], "step must lie in (0, 0.5]"),
    (["--step", "nan"], "step must be finite"),
    (["--step", "abc"], "invalid float value"),
    (["--index", "gci,foo"], "index must be one of"),
    (["--index", "gci,,mci"], "index must be a comma-separated list"),
    (["--quadrature", "gauss"], "quadrature must be one of"),
    (["--mode", "+/"], "mode must be one of"),
    (["--n-jobs", "0"], "n_jobs must be a positive integer"),
    (["--where", "r_mic >"], "where: expected a name or a number"),
    (["--where", "r_mic > 0.8 and"], "where: expected a name or a number"),
    (["--where", "gci 0.5"], "where: expected a comparison operator"),
    (["--where", "(gci > 0.5"], "where: expected ')'"),
    (["--where", "__import__('os').system('true')"], "where: unexpected character"),
    (["--where", "foo > 1"], "where: unknown name 'foo'"),
    (["--index", "gci", "--where", "gsi_max > 1"], "where: unknown name 'gsi_max'"),
    (["--n-jobs", "2", "--dask", "tcp://127.0.0.1:1"], "not allowed with argument"),
])
def test_bad_input_is_one_line_exit_2(tmp_path, capsys, argv, message):
    assert main(["atlas", "five-bar", "--out", str(tmp_path / "o"), *argv]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("mechopt: error: ")
    assert message in err
    assert not (tmp_path / "o" / "atlas.csv").exists()


def test_unreachable_scheduler_is_one_line_exit_3(tmp_path, capsys):
    pytest.importorskip("dask.distributed")
    address = f"tcp://127.0.0.1:{_free_port()}"
    t = time.perf_counter()
    assert main(["atlas", "five-bar", "--step", "0.5", "--out", str(tmp_path),
                 "--dask", address, "--dask-timeout", "1"]) == 3  # a runtime failure
    assert time.perf_counter() - t < 30
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "cannot reach the Dask scheduler" in err and address in err


def test_numba_is_optional():
    """Without numba the kernels fall back to NumPy (same values)."""
    code = ("import mechopt.mechanisms.five_bar.kernels as K, numpy as np; assert not K.HAVE_NUMBA; "
            "from mechopt.run.atlas import evaluate_designs; "
            "import json; print(json.dumps(evaluate_designs([0.85, 1.5], [1.6, 1.2], [0.55, 0.3]).tolist()))")
    env = dict(os.environ, MECHOPT_NO_NUMBA="1")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)
    assert proc.returncode == 0, proc.stderr
    got = np.array(json.loads(proc.stdout))
    ref = evaluate_designs([0.85, 1.5], [1.6, 1.2], [0.55, 0.3])
    assert np.allclose(got, ref, rtol=1e-11, atol=1e-13)


@pytest.mark.slow
def test_full_atlas_step_001_within_60_s_on_two_cores(tmp_path):
    t = time.perf_counter()
    assert main(["atlas", "five-bar", "--step", "0.01", "--n-jobs", "2", "--out", str(tmp_path),
                 "--where", "r_mic > 0.8 and gci > 0.6"]) == 0
    wall = time.perf_counter() - t
    table = pd.read_csv(tmp_path / "atlas.csv")
    assert len(table) == 33824 and table.gci.notna().sum() == 33824 - 149
    assert wall <= 60.0, wall
