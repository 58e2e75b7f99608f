"""mechopt.core.numerics: the one golden-section search of the package."""
from __future__ import annotations

import math

import numpy as np
import pytest

from mechopt.core.numerics import INV_PHI, golden_section_max


def test_finds_the_maximum_of_a_unimodal_function_to_tol():
    calls = []

    def parabola(x):
        return -(x - 0.3) ** 2

    def f(x):
        calls.append(x)
        return parabola(x)

    g = golden_section_max(f, 0.0, 1.0, tol=1e-9)
    assert g.b - g.a <= 1e-9 and g.a <= 0.3 <= g.b
    assert g.x_best == pytest.approx(0.3, abs=1e-9)
    assert g.f_best == max(parabola(x) for x in calls)
    # two first points, then one evaluation per step (the bracket shrinks by INV_PHI)
    steps = math.ceil(math.log(1e-9) / math.log(INV_PHI))
    assert len(calls) == 2 + steps
    assert calls[0] == 1.0 - INV_PHI and calls[1] == INV_PHI


def test_each_step_keeps_the_side_of_the_larger_value():
    """The bracket update of the loops it replaced: ``[a, x2]`` when ``f(x1) >= f(x2)``
    (ties to the left), else ``[x1, b]``; one new point per step, inside the new bracket
    at the golden ratio."""
    f = lambda x: -abs(x - 0.7)  # noqa: E731
    brackets, points = [], []
    golden_section_max(lambda x: points.append(x) or f(x), 0.0, 1.0,
                       stop=lambda a, b: brackets.append((a, b)) or len(brackets) > 30)
    assert points[:2] == [1.0 - INV_PHI, INV_PHI]
    for k, ((a, b), (a2, b2)) in enumerate(zip(brackets, brackets[1:])):
        x1, x2 = b - INV_PHI * (b - a), a + INV_PHI * (b - a)
        left = f(x1) >= f(x2)
        assert (a2, b2) == pytest.approx((a, x2) if left else (x1, b), abs=1e-15)
        new = b2 - INV_PHI * (b2 - a2) if left else a2 + INV_PHI * (b2 - a2)
        assert points[k + 2] == pytest.approx(new, abs=1e-15)
    assert len(points) == 2 + len(brackets) - 1


def test_vectorised_equals_one_search_at_a_time():
    rng = np.random.default_rng(0)
    c = rng.uniform(0.1, 0.9, 50)
    lo, hi = c - rng.uniform(0.05, 0.5, 50), c + rng.uniform(0.05, 0.5, 50)
    f_vec = lambda x: np.cos(3.0 * (x - c))  # noqa: E731
    g = golden_section_max(f_vec, lo, hi, max_iter=40)
    for i in range(50):
        one = golden_section_max(lambda x: math.cos(3.0 * (x - c[i])), lo[i], hi[i], max_iter=40)
        assert (one.x1, one.x2) == (g.x1[i], g.x2[i])
        assert one.f_best == pytest.approx(g.f_best[i], rel=1e-15) and one.x_best == g.x_best[i]


def test_stop_start_and_best_point():
    seen = []
    g = golden_section_max(lambda x: -(x - 2.0) ** 2, 0.0, 5.0, stop=lambda a, b: len(seen.append(b - a) or seen) > 5)
    assert len(seen) == 6 and g.b - g.a == pytest.approx(5.0 * INV_PHI ** 5)
    # a start point better than anything evaluated stays the best; ties keep the first
    g = golden_section_max(lambda x: 0.0, 0.0, 1.0, max_iter=5, start=(7.0, 0.0))
    assert (g.x_best, g.f_best) == (7.0, 0.0)
    g = golden_section_max(lambda x: float("nan"), 0.0, 1.0, max_iter=3, start=(0.5, 1.0))
    assert g.x_best == 0.5


def test_needs_a_way_to_end():
    with pytest.raises(ValueError, match="tol, max_iter or stop"):
        golden_section_max(lambda x: x, 0.0, 1.0)


def test_ties_move_right_within_a_margin():
    """``right_within``: the left side is kept only when f1 exceeds f2 by more than the
    margin, so on a staircase (equal levels up to noise) the search walks to the right
    edge of the top level; the default keeps the left side on a tie and stays left.
    Checked against a literal loop of the textbook search written here."""
    import numpy as np

    def stairs(x):  # two levels; the top one on [0.2, 0.7], noisy by 1e-12
        return (1.0 if 0.2 <= x <= 0.7 else 0.0) + 1e-12 * math.sin(1e4 * x)

    g = golden_section_max(stairs, 0.0, 1.0, tol=1e-6, right_within=1e-9)
    assert abs(g.a - 0.7) < 1e-5 and abs(g.b - 0.7) < 1e-5 and max(g.f1, g.f2) > 0.9
    left = golden_section_max(lambda x: 1.0 if 0.2 <= x <= 0.7 else 0.0, 0.0, 1.0, tol=1e-6)
    assert abs(left.a - 0.2) < 1e-5 and abs(left.b - 0.2) < 1e-5
    # the literal loop (Kiefer 1953), ties right within the margin
    r = (np.sqrt(5.0) - 1.0) / 2.0
    a, b = 0.0, 1.0
    x1, x2 = b - r * (b - a), a + r * (b - a)
    f1, f2, n = stairs(x1), stairs(x2), 2
    while b - a > 1e-6:
        if f1 > f2 + 1e-9:
            b, x2, f2 = x2, x1, f1
            x1 = b - r * (b - a)
            f1 = stairs(x1)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + r * (b - a)
            f2 = stairs(x2)
        n += 1
    assert (g.a, g.b, g.x1, g.x2, g.f1, g.f2, g.evaluations) == (a, b, x1, x2, f1, f2, n)
