"""Biglide (PRRRP) of Stan, Maties, Balan 2008: kinematics of the four modes, exact
workspace area, GTQI, Wu's velocity output ratio.

The generic protocol checks also run on the Biglide through tests/test_contract.py.
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from mechopt.mechanisms.biglide import ASSEMBLY_MODES, MODES, SUMMARY_KEYS, Biglide

HYP = settings(max_examples=60, deadline=None, derandomize=True)

# (l1, l2, q1_min, q1_max, q2_min, q2_max): equal strokes; unequal strokes with a
# guide inside the x range (l2 > 2 l1); Stan's non-dimensional range (L1 = 1 assumed).
DESIGNS = [
    (40.0, 100.0, 0.0, 200.0, 0.0, 200.0),
    (20.0, 100.0, -50.0, 150.0, 0.0, 250.0),
    (1.0, 1.1, 0.0, 1.0, 0.0, 1.0),
    (40.0, 100.0, 0.0, 100.0, 30.0, 90.0),
]


def _independent_chord(x, l1, l2, a1, c1, a2, c2, mode):
    """Vertical section of the workspace at x from Stan eq. (5) directly: leg i
    admits y with q_i = y + s_i sqrt(l2^2 - (x - g_i)^2) in [q_i_min, q_i_max]."""
    s1, s2 = (1.0 if ch == "+" else -1.0 for ch in mode)
    lo, hi = [], []
    for g, s, a, c in ((l1, s1, a1, c1), (-l1, s2, a2, c2)):
        r2 = l2 * l2 - (x - g) ** 2
        h = np.sqrt(np.maximum(r2, 0.0))
        lo.append(np.where(r2 >= 0, a - s * h, np.inf))
        hi.append(np.where(r2 >= 0, c - s * h, -np.inf))
    return np.maximum(0.0, np.minimum(*hi) - np.maximum(*lo))


@pytest.mark.parametrize("design", DESIGNS, ids=str)
@pytest.mark.parametrize("mode", MODES)
def test_workspace_area_is_exact(design, mode):
    """Closed form vs a fine trapezoid of independently computed chords (its
    error is below 1e-7 relative at 2e6 panels for these sqrt-type kinks)."""
    m = Biglide(*design, mode=mode)
    l1, l2 = design[:2]
    x = np.linspace(l1 - l2, l2 - l1, 2_000_001)
    ref = np.trapezoid(_independent_chord(x, *design, mode), x)
    w = m.workspace_area()
    assert w == pytest.approx(ref, rel=1e-6, abs=1e-9 * l2 * l2)
    np.testing.assert_allclose(m.chord(x[::1000]), _independent_chord(x[::1000], *design, mode),
                               rtol=1e-12, atol=1e-12 * l2)


def test_workspace_area_raster_of_reachable_agrees():
    m = Biglide(40.0, 100.0, 0.0, 200.0, mode="--")
    xmin, xmax, ymin, ymax = m.bounding_box()
    h = 0.25
    X, Y = np.meshgrid(np.arange(xmin + h / 2, xmax, h), np.arange(ymin + h / 2, ymax, h))
    assert np.count_nonzero(m.reachable(X, Y)) * h * h == pytest.approx(
        m.workspace_area(), rel=2e-3
    )


def test_equal_strokes_closed_form():
    """With equal strokes S and equal lower limits, the chord of "--" is S - |h1 - h2|
    (where positive): check W against that integral with scipy quad."""
    l1, l2, S = 40.0, 100.0, 200.0
    m = Biglide(l1, l2, 0.0, S)

    def chord(x):
        h1 = np.sqrt(l2**2 - (x - l1) ** 2)
        h2 = np.sqrt(l2**2 - (x + l1) ** 2)
        return max(0.0, S - abs(h1 - h2))

    ref = integrate.quad(chord, l1 - l2, l2 - l1, points=[0.0], epsabs=0, epsrel=1e-12)[0]
    assert m.workspace_area() == pytest.approx(ref, rel=1e-10)


def test_mirror_modes_have_equal_areas():
    for design in DESIGNS[::2]:  # equal strokes: x -> -x swaps legs and modes
        a = {mode: Biglide(*design, mode=mode).workspace_area() for mode in MODES}
        assert a["+-"] == pytest.approx(a["-+"], rel=1e-12)
    # y -> -y maps "--" with strokes [a, c] to "++" with [-c, -a]
    w1 = Biglide(40, 100, 10, 150, 30, 90, mode="--").workspace_area()
    w2 = Biglide(40, 100, -150, -10, -90, -30, mode="++").workspace_area()
    assert w1 == pytest.approx(w2, rel=1e-12)


# --- kinematics ----------------------------------------------------------------
@pytest.mark.parametrize("mode", MODES)
def test_ik_is_stan_eq5(mode):
    m = Biglide(40.0, 100.0, -500.0, 500.0, mode=mode)
    x, y = 13.0, 27.0
    q1, q2, ok = m.ik(x, y)
    s1, s2 = (1 if c == "+" else -1 for c in mode)
    assert ok
    assert q1 == pytest.approx(y + s1 * np.sqrt(100**2 - (x - 40) ** 2), rel=1e-15)
    assert q2 == pytest.approx(y + s2 * np.sqrt(100**2 - (x + 40) ** 2), rel=1e-15)
    # the links have length l2
    assert np.hypot(x - 40, y - q1) == pytest.approx(100.0, rel=1e-15)
    assert np.hypot(x + 40, y - q2) == pytest.approx(100.0, rel=1e-15)


@pytest.mark.parametrize("mode", MODES)
def test_ik_fk_round_trip_hypothesis(mode):
    m = Biglide(20.0, 100.0, -50.0, 150.0, 0.0, 250.0, mode=mode)
    xmin, xmax, ymin, ymax = m.bounding_box()

    @HYP
    @given(st.floats(0, 1), st.floats(0, 1))
    def check(u, v):
        x, y = xmin + u * (xmax - xmin), ymin + v * (ymax - ymin)
        q1, q2, ok = m.ik(x, y)
        if not ok:
            assert np.isnan(q1) and np.isnan(q2)
            return
        asm = m.assembly_of(x, y).item()
        xf, yf, valid = m.fk(q1, q2, asm)
        assert valid
        if abs(m.type2_function(x, y)) > 1e-6:  # on x = 0 (mixed modes) both coincide
            assert np.hypot(xf - x, yf - y) <= 1e-9 * m.l2
        p1, p2, ok2 = m.ik(xf, yf)
        assert ok2
        assert abs(p1 - q1) <= 1e-9 * m.l2 and abs(p2 - q2) <= 1e-9 * m.l2

    check()


def test_assembly_of_modes():
    """"--" is always "up" (P above S2 -> S1), "++" always "down"; the mixed modes
    switch across x = 0."""
    rng = np.random.default_rng(3)
    for mode, expect in (("--", "up"), ("++", "down")):
        m = Biglide(40.0, 100.0, -300.0, 300.0, mode=mode)
        x = rng.uniform(-59, 59, 500)
        y = rng.uniform(-100, 100, 500)
        ok = m.reachable(x, y)
        assert np.all(m.assembly_of(x[ok], y[ok]) == expect)
    m = Biglide(40.0, 100.0, -300.0, 300.0, mode="+-")
    a = m.assembly_of([-30.0, 30.0], [0.0, 0.0])
    assert a[0] != a[1]


@HYP
@given(st.floats(-100, 100), st.floats(-100, 100), st.sampled_from(ASSEMBLY_MODES))
def test_fk_points_lie_on_both_link_circles(q1, q2, assembly):
    m = Biglide(40.0, 100.0, -100.0, 100.0)
    x, y, valid = m.fk(q1, q2, assembly)
    if not valid:
        assert 4 * 40.0**2 + (q1 - q2) ** 2 > 4 * 100.0**2 - 1e-9
        return
    assert np.hypot(x - 40, y - q1) == pytest.approx(100.0, rel=1e-12)
    assert np.hypot(x + 40, y - q2) == pytest.approx(100.0, rel=1e-12)
    cross = 80.0 * (y - q2) - (q1 - q2) * (x + 40)
    assert (cross >= -1e-9) if assembly == "up" else (cross <= 1e-9)


def test_fk_respects_strokes():
    m = Biglide(40.0, 100.0, 0.0, 100.0)
    assert not m.fk(150.0, 50.0)[2]
    assert m.fk(150.0, 50.0, limits=False)[2]
    assert m.fk(0.0, 100.0)[2]  # at the limits
    x, y, _ = m.fk(0.0, 100.0)
    assert m.reachable(x, y)  # poses at a limit are reachable (LIMIT_RTOL)


@pytest.mark.parametrize("mode", MODES)
def test_jacobian_is_wu_eq4_and_matches_finite_differences(mode):
    m = Biglide(20.0, 100.0, -50.0, 150.0, 0.0, 250.0, mode=mode)
    rng = np.random.default_rng(4)
    xmin, xmax, ymin, ymax = m.bounding_box()
    x = rng.uniform(xmin, xmax, 4000)
    y = rng.uniform(ymin, ymax, 4000)
    keep = m.reachable(x, y) & (m.serial_clearance(x, y) > 1.0) & (m.lci(x, y) > 0.05)
    x, y = x[keep][:300], y[keep][:300]
    assert x.size > 50
    J = m.jacobian(x, y)
    q1, q2, _ = m.ik(x, y)
    np.testing.assert_allclose(J[:, :, 1], 1.0, rtol=1e-15)  # Wu eq. (4): J_i = [tan th_i, 1]
    np.testing.assert_allclose(J[:, 0, 0], (x - 20.0) / (y - q1), rtol=1e-13)
    h = 1e-5 * m.length_scale
    fd = np.empty_like(J)
    for j, (dx, dy) in enumerate(((h, 0.0), (0.0, h))):
        p1, p2, _ = m.ik(x + dx, y + dy)
        n1, n2, _ = m.ik(x - dx, y - dy)
        fd[:, :, j] = np.stack([p1 - n1, p2 - n2], -1) / (2 * h)
    rel = np.linalg.norm(J - fd, axis=(-2, -1)) / np.linalg.norm(J, axis=(-2, -1))
    assert rel.max() < 1e-6


def test_singularities():
    """Type II only on x = 0 in the mixed modes; type I on x = +/-(l2 - l1)."""
    y = np.linspace(-80, 80, 9)
    for mode in ("+-", "-+"):
        m = Biglide(40.0, 100.0, -300.0, 300.0, mode=mode)
        assert np.all(m.classify_singularity(0.0, y) == "type-II")
        assert np.all(m.tqi(0.0, y) == 0.0)
    m = Biglide(40.0, 100.0, -300.0, 300.0, mode="--")
    x = np.linspace(-59.9, 59.9, 2001)
    assert np.all(np.abs(m.type2_function(x, 50.0)) > 0.1)
    for mode in MODES:
        m = Biglide(40.0, 100.0, -300.0, 300.0, mode=mode)
        assert np.all(m.classify_singularity([-60.0, 60.0], [20.0, 20.0]) == "type-I")


def test_tqi_constant_along_y_and_tqi_of_x():
    """Stan Fig. 30: the Biglide's performance is constant along y."""
    for mode in MODES:
        m = Biglide(40.0, 100.0, -1000.0, 1000.0, mode=mode)
        x = np.linspace(-59, 59, 41)
        t = m.tqi(x[:, None], np.linspace(-300, 300, 7)[None, :])
        np.testing.assert_allclose(t, t[:, :1].repeat(7, 1), rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(m.tqi_of_x(x), t[:, 0], rtol=1e-12, atol=1e-15)


def test_serial_clearance_is_the_distance_to_the_boundary():
    for design in DESIGNS[:2]:
        for mode in MODES:
            m = Biglide(*design, mode=mode)
            rng = np.random.default_rng(5)
            xmin, xmax, ymin, ymax = m.bounding_box()
            x = rng.uniform(xmin, xmax, 4000)
            y = rng.uniform(ymin, ymax, 4000)
            c = m.serial_clearance(x, y)
            ok = m.reachable(x, y)
            assert np.all(ok == (c >= 0))
            keep = ok & (c > 0.5)
            x, y, c = x[keep][:15], y[keep][:15], c[keep][:15]
            phi = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
            for xi, yi, ci in zip(x, y, c):
                for rad in np.linspace(0, 0.999 * ci, 4)[1:]:
                    assert np.all(m.reachable(xi + rad * np.cos(phi), yi + rad * np.sin(phi)))
                assert not np.all(m.reachable(xi + 1.001 * ci * np.cos(phi),
                                              yi + 1.001 * ci * np.sin(phi)))


# --- GTQI and k_av -----------------------------------------------------------------
@pytest.mark.parametrize("mode", ["--", "+-"])
def test_gtqi_quad_and_raster_agree(mode):
    m = Biglide(40.0, 100.0, 0.0, 200.0, mode=mode)
    g = m.gtqi()
    val, err = m.tqi_integral(return_error=True)
    assert err <= 1e-8 * val
    # independent: 2-D mid-point raster of the base-class TQI at two steps
    r1, r2 = m.gtqi("raster", step=0.5), m.gtqi("raster", step=0.1)
    assert abs(r2 - g) < abs(r1 - g) + 1e-6
    assert r2 == pytest.approx(g, rel=5e-4)


def test_k_v_is_cot_theta_and_k_av_closed_form():
    m = Biglide(357.0, 616.4, 0.0, 900.0)
    x = np.linspace(-250, 250, 11)
    k1, k2 = m.k_v(x, 700.0)
    J = m.jacobian(x, 700.0)
    np.testing.assert_allclose(k1, 1 / np.abs(J[:, 0, 0]), rtol=1e-12)  # y_dot = 0 in eq. (4)
    np.testing.assert_allclose(k2, 1 / np.abs(J[:, 1, 0]), rtol=1e-12)
    f = lambda t: float(np.sqrt(616.4**2 - (t - 357) ** 2) / abs(t - 357))  # noqa: E731
    ref = integrate.quad(f, -250, 250, epsrel=1e-12)[0] / 500
    assert m.k_av(-250, 250, leg=1) == pytest.approx(ref, rel=1e-10)
    assert m.k_av(-250, 250, leg=2) == pytest.approx(ref, rel=1e-10)  # symmetric
    # with Wu's Table 1 dimensions (l = 616.4, d1 = 357, x in [-b/2, b/2]) the literal
    # eq. (7) gives 1.7875, not the printed 1.05 (as recorded in wu2008.csv)
    assert m.k_av(-250, 250) == pytest.approx(1.7875, abs=5e-5)
    # a range containing the guide diverges
    m2 = Biglide(20.0, 100.0, 0.0, 100.0)
    assert m2.k_av(leg=1) == np.inf
    with pytest.raises(ValueError, match="leg must be one of 1, 2"):
        m.k_av(leg=3)
    with pytest.raises(ValueError, match="x_max must be greater"):
        m.k_av(10, 10)
    with pytest.raises(ValueError, match="x range"):
        m.k_av(-300, 250)


def test_summary():
    m = Biglide(1.0, 1.1, 0.0, 1.0)
    s = m.summary()
    assert tuple(s) == SUMMARY_KEYS == Biglide.summary_keys
    assert all(isinstance(v, float) for k, v in s.items() if k != "quadrature")
    assert s["quadrature"] == "adaptive-1d"
    assert s["workspace_area"] == pytest.approx(m.workspace_area(), rel=1e-15)
    assert s["gtqi"] == pytest.approx(m.gtqi(), rel=1e-12)
    assert 0 < s["gtqi"] < 1
    assert s["k_av_1"] == pytest.approx(s["k_av_2"], rel=1e-12)
    assert s["k_av_1"] == m.k_av(*m.x_range, leg=1)  # the whole x range by default


def test_empty_workspace():
    m = Biglide(40.0, 100.0, 0.0, 10.0, 500.0, 510.0)  # strokes far apart
    assert m.workspace_area() == 0.0
    assert np.isnan(m.gtqi())


# --- validation ------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs,match",
    [
        (dict(l1=0.0), "l1 must be a positive"),
        (dict(l1=np.nan), "l1 must be finite"),
        (dict(l2=-1.0), "l2 must be a positive"),
        (dict(l2=40.0), "l2 must be greater than l1"),
        (dict(l2=30.0), "l2 must be greater than l1"),
        (dict(q1_min=100.0, q1_max=0.0), "q1_max must be greater than q1_min"),
        (dict(q2_min=5.0, q2_max=5.0), "q2_max must be greater than q2_min"),
        (dict(q1_max=np.inf), "q1_max must be finite"),
        (dict(mode="+"), "mode must be one of"),
        (dict(mode="up"), "mode must be one of"),
    ],
)
def test_constructor_rejects_bad_input(kwargs, match):
    args = dict(l1=40.0, l2=100.0, q1_min=0.0, q1_max=100.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        Biglide(**args)


def test_method_arguments_are_validated():
    m = Biglide(40.0, 100.0, 0.0, 100.0)
    with pytest.raises(ValueError, match="assembly must be one of"):
        m.fk(0.0, 0.0, "left")
    with pytest.raises(ValueError, match="method must be one of"):
        m.gtqi("exact")
    with pytest.raises(ValueError, match="step must be a positive"):
        m.gtqi("raster", step=-1.0)
    with pytest.raises(ValueError, match="broadcast"):
        m.ik(np.zeros(3), np.zeros(2))


def test_with_mode_and_attributes():
    m = Biglide(40.0, 100.0, 0.0, 100.0, 10.0, 120.0)
    n = m.with_mode("+-")
    assert n.mode == "+-" and n.q2_max == 120.0 and n.l1 == 40.0
    assert m.guides == (40.0, -40.0) and m.x_range == (-60.0, 60.0)
    assert m.joint_limits == ((0.0, 100.0), (10.0, 120.0))
    assert m.length_scale == 100.0 and not m.angular_joints


def test_gauss_gtqi_agrees_with_adaptive_quadrature():
    from mechopt import Biglide

    for l2 in (1.01, 1.1, 1.2):
        for mode in ("--", "+-"):
            g = Biglide(1.0, l2, 0.0, 1.0, mode=mode)
            assert g.gtqi(method="gauss") == pytest.approx(g.gtqi(method="quad"), rel=1e-6)
