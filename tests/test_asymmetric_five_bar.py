"""The general 5R (unequal legs) is a different implementation of the same kinematics:
with equal legs it must agree with the symmetric FiveBar everywhere (property test),
and it is offered by ``mechopt evaluate`` from its declaration alone."""
import json

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from mechopt import FiveBar
from mechopt.cli import main
from mechopt.mechanisms import registry
from mechopt.mechanisms.asymmetric_five_bar import MODES, AsymmetricFiveBar


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
