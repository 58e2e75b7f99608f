"""Five-bar (5R) specific properties: symmetry, scale invariance, Le 2013's IK
formulas written out literally, FK assembly convention, input validation."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from mechanism_cases import sample_away_from_singularities
from mechopt.mechanisms.five_bar.model import ASSEMBLY_MODES, MODES, FiveBar

HYP = settings(
    max_examples=25,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.filter_too_much],
)

LENGTHS = [(1.0, 1.5, 0.5), (1.6, 0.9, 0.5), (1.2, 1.8, 0.0), (0.7, 1.7, 0.6), (1.0, 1.0, 1.0)]

@st.composite
def design(draw):
    """(r1, r2, r3) with r1 + r2 + r3 = 3, r1, r2 >= 0.2, r3 in [0, 1.5]."""
    r3 = draw(st.floats(0.0, 1.5))
    r1 = draw(st.floats(0.2, 3.0 - r3 - 0.2))
    r2 = 3.0 - r3 - r1
    return r1, r2, r3


def _points(mech, seed, n=300):
    return sample_away_from_singularities(mech, np.random.default_rng(seed), n)


# --- symmetry --------------------------------------------------------------------
@pytest.mark.parametrize("lengths", LENGTHS, ids=str)
@pytest.mark.parametrize("mode", ["+-", "-+"])
def test_mirror_symmetry_of_symmetric_modes(lengths, mode):
    """Modes "+-" and "-+" are symmetric about the y axis: lci(x, y) == lci(-x, y)
    and theta1(x, y) + theta2(-x, y) == pi."""
    m = FiveBar(*lengths, mode)
    x, y = _points(m, 1)
    np.testing.assert_allclose(m.lci(-x, y), m.lci(x, y), rtol=1e-12, atol=1e-15)
    t1, _, _ = m.ik(x, y)
    _, t2m, _ = m.ik(-x, y)
    np.testing.assert_allclose(t1 + t2m, np.pi, rtol=0, atol=1e-12)
    # q1(x, y) = pi - q2(-x, y) differentiates into J(-x, y) = -P J(x, y) M with P the
    # row swap and M = diag(-1, 1)
    J = m.jacobian(x, y)
    Jm = m.jacobian(-x, y)
    np.testing.assert_allclose(Jm[:, 0, 0], J[:, 1, 0], rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(Jm[:, 0, 1], -J[:, 1, 1], rtol=1e-10, atol=1e-12)


@pytest.mark.parametrize("lengths", LENGTHS[:2] + LENGTHS[3:], ids=str)
def test_modes_plus_plus_and_minus_minus_are_mirror_images(lengths):
    pp, mm = FiveBar(*lengths, "++"), FiveBar(*lengths, "--")
    x, y = _points(pp, 2)
    np.testing.assert_allclose(mm.lci(-x, y), pp.lci(x, y), rtol=1e-12, atol=1e-15)
    t1, _, _ = pp.ik(x, y)
    _, t2m, _ = mm.ik(-x, y)
    np.testing.assert_allclose(t1 + t2m, np.pi, rtol=0, atol=1e-12)


@pytest.mark.parametrize("mode", ["+-", "-+", "++", "--"])
def test_reflection_in_x_axis(mode):
    """Reflecting the pose in the x axis (y -> -y) swaps each elbow sign: the
    conditioning of mode (s1, s2) at (x, -y) is that of (-s1, -s2) at (x, y)."""
    flip = {"+": "-", "-": "+"}
    m = FiveBar(1.0, 1.5, 0.5, mode)
    f = FiveBar(1.0, 1.5, 0.5, flip[mode[0]] + flip[mode[1]])
    x, y = _points(m, 3)
    np.testing.assert_allclose(f.lci(x, -y), m.lci(x, y), rtol=1e-12, atol=1e-15)


def test_r3_zero_with_equal_signs_is_singular_everywhere():
    """With r3 = 0 the modes "++" and "--" put both elbows on one point, so det A = 0
    at every reachable pose (why mechanism_cases leaves them out)."""
    for mode in ("++", "--"):
        m = FiveBar(1.2, 1.8, 0.0, mode)
        rng = np.random.default_rng(4)
        x, y = rng.uniform(-3, 3, 5000), rng.uniform(-3, 3, 5000)
        ok = m.reachable(x, y)
        assert ok.sum() > 1000
        assert np.max(m.lci(x, y)) < 1e-12
        b1x, b1y, b2x, b2y, _ = m.elbows(x[ok], y[ok])
        np.testing.assert_allclose(b1x, b2x, atol=1e-12)
        np.testing.assert_allclose(b1y, b2y, atol=1e-12)


# --- scale invariance ----------------------------------------------------------------
@HYP
@given(design(), st.sampled_from(MODES), st.floats(1e-3, 1e3), st.integers(0, 2**31 - 1))
def test_scale_invariance(lengths, mode, D, seed):
    """All lengths times D: LCI unchanged at D*P, J scales as 1/D, |D|max,min as D^2
    (Liu 2006 eq. 20)."""
    r1, r2, r3 = lengths
    assume(not (r3 == 0.0 and mode in ("++", "--")))
    m = FiveBar(r1, r2, r3, mode)
    try:
        x, y = sample_away_from_singularities(m, np.random.default_rng(seed), 20, max_rounds=20)
    except RuntimeError:
        assume(False)
    big = FiveBar(D * r1, D * r2, D * r3, mode)
    assert big.length_scale == pytest.approx(D * m.length_scale)
    np.testing.assert_allclose(big.lci(D * x, D * y), m.lci(x, y), rtol=1e-9, atol=1e-13)
    J, JD = m.jacobian(x, y), big.jacobian(D * x, D * y)
    np.testing.assert_allclose(JD * D, J, rtol=1e-9, atol=1e-12 * np.abs(J).max())
    dmax, dmin = m.stiffness_extremes(x, y)
    Dmax, Dmin = big.stiffness_extremes(D * x, D * y)
    np.testing.assert_allclose(Dmax, D**2 * dmax, rtol=1e-8)
    np.testing.assert_allclose(Dmin, D**2 * dmin, rtol=1e-8)
    vmax, vmin = m.velocity_extremes(x, y)
    Vmax, Vmin = big.velocity_extremes(D * x, D * y)
    np.testing.assert_allclose(Vmax, D * vmax, rtol=1e-8)
    np.testing.assert_allclose(Vmin, D * vmin, rtol=1e-8)
    # angles are dimensionless
    q1, q2, _ = m.ik(x, y)
    Q1, Q2, _ = big.ik(D * x, D * y)
    np.testing.assert_allclose(Q1, q1, atol=1e-10)
    np.testing.assert_allclose(Q2, q2, atol=1e-10)


def test_scaled_method():
    m = FiveBar(0.7, 1.7, 0.6, "-+")
    s = m.scaled(2.5)
    assert (s.r1, s.r2, s.r3) == pytest.approx((1.75, 4.25, 1.5))
    assert s.mode == "-+"
    with pytest.raises(ValueError, match="factor"):
        m.scaled(0.0)
    with pytest.raises(ValueError, match="factor"):
        m.scaled(float("nan"))


# --- Le 2013 eq. (13)-(18), literally -----------------------------------------------------
def le2013_ik(x, y, l0, l1, l2, signs):
    """Le, Kang, Doan 2013 eq. (13)-(18) as printed (plain arctan, not arctan2).

    alpha1 = arccos((l1^2 + ((l0 + x)^2 + y^2) - l2^2) / (2 l1 sqrt((l0 + x)^2 + y^2)))  (13)
    alpha2 = arccos((l1^2 + ((l0 - x)^2 + y^2) - l2^2) / (2 l1 sqrt((l0 - x)^2 + y^2)))  (14)
    beta1  = arctan(y / (l0 + x))                                                      (15)
    beta2  = arctan(y / (l0 - x))                                                      (16)
    theta_a1 = beta1 +/- alpha1                                                        (17)
    theta_a2 = pi - beta2 +/- alpha2                                                   (18)
    """
    s1, s2 = (1.0 if c == "+" else -1.0 for c in signs)
    alpha1 = np.arccos(
        (l1**2 + ((l0 + x) ** 2 + y**2) - l2**2) / (2 * l1 * np.sqrt((l0 + x) ** 2 + y**2))
    )
    alpha2 = np.arccos(
        (l1**2 + ((l0 - x) ** 2 + y**2) - l2**2) / (2 * l1 * np.sqrt((l0 - x) ** 2 + y**2))
    )
    beta1 = np.arctan(y / (l0 + x))
    beta2 = np.arctan(y / (l0 - x))
    return beta1 + s1 * alpha1, np.pi - beta2 + s2 * alpha2


def _wrap(d):
    return np.angle(np.exp(1j * d))


@pytest.mark.parametrize("lengths", [(1.0, 1.5, 0.5), (0.7, 1.7, 0.6), (1.6, 0.9, 0.5)], ids=str)
@pytest.mark.parametrize("mode", MODES)
def test_ik_matches_le2013_literally_between_the_base_joints(lengths, mode):
    """Where -l0 < x < l0 both denominators of eq. (15)-(16) are positive, plain arctan
    is quadrant-correct, and the printed formulas must give exactly ik's angles."""
    r1, r2, r3 = lengths
    m = FiveBar(r1, r2, r3, mode)
    x, y = _points(m, 5, 2000)
    sel = np.abs(x) < r3
    assert sel.sum() > 50
    x, y = x[sel], y[sel]
    t1, t2, ok = m.ik(x, y)
    assert np.all(ok)
    le1, le2 = le2013_ik(x, y, r3, r1, r2, mode)
    np.testing.assert_allclose(t1, le1, rtol=0, atol=1e-12)
    np.testing.assert_allclose(t2, le2, rtol=0, atol=1e-12)


@pytest.mark.parametrize("lengths", [(1.0, 1.5, 0.5), (0.7, 1.7, 0.6), (1.6, 0.9, 0.5)], ids=str)
@pytest.mark.parametrize("mode", MODES)
def test_ik_matches_le2013_everywhere_modulo_quadrant(lengths, mode):
    """Elsewhere the printed arctan loses the quadrant: eq. (15)-(16) read with the
    quadrant restored (arctan + pi where the denominator is negative) agrees with
    ik modulo 2 pi, and plain arctan differs from ik by exactly pi (mod 2 pi) there."""
    r1, r2, r3 = lengths
    m = FiveBar(r1, r2, r3, mode)
    x, y = _points(m, 6, 2000)
    t1, t2, _ = m.ik(x, y)
    le1, le2 = le2013_ik(x, y, r3, r1, r2, mode)
    # restore the quadrant: beta1 += pi where l0 + x < 0 (theta1 = beta1 + ...),
    # beta2 += pi where l0 - x < 0 (theta2 = pi - beta2 + ...)
    q1 = np.where(r3 + x < 0, np.pi, 0.0)
    q2 = np.where(r3 - x < 0, -np.pi, 0.0)
    np.testing.assert_allclose(_wrap(t1 - (le1 + q1)), 0.0, atol=1e-12)
    np.testing.assert_allclose(_wrap(t2 - (le2 + q2)), 0.0, atol=1e-12)
    off = r3 + x < 0
    if off.any():
        np.testing.assert_allclose(np.abs(_wrap(t1[off] - le1[off])), np.pi, atol=1e-12)


# theta1 = beta1 + s1 alpha1 with beta1 in (-pi, pi], alpha1 in [0, pi];
# theta2 = pi - beta2 + s2 alpha2 with pi - beta2 in [0, 2 pi).
_IK_RANGES = {
    "+": ((-np.pi, 2 * np.pi), (0.0, 3 * np.pi)),
    "-": ((-2 * np.pi, np.pi), (-np.pi, 2 * np.pi)),
}


@pytest.mark.parametrize("mode", MODES)
def test_ik_range_is_unwrapped(mode):
    """ik returns the formulas' angles unwrapped: theta1 in (-pi, 2 pi] for "+." and
    (-2 pi, pi] for "-."; theta2 in [0, 3 pi) for ".+" and (-pi, 2 pi) for ".-".
    five_bar.ik's docstring states (-pi, 2 pi) for both, true of mode "+-" only."""
    m = FiveBar(0.7, 1.7, 0.6, mode)
    rng = np.random.default_rng(7)
    x, y = rng.uniform(-2.5, 2.5, 20000), rng.uniform(-2.5, 2.5, 20000)
    t1, t2, ok = m.ik(x, y)
    lo1, hi1 = _IK_RANGES[mode[0]][0]
    lo2, hi2 = _IK_RANGES[mode[1]][1]
    eps = 1e-12
    assert np.all((t1[ok] >= lo1 - eps) & (t1[ok] <= hi1 + eps))
    assert np.all((t2[ok] >= lo2 - eps) & (t2[ok] <= hi2 + eps))
    # and the ranges are really used (more than pi of travel each)
    assert np.ptp(t1[ok]) > np.pi and np.ptp(t2[ok]) > np.pi


def test_liu_mode_plus_minus_has_both_elbows_outward():
    """Mode "+-" (Le eq. 17-18 with theta1 = beta1 + alpha1, theta2 = pi - beta2 - alpha2):
    at a point on the y axis above the base the elbows sit on the outer side of the
    lines A_i P."""
    m = FiveBar(0.7, 1.7, 0.6, "+-")
    b1x, b1y, b2x, b2y, ok = m.elbows(0.0, 1.2)
    assert ok
    # B1 on the left of A1->P (counter-clockwise), B2 on the right of A2->P
    cross1 = (0.0 - (-0.6)) * (b1y - 0.0) - (1.2 - 0.0) * (b1x - (-0.6))
    cross2 = (0.0 - 0.6) * (b2y - 0.0) - (1.2 - 0.0) * (b2x - 0.6)
    assert cross1 > 0 and cross2 < 0
    assert b1x < -0.6 and b2x > 0.6


# --- elbows and forward kinematics ----------------------------------------------------------
@pytest.mark.parametrize("lengths", LENGTHS, ids=str)
@pytest.mark.parametrize("mode", MODES)
def test_elbows_lie_on_both_circles(lengths, mode):
    m = FiveBar(*lengths, mode)
    rng = np.random.default_rng(8)
    x, y = rng.uniform(-3, 3, 5000), rng.uniform(-3, 3, 5000)
    b1x, b1y, b2x, b2y, ok = m.elbows(x, y)
    assert np.array_equal(ok, m.reachable(x, y))
    r1, r2, r3 = lengths
    np.testing.assert_allclose(np.hypot(b1x[ok] + r3, b1y[ok]), r1, rtol=1e-9)
    np.testing.assert_allclose(np.hypot(b2x[ok] - r3, b2y[ok]), r1, rtol=1e-9)
    np.testing.assert_allclose(np.hypot(x[ok] - b1x[ok], y[ok] - b1y[ok]), r2, rtol=1e-9)
    np.testing.assert_allclose(np.hypot(x[ok] - b2x[ok], y[ok] - b2y[ok]), r2, rtol=1e-9)
    # and they are the cranks of ik's angles
    t1, t2, _ = m.ik(x[ok], y[ok])
    np.testing.assert_allclose(b1x[ok], -r3 + r1 * np.cos(t1), atol=1e-9)
    np.testing.assert_allclose(b1y[ok], r1 * np.sin(t1), atol=1e-9)
    np.testing.assert_allclose(b2x[ok], r3 + r1 * np.cos(t2), atol=1e-9)
    np.testing.assert_allclose(b2y[ok], r1 * np.sin(t2), atol=1e-9)
    assert np.all(np.isnan(b1x[~ok]))


def test_fk_assemblies_are_mirror_images_about_b1b2():
    """'up' puts P on the left of B1 -> B2 (Le solution 1), 'down' on the right."""
    m = FiveBar(1.0, 1.5, 0.5)
    t1, t2 = np.array([1.2, 2.0, 0.3]), np.array([1.0, 0.5, -0.2])
    b1x, b1y = -0.5 + np.cos(t1), np.sin(t1)
    b2x, b2y = 0.5 + np.cos(t2), np.sin(t2)
    for asm, sign in (("up", 1), ("down", -1)):
        x, y, valid = m.fk(t1, t2, asm)
        assert np.all(valid)
        cross = (b2x - b1x) * (y - b1y) - (b2y - b1y) * (x - b1x)
        assert np.all(sign * cross > 0)
        np.testing.assert_allclose(np.hypot(x - b1x, y - b1y), 1.5, rtol=1e-12)
        np.testing.assert_allclose(np.hypot(x - b2x, y - b2y), 1.5, rtol=1e-12)
    assert set(ASSEMBLY_MODES) == {"up", "down"}


def test_fk_invalid_where_distal_circles_do_not_meet():
    m = FiveBar(1.0, 0.4, 1.5)
    x, y, valid = m.fk(np.pi, 0.0, "up")  # elbows 5 apart, 2 r2 = 0.8
    assert not valid and np.isnan(x) and np.isnan(y)


# --- bad input -------------------------------------------------------------------------
@pytest.mark.parametrize(
    "kwargs,name",
    [
        (dict(r1=0.0), "r1"),
        (dict(r1=-1.0), "r1"),
        (dict(r1=float("nan")), "r1"),
        (dict(r1=float("inf")), "r1"),
        (dict(r1="abc"), "r1"),
        (dict(r2=0.0), "r2"),
        (dict(r2=-0.5), "r2"),
        (dict(r2=float("nan")), "r2"),
        (dict(r2=float("-inf")), "r2"),
        (dict(r3=-1e-9), "r3"),
        (dict(r3=float("nan")), "r3"),
        (dict(r3=float("inf")), "r3"),
        (dict(mode="+"), "mode"),
        (dict(mode="up"), "mode"),
        (dict(mode=None), "mode"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, name):
    args = dict(r1=1.0, r2=1.5, r3=0.5, mode="+-")
    args.update(kwargs)
    with pytest.raises(ValueError, match=rf"\b{name}\b"):
        FiveBar(**args)


def test_r3_zero_is_allowed():
    assert FiveBar(1.0, 2.0, 0.0).r3 == 0.0


@pytest.mark.parametrize("assembly", ["left", "", None, "UP"])
def test_unknown_assembly_names_the_parameter(assembly):
    with pytest.raises(ValueError, match=r"\bassembly\b"):
        FiveBar(1.0, 1.5, 0.5).fk(0.1, 0.2, assembly)


def test_with_mode_validates():
    m = FiveBar(1.0, 1.5, 0.5)
    assert m.with_mode("--").mode == "--"
    with pytest.raises(ValueError, match="mode"):
        m.with_mode("+ -")


def test_repr_round_trips():
    m = FiveBar(0.7, 1.7, 0.6, "-+")
    assert eval(repr(m), {"FiveBar": FiveBar}).__dict__ == m.__dict__


# --- the fused LCI fast path (mechopt.mechanisms.five_bar.lci) -----------------------------------------------
from mechopt.core import indices as _ix  # noqa: E402
from mechopt.mechanisms.five_bar import lci as _k  # noqa: E402

FAST_LENGTHS = LENGTHS + [(1.0, 1.0, 0.3), (250.0, 400.0, 120.0), (2e-3, 3e-3, 1e-3)]


def _generic_lci(m, x, y):
    return _ix.lci(m.jacobian(x, y))


def _cloud(m, seed, n=40000):
    xmin, xmax, ymin, ymax = m.bounding_box()
    w, h = xmax - xmin, ymax - ymin
    rng = np.random.default_rng(seed)
    return rng.uniform(xmin - 0.1 * w, xmax + 0.1 * w, n), rng.uniform(ymin - 0.1 * h, ymax + 0.1 * h, n)


@pytest.mark.parametrize("lengths", FAST_LENGTHS, ids=str)
@pytest.mark.parametrize("mode", MODES)
def test_fast_lci_equals_generic_path(lengths, mode):
    """FiveBar.lci (fused kernel) == indices.lci(FiveBar.jacobian) to 1e-12, everywhere
    (unreachable points, both kinds of singularity and regular points)."""
    m = FiveBar(*lengths, mode)
    x, y = _cloud(m, 11)
    fast, slow = m.lci(x, y), _generic_lci(m, x, y)
    assert fast.shape == x.shape
    np.testing.assert_allclose(fast, slow, rtol=0, atol=1e-12)
    assert np.all(fast[~m.reachable(x, y)] == 0)
    good = slow > 0.05
    np.testing.assert_allclose(fast[good], slow[good], rtol=1e-12, atol=0)


@pytest.mark.parametrize("kernel", ["numpy", "numba"])
@pytest.mark.parametrize("mode", MODES)
def test_fast_lci_kernels_agree(kernel, mode):
    if kernel == "numba" and not _k.HAVE_NUMBA:
        pytest.skip("numba not importable")
    m = FiveBar(0.7, 1.7, 0.6, mode)
    x, y = _cloud(m, 12, 50001)  # not a multiple of the NumPy block size
    f = _k.five_bar_lci_numba if kernel == "numba" else _k.five_bar_lci_numpy
    got = f(x, y, m.r1, m.r2, m.r3, m._s1, m._s2)
    np.testing.assert_allclose(got, _generic_lci(m, x, y), rtol=0, atol=1e-12)
    ref = _k.five_bar_lci_numpy(x, y, m.r1, m.r2, m.r3, m._s1, m._s2, chunk=1000)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-15)


def test_fast_lci_shapes_and_special_inputs():
    m = FiveBar(1.0, 1.5, 0.5)
    assert isinstance(m.lci(0.1, 1.5), np.ndarray) and m.lci(0.1, 1.5).shape == ()
    assert m.lci(0.1, 1.5) == pytest.approx(float(_generic_lci(m, 0.1, 1.5)), rel=1e-12)
    assert m.lci(np.zeros((0,)), np.zeros((0,))).shape == (0,)
    x = np.linspace(-1, 1, 7)
    y = np.linspace(0.5, 2.0, 5)
    grid = m.lci(x[:, None], y[None, :])
    assert grid.shape == (7, 5)
    np.testing.assert_allclose(grid, _generic_lci(m, x[:, None], y[None, :]), atol=1e-12)
    # a non-contiguous view
    X = np.tile(x, (4, 1)).T[:, ::2]
    Y = np.full_like(X, 1.2)
    np.testing.assert_allclose(m.lci(X, Y), _generic_lci(m, X, Y), atol=1e-12)
    special = m.lci([np.nan, np.inf, -np.inf, 0.0, -0.5, 0.5], [1.0, 1.0, 0.0, np.nan, 0.0, 0.0])
    # a NaN coordinate is not a point: NaN (issue 27); beyond reach or singular: 0
    np.testing.assert_array_equal(special, [np.nan, 0.0, 0.0, np.nan, 0.0, 0.0])
    assert isinstance(m.lci(np.nan, 1.5), np.ndarray) and m.lci(np.nan, 1.5).shape == ()
    with pytest.raises(ValueError, match="broadcast"):
        m.lci(np.zeros(3), np.zeros(2))


def test_fast_lci_at_constructed_singularities():
    """0 at coincident elbows (type II) and on the Le eq. (19) circles (type I)."""
    m = FiveBar(1.0, 1.5, 0.5, "++")
    b = np.array([0.0, np.sqrt(1.0 - 0.25)])  # B1 = B2: crank circles meet
    psi = np.linspace(0.2, 2.8, 9)
    x, y = b[0] + 1.5 * np.cos(psi), b[1] + 1.5 * np.sin(psi)
    b1x, b1y, b2x, b2y, ok = m.elbows(x, y)
    same = ok & (np.hypot(b1x - b2x, b1y - b2y) < 1e-9)
    assert same.sum() >= 2
    assert np.max(m.lci(x[same], y[same])) < 1e-7
    np.testing.assert_allclose(m.lci(x, y), _generic_lci(m, x, y), atol=1e-12)
    phi = np.linspace(0.3, 1.2, 10)
    x, y = -0.5 + 2.5 * np.cos(phi), 2.5 * np.sin(phi)
    assert np.max(m.lci(x, y)) < 1e-6


def test_fast_lci_accuracy_against_extended_precision():
    """Against the generic formulas evaluated in long double: the fused kernel is
    at least as accurate (it uses Heron's form for the elbow height)."""
    if np.finfo(np.longdouble).eps >= np.finfo(float).eps:
        pytest.skip("no extended precision on this platform")
    m = FiveBar(1.6, 0.9, 0.5, "+-")
    x, y = sample_away_from_singularities(m, np.random.default_rng(13), 5000, lci_min=1e-4)
    X, Y = x.astype(np.longdouble), y.astype(np.longdouble)
    r1, r2, r3 = (np.longdouble(v) for v in (m.r1, m.r2, m.r3))
    rows = []
    for ax, s in ((-r3, m._s1), (r3, m._s2)):
        dx = X - ax
        q = dx * dx + Y * Y
        c = (r1 * r1 + q - r2 * r2) / (2 * q)
        h = s * np.sqrt((4 * q * r1 * r1 - (r1 * r1 - r2 * r2 + q) ** 2) / (4 * q * q))
        bx, by = ax + c * dx - h * Y, c * Y + h * dx
        kx, ky = X - bx, Y - by
        bb = (bx - ax) * ky - by * kx
        rows.append((kx / bb, ky / bb))
    (a, b), (c, d) = rows
    S = a * a + b * b + c * c + d * d
    disc = np.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))
    ref = (2 * abs(a * d - b * c) / (S + disc)).astype(float)
    err_fast = np.abs(m.lci(x, y) - ref)
    err_generic = np.abs(_generic_lci(m, x, y) - ref)
    assert err_fast.max() < 1e-13
    assert err_fast.max() <= 2 * err_generic.max()
