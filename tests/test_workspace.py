"""Workspace tools: MIC, usable region, GCW, squares, joint ranges."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from mechopt import FiveBar
from mechopt.quadrature import disk_rule
from mechopt.workspace import gcw, joint_ranges, largest_square, mic, usable_region


def _disk_is_free(fb, cy, radius):
    dx, dy, _ = disk_rule(radius, "polar", n_r=80, n_theta=240)
    x, y = dx, cy + dy
    f = fb.type2_function(x, y)
    f0 = fb.type2_function(0.0, cy)
    return bool(fb.reachable(x, y).all() and (np.sign(f) == np.sign(f0)).all())


designs = st.tuples(st.floats(0.3, 1.6), st.floats(0.3, 2.2), st.floats(0.0, 1.0))


@settings(max_examples=15, deadline=None)
@given(designs)
def test_mic_is_free_and_maximal(r):
    fb = FiveBar(*r)
    try:
        m = mic(fb)
    except ValueError:
        return
    # the disk itself is singularity-free ...
    assert _disk_is_free(fb, m.center_y, 0.999 * m.radius)
    # ... and 1 % more radius at the same centre meets a singular locus
    assert not _disk_is_free(fb, m.center_y, 1.01 * m.radius)
    # never larger than the annulus bound (half the annulus width = min(r1, r2))
    assert m.radius <= min(fb.r1, fb.r2) * (1 + 1e-9)


def test_mic_scales_with_the_lengths():
    fb = FiveBar(1.17, 1.45, 0.38)
    m1, m2 = mic(fb), mic(fb.scaled(7.5))
    assert m2.radius == pytest.approx(7.5 * m1.radius, rel=1e-6)
    assert m2.center_y == pytest.approx(7.5 * m1.center_y, rel=1e-4)


def test_usable_area_converges_and_scales():
    fb = FiveBar(0.65, 1.62, 0.73)
    a = usable_region(fb).area
    a_fine = usable_region(fb, step=fb.length_scale / 800).area
    assert abs(a - a_fine) <= 1e-3 * a_fine
    a_big = usable_region(fb.scaled(3.0)).area
    assert a_big == pytest.approx(9.0 * a, rel=1e-3)


def test_gcw_inside_usable_and_above_gamma():
    fb = FiveBar(0.85, 1.6, 0.55)
    u = usable_region(fb)
    g = gcw(fb, 0.5, u)
    assert np.all(u.mask[g.mask])
    x, y = g.points()
    assert fb.lci(x, y).min() >= 0.5
    assert g.area < u.area
    # a higher level gives a smaller region
    assert gcw(fb, 0.7, u).area < g.area


def test_largest_square_is_inside_and_tight():
    fb = FiveBar(0.85, 1.6, 0.55)
    g = gcw(fb, 0.5)
    side, cy = largest_square(g)
    h = side / 2 - 2 * g.grid.step
    s = np.linspace(-h, h, 101)
    X, Y = np.meshgrid(s, cy + s)
    assert fb.lci(X, Y).min() >= 0.5 - 1e-6
    h = side / 2 + 2 * g.grid.step
    s = np.linspace(-h, h, 101)
    X, Y = np.meshgrid(s, cy + s)
    assert fb.lci(X, Y).min() < 0.5


def test_joint_ranges_contain_every_point():
    fb = FiveBar(0.85, 1.6, 0.55)
    g = gcw(fb, 0.5)
    (a, b), (c, d) = joint_ranges(fb, g)
    x, y = g.points()
    t1, t2, _ = fb.ik(x, y)
    assert a == t1.min() and b == t1.max() and c == t2.min() and d == t2.max()


def test_empty_inputs_raise():
    with pytest.raises(ValueError, match="MIC radius 0"):
        mic(FiveBar(0.1, 0.1, 5.0))
    with pytest.raises(ValueError, match="gamma"):
        gcw(FiveBar(0.85, 1.6, 0.55), 1.5)
