"""One design, one number: every global mean names its quadrature, the gantry has a
dynamic model for every synthesis angle, and an empty good-conditioning workspace is
a result (Liu 2006 sec. 3.2.1 shows such a design)."""
import json
import math

import numpy as np
import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.mechanisms.gantry_dynamics import GantryDynamics, GantryInertia
from mechopt.mechanisms.gantry import dimensional_synthesis, wu2008_gantry
from mechopt.problems import get, names


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


# --- gantry: a valid dynamic model for every theta_1S the synthesis accepts ------------
@pytest.mark.parametrize("theta", [5, 10, 15, 20, 30, 40])
def test_evaluate_gantry_away_from_the_paper_design(capsys, theta):
    out = _json(capsys, ["evaluate", "gantry", "--theta-1s-deg", str(theta), "--json"])
    assert np.isfinite(out["eta_d"]) and out["eta_d"] >= 1.0
    assert out["quadrature"] == "gauss-legendre-48x48"


def test_table2_law_is_table2_at_the_table1_design_and_physical_elsewhere():
    table2 = GantryInertia.wu2008()
    l0 = 1e-3 * dimensional_synthesis(500.0, 400.0, math.radians(10.0))[2]
    at_l0 = GantryInertia.wu2008_scaled(l0, l0)
    for name in ("m11", "m21", "m12", "m22", "m13", "m23", "m4", "mN", "I12", "I22"):
        assert getattr(at_l0, name) == pytest.approx(getattr(table2, name), rel=1e-12), name
    # the cross-section invariant of a uniform plate, I_c/m - l^2/12 = w^2/12, is Table 2's
    w2_12 = table2.I12 / table2.m12 - l0 * l0 / 4.0 - l0 * l0 / 12.0
    assert w2_12 > 0.0
    for deg in np.linspace(1.0, 44.0, 12):
        g = wu2008_gantry(float(deg), unit="m")
        p = GantryInertia.wu2008_scaled(g.l, l0)
        assert p.m12 / g.l == pytest.approx(table2.m12 / l0, rel=1e-12)  # mass per length
        central = p.I12 - p.m12 * (g.l / 2.0) ** 2
        assert central / p.m12 - g.l * g.l / 12.0 == pytest.approx(w2_12, rel=1e-9)
        assert p.m13 == p.m23 == pytest.approx(0.5 * p.moving_mass, rel=1e-15)  # Wu sec. 6.2
        dyn = GantryDynamics(g, p)  # raises if the model is impossible
        assert np.isfinite(dyn.eta_d(n=12))


def test_absent_link_has_no_inertia_and_massless_inertia_is_refused():
    p = GantryInertia.wu2008()
    dyn = GantryDynamics(wu2008_gantry(10.0, unit="m"), p)
    assert dyn.mass_matrix(0.0, 0.5)[0, 0] == pytest.approx(1063.0, abs=0.05)
    with pytest.raises(ValueError, match="A4B4 must be 0 when its mass is 0"):
        GantryDynamics(wu2008_gantry(10.0, unit="m"), GantryInertia(
            **{f: getattr(p, f) for f in ("m11", "m21", "m12", "m22", "m13", "m23", "m4", "mN",
                                          "I12", "I22")}, I5=1.0))


def test_wu2008_dynamic_covers_its_whole_design_range():
    prob = get("wu2008-dynamic")
    X = np.linspace(prob.xl[0], prob.xu[0], 9)[:, None]
    F = prob.evaluate_designs(X)["F"]
    assert np.all(np.isfinite(F))


# --- five-bar: an empty GCW is a result -------------------------------------------------
def test_empty_gcw_is_a_result(capsys):
    out = _json(capsys, ["evaluate", "five-bar", "--r1", "0.4", "--r2", "2.33", "--r3", "0.27",
                         "--json"])
    assert out["gcw_area"] == 0.0 and out["gcw_square_side"] == 0.0
    assert out["gcw_gci"] is None and out["theta1_range_deg"] is None
    # Liu 2006 sec. 3.2.1 prints r_MIC = 0.4 (the annulus r2 - r1 ... r1 + r2 bound) for it
    assert out["r_mic"] == pytest.approx(0.4, abs=0.05)
    assert 0.0 < out["gci"] < 0.5  # no pose reaches LCI 0.5, so the mean is below it
    assert out["usable_area"] == pytest.approx(3.3453, abs=0.01)


def test_bad_input_and_no_workspace_stay_errors(capsys):
    assert main(["evaluate", "five-bar", "--r1", "0.1", "--r2", "0.1", "--r3", "5", "--json"]) == 2
    assert "MIC radius 0" in capsys.readouterr().err


# --- quadrature named everywhere ----------------------------------------------------------
def test_every_liu_problem_names_its_quadrature():
    for name in names():
        if name.startswith("liu2006"):
            for q in ("polar", "area"):
                p = get(name, quadrature=q)
                assert p.settings["quadrature"] == q and p.summary.endswith(f"{q} means")
            assert get(name).settings["quadrature"] == "polar"  # the paper's
    with pytest.raises(ValueError, match="takes no option 'quadrature'"):
        get("wu2008", quadrature="area")


@pytest.mark.parametrize("quadrature", ["polar", "area"])
def test_front_design_evaluates_to_the_same_numbers(tmp_path, capsys, quadrature):
    """A knee design of a Liu front, re-evaluated by ``mechopt evaluate`` with the
    quadrature its run.json names, gives the front's r_MIC and GCI to 1e-6."""
    out = tmp_path / "run"
    assert main(["optimize", "liu2006-w-gci", "--pop", "16", "--gen", "6", "--seed", "2",
                 "--n-jobs", "1", "--quadrature", quadrature, "--out", str(out)]) == 0
    capsys.readouterr()
    info = json.loads((out / "run.json").read_text())
    assert info["settings"] == {"quadrature": quadrature, "region": "w-gci"}  # every option recorded
    front = pd.read_csv(out / "front.csv")
    assert len(front) > 0
    # knee: the design closest to the ideal point of the normalised front
    f = front[["r_mic", "gci"]].to_numpy()
    span = np.ptp(f, axis=0)
    span[span == 0] = 1.0
    knee = front.iloc[int(np.argmin(np.hypot(*((f.max(axis=0) - f) / span).T)))]
    res = _json(capsys, ["evaluate", "five-bar", "--r1", repr(float(knee["r1"])), "--r2", repr(float(knee["r2"])),
                         "--r3", repr(float(knee["r3"])), "--quadrature", info["settings"]["quadrature"],
                         "--json"])
    assert res["quadrature"] == quadrature
    assert res["r_mic"] == pytest.approx(knee["r_mic"], rel=1e-6)
    assert res["gci"] == pytest.approx(knee["gci"], rel=1e-6)
