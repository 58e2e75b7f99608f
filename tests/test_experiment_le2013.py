"""experiments/le2013.py: the quick run's rows, recomputed independently of the table code.

The readings (the flowchart's staircase, its golden-section edge, the corner switch) and
the claims (isotropic point E, the shape of a_MAX(rho)) are recomputed here from the
mechanism alone: our own literal loop of Le Fig. 4 with the LCI from numpy's SVD of
``FiveBar.jacobian``, our own root finds; every number the table prints comes from
``mechopt/data/le2013.csv``.
"""
from __future__ import annotations

import re

import numpy as np
import pandas as pd
import pytest
from scipy.optimize import brentq

from mechopt import FiveBar
from mechopt.problems.le2013 import square_side
from mechopt.core.published import KINDS, TABLE_COLUMNS, load, printed_half_unit
from mechopt.analysis.workspace import mic

S2 = np.sqrt(2.0)
GAMMA = 0.5
THETA = (-np.pi / 3, 4 * np.pi / 3)  # Le sec. IV
QUICK_SECONDS = 60.0  # generous bound on shared cores; a quiet machine takes ~6 s

CLAIMS = ["lci_min_in_square", "claim:single_optimum_in_(1.8,2.3)", "claim:a_max_increases_to_about_2",
          "claim:a_max_increases_to_about_2[flowchart step=0.1]", "claim:isotropic_point_E"]
READINGS = ["a_max[flowchart step=0.1]", "a_max[flowchart step=0.01]",
            "rho_star[flowchart golden-section]", "rho_star[corner switch]", "a_max_relaxed"]


@pytest.fixture(scope="module")
def quick_run(quick_reproduction):
    """``le2013.run(out, quick=True)`` as the quick reproduction ran it (tests/conftest.py):
    its folder, its table and its time."""
    out, table, seconds = quick_reproduction.runs["le2013"]
    return out, table.set_index("quantity", drop=False), seconds


# ----------------------------------------------------------------------------- our own Le
def tied(rho):
    """Le eq. (24) with l1 = 1, written out here."""
    return FiveBar(1.0, rho, S2 / 2.0 * (rho - 1.0))


def lci_svd(fb, x, y):
    s = np.linalg.svd(fb.jacobian(x, y), compute_uv=False)
    return s[..., -1] / s[..., 0]


def mic_closed_form(rho):
    """r_MIC = l1 (half-width of the annulus of eq. 19), centre at distance l2 from A1, A2."""
    l0 = S2 / 2.0 * (rho - 1.0)
    return 1.0, np.sqrt(rho ** 2 - l0 ** 2)


def square_ok(fb, yc, a, n=129):
    h = a / 2.0
    u = np.linspace(-1.0, 1.0, n)
    g = np.linspace(-1.0, 1.0, 21)
    gx, gy = np.meshgrid(g, g)
    x = h * np.concatenate([u, u, -np.ones(n), np.ones(n), gx.ravel()])
    y = yc + h * np.concatenate([-np.ones(n), np.ones(n), u, u, gy.ravel()])
    t1, t2, ok = fb.ik(x, y)
    if not np.all(ok):
        return False
    lo, hi = THETA
    return bool(np.all(lci_svd(fb, x, y) >= GAMMA) and np.all((t1 >= lo) & (t1 <= hi))
                and np.all((t2 >= lo) & (t2 <= hi)))


def flowchart(rho, step):
    """Le Fig. 4: a = sqrt(2) r_MIC, then a = a - step until all constraints hold."""
    r, yc = mic_closed_form(rho)
    fb = tied(rho)
    a = S2 * r
    while a > 0 and not square_ok(fb, yc, a):
        a -= step
    return max(a, 0.0)


# ----------------------------------------------------------------------------- the table
def test_columns_kinds_and_rows(quick_run):
    out, table, seconds = quick_run
    assert list(table.columns[:len(TABLE_COLUMNS)]) == list(TABLE_COLUMNS)
    assert table["quantity"].is_unique
    assert set(table["kind"]) <= set(KINDS)
    for q in ["rho_star", "a_max", "a_max_at_paper_rho", "lci_max_in_square", *READINGS, *CLAIMS,
              "gamma", "theta_min_deg", "theta_max_deg", "rho_min", "rho_max", "l1"]:
        assert q in table.index, q
    assert (table.loc[READINGS, "kind"] == "reading").all()
    assert (table.loc[["gamma", "theta_min_deg", "theta_max_deg", "rho_min", "rho_max", "l1"], "kind"]
            == "setting").all()
    assert seconds < QUICK_SECONDS, seconds
    curve = pd.read_csv(out / "curve.csv")
    assert {"a_max", "a_flowchart[step=0.1]", "a_flowchart[step=0.01]", "lci_at_E"} <= set(curve.columns)
    for f in ("fig5_a_max.png", "fig6_lci_square.png", "front/front.csv", "relaxed/front.csv",
              "sweep/sweep.csv"):
        assert (out / f).is_file(), f


def test_every_printed_number_unit_and_tolerance_come_from_the_data_file(quick_run):
    """paper value, unit and tolerance (half the last printed digit, in the printed unit:
    our own accuracy is finer) of every compared row are those of le2013.csv."""
    _, table, _ = quick_run
    data = load("le2013").set_index("quantity")
    compared = table[table["paper"].notna()]
    assert len(compared) >= 14
    for row in compared.itertuples():
        base = "a_max" if row.quantity == "a_max_at_paper_rho" else row.quantity.split("[")[0]
        rec = data.loc[base]
        assert row.paper == rec["value"] and row.unit == rec["unit"], row.quantity
        tol = float(re.search(r"tol ([0-9.eE+-]+)", row.note).group(1))
        assert tol == pytest.approx(printed_half_unit(rec["digits"]), rel=1e-3), row.quantity
        assert row.source.startswith("Le 2013 " + rec["source"]), row.quantity
        assert row.status == ("match" if abs(row.reproduced - row.paper) <= tol * (1 + 1e-9)
                              else "differs"), row.quantity
    # the printed numbers of sec. IV that are not compared are in the data file too
    for q in ("rho_interval_lo", "rho_interval_hi", "rho_increase_end"):
        assert q in data.index


# ----------------------------------------------------------------------------- readings
def test_mic_is_the_annulus_half_width_along_the_tied_curve():
    """The flowchart starts at sqrt(2) r_MIC = sqrt(2) l1 because r_MIC = l1 = 1 there."""
    for rho in (1.2, 1.6, 1.9721, 2.5, 4.0):
        m = mic(tied(rho))
        r, yc = mic_closed_form(rho)
        assert m.radius == pytest.approx(r, abs=1e-8) and m.center_y == pytest.approx(yc, abs=1e-8)


def test_staircase_level_from_our_own_flowchart_loop(quick_run):
    _, table, _ = quick_run
    rhos = np.round(np.arange(1.3, 2.51, 0.05), 6)
    levels = {step: np.array([flowchart(r, step) for r in rhos]) for step in (0.1, 0.01)}
    top = levels[0.1].max()
    assert top == pytest.approx(S2 - 0.1, abs=1e-12)  # one decrement from sqrt(2)
    plateau = rhos[np.isclose(levels[0.1], top, atol=1e-9)]
    assert 1.5 < plateau.min() <= 1.55 and 1.9 < plateau.max() < 2.0
    start = bisect_level(1.5, 1.55, 0.1, rising=True)
    end = bisect_level(1.95, 2.0, 0.1, rising=False)
    row = table.loc["a_max[flowchart step=0.1]"]
    assert row["reproduced"] == pytest.approx(top, abs=1e-9) and row["status"] == "match"
    assert f"top level 1.31421 (k = 1) for rho in [{start:.4f}, {end:.4f}]" in row["note"]
    # step 0.01: over [1.2, 4] its top level is one step higher, but on the paper's
    # golden-section interval (1.8, 2.3) the top level is again sqrt(2) - 0.1
    assert levels[0.01].max() == pytest.approx(S2 - 0.09, abs=1e-9)
    inside = (rhos > 1.8) & (rhos < 2.3)
    assert levels[0.01][inside].max() == pytest.approx(S2 - 0.1, abs=1e-9)
    row = table.loc["a_max[flowchart step=0.01]"]
    assert row["reproduced"] == pytest.approx(S2 - 0.1, abs=1e-9) and row["status"] == "match"


def bisect_level(lo, hi, step, rising, level=S2 - 0.1, tol=1e-7):
    """The rho in (lo, hi) where our own flowchart loop reaches (rising) or leaves ``level``."""
    on = lambda r: flowchart(r, step) > level - 1e-9  # noqa: E731
    assert on(hi if rising else lo) and not on(lo if rising else hi)
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if on(mid) == rising:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def test_golden_section_ends_at_the_plateau_edge(quick_run):
    """The staircase's step down from sqrt(2) - 0.1: bisection of our own loop in rho."""
    _, table, _ = quick_run
    edge = bisect_level(1.95, 2.0, 0.1, rising=False)
    assert edge == pytest.approx(1.9628, abs=5e-5)  # the independent check's value
    row = table.loc["rho_star[flowchart golden-section]"]
    assert row["reproduced"] == pytest.approx(edge, abs=2e-6)
    assert row["status"] == "differs" and row["rel_error"] == pytest.approx(edge / 1.9721 - 1, abs=1e-5)
    # the staircase reading of "increases up to about 2": its top plateau ends there
    assert table.loc["claim:a_max_increases_to_about_2[flowchart step=0.1]", "status"] == "holds"
    assert f"{edge:.4f}" in table.loc["claim:a_max_increases_to_about_2[flowchart step=0.1]", "note"]


def test_corner_switch_from_the_svd_at_the_square_corners(quick_run):
    """Where the LCI at the top corners of the optimal square stops being the smaller one."""
    _, table, _ = quick_run

    def diff(rho):
        a = square_side(1.0, rho, S2 / 2.0 * (rho - 1.0))["a_max"]
        _, yc = mic_closed_form(rho)
        fb = tied(rho)
        return float(lci_svd(fb, a / 2, yc + a / 2) - lci_svd(fb, a / 2, yc - a / 2))

    switch = brentq(diff, 1.94, 1.99, xtol=1e-8)
    assert switch == pytest.approx(1.9656, abs=1e-4)
    row = table.loc["rho_star[corner switch]"]
    assert row["reproduced"] == pytest.approx(switch, abs=2e-5) and row["status"] == "differs"
    # the literal rows' note says where the switch is, and no longer that it is "exactly" 1.9721
    for q in ("rho_star", "a_max"):
        note = table.loc[q, "note"]
        assert f"{switch:.4f}" in note and "sits exactly" not in note


# ----------------------------------------------------------------------------- claims
def test_claim_rows_carry_status_and_evidence(quick_run):
    _, table, _ = quick_run
    claims = table[table["kind"] == "claim"]
    assert set(CLAIMS) <= set(claims.index)
    assert set(claims["status"]) <= {"holds", "fails"}
    for row in claims.itertuples():
        assert len(row.note) > 40 and re.search(r"\d\.\d{3}", row.note), row.quantity
        assert row.reproduced == (1.0 if row.status == "holds" else 0.0)


def test_isotropic_point_E_by_svd(quick_run):
    """E = (0, sqrt(2)/2 (l1 + l2)) of eq. (22): J's singular values are equal for every tied
    design, and E lies inside the paper's optimal square, so its max LCI is 1."""
    _, table, _ = quick_run
    for rho in np.linspace(1.2, 4.0, 15):
        s = np.linalg.svd(tied(rho).jacobian(0.0, S2 / 2 * (1 + rho)), compute_uv=False)
        assert s[-1] / s[0] == pytest.approx(1.0, abs=1e-12)
    rho = 1.9721
    a = square_side(1.0, rho, S2 / 2 * (rho - 1))["a_max"]
    _, yc = mic_closed_form(rho)
    assert abs(S2 / 2 * (1 + rho) - yc) < a / 2
    assert table.loc["claim:isotropic_point_E", "status"] == "holds"
    row = table.loc["lci_max_in_square"]
    assert row["reproduced"] == pytest.approx(1.0, abs=1e-12) and row["status"] == "match"


def test_shape_of_a_max_claims(quick_run):
    """Our a_MAX(rho) falls monotonically on (1.8, 2.3) and peaks near rho = 1.53: neither a
    single interior optimum in (1.8, 2.3) nor an increase up to about 2."""
    _, table, _ = quick_run
    rhos = np.round(np.arange(1.8, 2.31, 0.05), 6)
    a = np.array([square_side(1.0, r, S2 / 2 * (r - 1))["a_max"] for r in rhos])
    assert np.all(np.diff(a) < 0)
    assert table.loc["claim:single_optimum_in_(1.8,2.3)", "status"] == "fails"
    wide = np.round(np.arange(1.4, 1.71, 0.02), 6)
    aw = np.array([square_side(1.0, r, S2 / 2 * (r - 1))["a_max"] for r in wide])
    peak = wide[int(np.argmax(aw))]
    assert 1.45 < peak < 1.6
    assert table.loc["claim:a_max_increases_to_about_2", "status"] == "fails"
    assert abs(float(re.search(r"at rho = (1\.\d{4}) and falls", table.loc[
        "claim:a_max_increases_to_about_2", "note"]).group(1)) - peak) <= 0.02
    # the LCI bound is all there is: the joint limits hold on every inscribed square
    lo, hi = THETA
    for r in (1.2, 1.5, 2.0, 3.0, 4.0):
        rr, yc = mic_closed_form(r)
        h = S2 * rr / 2
        x, y = np.meshgrid(np.linspace(-h, h, 41), yc + np.linspace(-h, h, 41))
        t1, t2, ok = tied(r).ik(x, y)
        assert ok.all() and np.all((t1 >= lo) & (t1 <= hi) & (t2 >= lo) & (t2 <= hi))


def test_square_side_equals_the_plain_all_points_test_bit_for_bit():
    """square_side checks a square's points in a cheaper order (LCI first, the inverse
    kinematics only when it holds, the last failing point first): the bisection of
    ``largest_square_at`` must take the same steps as with the plain element-wise test
    of (23), (25)-(26), on tied, relaxed and gamma designs and on joint limits that bind."""
    from mechopt.analysis.workspace import largest_square_at

    from mechopt.problems import le2013 as P

    def plain(rho, l0, gamma, limits):
        fb = FiveBar(1.0, rho, l0)
        m = mic(fb)
        lo, hi = limits

        def feasible(x, y):
            t1, t2, ok = fb.ik(x, y)
            with np.errstate(invalid="ignore"):
                return ok & (fb.lci(x, y) >= gamma) & (t1 >= lo) & (t1 <= hi) & (t2 >= lo) & (t2 <= hi)

        return largest_square_at(feasible, m.center_y, m.radius / np.sqrt(2.0))

    rng = np.random.default_rng(2013)
    bound = 0
    for k in range(120):
        rho = float(rng.uniform(*P.RHO_BOUNDS))
        l0 = P.tied_half_base(rho) if k % 3 == 0 else float(rng.uniform(0.05, 2.0))
        gamma = GAMMA if k % 3 < 2 else float(rng.uniform(0.05, 0.95))
        limits = THETA if k % 4 else (-float(rng.uniform(0.0, 1.5)), float(rng.uniform(2.5, 4.5)))
        try:
            ref = plain(rho, l0, gamma, limits)
        except ValueError:  # no MIC: square_side reports a_max = 0
            assert square_side(1.0, rho, l0, gamma, limits)["a_max"] == 0.0
            continue
        got = square_side(1.0, rho, l0, gamma, limits)["a_max"]
        assert np.float64(got).tobytes() == np.float64(ref).tobytes(), (rho, l0, gamma, limits)
        bound += limits != THETA
    assert bound >= 20
