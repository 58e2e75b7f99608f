"""The general 5R (unequal legs) shares FiveBar's per-leg kinematics
(``five_bar.model.legs_*``): with unequal legs its poses are checked against the
definitions (crank ends, leg lengths, working-mode sides, Le's branch, fk of ik), with
equal legs it must agree with the symmetric FiveBar everywhere (property test), and it
is offered by ``mechopt evaluate`` from its declaration alone."""
import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mechopt import FiveBar
from mechopt.cli import main
from mechopt.mechanisms import registry
from mechopt.mechanisms.asymmetric_five_bar import ASSEMBLY_MODES, MODES, AsymmetricFiveBar


@settings(max_examples=40, deadline=None, derandomize=True)
@given(r1=st.floats(0.3, 2.0), r2=st.floats(0.3, 2.0), r3=st.floats(0.0, 1.0),
       mode=st.sampled_from(MODES), seed=st.integers(0, 2**16))
def test_equal_legs_are_the_symmetric_five_bar(r1, r2, r3, mode, seed):
    fb, ab = FiveBar(r1, r2, r3, mode), AsymmetricFiveBar(r1, r2, r1, r2, r3, mode)
    rng = np.random.default_rng(seed)
    reach = r1 + r2
    x, y = rng.uniform(-reach, reach, 300), rng.uniform(-reach, reach, 300)
    np.testing.assert_array_equal(ab.reachable(x, y), fb.reachable(x, y))
    ok = fb.reachable(x, y) & (np.abs(fb.serial_clearance(x, y)) > 1e-6)
    np.testing.assert_allclose(ab.jacobian(x[ok], y[ok]), fb.jacobian(x[ok], y[ok]), rtol=1e-9,
                               atol=1e-9)
    for a, b in zip(ab.ik(x[ok], y[ok])[:2], fb.ik(x[ok], y[ok])[:2]):
        np.testing.assert_allclose(np.angle(np.exp(1j * (a - b))), 0.0, atol=1e-9)


def test_offered_by_evaluate_from_its_declaration(capsys):
    assert registry()["asymmetric-five-bar"] is AsymmetricFiveBar
    assert main(["evaluate", "asymmetric-five-bar", "--a1", "1", "--c1", "1.5", "--a2", "0.8",
                 "--c2", "1.7", "--r3", "0.5", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["inputs"]["a2"] == 0.8 and out["quadrature"] == "raster-400"
    assert 0 < out["mean_lci"] < 1 and out["workspace_area"] > 0


@settings(max_examples=40, deadline=None, derandomize=True)
@given(r1=st.floats(0.3, 2.0), r2=st.floats(0.3, 2.0), r3=st.floats(0.0, 1.0),
       mode=st.sampled_from(MODES), seed=st.integers(0, 2**16))
def test_equal_legs_give_the_five_bar_bit_for_bit(r1, r2, r3, mode, seed):
    """Both classes run the one geometry of ``five_bar.model`` (``legs_*``): with equal legs
    every kinematic output is FiveBar's to the bit, NaNs and masks included."""
    fb, ab = FiveBar(r1, r2, r3, mode), AsymmetricFiveBar(r1, r2, r1, r2, r3, mode)
    rng = np.random.default_rng(seed)
    reach = r1 + r2
    x, y = rng.uniform(-reach, reach, 300), rng.uniform(-reach, reach, 300)
    x[:2], y[:2] = (-r3, r3), 0.0  # on the base joints
    assert ab.bounding_box() == fb.bounding_box()
    t1, t2 = rng.uniform(-4.0, 8.0, 300), rng.uniform(-4.0, 8.0, 300)
    for got, want in [(ab.elbows(x, y), fb.elbows(x, y)), (ab.closure(x, y), fb.closure(x, y)),
                      (ab.ik(x, y), fb.ik(x, y)), (ab.fk(t1, t2, "up"), fb.fk(t1, t2, "up")),
                      (ab.fk(t1, t2, "down"), fb.fk(t1, t2, "down")),
                      ((ab.reachable(x, y), ab.serial_clearance(x, y), ab.assembly_of(x, y)),
                       (fb.reachable(x, y), fb.serial_clearance(x, y), fb.assembly_of(x, y)))]:
        for g, w in zip(got, want):
            np.testing.assert_array_equal(g, w)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(a1=st.floats(0.3, 2.0), c1=st.floats(0.3, 2.0), a2=st.floats(0.3, 2.0),
       c2=st.floats(0.3, 2.0), r3=st.floats(0.0, 1.0), mode=st.sampled_from(MODES),
       seed=st.integers(0, 2**16))
def test_unequal_legs_against_the_definitions(a1, c1, a2, c2, r3, mode, seed):
    """Unequal legs, checked against what the outputs mean rather than how they are
    computed: the crank ends ``B_i = A_i + a_i (cos theta_i, sin theta_i)`` of ``ik`` are
    the circle-intersection ``elbows``; they close the legs (``|B_i - P| = c_i``); they
    lie on the working mode's side (``s_i (P - A_i) x (B_i - A_i) >= 0``); the angles are
    on Le's branch (``theta1 = beta1 + s1 alpha1``, ``theta2 = pi - beta2 + s2 alpha2``
    with ``alpha_i`` in [0, pi], eq. 17-18); and ``fk`` returns the pose."""
    m = AsymmetricFiveBar(a1, c1, a2, c2, r3, mode)
    xmin, xmax, ymin, ymax = m.bounding_box()
    if not (xmax > xmin):
        return  # the legs never meet: nothing to check
    rng = np.random.default_rng(seed)
    x, y = rng.uniform(xmin, xmax, 400), rng.uniform(ymin, ymax, 400)
    with np.errstate(invalid="ignore"):  # away from both singularities (B1 = B2 is one)
        ok = (m.reachable(x, y) & (m.serial_clearance(x, y) > 1e-6)
              & (np.abs(m.type2_function(x, y)) > 1e-6))
    x, y = x[ok], y[ok]
    th1, th2, reached = m.ik(x, y)
    assert reached.all()
    b1x, b1y, b2x, b2y, _ = m.elbows(x, y)
    s = {"+": 1.0, "-": -1.0}
    for th, (bx, by), ax, a, c, sign in ((th1, (b1x, b1y), -r3, a1, c1, s[mode[0]]),
                                         (th2, (b2x, b2y), r3, a2, c2, s[mode[1]])):
        ex, ey = ax + a * np.cos(th), a * np.sin(th)
        np.testing.assert_allclose(ex, bx, rtol=0, atol=1e-9)
        np.testing.assert_allclose(ey, by, rtol=0, atol=1e-9)
        np.testing.assert_allclose(np.hypot(x - ex, y - ey), c, rtol=1e-9)
        assert np.all(sign * ((x - ax) * ey - y * (ex - ax)) >= -1e-9)
    alpha1 = (th1 - np.arctan2(y, x + r3)) * s[mode[0]]
    alpha2 = (th2 - (np.pi - np.arctan2(y, r3 - x))) * s[mode[1]]
    for alpha in (alpha1, alpha2):
        assert np.all((alpha >= -1e-12) & (alpha <= np.pi + 1e-12))
    asm = m.assembly_of(x, y)
    for a in ASSEMBLY_MODES:
        sel = asm == a
        xf, yf, valid = m.fk(th1[sel], th2[sel], a)
        assert valid.all()
        np.testing.assert_allclose(np.hypot(xf - x[sel], yf - y[sel]), 0.0, atol=1e-9)
