"""Quadrature rules and the convergence of every global index at the default resolution."""
import numpy as np
import pytest

from mechopt import FiveBar
from mechopt.analysis.performance import global_indices
from mechopt.core.indices import GLOBAL_INDEX_NAMES
from mechopt.core.quadrature import disk_rule, gauss_legendre, grid_over
from mechopt.analysis.workspace import mic


@pytest.mark.parametrize("rule", ["area", "polar"])
def test_weights_sum_to_one(rule):
    _, _, w = disk_rule(2.0, rule)
    assert w.sum() == pytest.approx(1.0, abs=1e-14)


def test_area_rule_is_the_true_area_mean():
    # mean of r^2 over a disk of radius R is R^2/2; of r^4 it is R^4/3
    dx, dy, w = disk_rule(1.5, "area")
    r2 = dx**2 + dy**2
    assert np.sum(w * r2) == pytest.approx(1.5**2 / 2, rel=1e-12)
    assert np.sum(w * r2**2) == pytest.approx(1.5**4 / 3, rel=1e-12)


def test_polar_rule_is_the_plain_grid_mean():
    # the plain mean over uniform r weights the centre more: mean of r is R/2
    dx, dy, w = disk_rule(2.0, "polar")
    assert np.sum(w * np.hypot(dx, dy)) == pytest.approx(1.0, rel=1e-12)
    assert np.sum(w * (dx**2 + dy**2)) == pytest.approx(4.0 / 3.0, rel=1e-3)


def test_unknown_quadrature():
    with pytest.raises(ValueError, match="quadrature must be one of 'area', 'polar', got 'gauss'"):
        disk_rule(1.0, "gauss")


def test_grid_area_of_a_box():
    g = grid_over((0, 1, 0, 2), 0.1)
    assert g.area(np.ones(g.shape, bool)) == pytest.approx(2.0)


@pytest.mark.parametrize("r", [(1.1, 1.65, 0.25), (1.5, 1.2, 0.3), (0.85, 1.6, 0.55), (1.17, 1.45, 0.38)])
@pytest.mark.parametrize("rule", ["area", "polar"])
def test_global_indices_converged_at_default_resolution(r, rule):
    fb = FiveBar(*r)
    m = mic(fb)
    coarse = global_indices(fb, rule, mic=m)
    fine = global_indices(fb, rule, mic=m, n_r=192, n_theta=384)
    for name in GLOBAL_INDEX_NAMES:
        assert coarse[name] == pytest.approx(fine[name], rel=1e-3), name


@pytest.mark.parametrize("n", [1, 2, 5, 48, 128])
def test_gauss_legendre_is_exact_to_degree_2n_minus_1(n):
    """int_{-1}^{1} x^k dx = 2/(k+1) for even k, 0 for odd k (closed form), for every
    k <= 2n - 1; degree 2n is not integrated exactly (the rule has n nodes)."""
    t, w = gauss_legendre(n)
    for k in range(2 * n):
        exact = 2.0 / (k + 1) if k % 2 == 0 else 0.0
        assert abs(np.dot(w, t ** k) - exact) <= 1e-13 * max(1.0, n)
    assert abs(np.dot(w, t ** (2 * n)) - 2.0 / (2 * n + 1)) > 1e-6 * 2.0 ** (-2 * n)


def test_gauss_legendre_is_cached_and_read_only():
    t, w = gauss_legendre(64)
    assert gauss_legendre(64)[0] is t
    with pytest.raises(ValueError):
        t[0] = 0.0
    with pytest.raises(ValueError):
        w[0] = 0.0
