"""experiments/wu2008.py: the quick run produces every row and every file."""
from __future__ import annotations

import time

import numpy as np
import pandas as pd
import pytest

from mechopt.experiments import wu2008
from mechopt.published import TABLE_COLUMNS

QUANTITIES = [
    "d1[theta_1S=15deg]", "l[theta_1S=15deg]", "stroke[theta_1S=15deg]",
    "d1[table1]", "l[table1]", "stroke[table1]",
    "k_av[table1]", "k_av_alternative[table1]",
    "eta_d[built]", "eta_d_std[built]", "eta_d[symmetric]",
    "kappa_d_min[built]", "kappa_d_max[built]", "kappa_d_centre[built]",
    "kappa_d_min[symmetric]", "kappa_d_max[symmetric]",
    "driving_force_peak_1", "driving_force_peak_2",
]

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
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("wu2008")
    t0 = time.perf_counter()
    table = wu2008.run(out, quick=True)
    return out, table, time.perf_counter() - t0


def test_columns_and_quantities(quick_run):
    _, table, _ = quick_run
    assert isinstance(table, pd.DataFrame)
    assert list(table.columns[:len(TABLE_COLUMNS)]) == list(TABLE_COLUMNS)
    assert sorted(table["quantity"]) == sorted(QUANTITIES)
    assert table["quantity"].is_unique


def test_statuses_and_notes(quick_run):
    _, table, _ = quick_run
    assert set(table["status"]) <= {"match", "differs", "not-reported"}
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
    for q in QUANTITIES[8:]:
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


def test_quick_is_quick(quick_run):
    *_, seconds = quick_run
    assert seconds < 30.0
