"""Liu 2006 section 3 reproduced: every published value of mechopt/data/liu2006.csv.

Acceptance (issue "Foundation"): r_MIC within 0.5 %, GCI/GVI/GPI/GSI within 1 %
with the quadrature that matches, the GCW area 3.4817 and the theta1 range
[36.40, 274.97] deg within 1 %. The comparison table itself is built by
``experiments/liu2006.py``; these tests read its rows and also check the
physics behind the one place where the paper contradicts its own definition.
"""
import numpy as np
import pandas as pd
import pytest

from mechopt import FiveBar
from mechopt.experiments.liu2006 import reproduce_section3
from mechopt.core.published import load
from mechopt.core.quadrature import disk_rule
from mechopt.analysis.workspace import mic

INDEX_ROWS = {"gci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min"}
SELF_CONTRADICTION = "0.7/1.7/0.6"


@pytest.fixture(scope="module")
def table():
    return reproduce_section3()


def test_every_published_value_has_a_row(table):
    from mechopt.experiments.liu2006 import dimension_rows

    pub = load("liu2006")
    full = pd.concat([table, dimension_rows()])
    got = set(zip(full["design"], full["quantity"]))
    assert set(zip(pub["design"], pub["quantity"])) <= got
    assert set(table["status"]) <= {"match", "differs", "not-reported"}


def test_every_differs_row_is_explained_or_is_a_known_open_question(table):
    # rows the paper does not let us reproduce must say why in the note
    explained = table[(table.status == "differs") & (table.quadrature != "area")]
    for rec in explained.itertuples():
        assert rec.note, rec


@pytest.mark.parametrize("design", ["1.1/1.65/0.25", "1.5/1.2/0.3", "0.85/1.6/0.55",
                                    "1.17/1.45/0.38", "0.4/2.33/0.27", "0.65/1.62/0.73"])
def test_r_mic_within_half_percent(table, design):
    row = table[(table.design == design) & (table.quantity == "r_mic")].iloc[0]
    assert abs(row.reproduced - row.paper) <= 0.005 * row.paper


def test_r_mic_where_the_paper_contradicts_its_definition():
    # Liu prints r_MIC = 0.75 for (0.7, 1.7, 0.6). With r2 > r1 every reachable
    # point lies in the annulus r2 - r1 <= |P - A_i| <= r1 + r2 of width 2 r1,
    # so no disk inside the workspace has a radius above r1 = 0.70.
    fb = FiveBar(0.7, 1.7, 0.6)
    m = mic(fb)
    assert m.radius == pytest.approx(0.70, rel=1e-6)
    # the paper's disk of radius 0.75 at our centre leaves the workspace
    dx, dy, _ = disk_rule(0.75, "polar", n_r=64, n_theta=128)
    assert not fb.reachable(dx, m.center_y + dy).all()


def test_paper_gci_of_the_contradicting_example_comes_from_its_wrong_disk():
    # The published 0.7961 is reproduced (to 0.2 %) by the polar mean over the
    # paper's r = 0.75 disk with the unreachable nodes dropped; over our MIC the
    # value is 0.808. The note of that row says so.
    fb = FiveBar(0.7, 1.7, 0.6)
    m = mic(fb)
    dx, dy, _ = disk_rule(0.75, "polar", n_r=200, n_theta=400)
    ok = fb.reachable(dx, m.center_y + dy)
    val = fb.lci(dx, m.center_y + dy)[ok].mean()
    assert val == pytest.approx(0.7961, rel=0.002)


def test_global_indices_match_with_the_polar_quadrature(table):
    rows = table[table.quantity.isin(INDEX_ROWS) & (table.quadrature == "polar")
                 & (table.design != SELF_CONTRADICTION)]
    assert len(rows) == 14
    for rec in rows.itertuples():
        assert abs(rec.rel_error) <= 0.01, rec
    other = table[table.quantity.isin(INDEX_ROWS - {"gci"}) & (table.quadrature == "polar")
                  & (table.design == SELF_CONTRADICTION)]
    assert len(other) == 2 and (other.rel_error.abs() <= 0.01).all()


def test_polar_not_area_is_the_quadrature_of_the_paper(table):
    # DESIGN asks to verify, not assume: the area mean misses several GCI values by
    # more than 4 %, the polar mean none by more than 1 % (contradicting example aside).
    gci = table[(table.quantity == "gci") & (table.design != SELF_CONTRADICTION)]
    polar = gci[gci.quadrature == "polar"].rel_error.abs()
    area = gci[gci.quadrature == "area"].rel_error.abs()
    assert polar.max() < 0.01
    assert (area > 0.04).sum() >= 3


def test_usable_workspace_areas(table):
    rows = table[table.quantity == "usable_area"]
    assert len(rows) == 2
    assert (rows.rel_error.abs() <= 0.01).all()


def test_gcw_area_and_theta1_range(table):
    d = table[table.design == "0.85/1.6/0.55"].set_index("quantity")
    for q in ("gcw_area", "theta1_lo_deg", "theta1_hi_deg", "gcw_square_side"):
        assert abs(d.loc[q, "rel_error"]) <= 0.01, q
    # theta2 is the mirror image of theta1 (mode "+-" is symmetric): 180 - theta1
    assert d.loc["theta2_lo_deg", "reproduced"] == pytest.approx(180 - d.loc["theta1_hi_deg", "reproduced"])
    assert d.loc["theta2_hi_deg", "reproduced"] == pytest.approx(180 - d.loc["theta1_lo_deg", "reproduced"])


def test_each_example_design_lies_in_its_optimum_region(quick_reproduction):
    # Liu sec. 3.1 picks each example inside its region Omega; with our indices
    # (polar means) every example satisfies its region's inequalities. regions.csv is
    # what experiments.liu2006_figures.atlas_figures(out, quick=True) wrote in the
    # session's quick reproduction (liu2006.run calls it; tests/conftest.py), not
    # computed a second time here
    folder = quick_reproduction.runs["liu2006"][0]
    regions = pd.read_csv(folder / "regions.csv")
    examples = regions[regions["example"].notna()]
    assert len(examples) == 5
    assert examples["example_inside"].astype(bool).all()
    assert (regions["n_designs"] > 0).all()
