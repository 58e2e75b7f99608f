"""experiments/wu2008.py: the quick run produces every row and every file."""
from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from mechopt.experiments import wu2008
from mechopt.core.published import TABLE_COLUMNS

QUANTITIES = [
    "d1[theta_1S=15deg]", "l[theta_1S=15deg]", "stroke[theta_1S=15deg]",
    "d1[table1]", "l[table1]", "stroke[table1]",
    "k_av[table1]", "k_av_alternative[table1]",
    "eta_d[built]", "eta_d_std[built]", "eta_d[symmetric]",
    "kappa_d_min[built]", "kappa_d_max[built]", "kappa_d_centre[built]",
    "kappa_d_min[symmetric]", "kappa_d_max[symmetric]",
    "driving_force_peak_1", "driving_force_peak_2",
    "theta_2L[table1]", "claim:counterweights_half_moving_mass", "claim:a_s_gives_T0_0.15s",
    "claim:2l_greater_than_2d1", "claim:k_av_descends_with_theta",
]
DYNAMIC = QUANTITIES[8:18]

FILES = [
    "front/front.csv", "front/history.csv", "front/run.json", "front/front.png",
    "front_dynamic/front.csv", "front_dynamic/history.csv", "front_dynamic/run.json",
    "front_dynamic/front.png",
    "sweep/sweep.csv", "sweep/sweep.png",
    "fig2_workspace.png", "fig4_driving_forces.png", "driving_forces.csv",
    "fig5_inertia_ellipses.png", "fig6_kappa_d_built.png", "fig7_kappa_d_symmetric.png",
    "k_av_vs_theta.csv",
]


@pytest.fixture(scope="module")
def quick_run(quick_reproduction):
    """``wu2008.run(out, quick=True)`` as the quick reproduction ran it (tests/conftest.py)."""
    out, table, _ = quick_reproduction.runs["wu2008"]
    return out, table, None


def test_columns_and_quantities(quick_run):
    _, table, _ = quick_run
    assert isinstance(table, pd.DataFrame)
    assert list(table.columns[:len(TABLE_COLUMNS)]) == list(TABLE_COLUMNS)
    assert sorted(table["quantity"]) == sorted(QUANTITIES)
    assert table["quantity"].is_unique


def test_statuses_and_notes(quick_run):
    _, table, _ = quick_run
    assert set(table["status"]) <= {"match", "differs", "not-reported", "holds", "fails"}
    differs = table[table["status"] == "differs"]
    assert all(isinstance(n, str) and n.strip() for n in differs["note"])
    assert all(isinstance(n, str) and n.strip() for n in table["note"])
    assert np.all(np.isfinite(table["reproduced"].astype(float)))


def test_table1_and_15deg_design_match(quick_run):
    _, table, _ = quick_run
    status = table.set_index("quantity")["status"]
    for design in ("table1", "theta_1S=15deg"):
        for q in ("d1", "l", "stroke"):
            assert status[f"{q}[{design}]"] == "match", (q, design)


def test_k_av_rows(quick_run):
    _, table, _ = quick_run
    t = table.set_index("quantity")
    lit, alt = t.loc["k_av[table1]"], t.loc["k_av_alternative[table1]"]
    assert lit["paper"] == 1.05 and alt["paper"] == 1.05
    assert lit["status"] == "differs" and lit["reproduced"] == pytest.approx(1.78715, abs=5e-5)
    assert "literal" in lit["note"] and "max_speed" in lit["note"]
    assert alt["reproduced"] == pytest.approx(1.10946, abs=5e-5)
    assert wu2008.ALTERNATIVE_READING in alt["note"]


def test_dynamic_rows_not_reported(quick_run):
    _, table, _ = quick_run
    t = table.set_index("quantity")
    for q in DYNAMIC:
        assert t.loc[q, "status"] == "not-reported", q
        assert np.isnan(t.loc[q, "paper"])
    # what the text says qualitatively (sec. 6.2-6.3)
    assert 1.0 <= t.loc["kappa_d_min[built]", "reproduced"] <= t.loc["kappa_d_centre[built]", "reproduced"]
    assert t.loc["kappa_d_centre[built]", "reproduced"] < t.loc["kappa_d_max[built]", "reproduced"]
    assert t.loc["kappa_d_min[symmetric]", "reproduced"] < t.loc["kappa_d_max[symmetric]", "reproduced"]
    assert t.loc["driving_force_peak_1", "unit"] == "N"


def test_files(quick_run):
    out, _, _ = quick_run
    for name in FILES:
        f = out / name
        assert f.is_file() and f.stat().st_size > 0, name
    curve = pd.read_csv(out / "k_av_vs_theta.csv")
    assert {"theta_1S_deg", "k_av_literal", "k_av_max_speed"} <= set(curve.columns)
    forces = pd.read_csv(out / "driving_forces.csv")
    assert {"t", "x", "F1", "F2"} <= set(forces.columns) and len(forces) > 100
    assert len(pd.read_csv(out / "sweep" / "sweep.csv")) >= 2


def test_claims_hold_with_independent_evidence(quick_run):
    """Each claim row against a recomputation from the paper's printed numbers."""
    _, table, _ = quick_run
    t = table.set_index("quantity")
    claims = t[t["kind"] == "claim"]
    assert set(claims["status"]) <= {"holds", "fails"} and len(claims) == 4
    # Table 2: moving parts without counterweights, each counterweight half of them
    assert (250 + 198 + 80 + 80 + 80 + 236) / 2 == 462
    assert t.loc["claim:counterweights_half_moving_mass", "status"] == "holds"
    # Table 3: 6.67 m/s^2 is 1 m/s over T0 = 0.15 s to the printed digits
    assert round(1.0 / 0.15, 2) == 6.67
    assert t.loc["claim:a_s_gives_T0_0.15s", "status"] == "holds"
    assert "0.15" in t.loc["claim:a_s_gives_T0_0.15s", "note"]
    # Table 1: 616.4 > 357
    assert t.loc["claim:2l_greater_than_2d1", "status"] == "holds"
    assert t.loc["claim:k_av_descends_with_theta", "status"] == "holds"
    # theta_2L = 90 deg - theta_1S (eq. 11-13 at the task corner), printed 80 deg
    row = t.loc["theta_2L[table1]"]
    assert row["status"] == "match" and row["reproduced"] == pytest.approx(80.0, abs=1e-9)
