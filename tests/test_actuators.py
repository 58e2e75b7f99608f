"""Per-actuator (box) speed and force limits against a brute-force sweep of directions."""
from __future__ import annotations

import numpy as np
import pytest

from mechopt import Biglide, FiveBar
from mechopt.core.actuators import guaranteed_force, guaranteed_speed

N_DIR = 3600


def _poses(n=200, seed=3):
    """``n`` random reachable, non-singular poses of random five-bars and Biglides: their J."""
    rng = np.random.default_rng(seed)
    out = []
    while len(out) < n:
        if len(out) % 2:
            m = FiveBar(*rng.uniform(0.3, 1.5, 2), rng.uniform(0.0, 1.0), mode=rng.choice(["+-", "-+", "++", "--"]))
        else:
            l1 = rng.uniform(0.2, 1.0)
            m = Biglide(l1, l1 + rng.uniform(0.1, 1.0), -2.0, 2.0, mode=rng.choice(["--", "+-"]))
        x0, x1, y0, y1 = m.bounding_box()
        if not (x1 > x0 and y1 > y0):
            continue
        x, y = rng.uniform(x0, x1), rng.uniform(y0, y1)
        J = m.jacobian(x, y)
        if np.all(np.isfinite(J)) and m.lci(x, y) > 1e-3:
            out.append(J)
    return np.array(out)


def _sweep(J, w, t):
    """Independent brute force: for each of N_DIR unit directions u, the largest speed
    ``v`` with ``|v (J u)_i| <= w_i`` and the largest force ``f`` with
    ``|(J^-T f u)_i| <= t_i`` (the efforts balancing ``f u``); minima over u."""
    a = np.linspace(0.0, 2.0 * np.pi, N_DIR, endpoint=False)
    U = np.stack([np.cos(a), np.sin(a)])  # (2, N)
    qd = np.einsum("pij,jn->pin", J, U)  # joint rates per unit speed
    v = np.min(np.min(np.asarray(w)[None, :, None] / np.abs(qd), axis=1), axis=1)
    tau = np.linalg.solve(np.swapaxes(J, 1, 2), np.broadcast_to(U, (len(J), 2, N_DIR)))
    f = np.min(np.min(np.asarray(t)[None, :, None] / np.abs(tau), axis=1), axis=1)
    return v, f


@pytest.mark.parametrize("w, t", [((3.0, 3.0), (8.0, 8.0)), ((2.0, 5.0), (10.0, 3.0))])
def test_box_limits_equal_the_sweep_and_never_exceed_it(w, t):
    J = _poses()
    v_sweep, f_sweep = _sweep(J, w, t)
    v = guaranteed_speed(J, w)
    f = guaranteed_force(J, t)
    assert np.all(v <= v_sweep * (1 + 1e-12))
    assert np.all(f <= f_sweep * (1 + 1e-12))
    assert np.max(np.abs(v / v_sweep - 1)) < 1e-3
    assert np.max(np.abs(f / f_sweep - 1)) < 1e-3


def test_euclidean_reading_is_liu_and_below_the_box():
    J = _poses(60, seed=5)
    s_max = np.linalg.svd(J, compute_uv=False)[:, 0]
    s_min = np.linalg.svd(J, compute_uv=False)[:, 1]
    np.testing.assert_allclose(guaranteed_speed(J, 3.0, norm=2), 3.0 / s_max, rtol=1e-12)
    np.testing.assert_allclose(guaranteed_force(J, 8.0, norm=2), 8.0 * s_min, rtol=1e-12)
    assert np.all(guaranteed_speed(J, 3.0) >= guaranteed_speed(J, 3.0, norm=2) * (1 - 1e-12))
    assert np.all(guaranteed_force(J, 8.0) >= guaranteed_force(J, 8.0, norm=2) * (1 - 1e-12))


def test_biglide_speed_is_not_capped_at_one_over_sqrt2():
    # rows (tan theta_i, 1): at x = 0 of mode "--" both rows are (+-t, 1); box speed w/sqrt(1+t^2)
    m = Biglide(0.5, 1.0, -2.0, 2.0)
    J = m.jacobian(0.0, 0.5)
    t = np.tan(np.arcsin(0.5))
    assert guaranteed_speed(J, 1.0) == pytest.approx(1.0 / np.sqrt(1 + t * t), rel=1e-12)
    assert guaranteed_speed(J, 1.0, norm=2) < guaranteed_speed(J, 1.0)


def test_singular_and_unreachable_poses_and_bad_input():
    J = np.array([[[1.0, 2.0], [2.0, 4.0]], [[np.nan, 0.0], [0.0, 1.0]]])
    f = guaranteed_force(J, 1.0)
    assert f[0] == 0.0 and np.isnan(f[1])
    assert np.isnan(guaranteed_speed(J, 1.0)[1])
    for bad in (0.0, -1.0, np.nan, (1.0, 2.0, 3.0)):
        with pytest.raises(ValueError, match="^w must be a positive"):
            guaranteed_speed(J, bad)
    with pytest.raises(ValueError, match="^norm must be one of"):
        guaranteed_force(J, 1.0, norm=1)
