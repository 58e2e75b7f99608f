"""Wu 2008 gantry: published design values, kinematics, workspace, velocity output ratio."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

import mechopt
from mechopt import Biglide
from mechopt.mechanisms.gantry_dynamics import wu2008_published
from mechopt.mechanisms.gantry import (
    ASSEMBLY_MODES,
    K_AV_READINGS,
    MODES,
    SUMMARY_KEYS,
    Gantry,
    dimensional_synthesis,
    k_av_literal_of_design,
    wu2008_gantry,
)

PUB = wu2008_published()
DESIGNS = {"theta_1S=15deg": 15.0, "table1": 10.0}


def _half_unit(design, quantity):
    value, _, digits, _ = PUB[(design, quantity)]
    return value, 0.5 * 10.0 ** (-digits)


# --- published values ------------------------------------------------------------
@pytest.mark.parametrize("design", sorted(DESIGNS))
@pytest.mark.parametrize("quantity", ["d1", "l", "stroke"])
def test_dimensional_synthesis_reproduces_printed_digits(design, quantity):
    b = PUB[(design, "b")][0]
    h = PUB[(design, "h")][0]
    th = math.radians(PUB[(design, "theta_1S")][0])
    assert th == math.radians(DESIGNS[design])
    d, d1, l, stroke = dimensional_synthesis(b, h, th)
    got = dict(d1=d1, l=l, stroke=stroke)[quantity]
    value, tol = _half_unit(design, quantity)
    assert abs(got - value) <= tol, (design, quantity, got, value)


def test_table1_theta_2L_is_80_deg():
    assert PUB[("table1", "theta_2L")][0] == 90.0 - PUB[("table1", "theta_1S")][0]


@pytest.mark.parametrize("deg", [1.0, 10.0, 15.0, 30.0, 44.0])
def test_synthesis_satisfies_eq_10_to_13(deg):
    b, h, th = 500.0, 400.0, math.radians(deg)
    d, d1, l, stroke = dimensional_synthesis(b, h, th)
    th2L = math.pi / 2 - th
    assert math.isclose(math.sin(th), d / l, rel_tol=1e-13)  # eq. (10)
    assert math.isclose(math.sin(th2L), (b + d) / l, rel_tol=1e-13)  # eq. (11)
    y_d1 = l * (math.cos(th) - math.sin(math.pi / 2 - th2L))  # eq. (12)
    assert math.isclose(y_d1, b, rel_tol=1e-12)  # eq. (13)
    assert math.isclose(stroke, b + h, rel_tol=1e-12)  # eq. (16)
    assert math.isclose(d1, b / 2 + d, rel_tol=1e-13)


@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(b=500, h=400, theta_1S=0.0), "theta_1S"),
        (dict(b=500, h=400, theta_1S=math.pi / 4), "theta_1S"),
        (dict(b=500, h=400, theta_1S=-0.1), "theta_1S"),
        (dict(b=500, h=400, theta_1S=float("nan")), "theta_1S"),
        (dict(b=0, h=400, theta_1S=0.2), "b must"),
        (dict(b=500, h=-1, theta_1S=0.2), "h must"),
        (dict(b="wide", h=400, theta_1S=0.2), "b must"),
    ],
)
def test_dimensional_synthesis_rejects_bad_input(kwargs, match):
    with pytest.raises(ValueError, match=match) as err:
        dimensional_synthesis(**kwargs)
    assert "\n" not in str(err.value)


# --- construction ------------------------------------------------------------------
@pytest.mark.parametrize(
    "args,kwargs,match",
    [
        ((300.0, 300.0, 900.0), {}, "l must be greater than d1"),
        ((300.0, 200.0, 900.0), {}, "l must be greater than d1"),
        ((-1.0, 600.0, 900.0), {}, "d1 must"),
        ((300.0, 600.0, 0.0), {}, "stroke must"),
        ((300.0, 600.0, 900.0), dict(mode="-"), "mode must be one of"),
        ((300.0, 600.0, 900.0), dict(l2=-2.0), "l2 must"),
        ((300.0, 600.0, 900.0), dict(q_min=float("inf")), "q_min must"),
        ((300.0, 600.0, 900.0), dict(task_workspace=(1, 0, 0, 1)), "task_workspace"),
        ((300.0, 600.0, 900.0), dict(task_workspace=5), "task_workspace"),
    ],
)
def test_gantry_rejects_bad_input(args, kwargs, match):
    with pytest.raises(ValueError, match=match):
        Gantry(*args, **kwargs)


def test_bad_assembly_reading_leg_errors():
    g = wu2008_gantry()
    with pytest.raises(ValueError, match="assembly"):
        g.fk(0.0, 0.0, "sideways")
    with pytest.raises(ValueError, match="reading"):
        g.k_av(reading="average")
    with pytest.raises(ValueError, match="leg"):
        g.k_av(leg=3)
    with pytest.raises(ValueError, match="x_max"):
        g.k_av(100.0, -100.0)
    with pytest.raises(ValueError, match="reachable x range"):
        g.k_av(-1000.0, 0.0)
    with pytest.raises(ValueError, match="unit"):
        wu2008_gantry(unit="inch")
    with pytest.raises(ValueError, match="task_workspace"):
        Gantry(300.0, 600.0, 900.0).k_av()


def test_exported_from_package():
    assert mechopt.Gantry is Gantry
    assert mechopt.dimensional_synthesis is dimensional_synthesis


# --- kinematics -----------------------------------------------------------------------
def _mechs():
    base = wu2008_gantry()
    return [base.with_mode(m) for m in MODES]


def _inside(g, rng, n, margin=0.05):
    """Points well inside the reachable set (uniform in x, then in the y interval)."""
    lo, hi = g.x_range
    xs, ys = [], []
    while sum(map(len, xs)) < n:
        x = rng.uniform(lo, hi, 4 * n)
        ylo, yhi = g.y_interval(x)
        ok = np.isfinite(ylo) & (yhi - ylo > 2 * margin * g.l)
        x = x[ok]
        y = rng.uniform(ylo[ok] + margin * g.l, yhi[ok] - margin * g.l)
        keep = (g.serial_clearance(x, y) > 0.02 * g.l) & (np.abs(g.type2_function(x, y)) > 0.05)
        xs.append(x[keep])
        ys.append(y[keep])
    return np.concatenate(xs)[:n], np.concatenate(ys)[:n]


@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_ik_is_eq_2_and_jacobian_is_eq_4(g):
    x, y = _inside(g, np.random.default_rng(1), 300)
    q1, q2, ok = g.ik(x, y)
    assert np.all(ok)
    s1, s2 = (1.0 if c == "+" else -1.0 for c in g.mode)
    np.testing.assert_allclose(q1, y - g.l2 / 2 + s1 * np.sqrt(g.l**2 - (x + g.d1) ** 2), rtol=1e-13)
    np.testing.assert_allclose(q2, y - g.l2 / 2 + s2 * np.sqrt(g.l**2 - (x - g.d1) ** 2), rtol=1e-13)
    # eq. (1): sin(theta_i) = (x - x_Bi)/l, cos(theta_i) = (y - l2/2 - y_Bi)/l
    th1 = np.arctan2((x + g.d1) / g.l, (y - g.l2 / 2 - q1) / g.l)
    th2 = np.arctan2((x - g.d1) / g.l, (y - g.l2 / 2 - q2) / g.l)
    np.testing.assert_allclose(np.stack(g.link_angles(x, y)), np.stack([th1, th2]), rtol=1e-13)
    J = g.jacobian(x, y)
    np.testing.assert_allclose(J[:, 0, 0], np.tan(th1), rtol=1e-11)
    np.testing.assert_allclose(J[:, 1, 0], np.tan(th2), rtol=1e-11)
    np.testing.assert_allclose(J[:, :, 1], 1.0, rtol=1e-13)
    if g.mode == "--":  # the paper's branch: 0 < |theta_i| < pi/2 (sec. 3.1)
        assert np.all(np.abs(np.stack([th1, th2])) < np.pi / 2)


@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_jacobian_matches_finite_differences(g):
    x, y = _inside(g, np.random.default_rng(2), 300)
    h = 1e-5 * g.l
    cols = []
    for dx, dy in ((h, 0.0), (0.0, h)):
        qp = np.stack(g.ik(x + dx, y + dy)[:2], -1)
        qm = np.stack(g.ik(x - dx, y - dy)[:2], -1)
        cols.append((qp - qm) / (2 * h))
    Jfd = np.stack(cols, -1)
    J = g.jacobian(x, y)
    rel = np.linalg.norm(J - Jfd, axis=(1, 2)) / np.linalg.norm(J, axis=(1, 2))
    assert rel.max() < 1e-6


@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_batch_equals_pointwise(g):
    x, y = _inside(g, np.random.default_rng(3), 12)
    x = np.append(x, [1e4, 0.0])
    y = np.append(y, [0.0, -1e4])
    for f in (g.ik, g.closure, g.serial_clearance, g.link_angles, g.lci, g.reachable):
        whole = f(x, y)
        whole = whole if isinstance(whole, tuple) else (whole,)
        singles = [f(a, b) for a, b in zip(x, y)]
        singles = [s if isinstance(s, tuple) else (s,) for s in singles]
        for k, arr in enumerate(whole):
            pts = np.stack([np.asarray(s[k]) for s in singles])
            np.testing.assert_array_equal(pts, np.asarray(arr))


ROUND_TRIP = settings(max_examples=60, deadline=None, derandomize=True)


@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_ik_fk_round_trip_hypothesis(g):
    lo, hi = g.x_range

    @ROUND_TRIP
    @given(st.floats(0.02, 0.98), st.floats(0.02, 0.98))
    def check(u, v):
        x = lo + u * (hi - lo)
        ylo, yhi = g.y_interval(x)
        if not np.isfinite(ylo):
            return
        y = float(ylo + v * (yhi - ylo))
        if abs(g.type2_function(x, y)) < 1e-6:
            return
        q1, q2, ok = g.ik(x, y)
        assert ok
        asm = str(g.assembly_of(x, y))
        assert asm in ASSEMBLY_MODES
        xf, yf, valid = g.fk(q1, q2, asm)
        assert valid
        assert math.hypot(xf - x, yf - y) <= 1e-9 * g.l
        q1b, q2b, okb = g.ik(xf, yf)
        assert okb and abs(q1b - q1) <= 1e-9 * g.l and abs(q2b - q2) <= 1e-9 * g.l

    check()


def test_fk_is_invalid_outside_the_stroke_and_when_circles_miss():
    g = wu2008_gantry()
    x, y, ok = g.fk([g.q_min - 1.0, g.q_min, g.q_min], [g.q_min, g.q_min, g.q_min + 2.5 * g.l], "up")
    assert list(ok) == [False, True, False]
    assert np.isnan(x[0]) and np.isnan(y[2])


def test_paper_pose_is_up_assembly_and_symmetric_pose_at_x0():
    g = wu2008_gantry()
    q1, q2, _ = g.ik(0.0, 500.0)
    assert q1 == q2  # eq. (2) at x = 0
    assert g.assembly_of(0.0, 500.0) == "up"
    x, y, _ = g.fk(q1, q2, "up")
    assert abs(x) < 1e-12 and abs(y - 500.0) < 1e-9


# --- singularities ----------------------------------------------------------------------
def test_type1_on_vertical_sides_and_no_type2_in_paper_mode():
    g = wu2008_gantry()
    lo, hi = g.x_range
    for x in (lo, hi):
        ylo, yhi = g.y_interval(x)
        y = 0.5 * (ylo + yhi)
        assert g.classify_singularity(x, y, tol=1e-9) == "type-I"
        assert abs(g.serial_clearance(x, y)) < 1e-9 * g.l
    xs = np.linspace(lo, hi, 2001)[1:-1]
    ylo, yhi = g.y_interval(xs)
    # sec. 3.1: "--" never has parallel links (d1 > 0)
    assert np.all(np.abs(g.type2_function(xs, 0.5 * (ylo + yhi))) > 0.05)


def test_mixed_mode_type2_at_x0():
    """Mode "-+": at x = 0 the links A1B1 and A2B2 are collinear (Wu sec. 3.1)."""
    g = wu2008_gantry().with_mode("-+")
    assert np.isnan(g.y_interval(0.0)[0])  # |c1 - c2| = 2 sqrt(l^2 - d1^2) > stroke: empty
    g = Gantry(g.d1, g.l, 1500.0, mode="-+")
    ylo, yhi = g.y_interval(0.0)
    y = 0.5 * (ylo + yhi)
    assert g.reachable(0.0, y)
    assert abs(g.type2_function(0.0, y)) < 1e-15
    assert g.classify_singularity(0.0, y) == "type-II"
    assert g.lci(0.0, y) < 1e-12


# --- workspace ---------------------------------------------------------------------------
@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_workspace_area_exact(g):
    """Closed form against adaptive quadrature of the interval length at each x."""
    lo, hi = g.x_range

    def length(x):
        ylo, yhi = g.y_interval(x)
        return 0.0 if not np.isfinite(ylo) else float(yhi - ylo)

    ref, err = integrate.quad(length, lo, hi, limit=400, epsabs=1e-9, epsrel=1e-12,
                              points=[0.0])
    assert math.isclose(g.workspace_area(), ref, rel_tol=1e-8)


def test_workspace_area_monte_carlo_and_breakpoints():
    # a short stroke makes the region pinch off (|c1 - c2| > stroke near the sides)
    for g in (wu2008_gantry(), Gantry(300.0, 650.0, 120.0, l2=50.0), Gantry(100.0, 650.0, 40.0)):
        xmin, xmax, ymin, ymax = g.bounding_box()
        X, Y = np.meshgrid(np.linspace(xmin, xmax, 1501), np.linspace(ymin, ymax, 1501))
        raster = g.reachable(X, Y).mean() * (xmax - xmin) * (ymax - ymin)
        assert math.isclose(g.workspace_area(), raster, rel_tol=5e-3)


def test_task_rectangle_corners_on_the_boundary():
    """Wu Fig. 2: Q1..Q4 lie on the boundary of the reachable set; W_t is inside it."""
    for deg in (10.0, 15.0):
        g = wu2008_gantry(deg)
        xmin, xmax, ymin, ymax = g.task_workspace
        cx = np.array([xmin, xmax, xmin, xmax])
        cy = np.array([ymin, ymin, ymax, ymax])
        assert np.all(np.abs(g.serial_clearance(cx, cy)) < 1e-9 * g.l)
        X, Y = np.meshgrid(np.linspace(xmin, xmax, 61)[1:-1], np.linspace(ymin, ymax, 41)[1:-1])
        assert np.all(g.reachable(X, Y))
        assert g.task_workspace_area() == pytest.approx(500.0 * 400.0)
        # q2 = q_2S at Q3, q1 = q_1S at Q2
        q1, q2, _ = g.ik(cx[:2], cy[:2] + 1e-9)
        assert q1[0] == pytest.approx(g.q_min, abs=1e-6) and q2[1] == pytest.approx(g.q_min, abs=1e-6)


@pytest.mark.parametrize("g", _mechs(), ids=MODES)
def test_serial_clearance_is_the_distance_to_the_boundary_inside(g):
    """Inside, the clearance equals the distance to a dense sampling of the boundary."""
    lo, hi = g.x_range
    xs = np.linspace(lo, hi, 40001)
    ylo, yhi = g.y_interval(xs)
    ok = np.isfinite(ylo)
    bx = [xs[ok], xs[ok]]
    by = [ylo[ok], yhi[ok]]
    for xe in (xs[ok][0], xs[ok][-1]):  # vertical pieces at the ends of the x range
        a, b = g.y_interval(xe)
        t = np.linspace(a, b, 4001)
        bx.append(np.full_like(t, xe))
        by.append(t)
    bx, by = np.concatenate(bx), np.concatenate(by)
    x, y = _inside(g, np.random.default_rng(4), 150, margin=0.0)
    dist = np.min(np.hypot(x[:, None] - bx[None, :], y[:, None] - by[None, :]), axis=1)
    c = g.serial_clearance(x, y)
    assert np.all(c > 0)
    # the sampling spacing bounds the brute-force error from above
    np.testing.assert_allclose(c, dist, atol=2e-3 * g.l, rtol=0)
    assert np.all(c <= dist + 1e-9 * g.l)


def test_bounding_box_is_tight_for_the_paper_mode():
    g = wu2008_gantry()
    xmin, xmax, ymin, ymax = g.bounding_box()
    xs = np.linspace(xmin, xmax, 20001)
    ylo, yhi = g.y_interval(xs)
    assert np.nanmin(ylo) >= ymin - 1e-9 and np.nanmax(yhi) <= ymax + 1e-9
    assert np.nanmin(ylo) - ymin < 1e-3 * g.l and ymax - np.nanmax(yhi) < 1e-3 * g.l


def test_scaled_to_metres_keeps_jacobian_and_scales_area():
    g = wu2008_gantry()
    gm = wu2008_gantry(unit="m")
    x, y = _inside(g, np.random.default_rng(5), 50)
    np.testing.assert_allclose(gm.jacobian(x * 1e-3, y * 1e-3), g.jacobian(x, y), rtol=1e-10)
    assert gm.workspace_area() == pytest.approx(g.workspace_area() * 1e-6, rel=1e-12)
    assert gm.task_workspace == pytest.approx(tuple(1e-3 * v for v in g.task_workspace))


# --- velocity output ratio (Wu sec. 3.3, 4.3) ----------------------------------------------
def test_k_v_is_x_dot_over_q_dot_at_y_dot_zero():
    g = wu2008_gantry()
    x, y = _inside(g, np.random.default_rng(6), 100)
    J = g.jacobian(x, y)
    for leg in (1, 2):
        qdot = J[:, leg - 1, 0] * 1.0  # x_dot = 1, y_dot = 0
        np.testing.assert_allclose(g.velocity_output_ratio(x, leg), np.abs(1.0 / qdot), rtol=1e-12)


def _literal_by_quadrature(g, leg=1):
    xmin, xmax = g.task_workspace[:2]
    val, _ = integrate.quad(lambda x: float(g.velocity_output_ratio(x, leg)), xmin, xmax,
                            epsabs=0, epsrel=1e-13, limit=200)
    return val / (xmax - xmin)


@pytest.mark.parametrize("deg", [10.0, 15.0])
def test_k_av_literal_against_independent_quadrature(deg):
    g = wu2008_gantry(deg)
    ref = _literal_by_quadrature(g)
    for leg in (1, 2):  # Wu: k_av(1) = k_av(2)
        assert g.k_av(leg=leg) == pytest.approx(ref, rel=1e-10)
    assert k_av_literal_of_design(math.radians(deg)) == pytest.approx(ref, rel=1e-10)
    # independent of the length unit and of b (a function of theta_1S only)
    assert wu2008_gantry(deg, unit="m").k_av() == pytest.approx(ref, rel=1e-12)
    g2 = Gantry.from_synthesis(123.0, 77.0, math.radians(deg))
    assert g2.k_av() == pytest.approx(ref, rel=1e-12)


def test_k_av_literal_value_and_monotonicity():
    g = wu2008_gantry(10.0)
    assert g.k_av() == pytest.approx(1.78715, abs=5e-6)  # eq. (6)-(7) read literally (a plain mean of cot theta); Wu prints k_av = 1.05
    th = np.radians(np.linspace(1.0, 44.0, 200))
    k = k_av_literal_of_design(th)
    assert np.all(np.diff(k) < 0) and k[-1] > 1.0  # "k_av descends" (sec. 4.3)


def test_k_av_other_readings():
    g = wu2008_gantry(10.0)
    assert g.k_av(reading="displacement") == pytest.approx(1.0, rel=1e-12)  # eq. (13)
    xmin, xmax = g.task_workspace[:2]

    def max_speed(x):
        J = g.jacobian(x, 500.0)
        return 2.0 / abs(J[0, 0] - J[1, 0])

    ref = integrate.quad(max_speed, xmin, xmax, epsrel=1e-12)[0] / (xmax - xmin)
    assert g.k_av(reading="max_speed") == pytest.approx(ref, rel=1e-10)
    assert g.k_av(reading="max_speed") == pytest.approx(1.10946, abs=5e-6)
    # across x = x_B the literal integrand |cot| ~ 1/|u| diverges
    wide = Gantry(100.0, 616.0, 900.0)  # l > 2 d1: x = -d1 is reachable
    assert wide.k_av(-110.0, -90.0) == math.inf


def test_table1_k_av_is_not_reproduced():
    """Table 1 prints k_av = 1.05; no reading found gives it (recorded, not hidden).

    Checked for the Table 1 design over [-b/2, b/2] (and the reachable x range):
    literal x-mean of |cot theta| 1.787 (1.832 over the reachable range), mean over
    theta of cot 1.420, geometric mean 1.362, median 1.407, rms 2.20, x over slider
    travel 1.000, max |x_dot| with unit slider speeds 1.109, |V|max = 1/s_min of J
    0.992, sqrt(2)/|J q| 1.004, |p_dot|/|q_dot_1| with q2 fixed 0.783. The literal
    value reaches 1.05 only near theta_1S = 34 deg.
    """
    value, tol = _half_unit("table1", "k_av")
    g = wu2008_gantry(10.0)
    for reading in K_AV_READINGS:
        assert abs(g.k_av(reading=reading) - value) > 10 * tol, reading
    th = np.radians(np.linspace(30.0, 40.0, 1001))
    k = k_av_literal_of_design(th)
    at = np.degrees(th[np.argmin(np.abs(k - value))])
    assert 33.0 < at < 35.0


# --- summary ---------------------------------------------------------------------------------
def test_summary_for_table1():
    s = Gantry.from_parameters().summary()
    assert tuple(s) == SUMMARY_KEYS == Gantry.summary_keys
    assert all(isinstance(v, float) for k, v in s.items() if k != "quadrature")
    assert s["quadrature"] == "gauss-legendre-48x48"
    g = wu2008_gantry()
    assert s["workspace_area"] == pytest.approx(g.workspace_area(), rel=1e-12)
    assert s["k_av"] == pytest.approx(g.k_av(), rel=1e-12)
    assert s["d1"] == pytest.approx(357.0, abs=0.5) and s["l"] == pytest.approx(616.4, abs=0.05)
    assert s["stroke"] == pytest.approx(900.0, abs=0.5)
    assert 1.0 < s["eta_d"] < 5.0 and 0.0 < s["gtqi"] <= 1.0
    s_m = Gantry.from_parameters(0.5, 0.4, 10.0, 0.1, 0.2, length_unit="m").summary()
    assert s_m["eta_d"] == pytest.approx(s["eta_d"], rel=1e-12)
    assert s_m["workspace_area"] == pytest.approx(s["workspace_area"] * 1e-6, rel=1e-12)
    with pytest.raises(ValueError, match="length_unit"):
        Gantry.from_parameters(length_unit="km")
    # a gantry not made by from_parameters (its task 300 mm higher): the same numbers,
    # eta_d once its length unit is given (NaN without: the dynamics is in metres)
    other = wu2008_gantry().summary()
    assert np.isnan(other["eta_d"]) and other["k_av"] == pytest.approx(s["k_av"], rel=1e-12)
    assert other["d"] == pytest.approx(s["d"], rel=1e-12) and other["gtqi"] == pytest.approx(s["gtqi"], rel=1e-9)
    assert wu2008_gantry().summary(length_unit="mm")["eta_d"] == pytest.approx(s["eta_d"], rel=1e-9)


# --- one topology with the Biglide -----------------------------------------------------------
@pytest.mark.parametrize("mode", MODES)
def test_the_gantry_is_the_biglide_with_a_platform_offset(mode):
    """Both are the two-slider topology of mechopt.mechanisms.sliders: the gantry numbers its
    legs from the left, the Biglide from the right, and reports a point l2/2 above the link
    joint. The same machine as a Biglide (legs and mode swapped; its point is the link
    joint, l2/2 below the gantry's) has the same area, slider positions, Jacobian,
    assembly modes, forward kinematics and k_av."""
    g = Gantry(300.0, 600.0, 700.0, q_min=-100.0, l2=50.0, mode=mode)
    b = Biglide(300.0, 600.0, -100.0, 600.0, mode=mode[::-1])
    assert g.workspace_area() == pytest.approx(b.workspace_area(), rel=1e-12)
    assert g.x_range == b.x_range and g.guides == b.guides[::-1]
    rng = np.random.default_rng(7)
    x, y = rng.uniform(-299.0, 299.0, 400), rng.uniform(-500.0, 900.0, 400)
    np.testing.assert_array_equal(g.reachable(x, y + 25.0), b.reachable(x, y))
    qg, qb = g.slider_positions(x, y + 25.0), b.slider_positions(x, y)
    np.testing.assert_allclose(qg, qb[::-1], rtol=1e-12, atol=1e-9)
    ok = g.reachable(x, y + 25.0)
    np.testing.assert_allclose(g.jacobian(x, y + 25.0)[ok], b.jacobian(x, y)[ok][:, ::-1], rtol=1e-9)
    np.testing.assert_array_equal(g.assembly_of(x, y + 25.0), b.assembly_of(x, y))
    np.testing.assert_allclose(g.chord(x), b.chord(x), rtol=1e-12, atol=1e-9)
    for reading in K_AV_READINGS:
        for leg in (1, 2):
            assert g.k_av(-100.0, 150.0, leg=leg, reading=reading) == pytest.approx(
                b.k_av(-100.0, 150.0, leg=3 - leg, reading=reading), rel=1e-12)
    xg, yg, vg = g.fk(qg[0][ok], qg[1][ok], "up")
    xb, yb, vb = b.fk(qb[0][ok], qb[1][ok], "up")
    np.testing.assert_array_equal(vg, vb)
    np.testing.assert_allclose(xg, xb, atol=1e-9)
    np.testing.assert_allclose(yg - 25.0, yb, atol=1e-9)


def test_max_speed_reading_follows_the_mode():
    """``2 / |tan theta_1 - tan theta_2|`` with the signed link angles: the mirror modes
    agree, the mixed modes (links on both sides) give a larger speed."""
    g = wu2008_gantry()
    k = {m: g.with_mode(m).k_av(reading="max_speed") for m in MODES}
    assert k["--"] == k["++"] and k["-+"] == pytest.approx(k["+-"], rel=1e-12)
    assert k["-+"] > k["--"]


def test_empty_workspace_has_a_degenerate_box():
    g = Gantry(0.3, 0.5, 0.1, q_min=2.0, l2=0.2, mode="+-")  # |c1 - c2| > stroke everywhere
    assert g.workspace_area() == 0.0
    xmin, xmax, ymin, ymax = g.bounding_box()
    assert xmin < xmax and ymin == ymax


def test_dynamics_and_eta_d_of_a_synthesized_gantry():
    """``eta_D`` is a method of the gantry: its dynamics in metres, Wu's Table 2 carried
    over to its link length; Table 2 itself for the Table 1 design."""
    from mechopt.mechanisms.gantry_dynamics import GantryDynamics, GantryInertia

    g = Gantry.from_parameters()
    assert g.eta_d() == g.summary()["eta_d"]
    dyn = g.dynamics()
    assert isinstance(dyn, GantryDynamics) and dyn.gantry.l == pytest.approx(g.l * 1e-3, rel=1e-15)
    table2 = GantryInertia.wu2008()
    assert dyn.inertia.m12 == pytest.approx(table2.m12, rel=1e-12)
    assert dyn.inertia.I12 == pytest.approx(table2.I12, rel=1e-12)
    w = wu2008_gantry()
    assert w.dynamics(length_unit="mm").eta_d() == pytest.approx(g.eta_d(), rel=1e-12)
    assert w.eta_d(inertia=table2, length_unit="mm") == GantryDynamics(w.scaled(1e-3), table2).eta_d()
    with pytest.raises(ValueError, match="length_unit must be given"):
        w.dynamics()
