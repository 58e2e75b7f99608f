"""Workspace tools: MIC, usable region, GCW, squares, joint ranges."""
import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from mechopt import FiveBar
from mechopt.core.quadrature import disk_rule
from mechopt.analysis.workspace import gcw, joint_ranges, largest_square, mic, usable_region


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


# --- the one-design path: same values as the compiled kernels, no scipy or numba -------------
import os  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402

from mechopt.mechanisms.five_bar import lci as fast_lci
from mechopt.analysis import workspace as W  # noqa: E402
from mechopt.mechanisms.five_bar import mic as M  # noqa: E402

MODES = ("+-", "-+", "++", "--")


def _random_designs(seed, n):
    rng = np.random.default_rng(seed)
    r = rng.uniform(0.05, 2.5, (n, 3))
    r[:, 2] = rng.uniform(0.0, 1.5, n)
    r[::11, 2] = 0.0  # coincident base joints
    r[3::13, 1] = r[3::13, 0]  # equal links
    r[5::17, 2] = r[5::17, 0]  # crank = half base
    r[7::19] *= 10.0 ** rng.uniform(-3, 3, (len(r[7::19]), 1))  # other sizes (scale invariant)
    return r


def test_mic_port_sizes_are_the_kernels():
    from mechopt.mechanisms.five_bar import kernels as K

    assert M.MIC_SIZES == K.MIC_SIZES
    assert M._N_SUB_BRANCH == K._N_SUB_BRANCH and M._GOLD == K._GOLD


@pytest.mark.skipif(not fast_lci.HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("mode", MODES)
def test_mic_port_equals_the_compiled_kernel_bit_for_bit(mode):
    """The NumPy port of one design (what ``mic`` uses first in a process) gives the
    compiled kernel's radius and centre exactly, so that which one runs never shows."""
    from mechopt.mechanisms.five_bar import kernels as K

    d = _random_designs(7 + MODES.index(mode), 400)
    R, Y = K.mic_batch(d[:, 0], d[:, 1], d[:, 2], mode=mode, compiled=True)
    port = np.array([M._mic_one_port(*map(float, row), mode) for row in d])
    np.testing.assert_array_equal(port[:, 0], R)
    np.testing.assert_array_equal(port[:, 1], Y)


def test_mic_switches_to_the_compiled_kernel_with_the_same_values(monkeypatch):
    """The first MICs of a process come from the NumPy port; once the port has taken
    MIC_NUMBA_AFTER_SECONDS, from the compiled kernel (when numba is there), with the
    same values. The paths taken are counted, so a switch that never happens fails."""
    fb = FiveBar(0.85, 1.6, 0.55)
    calls = []
    for name in ("_mic_one_port", "_compiled_one"):
        real = getattr(M, name)
        monkeypatch.setattr(M, name, lambda *a, _real=real, _name=name: calls.append(_name) or _real(*a))
    monkeypatch.setattr(M, "_port_seconds", 0.0)
    first = mic(fb)
    assert calls and set(calls) == {"_mic_one_port"}
    calls.clear()
    monkeypatch.setattr(M, "_port_seconds", M.MIC_NUMBA_AFTER_SECONDS)
    assert mic(fb) == first
    assert calls and set(calls) == ({"_compiled_one"} if M.HAVE_NUMBA else {"_mic_one_port"})


@pytest.mark.skipif(not fast_lci.HAVE_NUMBA, reason="numba not installed")
@pytest.mark.parametrize("mode", MODES)
def test_fast_lci_numpy_and_numba_agree_bit_for_bit(mode):
    rng = np.random.default_rng(MODES.index(mode))
    s1, s2 = (1.0 if c == "+" else -1.0 for c in mode)
    for r1, r2, r3 in _random_designs(3, 12):
        L = r1 + r2 + r3
        x, y = rng.uniform(-L, L, 30001), rng.uniform(-L, L, 30001)
        np.testing.assert_array_equal(fast_lci.five_bar_lci_numba(x, y, r1, r2, r3, s1, s2),
                                      fast_lci.five_bar_lci_numpy(x, y, r1, r2, r3, s1, s2))


def test_reach_filter_never_drops_a_finite_type2_value():
    """The usable region evaluates ``type2_function`` only where the filter lets it:
    wherever the filter says no, the value is NaN (also next to the annuli's circles
    and for extreme link ratios)."""
    rng = np.random.default_rng(5)
    for k, r in enumerate(_random_designs(9, 60)):
        r = r * 10.0 ** rng.uniform(-4, 4, 3) if k % 3 == 0 else r
        fb = FiveBar(*r, mode=MODES[k % 4])
        L = r.sum()
        x, y = rng.uniform(-1.1 * L, 1.1 * L, 20000), rng.uniform(0.0, 1.1 * L, 20000)
        phi = rng.uniform(0.0, np.pi, 2000)
        for radius in (abs(r[0] - r[1]), r[0] + r[1]):
            for ax in (-r[2], r[2]):
                rr = radius * (1.0 + rng.normal(0.0, 1e-9, phi.size))
                x, y = np.r_[x, ax + rr * np.cos(phi)], np.r_[y, rr * np.sin(phi)]
        near = fb.explicit_workspace().reach_filter()(x, y)
        assert not np.isfinite(fb.type2_function(x[~near], y[~near])).any()


def test_component_is_scipys_4_connected_label():
    from scipy import ndimage

    rng = np.random.default_rng(1)
    for k in range(200):
        ny, nx = (int(v) for v in rng.integers(1, 50, 2))
        free = rng.random((ny, nx)) < rng.uniform(0.3, 0.9)
        if k % 2:
            free = ndimage.binary_opening(free)
        cells = np.argwhere(free)
        if not len(cells):
            continue
        i, j = (int(v) for v in cells[rng.integers(len(cells))])
        labels, _ = ndimage.label(free)
        np.testing.assert_array_equal(W._component(free, i, j), labels == labels[i, j])


@pytest.mark.parametrize("r", [(0.85, 1.6, 0.55), (1.6, 0.9, 0.5), (1.2, 1.8, 0.0), (0.4, 2.33, 0.27)])
def test_usable_region_is_the_whole_raster_labelling(r):
    """Blocks, the reach filter and the run labelling give the mask of the direct
    route: ``type2_function`` on the whole raster, then ``scipy.ndimage.label``."""
    from scipy import ndimage

    fb = FiveBar(*r)
    m = mic(fb)
    u = usable_region(fb, center=(0.0, m.center_y))
    X, Y = u.grid.points()
    free = np.sign(fb.type2_function(X, Y)) == np.sign(fb.type2_function(0.0, m.center_y))
    labels, _ = ndimage.label(free)
    i = int(np.clip(np.searchsorted(u.grid.y, m.center_y), 0, u.grid.y.size - 1))
    j = int(np.clip(np.searchsorted(u.grid.x, 0.0), 0, u.grid.x.size - 1))
    np.testing.assert_array_equal(u.mask, labels == labels[i, j])
    g = gcw(fb, 0.5, u)
    np.testing.assert_array_equal(g.mask, u.mask & (fb.lci(X, Y) >= 0.5))
    x, y = g.points()
    np.testing.assert_array_equal(x, X[g.mask])
    np.testing.assert_array_equal(y, Y[g.mask])
    assert not x.flags.writeable


def test_one_evaluation_imports_neither_scipy_nor_numba(tmp_path):
    # a fresh interpreter in an empty folder, without what other tests of this worker may
    # have put in its environment (warning filters, test tags, numba switches): the
    # imports measured are the package's own
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "MECHOPT", "NUMBA"))}
    code = ("import sys; from mechopt.analysis.evaluate import evaluate; from mechopt import FiveBar; "
            "evaluate(FiveBar(0.85, 1.6, 0.55)); "
            "print(sorted(m for m in ('scipy', 'numba', 'mechopt.mechanisms.five_bar.kernels', 'matplotlib', 'pandas') "
            "if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env,
                         cwd=tmp_path)
    assert out.stdout.strip() == "[]"
