"""Exact area primitives of mechopt.core.geometry against closed forms and quadrature."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import integrate

from mechopt.core import geometry as g


def _lens_by_quadrature(ra, rb, d):
    """Independent lens area: integrate the overlap of the two disks' vertical chords."""

    def chord(x):
        ha = np.sqrt(max(ra * ra - x * x, 0.0))
        hb = np.sqrt(max(rb * rb - (x - d) ** 2, 0.0))
        return 2.0 * max(0.0, min(ha, hb)) if abs(x) <= ra and abs(x - d) <= rb else 0.0

    lo, hi = max(-ra, d - rb), min(ra, d + rb)
    if hi <= lo:
        return 0.0
    # kink where the two circles cross
    pts = [(d * d + ra * ra - rb * rb) / (2 * d)] if d > 0 else []
    pts = [p for p in pts if lo < p < hi]
    return integrate.quad(chord, lo, hi, points=pts or None, epsabs=0, epsrel=1e-11, limit=400)[0]


def test_lens_known_values():
    # two unit circles one radius apart: 2 pi/3 - sqrt(3)/2
    assert g.lens_area(1.0, 1.0, 1.0) == pytest.approx(2 * np.pi / 3 - np.sqrt(3) / 2, rel=1e-14)
    assert g.lens_area(1.0, 2.0, 3.0) == 0.0  # tangent outside
    assert g.lens_area(1.0, 2.0, 5.0) == 0.0  # apart
    assert g.lens_area(1.0, 2.0, 1.0) == pytest.approx(np.pi, rel=1e-15)  # tangent inside
    assert g.lens_area(3.0, 2.0, 0.5) == pytest.approx(4 * np.pi, rel=1e-15)  # contained
    assert g.lens_area(2.0, 2.0, 0.0) == pytest.approx(4 * np.pi, rel=1e-15)
    assert g.lens_area(0.0, 2.0, 1.0) == 0.0


@settings(max_examples=60, deadline=None, derandomize=True)
@given(
    st.floats(0.1, 10.0), st.floats(0.1, 10.0), st.floats(0.0, 1.0),
)
def test_lens_against_quadrature_and_symmetric(ra, rb, t):
    d = t * (ra + rb) * 1.05
    a = g.lens_area(ra, rb, d)
    assert a == pytest.approx(g.lens_area(rb, ra, d), rel=1e-12, abs=1e-14)
    assert a == pytest.approx(_lens_by_quadrature(ra, rb, d), rel=1e-8, abs=1e-10)
    assert 0.0 <= a <= np.pi * min(ra, rb) ** 2 * (1 + 1e-15)


def test_lens_tiny_overlap_has_no_cancellation():
    # overlap depth 1e-6 of two unit disks: area ~ (4/3) sqrt(r) h^(3/2) for small h
    h = 1e-6
    a = g.lens_area(1.0, 1.0, 2.0 - h)
    assert a == pytest.approx(_lens_by_quadrature(1.0, 1.0, 2.0 - h), rel=1e-6)
    assert a > 0


def test_lens_vectorised_equals_pointwise():
    rng = np.random.default_rng(0)
    ra, rb, d = rng.uniform(0, 3, (3, 50))
    batch = g.lens_area(ra, rb, d)
    assert batch.shape == (50,)
    single = np.array([g.lens_area(*v) for v in zip(ra, rb, d)])
    np.testing.assert_array_equal(batch, single)
    assert g.lens_area(ra[:, None], rb[None, :], 1.0).shape == (50, 50)


@pytest.mark.parametrize(
    "args,match",
    [((-1.0, 1.0, 1.0), "r_a"), ((1.0, -1.0, 1.0), "r_b"), ((1.0, 1.0, -1.0), "d"),
     ((np.nan, 1.0, 1.0), "r_a"), ((1.0, np.inf, 1.0), "r_b"), (("x", 1.0, 1.0), "r_a"),
     ((np.ones(2), np.ones(3), 1.0), "broadcast")],
)
def test_lens_rejects_bad_input(args, match):
    with pytest.raises(ValueError, match=match):
        g.lens_area(*args)


def test_annuli_intersection_concentric_and_disjoint():
    # concentric annuli [1, 3] and [2, 4]: the annulus [2, 3]
    a = g.annuli_intersection_area((0, 0), 1, 3, (0, 0), 2, 4)
    assert a == pytest.approx(np.pi * (9 - 4), rel=1e-14)
    assert g.annuli_intersection_area((0, 0), 1, 2, (10, 0), 1, 2) == 0.0
    # disk (r_in = 0) inside the hole of the other annulus
    assert g.annuli_intersection_area((0, 0), 0, 1, (0.5, 0), 3, 4) == 0.0


def test_annuli_half_plane_and_validation():
    full = g.annuli_intersection_area((0, 0), 80, 130, (60, 0), 80, 130)
    assert g.annuli_intersection_area((0, 0), 80, 130, (60, 0), 80, 130, "upper") == 0.5 * full
    with pytest.raises(ValueError, match="x axis"):
        g.annuli_intersection_area((0, 1), 80, 130, (60, 0), 80, 130, "upper")
    with pytest.raises(ValueError, match="half_plane"):
        g.annuli_intersection_area((0, 0), 80, 130, (60, 0), 80, 130, "left")
    with pytest.raises(ValueError, match="r1_out"):
        g.annuli_intersection_area((0, 0), 130, 80, (60, 0), 80, 130)
    with pytest.raises(ValueError, match=r"\(\.\.\., 2\)"):
        g.annuli_intersection_area((0, 0, 0), 80, 130, (60, 0), 80, 130)


def test_annuli_off_axis_against_polar_integration():
    """Annuli with centres off the x axis against an independent integration in
    polar coordinates about c1 (trapezoid in r and phi on the membership indicator)."""
    c1, c2 = np.array([0.3, -0.2]), np.array([1.1, 0.9])
    r1i, r1o, r2i, r2o = 0.5, 1.6, 0.4, 1.2

    def radial_measure(phi):
        # length (times r) of the ray from c1 inside annulus 2, between r1i and r1o
        r = np.linspace(r1i, r1o, 4001)
        p = c1[:, None] + r[None, :] * np.array([np.cos(phi), np.sin(phi)])[:, None]
        d2 = np.hypot(*(p - c2[:, None]))
        inside = (d2 >= r2i) & (d2 <= r2o)
        return np.trapezoid(inside * r, r)

    phis = np.linspace(0, 2 * np.pi, 2001)
    approx = np.trapezoid([radial_measure(p) for p in phis], phis)
    exact = g.annuli_intersection_area(c1, r1i, r1o, c2, r2i, r2o)
    assert exact == pytest.approx(approx, rel=2e-3)


def test_chord_integral():
    assert g.chord_integral(2.0, -2.0, 2.0) == pytest.approx(2 * np.pi, rel=1e-15)
    assert g.chord_integral(2.0, -5.0, 5.0) == pytest.approx(2 * np.pi, rel=1e-15)  # clipped
    assert g.chord_integral(2.0, 1.0, 0.0) == pytest.approx(
        -integrate.quad(lambda u: np.sqrt(4 - u * u), 0, 1)[0], rel=1e-12
    )
    assert g.chord_integral(0.0, -1.0, 1.0) == 0.0


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.floats(-3, 3), st.floats(0, 4), st.floats(-3, 3), st.floats(0, 4), st.floats(-6, 6))
def test_box_ramp_formulas(a1, w1, a2, w2, c):
    b1, b2 = a1 + w1 + 1e-3, a2 + w2 + 1e-3

    def len_diff(x):  # |{y in [a2, b2]: y < x - c}|
        return np.clip(x - c - a2, 0.0, b2 - a2)

    def len_sum(x):  # |{y in [a2, b2]: y < c - x}|
        return np.clip(c - x - a2, 0.0, b2 - a2)

    pts = [p for p in (a2 + c, b2 + c, c - a2, c - b2) if a1 < p < b1]
    ref_d = integrate.quad(len_diff, a1, b1, points=pts or None, epsabs=1e-13)[0]
    ref_s = integrate.quad(len_sum, a1, b1, points=pts or None, epsabs=1e-13)[0]
    assert g.box_area_diff_above(a1, b1, a2, b2, c) == pytest.approx(ref_d, rel=1e-9, abs=1e-11)
    assert g.box_area_sum_below(a1, b1, a2, b2, c) == pytest.approx(ref_s, rel=1e-9, abs=1e-11)


def test_interval_overlap():
    assert g.interval_overlap(0, 2, 1, 5) == 1.0
    assert g.interval_overlap(0, 1, 2, 5) == 0.0
    np.testing.assert_array_equal(g.interval_overlap([0, 0], [2, 1], 1, 5), [1.0, 0.0])
