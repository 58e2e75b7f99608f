"""Liu, Wang, Pritschow (2006): section 3 side by side with the published values.

Thin script: it only calls the evaluators (:mod:`mechopt.workspace`,
:mod:`mechopt.performance`) and the comparison helpers of :mod:`mechopt.published`.
"""
from __future__ import annotations

import numpy as np
import pandas as pd

from mechopt import FiveBar
from mechopt.performance import global_indices, region_indices
from mechopt.published import comparison_row, load
from mechopt.workspace import gcw, joint_ranges, largest_square, mic, usable_region

__all__ = ["reproduce_section3", "dimension_rows", "run", "REL_TOL", "NOTES"]

#: acceptance tolerance per quantity class (issue "Foundation"): the paper does not
#: state its quadrature or resolution, so its own numerical error is of this order
REL_TOL = {"r_mic": 0.005, "usable_area": 0.01, "gcw_area": 0.01, "default": 0.01}
#: actuator angles [deg] get an absolute tolerance: a 1 % error of the GCW's lengths
#: (the class of REL_TOL) moves a boundary pose by 0.01 L, which turns the crank of
#: length r1 by 0.01 L / r1 rad, for the example (0.85, 1.6, 0.55) 0.67 deg, the same
#: for 36 deg as for 276 deg (a relative tolerance would not be: 1 % of 276 deg is 2.8 deg)
ANGLE_TOL_DEG = float(np.degrees(0.01 * (0.85 + 1.6 + 0.55) / 3.0 / 0.85))

#: explanations of known differences, keyed by (design, quantity)
NOTES = {
    ("0.7/1.7/0.6", "r_mic"): (
        "paper contradicts its own MIC definition: with r2 > r1 the workspace lies in an annulus "
        "of width 2 r1 = 1.4, so no inscribed disk exceeds r1 = 0.70; we report 0.70"
    ),
    ("0.7/1.7/0.6", "gci"): (
        "our MIC (0.70) gives this; the paper's 0.7961 is close to the polar mean over its "
        "r=0.75 disk with unreachable nodes dropped (0.795), i.e. computed on the wrong disk"
    ),
    **{("0.85/1.6/0.55", q): (
        "the paper does not state the measure of its GCW means; ours is the area mean "
        "(raster converged to 1e-4); a joint-space-uniform mean gives gci 0.686, "
        "gsi_max 0.719, gsi_min 0.356: no single reading reproduces all three"
    ) for q in ("gcw_gci", "gcw_gsi_max", "gcw_gsi_min")},
    **{("0.85/1.6/0.55", q): (
        "the extreme sits at the thin far-left tip of the GCW near the base "
        "(x = -1.59, y = 0.28, LCI = 0.5); ours is converged (L/400 vs L/200 raster: "
        "0.01 deg), a coarser grid clips the tip; theta2 mirrors theta1 (180 - theta1)"
    ) for q in ("theta1_hi_deg", "theta2_lo_deg")},
}


def _design(key: str) -> FiveBar:
    r1, r2, r3 = (float(v) for v in key.split("/"))
    return FiveBar(r1, r2, r3, "+-")


def _reproduce_design(key: str, quantities, quadrature: str) -> dict:
    fb = _design(key)
    m = mic(fb)
    out = global_indices(fb, quadrature, mic=m)
    needs_region = {"usable_area", "gcw_area", "gcw_gci", "gcw_gsi_max", "gcw_gsi_min",
                    "gcw_square_side"} | {q for q in quantities if q.startswith("theta")}
    if needs_region & set(quantities):
        usable = usable_region(fb, center=(0.0, m.center_y))
        out["usable_area"] = usable.area
        if needs_region - {"usable_area"} & set(quantities):
            good = gcw(fb, 0.5, usable)
            out["gcw_area"] = good.area
            reg = region_indices(fb, good)
            out.update(gcw_gci=reg["gci"], gcw_gsi_max=reg["gsi_max"], gcw_gsi_min=reg["gsi_min"])
            out["gcw_square_side"] = largest_square(good)[0]
            (a, b), (c, d) = joint_ranges(fb, good)
            out.update(theta1_lo_deg=np.degrees(a), theta1_hi_deg=np.degrees(b),
                       theta2_lo_deg=np.degrees(c), theta2_hi_deg=np.degrees(d))
    return out


def _tolerances(quantity: str) -> dict:
    """``rel_tol``/``abs_tol`` of :func:`mechopt.published.comparison_row` for a quantity."""
    if "theta" in quantity:
        return {"rel_tol": 0.0, "abs_tol": ANGLE_TOL_DEG}
    return {"rel_tol": REL_TOL.get(quantity, REL_TOL["default"]), "abs_tol": 0.0}


def reproduce_section3(quadratures=("polar", "area")) -> pd.DataFrame:
    """Every published number of ``mechopt/data/liu2006.csv`` against ours.

    Disk means are computed with each named quadrature (one row each); raster
    quantities (areas, GCW means, ranges) do not depend on it.
    """
    pub = load("liu2006")
    rows = []
    pub = pub[~pub["quantity"].str.startswith(("gcw_D", "gcw_R", "square_", "gcw_gsi_m") )
              | pub["quantity"].isin(["gcw_gsi_max", "gcw_gsi_min"])]
    for key, grp in pub.groupby("design", sort=False):
        per_q = {q: _reproduce_design(key, list(grp["quantity"]), q) for q in quadratures}
        for rec in grp.itertuples():
            disk_mean = rec.quantity in {"gci", "gvi_max", "gvi_min", "gpi_max", "gpi_min",
                                         "gsi_max", "gsi_min"}
            for q in (quadratures if disk_mean else quadratures[:1]):
                note = NOTES.get((key, rec.quantity), "")
                qnote = f"quadrature {q}" if disk_mean else "raster area mean" if rec.quantity.startswith("gcw_g") else ""
                if disk_mean and q == "area":
                    qnote += ("; the true area mean: the paper's values are polar means (its polar "
                              "row matches), this row shows what that choice changes")
                note = "; ".join(s for s in (qnote, note) if s)
                tol = _tolerances(rec.quantity)
                row = comparison_row(rec.quantity, f"Liu 2006 {rec.source}", rec.value,
                                     per_q[q][rec.quantity], rec.unit, rec.digits,
                                     tol["rel_tol"], note, abs_tol=tol["abs_tol"],
                                     kind="reading" if disk_mean and q == "area" else "computed")
                row = {"design": key, "quadrature": q if disk_mean else "", **row}
                rows.append(row)
    return pd.DataFrame(rows)


def _dimension_values(fb: FiveBar) -> dict:
    """Liu 2006 sec. 3.2.3 steps 2-4 and the square example, from our GCW."""
    good = gcw(fb, 0.5)
    d = np.sqrt(150.0 / good.area)  # eq. (20) with the 150 mm^2 objective workspace
    big = fb.scaled(d)
    reg = region_indices(big, gcw(big, 0.5))
    side, cy = largest_square(good)
    d_sq = 10.0 / side  # a 10 mm x 10 mm square (eq. 20 for a similar square)
    s = np.linspace(-side / 2, side / 2, 201)
    X, Y = np.meshgrid(s, cy + s)
    t1, t2, _ = fb.ik(X, Y)
    out = {"gcw_D": d, "gcw_gsi_max_scaled": reg["gsi_max"], "gcw_gsi_min_scaled": reg["gsi_min"],
           "square_D": d_sq}
    for i, r in enumerate((fb.r1, fb.r2, fb.r3), 1):
        out[f"gcw_R{i}"] = d * r
        out[f"square_R{i}"] = d_sq * r
    out.update(square_theta1_lo_deg=np.degrees(np.nanmin(t1)), square_theta1_hi_deg=np.degrees(np.nanmax(t1)),
               square_theta2_lo_deg=np.degrees(np.nanmin(t2)), square_theta2_hi_deg=np.degrees(np.nanmax(t2)))
    return out


DIMENSION_NOTES = {
    "gcw_D": "D = sqrt(150 / GCW area) with our GCW area",
    "gcw_R": "R_i = D r_i with our unrounded D (the paper multiplies its rounded D = 6.6)",
    "gcw_gsi": ("GSI over the GCW of the scaled mechanism; it scales as D^2 (tests), so it inherits "
                "the difference of the non-dimensional GCW GSI (measure of the GCW mean not stated)"),
    "square_D": ("D = 10 mm / square side; the paper's own 1.11 gives 10/1.11 = 9.01, not its "
                 "printed 9.1, with which it computes R_i"),
    "square_R": "R_i = D r_i with our D (the paper prints all three as 'R_1')",
    "square_theta": "input range over our largest square (side and centre from the GCW raster)",
}


def dimension_rows() -> pd.DataFrame:
    """Rows for sec. 3.2.3's dimensional example (D, R_i, scaled GSI, the square)."""
    pub = load("liu2006")
    pub = pub[pub["quantity"].str.startswith(("gcw_D", "gcw_R", "gcw_gsi_max_s", "gcw_gsi_min_s", "square_"))]
    vals = _dimension_values(_design("0.85/1.6/0.55"))
    rows = []
    for rec in pub.itertuples():
        note = next(v for k, v in DIMENSION_NOTES.items() if rec.quantity.startswith(k))
        tol = _tolerances(rec.quantity)
        row = comparison_row(rec.quantity, f"Liu 2006 {rec.source}", rec.value, vals[rec.quantity],
                             rec.unit, rec.digits, tol["rel_tol"], note, abs_tol=tol["abs_tol"])
        rows.append({"design": rec.design, "quadrature": "", **row})
    return pd.DataFrame(rows)


def run(out, quick: bool = False) -> pd.DataFrame:
    """All of Liu 2006 section 3 (both quadratures) and its figures into ``out``."""
    from pathlib import Path

    from . import liu2006_figures as figs

    from mechopt.problems import get
    from mechopt.runner import optimize, parse_weights, sweep

    out = Path(out)
    table = pd.concat([reproduce_section3(), dimension_rows()], ignore_index=True)
    figs.draw_all(out, quick=quick)
    # the (r_MIC, GCI) trade-off inside Omega_W-GCI: front and weighting sweep
    sizes = dict(pop=8, gen=3) if quick else {}
    optimize(get("liu2006-w-gci"), seed=1, out=out / "front", progress=False, **sizes)
    optimize(get("liu2006-many"), seed=1, out=out / "front_many", progress=False, **sizes)
    sweep(get("liu2006-w-gci"), parse_weights("0,0.5,1" if quick else "0:1:0.1"), seed=1,
          out=out / "sweep", progress=False, **sizes)
    return table


if __name__ == "__main__":  # pragma: no cover
    with pd.option_context("display.width", 200, "display.max_colwidth", 60):
        print(reproduce_section3().to_string(index=False))
