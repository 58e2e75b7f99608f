"""Wu 2008 gantry dynamics: inertia matrix from energy, equations of motion, kappa_D, eta_D."""
from __future__ import annotations

import math

import numpy as np
import pytest

from mechopt.mechanisms import gantry_dynamics as dynamics
from mechopt.core import motion
from mechopt.data import published_values
from mechopt.mechanisms.gantry_dynamics import (
    ELLIPSE_KINDS,
    GantryDynamics,
    GantryInertia,
    rectangle_rule,
    wu2008_driving_forces,
    wu2008_published,
)
from mechopt.mechanisms.gantry import MODES, Gantry, wu2008_gantry
from mechopt.core.motion import trapezoidal_profile, wu2008_trajectory
from mechopt.core.quadrature import grid_over

PUB = wu2008_published()


@pytest.fixture(scope="module")
def wu():
    return GantryDynamics(wu2008_gantry(10.0, unit="m"), GantryInertia.wu2008())


@pytest.fixture(scope="module")
def sym():
    return GantryDynamics(wu2008_gantry(10.0, unit="m"), GantryInertia.wu2008().symmetric_variant())


def _task_points(dyn, n=40, margin=1e-6):
    xmin, xmax, ymin, ymax = dyn.gantry.task_workspace
    X, Y = np.meshgrid(np.linspace(xmin + margin, xmax - margin, n),
                       np.linspace(ymin + margin, ymax - margin, n))
    return X.ravel(), Y.ravel()


def _random_poses(dyn, rng, n):
    xmin, xmax, ymin, ymax = dyn.gantry.task_workspace
    return rng.uniform(xmin, xmax, n), rng.uniform(ymin, ymax, n)


# --- data --------------------------------------------------------------------------
def test_table2_loaded_from_the_data_file():
    p = GantryInertia.wu2008()
    for k in ("m11", "m21", "m12", "m22", "m13", "m23", "m4", "mN", "I12", "I22"):
        assert getattr(p, k) == PUB[("table2", k)][0]
    assert p.g == 9.8
    # sec. 6.2: "each [counterweight] is half of the masses of all moving parts"
    assert p.moving_mass == 924.0 and p.m13 == p.m23 == p.moving_mass / 2


def test_data_and_motion_live_apart_and_stay_importable_from_dynamics():
    """Wu's printed numbers come from mechopt/data/wu2008.csv (with their source), the
    motion profile from mechopt.core.motion; the old names still import from mechopt.mechanisms.gantry_dynamics."""
    assert dynamics.trapezoidal_profile is motion.trapezoidal_profile
    assert dynamics.wu2008_trajectory is motion.wu2008_trajectory
    assert PUB == published_values("wu2008") and PUB is not published_values("wu2008")
    assert PUB[("table2", "g")] == (dynamics.G_WU2008, "m/s^2", 1, "sec. 5.2, text after eq. (29)")
    assert all(source for _, _, _, source in PUB.values())


def test_symmetric_variant():
    p = GantryInertia.wu2008().symmetric_variant()
    assert (p.m21, p.m22, p.I22, p.m5) == (p.m11, p.m12, p.I12, p.m4)
    assert p.m13 == p.m23 == p.moving_mass / 2


@pytest.mark.parametrize("name", ["m11", "m23", "m4", "mN", "I12", "s22", "m5", "g"])
def test_negative_mass_or_inertia_rejected(name):
    kw = dict(m11=1, m21=1, m12=1, m22=1, m13=1, m23=1, m4=1, mN=1, I12=1, I22=1)
    kw[name] = -1.0
    with pytest.raises(ValueError, match=name) as err:
        GantryInertia(**kw)
    assert "\n" not in str(err.value)
    with pytest.raises(ValueError, match=name):
        GantryInertia(**{**kw, name: float("nan")})


def test_physically_impossible_link_inertia_rejected():
    g = wu2008_gantry(unit="m")
    p = GantryInertia.wu2008()
    with pytest.raises(ValueError, match="A1B1"):  # I about B below m s^2
        GantryDynamics(g, GantryInertia(**{**_fields(p), "I12": 1.0}))
    with pytest.raises(ValueError, match="A2B2"):
        GantryDynamics(g, GantryInertia(**{**_fields(p), "s22": 2.0}))
    with pytest.raises(ValueError, match="gantry"):
        GantryDynamics("gantry", p)
    with pytest.raises(ValueError, match="inertia"):
        GantryDynamics(g, {"m11": 1})


def _fields(p):
    from dataclasses import asdict

    return asdict(p)


# --- inertia matrix ---------------------------------------------------------------------
@pytest.mark.parametrize("variant", ["wu", "sym"])
def test_mass_matrix_symmetric_positive_definite_over_task_workspace(variant, wu, sym):
    dyn = {"wu": wu, "sym": sym}[variant]
    x, y = _task_points(dyn)
    M = dyn.mass_matrix(x, y)
    assert M.shape == (x.size, 2, 2) and np.all(np.isfinite(M))
    np.testing.assert_array_equal(M, np.swapaxes(M, -1, -2))
    ev = np.linalg.eigvalsh(M)
    assert ev.min() > 0
    # M depends on x only (theta_i does, eq. 1)
    np.testing.assert_array_equal(dyn.mass_matrix(x, np.full_like(y, 0.5)), M)


def _kinetic_energy_from_bodies(dyn, x, y, xd, yd, h=1e-6):
    """sum 1/2 m |v_c|^2 + 1/2 I_c omega^2, with v_c, omega by central differences of the
    body positions along p(t) = p + t p_dot (positions come from the geometry only)."""
    plus = dyn.bodies(x + h * xd, y + h * yd)
    minus = dyn.bodies(x - h * xd, y - h * yd)
    T = 0.0
    for name in plus:
        m, Ic, cxp, cyp, php = plus[name]
        _, _, cxm, cym, phm = minus[name]
        vx, vy, w = (cxp - cxm) / (2 * h), (cyp - cym) / (2 * h), (php - phm) / (2 * h)
        T = T + 0.5 * m * (vx * vx + vy * vy) + 0.5 * Ic * w * w
    return T


@pytest.mark.parametrize("variant", ["wu", "sym"])
def test_kinetic_energy_equals_sum_over_bodies(variant, wu, sym):
    dyn = {"wu": wu, "sym": sym}[variant]
    rng = np.random.default_rng(7)
    x, y = _random_poses(dyn, rng, 400)
    xd, yd = rng.normal(size=(2, 400))
    T_bodies = _kinetic_energy_from_bodies(dyn, x, y, xd, yd)
    T_M = dyn.kinetic_energy(x, y, xd, yd)
    rel = np.abs(T_M - T_bodies) / T_bodies
    assert rel.max() < 1e-6, rel.max()


@pytest.mark.parametrize("mode", MODES)
def test_kinetic_energy_every_mode_and_offsets(mode):
    g = Gantry(0.2, 0.6, 1.5, q_min=-1.0, l2=0.15, mode=mode)
    p = GantryInertia(m11=10, m21=7, m12=3, m22=4, m13=2, m23=5, m4=3.5, mN=9, I12=0.5,
                      I22=0.6, s12=0.2, s22=0.35, I4=0.4, s4=0.25, m5=1.5, I5=0.2, s5=0.3)
    dyn = GantryDynamics(g, p)
    rng = np.random.default_rng(8)
    lo, hi = g.x_range
    x = rng.uniform(0.9 * lo, 0.9 * hi, 2000)
    ylo, yhi = g.y_interval(x)
    ok = np.isfinite(ylo) & (yhi - ylo > 0.05)
    x = x[ok][:300]
    y = rng.uniform(ylo[ok][:300] + 0.02, yhi[ok][:300] - 0.02)
    keep = np.abs(g.type2_function(x, y)) > 0.05
    x, y = x[keep], y[keep]
    assert x.size > 50
    xd, yd = rng.normal(size=(2, x.size))
    T_bodies = _kinetic_energy_from_bodies(dyn, x, y, xd, yd)
    rel = np.abs(dyn.kinetic_energy(x, y, xd, yd) - T_bodies) / T_bodies
    assert rel.max() < 1e-6, rel.max()
    ev = np.linalg.eigvalsh(dyn.mass_matrix(x, y))
    assert ev.min() > 0


def test_bodies_geometry(wu):
    g = wu.gantry
    x, y = _task_points(wu, 7)
    b = wu.bodies(x, y)
    q1, q2, _ = g.ik(x, y)
    # link mass centres lie at s = l/2 from the slider joints
    for name, xb, q in (("A1B1", -g.d1, q1), ("A2B2", g.d1, q2), ("A3B3", -g.d1, q1 + g.l2)):
        _, _, cx, cy, _ = b[name]
        np.testing.assert_allclose(np.hypot(cx - xb, cy - q), g.l / 2, rtol=1e-12)
    np.testing.assert_allclose(b["counterweight1"][3], -q1)


def test_mass_matrix_dx_matches_finite_differences(wu):
    x, y = _task_points(wu, 15, margin=1e-3)
    h = 1e-6
    fd = (wu.mass_matrix(x + h, y) - wu.mass_matrix(x - h, y)) / (2 * h)
    np.testing.assert_allclose(wu.mass_matrix_dx(x, y), fd, rtol=1e-6, atol=1e-6)


# --- equations of motion ----------------------------------------------------------------
def _potential(dyn, x, y):
    return sum(dyn.inertia.g * m * cy for m, _, _, cy, _ in dyn.bodies(x, y).values())


def test_gravity_is_gradient_of_body_potential(wu):
    x, y = _task_points(wu, 9, margin=1e-3)
    h = 1e-6
    Gx = (_potential(wu, x + h, y) - _potential(wu, x - h, y)) / (2 * h)
    Gy = (_potential(wu, x, y + h) - _potential(wu, x, y - h)) / (2 * h)
    G = wu.gravity(x, y)
    np.testing.assert_allclose(G[:, 0], Gx, rtol=1e-6, atol=1e-5)
    np.testing.assert_allclose(G[:, 1], Gy, atol=1e-4)
    # Table 2 counterweights cancel the vertical weight exactly
    np.testing.assert_allclose(G[:, 1], 0.0, atol=1e-9)


def test_lagrange_equations_by_finite_differences(wu):
    """J^T tau = d/dt(dT/dp_dot) - dT/dp + dV/dp along a curved, accelerating path."""
    g = wu.gantry
    xc, yc = 0.02, 0.5

    def path(t):  # position, velocity, acceleration
        x = xc + 0.1 * np.sin(3 * t) + 0.2 * t**2
        y = yc + 0.05 * np.cos(2 * t) - 0.3 * t
        xd = 0.3 * np.cos(3 * t) + 0.4 * t
        yd = -0.1 * np.sin(2 * t) - 0.3
        xdd = -0.9 * np.sin(3 * t) + 0.4
        ydd = -0.2 * np.cos(2 * t)
        return x, y, xd, yd, xdd, ydd

    t = np.linspace(0.0, 0.3, 13)
    x, y, xd, yd, xdd, ydd = path(t)
    F1, F2 = wu.driving_forces(x, y, xd, yd, xdd, ydd)
    J = g.jacobian(x, y)
    Q = np.einsum("nji,nj->ni", J, np.stack([F1, F2], -1))  # J^T tau
    h = 1e-5

    def momentum(tt):
        px, py, pxd, pyd, _, _ = path(tt)
        M = wu.mass_matrix(px, py)
        return np.einsum("nij,nj->ni", M, np.stack([pxd, pyd], -1))

    dmom = (momentum(t + h) - momentum(t - h)) / (2 * h)
    dT = np.stack([
        (wu.kinetic_energy(x + h, y, xd, yd) - wu.kinetic_energy(x - h, y, xd, yd)) / (2 * h),
        (wu.kinetic_energy(x, y + h, xd, yd) - wu.kinetic_energy(x, y - h, xd, yd)) / (2 * h),
    ], -1)
    dV = np.stack([
        (_potential(wu, x + h, y) - _potential(wu, x - h, y)) / (2 * h),
        (_potential(wu, x, y + h) - _potential(wu, x, y - h)) / (2 * h),
    ], -1)
    ref = dmom - dT + dV
    np.testing.assert_allclose(Q, ref, rtol=1e-5, atol=1e-4 * np.abs(ref).max())


def test_power_balance_along_table3_path(wu):
    """tau . q_dot = d(T + V)/dt in every phase of the Table 3 motion."""
    tr = wu2008_trajectory(651)
    T0, Tf = tr["T0"], tr["Tf"]
    t = np.concatenate([np.linspace(0.01, T0 - 0.01, 5), np.linspace(T0 + 0.01, Tf - T0 - 0.01, 5),
                        np.linspace(Tf - T0 + 0.01, Tf - 0.01, 5)])
    pub = {k: PUB[("table3", k)][0] for k in ("x0", "y0", "x1", "y1", "v_max", "a_s")}

    def state(tt):
        return trapezoidal_profile((pub["x0"], pub["y0"]), (pub["x1"], pub["y1"]), pub["v_max"],
                                   pub["a_s"], tt)

    def energy(tt):
        s = state(tt)
        return wu.kinetic_energy(s["x"], s["y"], s["xd"], s["yd"]) + _potential(wu, s["x"], s["y"])

    h = 1e-6
    dE = (energy(t + h) - energy(t - h)) / (2 * h)
    s = state(t)
    F1, F2 = wu.driving_forces(s["x"], s["y"], s["xd"], s["yd"], s["xdd"], s["ydd"])
    q1d, q2d = np.einsum("nij,nj->ni", wu.gantry.jacobian(s["x"], s["y"]),
                         np.stack([s["xd"], s["yd"]], -1)).T
    power = F1 * q1d + F2 * q2d
    np.testing.assert_allclose(power, dE, rtol=1e-5, atol=1e-6 * np.abs(power).max())


def test_static_forces_and_batch(wu):
    x, y = _task_points(wu, 6)
    F1, F2 = wu.driving_forces(x, y, 0.0, 0.0, 0.0, 0.0)
    Jt = np.swapaxes(wu.gantry.jacobian(x, y), -1, -2)
    tau = np.linalg.solve(Jt, wu.gravity(x, y)[..., None])[..., 0]
    np.testing.assert_allclose(np.stack([F1, F2], -1), tau, rtol=1e-10, atol=1e-9)
    F1b = np.array([wu.driving_forces(a, b, 0.1, 0.2, 1.0, -2.0)[0] for a, b in zip(x, y)])
    np.testing.assert_allclose(wu.driving_forces(x, y, 0.1, 0.2, 1.0, -2.0)[0], F1b, rtol=1e-13)


def test_table3_trajectory_and_forces():
    tr = wu2008_trajectory(651)
    assert tr["T0"] == pytest.approx(0.15, abs=5e-4)  # |v_max| / |a_s| = 1/6.67
    assert tr["Tf"] == pytest.approx(0.65, abs=5e-4)  # eq. (45)
    assert tr["x"][0] == -0.25 and tr["x"][-1] == pytest.approx(0.25, abs=1e-12)
    np.testing.assert_array_equal(tr["y"], 0.5)
    assert np.max(np.abs(tr["xd"])) == pytest.approx(1.0)
    assert np.max(np.abs(tr["xdd"])) == pytest.approx(6.67)
    out = wu2008_driving_forces(wu2008_gantry(10.0, unit="m"), 651)
    assert np.all(np.isfinite(out["F1"])) and np.all(np.isfinite(out["F2"]))
    # zero acceleration and constant speed: forces continuous across the cruise
    cruise = (out["t"] > out["T0"] + 1e-3) & (out["t"] < out["Tf"] - out["T0"] - 1e-3)
    assert np.max(np.abs(np.diff(out["F1"][cruise]))) < 0.05 * np.ptp(out["F1"])


def test_trapezoidal_profile_triangular_and_errors():
    pr = trapezoidal_profile((0, 0), (0.01, 0), 1.0, 1.0, np.linspace(0, 1, 101))
    assert pr["T0"] == pytest.approx(0.1) and pr["Tf"] == pytest.approx(0.2)
    assert pr["x"][-1] == pytest.approx(0.01)
    with pytest.raises(ValueError, match="v_max"):
        trapezoidal_profile((0, 0), (1, 0), 0.0, 1.0, [0.0])
    with pytest.raises(ValueError, match="p1 must differ"):
        trapezoidal_profile((0, 0), (0, 0), 1.0, 1.0, [0.0])


# --- kappa_D, eta_D, GIE -----------------------------------------------------------------
def test_kappa_d_is_the_condition_number_of_jt_inv_m(wu):
    x, y = _task_points(wu, 12)
    L = np.linalg.solve(np.swapaxes(wu.gantry.jacobian(x, y), -1, -2), wu.mass_matrix(x, y))
    np.testing.assert_allclose(wu.inertia_matrix(x, y), L, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(wu.kappa_d(x, y), np.linalg.cond(L), rtol=1e-10)
    assert np.all(wu.kappa_d(x, y) >= 1.0)
    pointwise = np.array([wu.kappa_d(a, b) for a, b in zip(x, y)])
    np.testing.assert_allclose(wu.kappa_d(x, y), pointwise, rtol=1e-14)
    assert np.isnan(wu.kappa_d(10.0, 0.0))


def test_kappa_d_symmetric_only_for_the_symmetric_variant(wu, sym):
    """Wu sec. 6.3 / Fig. 7: symmetric about the y axis with link A4B4; Fig. 6 / conclusion 2:
    not symmetric for the built machine."""
    X, Y, Ks = sym.kappa_d_map(n=41)
    np.testing.assert_allclose(Ks, Ks[:, ::-1], rtol=1e-11)
    _, _, Kw = wu.kappa_d_map(n=41)
    asym = np.abs(Kw - Kw[:, ::-1]) / Kw
    assert asym.max() > 0.05


def test_kappa_d_more_isotropic_in_the_centre(wu, sym):
    """Wu sec. 6.2: "more isotropic in the centre than at the peripheries"."""
    for dyn in (wu, sym):
        xmin, xmax = dyn.gantry.task_workspace[:2]
        k = dyn.kappa_d(np.array([xmin, 0.0, xmax]), 0.5)
        assert k[1] < k[0] and k[1] < k[2]


def test_eta_d_quadratures_agree(wu):
    eta = wu.eta_d(n=48)
    assert wu.eta_d(n=96) == pytest.approx(eta, rel=1e-9)
    grid = grid_over(wu.gantry.task_workspace, 0.001)  # mid-point rule, error O(step^2)
    X, Y = grid.points()
    assert grid.mean(wu.kappa_d(X, Y), np.ones(X.shape, bool)) == pytest.approx(eta, rel=1e-4)
    x, y, w = rectangle_rule(wu.gantry.task_workspace, 48)
    k = wu.kappa_d(x, y)
    assert wu.eta_d_std() == pytest.approx(math.sqrt(np.sum(w * (k - eta) ** 2)), rel=1e-12)
    assert 1.0 < eta < k.max()
    with pytest.raises(ValueError, match="region"):
        wu.eta_d(region=(0.0, -1.0, 0.0, 1.0))
    with pytest.raises(ValueError, match="inside the reachable"):
        wu.eta_d(region=(-1.0, 1.0, 0.0, 1.0))


@pytest.mark.parametrize("kind", ELLIPSE_KINDS)
def test_inertia_ellipse_axes(kind, wu):
    x, y = _task_points(wu, 8)
    major, minor, ang = wu.inertia_ellipse(x, y, kind)
    assert np.all(major >= minor) and np.all(np.abs(ang) <= np.pi / 2)
    u = np.stack([np.cos(ang), np.sin(ang)], -1)
    v = np.stack([-np.sin(ang), np.cos(ang)], -1)
    if kind == "acceleration":
        L = wu.inertia_matrix(x, y)
        np.testing.assert_allclose(major / minor, wu.kappa_d(x, y), rtol=1e-9)
        # the boundary points major*u and minor*v need unit driving force
        np.testing.assert_allclose(np.linalg.norm(np.einsum("nij,nj->ni", L, major[:, None] * u), axis=-1), 1, rtol=1e-9)
        np.testing.assert_allclose(np.linalg.norm(np.einsum("nij,nj->ni", L, minor[:, None] * v), axis=-1), 1, rtol=1e-9)
    else:
        M = wu.mass_matrix(x, y)
        for r, e in ((major, u), (minor, v)):
            pe = r[:, None] * e
            np.testing.assert_allclose(np.einsum("ni,nij,nj->n", pe, M, pe), 1.0, rtol=1e-10)
    with pytest.raises(ValueError, match="kind"):
        wu.inertia_ellipse(0.0, 0.5, "force")


def test_symmetric_variant_axis_on_the_y_axis(sym):
    """On the y axis the symmetric machine's ellipse axes are the x and y directions.

    Wu sec. 6.3 says acceleration there is easiest along y; with mid-link mass centres
    mechopt finds the acceleration ellipse's major axis along x (see the report)."""
    major, minor, ang = sym.inertia_ellipse(0.0, 0.5)
    assert abs(ang) < 1e-12 or abs(abs(ang) - np.pi / 2) < 1e-12
