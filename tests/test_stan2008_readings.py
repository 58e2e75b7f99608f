"""Stan 2008 readings, claims and tolerances of experiments/stan2008.py, each value
recomputed here independently of the table code (closed forms, mechopt.core.geometry,
numerical integration written in this file, pymoo directly) and checked against the
table row of one quick run."""
import re

import numpy as np
import pandas as pd
import pytest
from scipy import integrate

from mechopt.core import geometry
from mechopt.experiments import stan2008
from mechopt.core.published import counts, printed_half_unit

PRINTED_AREA = 4693.33
HALF_AREA = printed_half_unit(2)
BIPOD_RANGE = (0.52, 1.35)
BIGLIDE_RANGE = (1.0, 1.2)
LABELS = ("W1=0.7,W2=0.3", "W1=0.3,W2=0.7", "W1=1,W2=0", "W1=0,W2=1")


@pytest.fixture(scope="module")
def quick(quick_reproduction):
    """``stan2008.run(out, quick=True)`` as the quick reproduction ran it (tests/conftest.py)."""
    out, table, _ = quick_reproduction.runs["stan2008"]
    return out, table


def _row(df, q):
    sel = df[df["quantity"] == q]
    assert len(sel) == 1, q
    return sel.iloc[0]


def _tol(note):
    return float(re.search(r"tol ([0-9.eE+-]+) ", note).group(1))


# --- independent helpers -------------------------------------------------------------------
def _half_area_by_chords(b, r, R):
    """y > 0 area of {r <= |P| <= R} ^ {r <= |P - (b, 0)| <= R} by integrating, along x, the
    length of the y > 0 set: y^2 in [max(r^2 - x^2, r^2 - (x-b)^2, 0), min(R^2 - x^2, R^2 - (x-b)^2)]."""
    def chord(x):
        lo = max(r * r - x * x, r * r - (x - b) ** 2, 0.0)
        hi = min(R * R - x * x, R * R - (x - b) ** 2)
        return np.sqrt(hi) - np.sqrt(lo) if hi > lo else 0.0
    # kinks where a circle bound switches or ends
    pts = sorted({-r, r, b - r, b + r, b / 2.0, b - R, R, -R, b + R})
    lo, hi = b - R, R
    pts = [p for p in pts if lo < p < hi]
    return integrate.quad(chord, lo, hi, points=pts, limit=400, epsabs=1e-9, epsrel=1e-13)[0]


def _sin_gamma(q1, q2, b=1.0):
    """Sine of the angle between the struts from the law of cosines."""
    c = (q1 * q1 + q2 * q2 - b * b) / (2.0 * q1 * q2)
    return np.sqrt(np.clip(1.0 - c * c, 0.0, 1.0))


# --- item 1: the area reading and the search ---------------------------------------------------
def test_area_b62_reading(quick):
    _, df = quick
    r = _row(df, "workspace_area[b=62mm]")
    full = geometry.annuli_intersection_area((0.0, 0.0), 80.0, 130.0, (62.0, 0.0), 80.0, 130.0)
    by_chords = _half_area_by_chords(62.0, 80.0, 130.0)
    assert by_chords == pytest.approx(full / 2.0, rel=1e-10)
    assert r["reproduced"] == pytest.approx(by_chords, rel=1e-10)
    assert abs(by_chords - PRINTED_AREA) <= HALF_AREA  # 4693.326: the printed digits
    assert r["status"] == "match" and r["kind"] == "reading"
    assert _tol(r["note"]) == pytest.approx(HALF_AREA)  # printed digits only
    assert "62" in r["note"] and "4693.33" in r["note"]
    # the literal row keeps b = 60 mm and its status
    lit = _row(df, "workspace_area")
    assert lit["status"] == "differs" and lit["kind"] == "computed"
    assert lit["reproduced"] == pytest.approx(_half_area_by_chords(60.0, 80.0, 130.0), rel=1e-10)


def test_area_search_hits(quick):
    out, df = quick
    box = stan2008.AREA_SEARCH
    b, a, c = np.meshgrid(*(np.arange(lo, hi + 1, dtype=float) for lo, hi in
                            (box["b"], box["q_min"], box["q_max"])), indexing="ij")
    b, a, c = b.ravel(), a.ravel(), c.ravel()
    zero = np.zeros_like(b)
    area = geometry.annuli_intersection_area(np.stack([zero, zero], -1), a, c,
                                             np.stack([b, zero], -1), a, c) / 2.0
    hit = np.abs(area - PRINTED_AREA) <= HALF_AREA
    hits = sorted(zip(b[hit], a[hit], c[hit]))
    assert hits == [(62.0, 80.0, 130.0)]
    table = pd.read_csv(out / "area_search.csv")
    got = table[table["rounds_to_printed"]]
    assert sorted(zip(got["b"], got["q_min"], got["q_max"])) == hits
    near = np.abs(area - PRINTED_AREA) <= stan2008.AREA_NEAR
    assert len(table) == int(near.sum())
    assert "1 hit(s)" in _row(df, "workspace_area[b=62mm]")["note"]


# --- item 2: T-only 0.71 and the weighted optima ----------------------------------------------
def test_retracted_pose_reading_is_one_over_sqrt2(quick):
    _, df = quick
    # law of cosines with q1 = q2 = u b, |A1A2| = b: cos gamma = 1 - 1/(2 u^2) = 0 at u = 1/sqrt(2)
    u_star = 1.0 / np.sqrt(2.0)
    assert 1.0 - 1.0 / (2.0 * u_star ** 2) == pytest.approx(0.0, abs=1e-15)
    u = np.linspace(*BIPOD_RANGE, 100001)
    assert u[np.argmax(_sin_gamma(u, u))] == pytest.approx(u_star, abs=1e-5)
    r = _row(df, "q1_over_b[W1=1,W2=0;retracted pose]")
    assert r["reproduced"] == pytest.approx(u_star, abs=1e-6)
    assert r["status"] == "match" and r["kind"] == "reading" and r["paper"] == 0.71
    lit = _row(df, "q1_over_b[W1=1,W2=0]")
    assert lit["status"] == "differs" and lit["kind"] == "computed"


def _area_mean_tqi(u, n=40):
    """Area mean of the TQI over the y > 0 workspace (b = 1, q in [u, 1.6u]) in joint space:
    dA = dq1 dq2 / sin(gamma), TQI = sin(gamma), so the mean is |Q| / int dq / sin(gamma)."""
    t, w = np.polynomial.legendre.leggauss(n)
    q = 1.3 * u + 0.3 * u * t
    Q1, Q2 = np.meshgrid(q, q)
    area = np.sum(np.outer(w, w) / _sin_gamma(Q1, Q2)) * (0.3 * u) ** 2
    return (0.6 * u) ** 2 / area


def test_workspace_means_peak_near_056(quick):
    out, _ = quick
    u = np.linspace(*BIPOD_RANGE, 831)
    T = np.array([_area_mean_tqi(x) for x in u])
    fam = pd.read_csv(out / "bipod_reachable_optima.csv").set_index("T_reading")
    step = (BIPOD_RANGE[1] - BIPOD_RANGE[0]) / (stan2008.SETTINGS[True]["n_readings"] - 1)
    assert fam.loc["area mean (ours)", "peak_of_T"] == pytest.approx(u[np.argmax(T)], abs=step)
    assert u[np.argmax(T)] == pytest.approx(0.561, abs=0.002)
    assert fam.loc["retracted pose q1 = q2 = q_min", "peak_of_T"] == pytest.approx(2 ** -0.5, abs=step)


def test_no_weighting_and_scale_of_w_reaches_092_or_113(quick):
    """Z = W1 T + W2 W/c = W1 (T + lambda W): all weightings and scales are one lambda >= 0.
    Recomputed with the closed-form retracted TQI and the area mean, W from geometry."""
    out, df = quick
    u = np.linspace(*BIPOD_RANGE, 831)
    zero = np.zeros_like(u)
    W = geometry.annuli_intersection_area(np.stack([zero, zero], -1), u, 1.6 * u,
                                          np.stack([zero + 1.0, zero], -1), u, 1.6 * u) / 2.0
    tol = 0.01 * (BIPOD_RANGE[1] - BIPOD_RANGE[0])
    lam = np.concatenate([[0.0], np.logspace(-4, 5, 1801)])
    for T in (_sin_gamma(u, u), np.array([_area_mean_tqi(x) for x in u])):
        opt = u[np.argmax(T[None, :] + lam[:, None] * (W / W.max())[None, :], axis=1)]
        for target in (0.92, 1.13):
            assert np.min(np.abs(opt - target)) > tol
    fam = pd.read_csv(out / "bipod_reachable_optima.csv")
    assert not fam["reaches_0.92"].any() and not fam["reaches_1.13"].any()
    pairs = pd.read_csv(out / "bipod_readings.csv")
    assert set(pairs["weights"]) == set(LABELS)
    assert not pairs[pairs["weights"].isin(LABELS[:2])]["match"].any()
    for label in LABELS[:2]:
        r = _row(df, f"q1_over_b[{label}]")
        assert r["status"] == "differs" and "readings analysis" in r["note"] and "no such pair" in r["note"]


def test_w_only_design_reading(quick):
    _, df = quick
    r = _row(df, "q1_over_b[W1=0,W2=1;design 80/62]")
    assert r["reproduced"] == pytest.approx(80.0 / 62.0, rel=1e-12)
    assert r["status"] == "match" and r["kind"] == "reading" and "Not discriminating" in r["note"]


# --- item 3: the Biglide L1 ------------------------------------------------------------------
def _centre_tqi(l1, l2):
    """TQI at x = 0 (mode '--'): links at theta from the guides, tan theta = l1/sqrt(l2^2 - l1^2);
    J rows (tan theta, 1), (-tan theta, 1): kappa = tan theta or its inverse, TQI = sin 2 theta."""
    theta = np.arctan2(l1, np.sqrt(l2 * l2 - l1 * l1))
    return np.sin(2.0 * theta)


def test_biglide_t_falls_only_beyond_sqrt2_l1(quick):
    out, df = quick
    l2 = np.linspace(1.0 + 1e-6, 1.2, 201)
    assert np.all(np.diff(_centre_tqi(stan2008.BIGLIDE_L1, l2)) < 0)  # L2 > sqrt(2) * 0.5
    assert np.all(np.diff(_centre_tqi(1.0, l2)) > 0)  # L2 < sqrt(2) * 1: T rises
    assert _centre_tqi(1.0, np.sqrt(2.0)) == pytest.approx(1.0)
    # the workspace mean under the reading falls too (raster, not the table's quadrature)
    from mechopt.mechanisms.biglide import Biglide
    lo, hi = stan2008.BIGLIDE_STROKES
    T = [Biglide(stan2008.BIGLIDE_L1, v, lo, hi).gtqi(method="raster") for v in (1.01, 1.1, 1.19)]
    assert T[0] > T[1] > T[2]
    r = _row(df, "L2[W1=1,W2=0;L1=0.5]")
    assert r["reproduced"] == pytest.approx(1.0, abs=1e-5) and r["status"] == "match"
    assert r["kind"] == "reading"
    assert _row(df, "L2[W1=0,W2=1;L1=0.5]")["reproduced"] == pytest.approx(1.2, abs=1e-9)
    assert _row(df, "L2[W1=1,W2=0]")["status"] == "differs"  # literal L1 = 1 keeps its status
    scan = pd.read_csv(out / "biglide_l1_scan.csv")
    assert not scan["some_c_gives_all_four"].any()
    assert "L1 = 0.5" in stan2008.__doc__


# --- item 4: Table 1's GA rates ------------------------------------------------------------------
def test_ga_table1_rates(quick):
    from pymoo.algorithms.soo.nonconvex.ga import GA
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PM
    from pymoo.optimize import minimize

    from mechopt.problems import get
    from mechopt.run.weighted import WeightedSum

    _, df = quick
    s = stan2008.SETTINGS[True]
    algo = GA(pop_size=s["pop"], crossover=SBX(prob=0.08, prob_var=1.0),
              mutation=PM(prob=0.005, prob_var=1.0), eliminate_duplicates=False)
    res = minimize(WeightedSum(get("stan2008-bipod"), 0.0), algo, ("n_gen", s["gen"]), seed=1)
    r = _row(df, "q1_over_b[W1=1,W2=0;GA Table 1 rates]")
    assert r["reproduced"] == pytest.approx(float(res.X[0]), abs=1e-12) and r["kind"] == "reading"
    for prefix in ("q1_over_b", "L2"):
        for label in LABELS:
            assert _row(df, f"{prefix}[{label};GA Table 1 rates]")["kind"] == "reading"
    cx, mut = _row(df, "ga_crossover_rate"), _row(df, "ga_mutation_rate")
    assert cx["reproduced"] == 0.08 and mut["reproduced"] == 0.005
    assert cx["kind"] == mut["kind"] == "setting"
    assert "SBX" in cx["note"] and "runner.optimize" in cx["note"]


# --- item 5: claims --------------------------------------------------------------------------------
def test_claim_max_workspace_at_upper_bound(quick):
    _, df = quick
    u = np.linspace(*BIPOD_RANGE, 401)
    W = np.array([_half_area_by_chords(1.0, x, 1.6 * x) for x in u[::40]])
    assert np.all(np.diff(W) > 0)
    r = _row(df, "claim:max_workspace_at_q1min/b=1.35")
    assert r["status"] == "holds" and r["kind"] == "claim"


@pytest.mark.parametrize("fig, xp, mirror_x", [("fig9", 25.0, 35.0), ("fig10", 35.0, 25.0)])
def test_claim_fig_poses_regular(quick, fig, xp, mirror_x):
    _, df = quick
    yp, b = 60.0, 60.0
    e1 = np.array([xp, yp]) / np.hypot(xp, yp)
    e2 = np.array([xp - b, yp]) / np.hypot(xp - b, yp)
    s = e1[0] * e2[1] - e1[1] * e2[0]  # det of the unit-row Jacobian: sin(angle between struts)
    assert abs(s) > 0.5  # far from the type-II locus
    assert np.hypot(xp, yp) < 80.0 and np.hypot(xp - b, yp) < 80.0  # below the sec. 5.1 q_min
    assert xp + mirror_x == pytest.approx(b)
    r = _row(df, f"claim:{fig}_pose_regular")
    assert r["status"] == "holds" and r["kind"] == "claim"
    assert f"{s:.4f}" in r["note"] and "'none'" in r["note"] and "'unreachable'" in r["note"]


# --- item 6: tolerances from printed digits --------------------------------------------------------
def test_optimum_tolerances_follow_printed_digits(quick):
    _, df = quick
    rng = {"q1_over_b": BIPOD_RANGE, "L2": BIGLIDE_RANGE}
    for r in df.itertuples():
        prefix = r.quantity.split("[", 1)[0]
        if prefix not in rng:
            continue
        digits = len(f"{r.paper:g}".split(".")[1]) if "." in f"{r.paper:g}" else 0
        if prefix == "L2" and r.paper == 1.0:
            digits = 4  # the data file's column digits for the printed "1"
        lo, hi = rng[prefix]
        expected = max(printed_half_unit(digits), 0.01 * (hi - lo))
        assert _tol(r.note) == pytest.approx(expected, rel=1e-2), r.quantity
    assert _tol(_row(df, "workspace_area")["note"]) == pytest.approx(0.01 * PRINTED_AREA, rel=1e-2)


def test_kinds_and_counts(quick):
    _, df = quick
    c = counts(df)
    assert c["computed"] == 9  # the area and the 8 optima of Tables 2-3
    assert c["settings"] == 4
    assert c["claims hold"] + c["claims fail"] == 3
    assert c["readings"] == len(df) - 9 - 4 - 3
