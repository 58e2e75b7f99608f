"""MCI (maximum LCI over the MIC disk, Liu 2006 sec. 2.1) by two independent algorithms.

* :func:`mechopt.performance.max_lci`, called by ``global_indices``: generic (only
  ``mech.lci`` and ``mech.jacobian``); Newton on the isotropy residual of
  ``J^T J`` from a grid of starts, trust-region Newton on a smooth surrogate from
  the best grid maxima, golden section along the rim.
* the atlas kernel, :func:`mechopt.atlas.evaluate_designs` (``kernels._mci_nb``):
  five-bar specific and compiled; compass search and damped Newton on the
  rotation/reflection conditions from three nodes, golden section on the rim.

Independent certificates, used where the two disagree and for ``MCI = 1``:

* for the symmetric five-bar (mode ``"+-"``) the mirror symmetry makes ``G12 = 0``
  of ``G = J^T J`` on the whole y axis, so an isotropic point on the axis is a sign
  change of ``G11 - G22``, located here by brentq;
* a dense polar grid (no maximiser can be below its best node), and SLSQP from
  the best nodes of a grid for mechanisms without that symmetry.

Known shortfall of the atlas kernel (found by this file): on about 0.5 % of the
designs (7 of 1500) it stops short of an isotropic point inside the MIC, by up
to 8e-4 below MCI = 1. Most have nearly coincident base joints (``r3`` ~
0.002-0.02): the isotropic point sits at the end of a long curved valley of
near-isotropy (the isotropic points form a circle when ``r3 = 0``) that its damped
Newton with a monotone line search does not cross, e.g. (1.5503, 1.4295, 0.0202);
a few do not, e.g. (1.3865, 1.5140, 0.0995). The random comparison below
tolerates such a design only when the global value is higher and an independent
certificate confirms it; ``test_atlas_mci_where_it_is_known_to_fall_short``
records the shortfall (xfail, not strict).
"""
import numpy as np
import pytest
from scipy.optimize import brentq, minimize

from mechopt import FiveBar
from mechopt.atlas import RESULT_COLUMNS, evaluate_designs
from mechopt.performance import global_indices, max_lci
from mechopt.quadrature import disk_rule
from mechopt.workspace import mic

N_DESIGNS = 200
SEED = 2024
MCI = RESULT_COLUMNS.index("mci")
R_MIC = RESULT_COLUMNS.index("r_mic")
LIU_EXAMPLE = (1.2576, 1.5842, 0.1583)  # compass search of the old max_lci: 1.2e-3 short
# designs on which the atlas MCI is short of 1 (found with other seeds); most
# have nearly coincident base joints
NEAR_COINCIDENT = [
    (1.5502902514426262, 1.4294950678170584, 0.02021468074031535),   # seed 2024: 4.9e-4
    (1.4179969047877323, 1.5599436377642137, 0.022059457448053932),  # seed 0: 8.0e-4
    (1.4, 1.597, 0.003),
    (2.2, 0.799, 0.001),
    (1.7, 1.2999, 1e-4),
]


def _liu_designs(n, seed):
    """Uniform designs of Liu's space r1 + r2 + r3 = 3, 0 <= r3 <= 1.5, r1, r2 > 0."""
    rng = np.random.default_rng(seed)
    r3 = rng.uniform(0.0, 1.5, n)
    r1 = rng.uniform(0.0, 1.0, n) * (3.0 - r3)
    return r1, 3.0 - r1 - r3, r3


def _g_matrix(mech, x, y):
    J = mech.jacobian(np.asarray(x, float), np.asarray(y, float))
    a, b, c, d = J[..., 0, 0], J[..., 0, 1], J[..., 1, 0], J[..., 1, 1]
    return a * a + c * c, b * b + d * d, a * b + c * d  # G11, G22, G12


def _axis_isotropic_points(fb, cy, R, n=4001):
    """Isotropic points ``(0, y)`` strictly inside the disk, by brentq on
    ``G11 - G22`` (``G12 = 0`` on the axis of the symmetric five-bar)."""
    lim = R * (1.0 - 1e-7)
    f = lambda t: float(np.subtract(*_g_matrix(fb, 0.0, cy + t)[:2]))  # noqa: E731
    ts = np.linspace(-lim, lim, n)
    g11, g22, g12 = _g_matrix(fb, np.zeros(n), cy + ts)
    assert np.all(np.abs(g12) <= 1e-12 * (g11 + g22)), "G12 must vanish on the y axis"
    s = np.sign(g11 - g22)
    out = []
    for k in np.flatnonzero(s[:-1] * s[1:] < 0):
        t = brentq(f, ts[k], ts[k + 1], xtol=1e-14 * max(R, 1.0))
        out.append(t)
    return out


def _dense_max(mech, cy, R, n_r=300, n_theta=1200):
    dx, dy, _ = disk_rule(R, "polar", n_r=n_r, n_theta=n_theta)
    return float(np.max(mech.lci(dx, cy + dy)))


def _slsqp_mci(mech, cy, R, n_starts=12):
    """Independent maximiser: SLSQP on ``g = 1 - 4 det G / tr(G)^2`` (smooth,
    decreasing in LCI) within the disk, from the best nodes of a 96 x 192 grid."""
    dx, dy, _ = disk_rule(R, "polar", n_r=96, n_theta=192)
    v = mech.lci(dx, cy + dy)
    best = float(np.max(v))

    def g(p):
        g11, g22, g12 = _g_matrix(mech, p[0], cy + p[1])
        t = g11 + g22
        return float(((g11 - g22) ** 2 + 4 * g12 ** 2) / (t * t))

    cons = [{"type": "ineq", "fun": lambda p: (R * R - p @ p) / (R * R)}]
    for k in np.argsort(-v, kind="stable")[: 20 * n_starts: 20]:
        res = minimize(g, [dx[k], dy[k]], method="SLSQP", constraints=cons,
                       options={"ftol": 1e-20, "maxiter": 500})
        p = res.x * min(1.0, R / max(np.hypot(*res.x), 1e-300))
        best = max(best, float(mech.lci(p[0], cy + p[1])))
    return best


@pytest.fixture(scope="module")
def random_designs():
    """Atlas rows and global MCI of the random designs that have a MIC."""
    r1, r2, r3 = _liu_designs(N_DESIGNS, SEED)
    atlas = evaluate_designs(r1, r2, r3, "polar")
    rows = []
    skipped = 0
    for i in range(N_DESIGNS):
        if not (atlas[i, R_MIC] > 0 and np.isfinite(atlas[i, MCI])):
            skipped += 1
            continue
        fb = FiveBar(r1[i], r2[i], r3[i])
        g = global_indices(fb, "polar")
        rows.append(dict(r=(r1[i], r2[i], r3[i]), fb=fb, glob=g, atlas=atlas[i]))
    return rows, skipped


def test_global_mci_equals_atlas_on_200_random_designs(random_designs):
    rows, skipped = random_designs
    assert len(rows) + skipped == N_DESIGNS
    assert len(rows) >= 150, f"only {len(rows)} designs with a MIC ({skipped} skipped)"
    atlas_short = []
    worst = 0.0
    for row in rows:
        g, a = row["glob"], row["atlas"]
        assert g["r_mic"] == pytest.approx(a[R_MIC], rel=1e-9), row["r"]  # the same disk
        cy, R = g["mic_center_y"], g["r_mic"]
        mci = g["mci"]
        assert 0.0 <= mci <= 1.0
        # a maximum is not below the best node of a dense grid
        assert mci >= _dense_max(row["fb"], cy, R) - 1e-12, row["r"]
        diff = mci - a[MCI]
        if abs(diff) <= 1e-6:
            worst = max(worst, abs(diff))
            continue
        # only a certified shortfall of the atlas is tolerated: global higher, and
        # an independent method reaches the global value
        assert diff > 0, f"{row['r']}: global MCI {mci!r} below the atlas {a[MCI]!r}"
        iso = _axis_isotropic_points(row["fb"], cy, R)
        ref = 1.0 if iso else _slsqp_mci(row["fb"], cy, R)
        assert ref >= mci - 1e-9, (row["r"], mci, ref)
        atlas_short.append((row["r"], diff))
    assert worst <= 1e-6
    # the atlas kernel's known shortfall (module docstring) is rare
    assert len(atlas_short) <= 2, atlas_short


def test_liu_space_example_reaches_mci_one():
    fb = FiveBar(*LIU_EXAMPLE)
    g = global_indices(fb, "polar")
    a = evaluate_designs(*LIU_EXAMPLE, "polar")[0]
    assert g["r_mic"] == pytest.approx(a[R_MIC], rel=1e-9)
    assert _axis_isotropic_points(fb, g["mic_center_y"], g["r_mic"])  # an isotropic point inside
    assert abs(g["mci"] - 1.0) < 1e-9
    assert abs(g["mci"] - a[MCI]) < 1e-6


def test_mci_is_one_where_an_isotropic_point_lies_in_the_mic(random_designs):
    rows, _ = random_designs
    hits = 0
    for row in rows:
        g = row["glob"]
        if _axis_isotropic_points(row["fb"], g["mic_center_y"], g["r_mic"]):
            hits += 1
            assert abs(g["mci"] - 1.0) < 1e-9, (row["r"], g["mci"])
    assert hits >= 50, hits  # about two thirds of the designs


@pytest.mark.parametrize("r", NEAR_COINCIDENT + [(1.4, 1.6, 0.0), (1.7, 1.3 - 1e-6, 1e-6)])
def test_mci_one_with_nearly_coincident_base_joints(r):
    fb = FiveBar(*r)
    m = mic(fb)
    assert _axis_isotropic_points(fb, m.center_y, m.radius) or r[2] == 0.0
    assert abs(max_lci(fb, m.center_y, m.radius) - 1.0) < 1e-9


ATLAS_SHORT = NEAR_COINCIDENT[:2] + [
    (1.3865419448645502, 1.5139969471555828, 0.09946110797986712),  # 3.0e-4
    (1.0922198627538615, 1.5714866918144899, 0.3362934454316485),   # 2.3e-5
]


def test_mci_is_one_where_the_atlas_falls_short():
    for r in ATLAS_SHORT:
        fb = FiveBar(*r)
        g = global_indices(fb, "polar")
        assert _axis_isotropic_points(fb, g["mic_center_y"], g["r_mic"]), r
        assert abs(g["mci"] - 1.0) < 1e-9, r


@pytest.mark.xfail(reason="atlas kernel (kernels._mci_nb): its damped Newton with a monotone "
                          "line search stops short of these isotropic points", strict=False)
def test_atlas_mci_where_it_is_known_to_fall_short():
    r1, r2, r3 = (np.array(v) for v in zip(*ATLAS_SHORT))
    a = evaluate_designs(r1, r2, r3, "polar")
    assert np.all(np.abs(a[:, MCI] - 1.0) < 1e-6), a[:, MCI]


def _generic_cases():
    from mechanism_cases import CASES

    want = ("FiveBar[r1<r2,-+]", "FiveBar[r1>r2,++]", "Bipod[asym-crossing,up]",
            "Biglide[l1=20,l2=100,unequal,--]", "Gantry[wu2008-table1,--]")
    return [pytest.param(factory, id=cid) for cid, factory, _ in CASES if cid in want]


@pytest.mark.parametrize("factory", _generic_cases())
def test_max_lci_of_other_mechanisms_matches_an_independent_maximiser(factory):
    mech = factory()
    m = mic(mech)
    got = max_lci(mech, m.center_y, m.radius)
    ref = max(_slsqp_mci(mech, m.center_y, m.radius), _dense_max(mech, m.center_y, m.radius))
    assert got >= ref - 1e-9
    assert got <= ref + 1e-9  # SLSQP converges here: the two agree


def test_max_lci_small_cases():
    fb = FiveBar(*LIU_EXAMPLE)
    m = mic(fb)
    a = max_lci(fb, m.center_y, m.radius)
    assert max_lci(fb, m.center_y, m.radius) == a  # deterministic
    assert max_lci(fb, m.center_y, 0.0) == pytest.approx(float(fb.lci(0.0, m.center_y)), abs=0)
    coarse = max_lci(fb, m.center_y, m.radius, iters=0)  # grid and rim samples only
    dx, dy, _ = disk_rule(m.radius, "polar", n_r=64, n_theta=128)
    assert coarse >= float(np.max(fb.lci(dx, m.center_y + dy)))
    assert coarse <= a
    with pytest.raises(ValueError, match="n_seeds"):
        max_lci(fb, m.center_y, m.radius, n_seeds=0)
