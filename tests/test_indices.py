"""Local indices (mechopt.core.indices) against numpy.linalg on 2x2 matrices."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mechopt.core import indices as ix

HYP = settings(max_examples=60, deadline=None, derandomize=True)

# Entries spanning many magnitudes (a Jacobian's entries are ~1/L in any unit),
# including exact zeros. The closed form multiplies two sums of squares (~|J|^4), so
# its range is about 1e-73 < |J| < 1e77 (see test_closed_form_range_limit).
entry = st.one_of(
    st.just(0.0),
    st.builds(
        lambda sign, m, e: sign * m * 10.0**e,
        st.sampled_from([1.0, -1.0]),
        st.floats(1.0, 10.0),
        st.integers(-60, 60),
    ),
)
mat = arrays(np.float64, (2, 2), elements=entry)


@st.composite
def well_scaled(draw):
    """A 2x2 matrix D * R(a) diag(s1, s2) R(b), with controlled condition number."""
    a, b = draw(st.floats(-np.pi, np.pi)), draw(st.floats(-np.pi, np.pi))
    s1 = 10.0 ** draw(st.floats(-50, 50))
    k = 10.0 ** draw(st.floats(0, 12))
    flip = draw(st.sampled_from([1.0, -1.0]))

    def R(t):
        return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])

    return R(a) @ np.diag([s1, flip * s1 / k]) @ R(b)


def _svd(J):
    s = np.linalg.svd(J, compute_uv=False)
    return s[..., 0], s[..., 1]


@HYP
@given(mat)
def test_singular_values_match_svd(J):
    smax, smin = ix.singular_values(J)
    rmax, rmin = _svd(J)
    assert smax == pytest.approx(rmax, rel=1e-13, abs=0)
    # s_min is fixed by |det| / s_max: accurate to a few ulps of s_max from svd
    assert abs(smin - rmin) <= 1e-13 * rmax
    assert smax >= smin >= 0


@HYP
@given(well_scaled())
def test_singular_values_relative_accuracy_of_s_min(J):
    """Closed form s_min = |det|/s_max keeps relative accuracy of s_min where the
    entries are exact to rounding (error bound ~ kappa * eps for svd, so compare
    within kappa * 1e-14)."""
    smax, smin = ix.singular_values(J)
    rmax, rmin = _svd(J)
    kappa = rmax / rmin
    assert smax == pytest.approx(rmax, rel=1e-13, abs=0)
    assert smin == pytest.approx(rmin, rel=max(1e-13, 1e-14 * kappa), abs=0)


def test_singular_values_batch_shapes():
    rng = np.random.default_rng(0)
    J = rng.normal(size=(3, 4, 5, 2, 2))
    smax, smin = ix.singular_values(J)
    assert smax.shape == smin.shape == (3, 4, 5)
    rmax, rmin = _svd(J)
    np.testing.assert_allclose(smax, rmax, rtol=1e-13)
    np.testing.assert_allclose(smin, rmin, rtol=1e-11, atol=1e-14 * rmax.max())
    s0 = ix.singular_values(J[1, 2, 3])
    assert np.shape(s0[0]) == ()
    assert s0[0] == smax[1, 2, 3] and s0[1] == smin[1, 2, 3]


@HYP
@given(mat)
def test_lci_is_svd_ratio(J):
    rmax, rmin = _svd(J)
    expected = rmin / rmax if rmax > 0 else 0.0
    c = ix.lci(J)
    assert 0.0 <= c <= 1.0
    assert c == pytest.approx(expected, rel=1e-12, abs=1e-13)


@HYP
@given(mat, st.floats(-1e10, 1e10).filter(lambda c: abs(c) > 1e-10))
def test_lci_scale_invariant(J, c):
    assert ix.lci(c * J) == pytest.approx(ix.lci(J), rel=1e-12, abs=1e-14)


@HYP
@given(well_scaled())
def test_tqi_is_two_kappa_over_kappa_squared_plus_one(J):
    rmax, rmin = _svd(J)
    kappa = rmax / rmin
    t = ix.tqi(J)
    assert t == pytest.approx(2 * kappa / (kappa**2 + 1), rel=1e-13 + 1e-14 * kappa, abs=0)
    # Stan 2008 eq. (9) with Frobenius norms: 2 / (||J||_F ||J^-1||_F)
    if kappa < 1e6:
        frob = np.linalg.norm(J, "fro") * np.linalg.norm(np.linalg.inv(J), "fro")
        assert t == pytest.approx(2.0 / frob, rel=1e-8, abs=0)
    assert 0.0 <= t <= 1.0


@HYP
@given(well_scaled())
def test_extremes_are_powers_of_singular_values(J):
    rmax, rmin = _svd(J)
    # s_min of a matrix known to rounding is fixed to ~ eps * kappa relative
    rel_min = 1e-13 + 1e-14 * rmax / rmin
    vmax, vmin = ix.velocity_extremes(J)
    assert vmax == pytest.approx(1 / rmin, rel=rel_min, abs=0)
    assert vmin == pytest.approx(1 / rmax, rel=1e-13, abs=0)
    tmax, tmin = ix.payload_extremes(J)
    assert tmax == pytest.approx(rmax, rel=1e-13, abs=0)
    assert tmin == pytest.approx(rmin, rel=rel_min, abs=0)
    dmax, dmin = ix.stiffness_extremes(J)
    assert dmax == pytest.approx(1 / rmin**2, rel=2 * rel_min, abs=0)
    assert dmin == pytest.approx(1 / rmax**2, rel=1e-12, abs=0)
    m = ix.manipulability(J)
    assert m == pytest.approx(1 / (rmax * rmin), rel=rel_min, abs=0)
    if rmax / rmin < 1e3 and 1e-50 < rmin and rmax < 1e50:
        Ji = np.linalg.inv(J)
        assert m == pytest.approx(np.sqrt(np.linalg.det(Ji @ Ji.T)), rel=1e-6, abs=0)


@HYP
@given(well_scaled())
def test_local_indices_agree_with_single_functions(J):
    out = ix.local_indices(J)
    assert set(out) == set(ix.LOCAL_INDEX_NAMES)
    assert out["lci"] == pytest.approx(ix.lci(J), rel=1e-12, abs=1e-15)
    vmax, vmin = ix.velocity_extremes(J)
    tmax, tmin = ix.payload_extremes(J)
    dmax, dmin = ix.stiffness_extremes(J)
    for k, v in dict(v_max=vmax, v_min=vmin, tau_max=tmax, tau_min=tmin,
                     d_max=dmax, d_min=dmin).items():
        assert out[k] == pytest.approx(v, rel=1e-12, abs=0), k


def test_known_values():
    J = np.diag([2.0, 0.5])
    assert ix.lci(J) == 0.25
    assert ix.singular_values(J) == (2.0, 0.5)
    assert ix.tqi(J) == pytest.approx(2 * 4 / 17)
    assert ix.velocity_extremes(J) == (2.0, 0.5)
    assert ix.stiffness_extremes(J) == (4.0, 0.25)
    assert ix.manipulability(J) == 1.0
    R = np.array([[0.6, -0.8], [0.8, 0.6]])  # a rotation: perfectly conditioned
    assert ix.lci(3 * R) == pytest.approx(1.0, rel=1e-15, abs=0)
    assert ix.tqi(3 * R) == pytest.approx(1.0, rel=1e-15, abs=0)


# --- singular, zero and NaN matrices --------------------------------------------------
SINGULAR = [
    np.zeros((2, 2)),
    np.array([[1.0, 2.0], [2.0, 4.0]]),
    np.array([[1.0, 0.0], [0.0, 0.0]]),
    np.array([[0.0, 3.0], [0.0, -1.5]]),
    np.outer([2.0**-190, 3 * 2.0**-190], [2.0, -7.0]),  # exactly rank one
    np.outer([2.0**190, 3 * 2.0**190], [2.0, -7.0]),
]


@pytest.mark.parametrize("J", SINGULAR, ids=range(len(SINGULAR)))
def test_lci_zero_on_singular_matrices(J):
    assert ix.lci(J) == 0.0
    assert ix.tqi(J) == 0.0
    smax, smin = ix.singular_values(J)
    assert smin == 0.0
    assert ix.local_indices(J)["lci"] == 0.0
    assert ix.manipulability(J) == np.inf
    if smax > 0:
        assert ix.stiffness_extremes(J)[0] == np.inf
        assert ix.velocity_extremes(J)[0] == np.inf


small_entry = st.builds(lambda m, e: m * 10.0**e, st.floats(-10.0, 10.0), st.integers(-30, 30))


@HYP
@given(arrays(np.float64, 2, elements=small_entry), arrays(np.float64, 2, elements=small_entry))
def test_lci_zero_on_rank_one(u, v):
    """Rank one up to the rounding of the outer product: LCI at the rounding level."""
    J = np.outer(u, v)
    assert ix.lci(J) <= 1e-15


@pytest.mark.parametrize(
    "J",
    [
        np.full((2, 2), np.nan),
        np.array([[np.nan, 1.0], [0.0, 1.0]]),
        np.array([[1.0, 0.0], [0.0, np.nan]]),
        np.array([[np.inf, 0.0], [0.0, 1.0]]),
    ],
    ids=["all-nan", "one-nan", "diag-nan", "inf"],
)
def test_lci_zero_on_nan_matrices(J):
    assert ix.lci(J) == 0.0
    assert ix.tqi(J) == 0.0
    assert ix.local_indices(J)["lci"] == 0.0


def test_nan_propagates_to_other_indices():
    J = np.full((2, 2), np.nan)
    for f in (ix.velocity_extremes, ix.payload_extremes, ix.stiffness_extremes):
        assert all(np.isnan(v) for v in f(J))
    assert np.isnan(ix.manipulability(J))


def test_lci_batch_mixing_regular_singular_and_nan():
    J = np.stack([np.eye(2), np.zeros((2, 2)), np.full((2, 2), np.nan), np.diag([1.0, 0.1])])
    np.testing.assert_array_equal(ix.lci(J), [1.0, 0.0, 0.0, 0.1])


@pytest.mark.parametrize(
    "f",
    [ix.singular_values, ix.lci, ix.tqi, ix.velocity_extremes, ix.payload_extremes,
     ix.stiffness_extremes, ix.manipulability, ix.local_indices],
)
@pytest.mark.parametrize("shape", [(2,), (2, 3), (3, 2), (4, 4), (5, 3, 3)])
def test_wrong_shape_is_value_error(f, shape):
    with pytest.raises(ValueError, match=r"\(\.\.\., 2, 2\)"):
        f(np.ones(shape))


def test_nan_lci_is_zero_but_singular_values_nan_for_smax():
    J = np.full((3, 2, 2), np.nan)
    smax, _ = ix.singular_values(J)
    assert np.all(np.isnan(smax))
    np.testing.assert_array_equal(ix.lci(J), 0.0)


@pytest.mark.parametrize(
    "J",
    [np.array([[0.0, 1e66], [1e78, 0.0]]), np.diag([0.0, 1e-78]), np.diag([3e80, 1e80])],
    ids=["overflow-lci", "underflow-smax", "overflow-diag"],
)
def test_closed_form_range_limit(J):
    with np.errstate(over="ignore", under="ignore"):
        smax, smin = ix.singular_values(J)
        c = ix.lci(J)
    rmax, rmin = _svd(J)
    assert smax == pytest.approx(rmax, rel=1e-13, abs=0)
    assert c == pytest.approx(rmin / rmax, rel=1e-12, abs=0)
