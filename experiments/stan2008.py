"""Stan, Maties, Balan (2008): Bipod (RPRPR) and Biglide (PRRRP) side by side with
the published values.

Thin script: it only calls the problems of :mod:`mechopt.problems.stan2008`, the
runner (:func:`mechopt.run.runner.optimize`, :func:`mechopt.run.runner.sweep`), pymoo's GA
(for Table 1's operator rates), the mechanism evaluators and the comparison helpers
of :mod:`mechopt.core.published`.

``run(out, quick)`` returns one row per published quantity, reading and checked claim
(columns :data:`mechopt.core.published.TABLE_COLUMNS`, row kinds of
:data:`mechopt.core.published.KINDS`) and writes into ``out``:

``bipod/``, ``biglide/``      NSGA-II front (``front.csv``, ``history.csv``, ``run.json``,
                              ``front.png``) and weighting sweep (``sweep.csv``,
                              ``sweep.png``, weights 0:1:0.1, w = W2 weighs W)
``fig29_tqi_bipod.png``       Fig. 29 redrawn: TQI over the Bipod workspace
                              (b = 60 mm, q in [80, 130] mm, y > 0)
``fig30_tqi_biglide.png``     Fig. 30 redrawn: TQI over the Biglide workspace
                              (L1 = 1, L2 = 1.1, the middle of sec. 5.2's design
                              range 1 < L2 < 1.2, q in [0, 1], mode "--")
``tradeoff_bipod.png``,       W_n and T over the design variable, and T against W_n,
``tradeoff_biglide.png``      with the paper's Table 2/3 optima and ours marked
``curves.csv``                W, W_n, T over a dense grid of each design variable
``area_search.csv``           integer (b, q_min, q_max) [mm] of the search box
                              :data:`AREA_SEARCH` whose exact y > 0 area lies within
                              :data:`AREA_NEAR` of the printed 4693.33 mm^2
``bipod_readings.csv``        Table 2's optima for every pair of readings of W and T
``bipod_reachable_optima.csv`` per T reading: every optimum that ``T + lambda W``
                              reaches over all lambda >= 0 (all weightings, all
                              positive scales of W) and whether 0.92 / 1.13 are among them
``biglide_l1_scan.csv``       Table 3's rows over a grid of L1 and strokes

Scalarisation: ``Z = W1 T + W2 W_n`` with ``W_n = W / W(upper bound)`` (the paper does
not state its normalisation of W; see :mod:`mechopt.problems.stan2008`).

Readings shown beside the literal rows (kind ``reading``):

* ``workspace_area[b=62mm]``: the printed struts 80-130 mm on a base of 62 mm instead
  of the printed 60 mm. The exact area is 4693.326 mm^2, 4693.33 to the printed digits;
  it is the only integer (b, q_min, q_max) of the search box that gives the printed
  number (``area_search.csv``).
* ``q1_over_b[W1=1,W2=0;retracted pose]``: T read as the TQI at the retracted pose
  ``q1 = q2 = q_min``, where the struts and the base form an isosceles triangle:
  ``cos gamma = 1 - 1/(2 u^2)`` (law of cosines, ``|A1A2| = b``), the TQI
  ``|sin gamma|`` is 1 at ``u = 1/sqrt(2) = 0.7071``: Table 2's 0.71. Every workspace
  mean of the TQI peaks near 0.56 instead.
* ``q1_over_b[W1=0,W2=1;design 80/62]``: Table 2's W-only 1.3 read as the ratio of
  the design whose area is printed, 80/62 = 1.290 (not discriminating: 80/60 = 1.333
  and the bound 1.35 are as close to 1.3 at its one printed decimal).
* ``L2[...;L1=0.5]``: Table 3 under the Biglide setup chosen below.
* ``...;GA Table 1 rates]``: the literal problems solved by a GA with Table 1's
  crossover rate 0.08 and mutation rate 0.005 instead of pymoo's default operators.

Biglide setup (the paper prints no L1 and no strokes). At the centre pose ``x = 0`` the
links make the angle ``theta`` with ``tan theta = L1 / sqrt(L2^2 - L1^2)`` with the
guides and the TQI is ``sin 2 theta``, largest at ``L2 = sqrt(2) L1``: the TQI falls with
L2 only beyond ``sqrt(2) L1``. Table 3's T-only optimum at the lower bound L2 = 1 thus
needs ``L1 < 1/sqrt(2)`` (for the workspace mean of our T, L1 <= 0.64 to 0.68
depending on the stroke: ``biglide_l1_scan.csv`` of the full run); the literal problem's
``L1 = 1`` (like every L1 >= 0.86 of the scan) makes T rise with L2 and contradicts that
row by construction. We choose
**L1 = 0.5**, guides 2 L1 = 1 apart: L2's design range (1, 1.2) is then measured in
units of the distance between the guides, as the Bipod's design variable ``q1min/b``
is measured in units of the distance between its base joints; it lies inside the range
the T-only row implies for every stroke of the scan. Strokes are kept at ``q in [0, 1]``
(one guide distance): the only Biglide dimensions the paper prints are Fig. 25's strokes
q_max = 100, 200, 400 mm, which give no length unit for L1 and L2; at L1 = 0.5 the
T-only and W-only rows do not depend on the stroke (scan). No (L1, stroke,
normalisation of W) of the scan (L1 in [0.3, 1] by 0.02, strokes 0.25-4) reproduces the
two interior weighted optima 1.1 and 1.1556 together with the T-only row L2 = 1; with
``W_n`` two pairs fitted to the rows (L1 = 0.54, stroke 0.5: 1.140; L1 = 0.58, stroke
0.25: 1.106) would also give the 0.7/0.3 row, never the 0.3/0.7 row (always 1.2): a fit,
not adopted.

Every printed number (value, unit, digits, source) comes from ``mechopt/data/stan2008.csv``
through :func:`mechopt.core.published.lookup`. Tolerances (printed unit): half a unit of
the last printed digit, or the accuracy class the data file names if larger
(:data:`mechopt.core.published.ACCURACY`): an optimum of the one design variable is of
class ``ga_optimum``, 1 % of the design range, absolute (the location error of an
optimum does not scale with its value); the literal workspace area of class
``raster``, 1 % (a raster count's error scales with the workspace); settings and the
exact-area reading only the printed digits.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator
from scipy.optimize import brentq, minimize_scalar

from mechopt.core import validation as _v
from mechopt.run import io as _io
from mechopt.mechanisms.biglide import Biglide
from mechopt.mechanisms.bipod import Bipod, bipod_tqi_integral, bipod_workspace_area
from mechopt.run.parallel import parallel_map
from mechopt.problems import get
from mechopt.problems.stan2008 import Q_MAX_OVER_Q_MIN, StanBiglide
from mechopt.run.weighted import WeightedSum
from mechopt.run.plotting import labelled_colorbar
from mechopt.core.published import (ACCURACY, TABLE_COLUMNS, claim_row, compare, lookup,
                                    printed_half_unit, records, tolerance)
from mechopt.core.quadrature import gauss_legendre, grid_over
from mechopt.run.runner import make_algorithm, optimize, parse_weights, sweep

__all__ = ["run", "SETTINGS", "WEIGHTS", "SEED",
           "AREA_SEARCH", "AREA_READING_B", "BIGLIDE_L1", "BIGLIDE_STROKES", "paper_ga",
           "area_search", "retracted_pose_tqi", "bipod_t_readings"]

PAPER = "stan2008"


def _rec(design, quantity):
    return lookup(PAPER, quantity, design)


def _inputs() -> dict:
    """The printed inputs of sec. 5.1 and eq. (12)-(13), ``{quantity: value}``: b,
    strokes [mm], q1min/b (printed and bounds), q_max/q_min."""
    return {r.quantity: r.value for r in records(PAPER) if r.design in ("bipod-sec5.1", "bipod-eq12-13")}


def _comma(x: float) -> str:
    """``x`` as the paper prints it, with a decimal comma (``1,35``)."""
    return f"{x:g}".replace(".", ",")


#: weights of the sweep (w = W2, the weight of W_n; W1 = 1 - w)
WEIGHTS = "0:1:0.1"
SEED = 1
#: run sizes: GA/NSGA-II population and generations (the full run uses Table 1's),
#: points of the design-variable curves, cells across the TQI maps, rasters tried for
#: the workspace area [mm], points of q1min/b for the readings of T and W, and the
#: Biglide scan (L1 values, strokes, points of L2)
SETTINGS = {
    False: dict(pop=int(_rec("table1", "population").value), gen=int(_rec("table1", "generations").value),
                n_curve=401, n_map=400, raster_steps=(2.0, 1.0, 0.5),
                n_readings=831, scan_l1=tuple(np.round(np.arange(0.30, 1.0001, 0.02), 2)),
                scan_strokes=(0.25, 0.5, 1.0, 2.0, 4.0), scan_n=101),
    True: dict(pop=10, gen=10, n_curve=41, n_map=80, raster_steps=(2.0, 1.0),
               n_readings=167, scan_l1=(0.5, 0.64, 0.7, 1.0), scan_strokes=(1.0,), scan_n=21),
}
PROBLEMS = {"bipod": "stan2008-bipod", "biglide": "stan2008-biglide"}
#: (mechanism, Table, quantity prefix) of the optima rows
OPTIMA = (("bipod", "table2", "q1_over_b"), ("biglide", "table3", "L2"))
#: the search box of the Bipod area (integers, mm, inclusive)
AREA_SEARCH = {"b": (40, 80), "q_min": (60, 100), "q_max": (110, 150)}
#: |area - printed area| [mm^2] up to which a design is written to area_search.csv
AREA_NEAR = 1.0
#: base width [mm] of the area reading
AREA_READING_B = 62.0
#: the row of the area reading
AREA_READING = f"workspace_area[b={AREA_READING_B:g}mm]"
#: the tags of the readings of Table 2's optima: T-only as the TQI of the retracted pose,
#: W-only as q1min/b of the design of the area reading
RETRACTED_TAG = "retracted pose"
DESIGN_TAG = f"design {_inputs()['q1_min']:g}/{AREA_READING_B:g}"
#: the claim row of sec. 5.1's maximum workspace at the bound of eq. (12)
MAX_CLAIM = f"claim:max_workspace_at_q1min/b={_rec('bipod-sec5.1', 'q1_min_over_b').value:g}"
#: Biglide setup of the L1 reading (module docstring)
BIGLIDE_L1 = 0.5
BIGLIDE_STROKES = (0.0, 1.0)
#: strokes of a Bipod (b = 1) that contain every strut length of the design range
#: [0.52, 1.6 * 1.35]: the TQI at a pose does not depend on the strokes
_PROBE_STROKES = (0.5, 2.2)
_LAMBDAS = np.concatenate([[0.0], np.logspace(-4, 5, 1801)])


def _span(problem) -> float:
    """The design range of a one-variable problem: the span of the ``ga_optimum`` class."""
    return float(problem.xu[0] - problem.xl[0])


def _labels(table_id):
    """``[(design, label, W1, W2)]`` of a Table in the order of the data file."""
    out = []
    for design in dict.fromkeys(r.design for r in records(PAPER) if r.design.startswith(table_id + ":")):
        label = design.split(":", 1)[1]
        w1, w2 = (float(t.split("=")[1]) for t in label.split(","))
        out.append((design, label, w1, w2))
    return out


def _maximise(fun, lo, hi, n):
    """Maximiser of a scalar ``fun`` on [lo, hi]: best of ``n`` grid points, refined by
    bounded Brent between its neighbours (an end of the range is returned as is)."""
    x = np.linspace(lo, hi, n)
    v = np.array([fun(t) for t in x])
    i = int(np.argmax(v))
    if i in (0, n - 1):
        return float(x[i])
    r = minimize_scalar(lambda t: -fun(t), bounds=(x[i - 1], x[i + 1]), method="bounded",
                        options={"xatol": 1e-10})
    return float(r.x) if -r.fun >= v[i] else float(x[i])


# --- the paper's GA (Table 1 rates) ------------------------------------------------------
def paper_ga(pop: int, crossover_rate: float, mutation_rate: float):
    """pymoo GA with Table 1's rates: SBX applied to a mating with probability
    ``crossover_rate`` (its one variable always crossed), polynomial mutation of an
    individual with probability ``mutation_rate`` (its one variable always mutated), no
    duplicate elimination (GAOT keeps copies; eliminating them would discard every
    unchanged offspring and so raise the effective rates).

    Parameters
    ----------
    pop : int
        Population size.
    crossover_rate : float
        Table 1's crossover rate.
    mutation_rate : float
        Table 1's mutation rate.

    Returns
    -------
    Algorithm
        The pymoo GA.
    """
    from pymoo.algorithms.soo.nonconvex.ga import GA
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PM

    return GA(pop_size=pop, crossover=SBX(prob=crossover_rate, prob_var=1.0),
              mutation=PM(prob=mutation_rate, prob_var=1.0), eliminate_duplicates=False)


def _run_paper_ga(problem, w, pop, gen, rates):
    """``(optimum, evaluations, best initial design, distinct designs in the final
    population)`` of the GA of Table 1's rates on ``Z`` with weight ``w`` of W, through
    the runner (an algorithm object; the same run as ``pymoo.optimize.minimize`` with
    the same seed)."""
    single = WeightedSum(problem, w)
    var = problem.var_names[0]

    def go(n_gen):
        return optimize(single, algorithm=paper_ga(pop, *rates), gen=n_gen, seed=SEED, n_jobs=1,
                        progress=False, plot=False)

    res, first = go(gen), go(1)
    n_distinct = int(res.population[var].nunique())
    return (float(res.front[var].iloc[0]), int(res.info["evaluations"]),
            float(first.front[var].iloc[0]), n_distinct)


# --- optimisation (one job per mechanism, run in parallel in the full run) ---------------
def _optimise_mechanism(args):
    """Weighting sweep and NSGA-II front of one mechanism into ``folder``, and the GA of
    Table 1's rates for the weights ``ws`` of the paper's Table."""
    key, folder, pop, gen, ws, rates = args
    problem = get(PROBLEMS[key])
    # the sweep writes its NSGA-II front run's files too (front.csv, front.png)
    table = sweep(problem, parse_weights(WEIGHTS), pop, gen, SEED, n_jobs=1, out=folder,
                  progress=False, overwrite=True)
    return table, {w: _run_paper_ga(problem, w, pop, gen, rates) for w in ws}


# --- curves over the design variable ------------------------------------------------------
def _curve(problem, n):
    x = np.linspace(problem.xl[0], problem.xu[0], n)
    cols = problem.describe(x[:, None])
    var = problem.var_names[0]
    return pd.DataFrame({"variable": var, "value": x, "W": cols["W"], "W_n": cols["W_n"],
                         "T": cols["T"]})


def _z(curve, w1, w2, x0):
    """``Z = W1 T + W2 W_n`` at ``x0`` on the (linearly interpolated) curve."""
    x = curve["value"].to_numpy()
    return w1 * np.interp(x0, x, curve["T"].to_numpy()) + w2 * np.interp(x0, x, curve["W_n"].to_numpy())


def _problem_optimum(problem, w1, w2, n):
    """Exact optimum of ``Z = W1 T + W2 W_n`` of a one-variable Stan problem."""
    def z(t):
        c = problem.describe(np.array([[t]]))
        return w1 * float(c["T"][0]) + w2 * float(c["W_n"][0])
    return _maximise(z, float(problem.xl[0]), float(problem.xu[0]), n)


def _reachable_optima(x, T, W):
    """Grid maximisers of ``T + lambda W`` over every ``lambda`` of ``_LAMBDAS`` and
    ``lambda -> inf``: the optima of all weightings and all positive scales of W."""
    Z = T[None, :] + _LAMBDAS[:, None] * (W / np.max(np.abs(W)))[None, :]
    return np.unique(np.concatenate([x[np.argmax(Z, axis=1)], [x[np.argmax(W)]]]))


def _interval_text(opt, hi):
    inner = opt[opt < hi - _v.ROUNDING]
    parts = []
    if inner.size:
        parts.append(f"[{inner.min():.3f}, {inner.max():.3f}]" if inner.size > 1 else f"{inner[0]:.3f}")
    if np.any(opt >= hi - _v.ROUNDING):
        parts.append(f"{{{hi:g}}}")
    return " U ".join(parts)


# --- Bipod area: the b = 62 mm reading and the systematic search -------------------------
def area_search(target: float, half: float, box=None, near: float = AREA_NEAR):
    """Exact y > 0 areas [mm^2] of every integer ``(b, q_min, q_max)`` of ``box``
    (equal strokes, as printed) and the designs within ``near`` of ``target``.

    Returns ``(table, info)``: ``table`` has columns b, q_min, q_max, area, abs_diff,
    rounds_to_printed (``|area - target| <= half``), sorted by ``abs_diff``; ``info``
    the number of designs searched and the expected number of chance hits (designs
    within +-50 mm^2 of the target times the hit window ``2 half`` over 100 mm^2).

    Parameters
    ----------
    target : float
        The printed area [mm^2].
    half : float
        Half-width of the search box around the printed inputs [mm].
    box : tuple, optional
        ``(b, q_min, q_max)`` ranges [mm].
    near : float
        Distance to ``target`` that counts [mm^2].

    Returns
    -------
    table : DataFrame
        The designs near the target.
    info : dict
        Counts and the best design.
    """
    box = box or AREA_SEARCH
    axes = [np.arange(lo, hi + 1, dtype=float) for lo, hi in (box["b"], box["q_min"], box["q_max"])]
    B, A, C = (g.ravel() for g in np.meshgrid(*axes, indexing="ij"))
    area = bipod_workspace_area(B, A, C, A, C)
    diff = np.abs(area - target)
    keep = diff <= near
    table = pd.DataFrame({"b": B[keep], "q_min": A[keep], "q_max": C[keep], "area": area[keep],
                          "abs_diff": diff[keep], "rounds_to_printed": diff[keep] <= half})
    table = table.sort_values("abs_diff", kind="mergesort").reset_index(drop=True)
    info = {"searched": int(area.size), "within_50": int((diff <= 50.0).sum()),
            "expected_chance_hits": float((diff <= 50.0).sum() * 2 * half / 100.0)}
    return table, info


def _area_rows(bip, inputs, steps, out):
    rec = _rec("bipod-sec5.1", "workspace_area")
    half = printed_half_unit(rec.digits)
    table, info = area_search(rec.value, half)
    _io.write_csv(table, out / "area_search.csv")
    hits = table[table["rounds_to_printed"]]
    b, a, c = inputs["b"], inputs["q1_min"], inputs["q1_max"]
    ratio, upper = inputs["q_max_over_q_min"], inputs["q1_min_over_b"]
    # literal row: rasters and other readings of the printed inputs
    rasters = []
    for h in steps:
        grid = grid_over(bip.bounding_box(), h)
        X, Y = grid.points()
        rasters.append(f"{h:g} mm: {grid.area(bip.reachable(X, Y)):.2f}")
    alt = [
        (f"q_max = {ratio:g}*{a:g} = {ratio * a:g} (eq. 13)", Bipod(b, a, ratio * a)),
        (f"b = {a:g}/{upper:g} = {a / upper:.2f} (q1min/b = {upper:g} as printed)",
         Bipod(a / upper, a, c)),
        ("both", Bipod(a / upper, a, ratio * a)),
        (f"q_min = {upper:g}*{b:g} = {upper * b:g}, q_max = {ratio:g} q_min = {ratio * upper * b:g} "
         "(eq. 12-13 at the bound)", Bipod(b, upper * b, ratio * upper * b)),
        ("both branches (y > 0 and y < 0)", Bipod(b, a, c, branch="full")),
    ]
    alt_txt = "; ".join(f"{t}: {mm.workspace_area():.2f}" for t, mm in alt)
    m62 = Bipod(AREA_READING_B, a, c)
    w62 = m62.workspace_area()
    literal = compare(
        rec, bip.workspace_area(),
        note=(f"exact area of the y > 0 half of the intersection of the annuli {a:g} <= |P - A_i| <= "
              f"{c:g} around A1 = (0, 0), A2 = ({b:g}, 0) (closed form, mechopt.mechanisms.bipod). "
              f"Not a raster artefact: cell-centre rasters (Stan eq. 1-3, cells of side h) give "
              f"{', '.join(rasters)} mm^2, converging to the exact value. Other readings of the "
              f"paper's inconsistent inputs ({a:g}/{b:g} = {a / b:.3f} vs printed q1min/b = {upper:g}; "
              f"q_max = {c:g} vs {ratio:g}*{a:g}): {alt_txt} mm^2, none {rec.printed}. The base width "
              f"b = {AREA_READING_B:g} mm reproduces it (row {AREA_READING}); this literal "
              f"row keeps the printed b = {b:g} mm"))
    hit_txt = ", ".join(f"(b, q_min, q_max) = ({r.b:g}, {r.q_min:g}, {r.q_max:g}) mm: {r.area:.4f}"
                        for r in hits.itertuples()) or "none"
    near_txt = ", ".join(f"({r.b:g}, {r.q_min:g}, {r.q_max:g}): {r.area:.4f}"
                         for r in table[~table["rounds_to_printed"]].head(3).itertuples())
    b_root = brentq(lambda bb: bipod_workspace_area(bb, a, c, a, c) - rec.value, b, b + 5.0,
                    xtol=1e-10)
    slope = (bipod_workspace_area(AREA_READING_B - 1, a, c, a, c)
             - bipod_workspace_area(AREA_READING_B + 1, a, c, a, c)) / 2.0
    box = AREA_SEARCH
    w_only = _rec("table2:W1=0,W2=1", "q1_over_b")
    reading = compare(
        rec, w62, accuracy="printed", quantity=AREA_READING, kind="reading",
        note=(f"reading: the printed struts {a:g}-{c:g} mm on a base b = {AREA_READING_B:g} mm instead of "
              f"the printed {b:g} mm: exact y > 0 area {w62:.6f} mm^2, which reproduces the printed "
              f"{rec.printed} to its digits (|diff| {abs(w62 - rec.value):.4f} <= {half:g}). Systematic search "
              f"(area_search.csv) over every integer b in [{box['b'][0]}, {box['b'][1]}], q_min in "
              f"[{box['q_min'][0]}, {box['q_min'][1]}], q_max in [{box['q_max'][0]}, {box['q_max'][1]}] mm "
              f"(equal strokes, {info['searched']} designs): {len(hits)} hit(s) to the printed digits, "
              f"{hit_txt}; nearest misses {near_txt}. At the printed struts the area equals {rec.printed} "
              f"exactly for b = {b_root:.5f} mm. Plausible, not a coincidence of the search: "
              f"{info['within_50']} designs of the box lie within +-50 mm^2, so about "
              f"{info['expected_chance_hits']:.2f} chance hits are expected in the {2 * half:g} mm^2 window over "
              f"the whole box, and the hit keeps both printed strut lengths and moves only b by "
              f"{AREA_READING_B - b:g} mm "
              f"(the area changes by {slope:.1f} mm^2 per mm of b there, so one integer b lands in the "
              f"window by chance with probability ~{2 * half / slope:.0e}); the paper's area is then an "
              f"exact intersection area ('the area can be also computed', sec. 4.1) of a b = "
              f"{AREA_READING_B:g} mm design, and {a:g}/{AREA_READING_B:g} = {a / AREA_READING_B:.3f} "
              f"rounds to Table 2's W-only {w_only.printed}. The "
              "closed-form area has no quadrature error: only the printed digits are the tolerance"))
    return [literal, reading], {"b_root": b_root, "hits": hits, "w62": w62}


# --- Bipod: readings of T and W --------------------------------------------------------------
def retracted_pose_tqi(u):
    """TQI of the Bipod (b = 1) at the retracted pose ``q1 = q2 = u`` (vectorised).

    Parameters
    ----------
    u : array_like
        ``q / b``.

    Returns
    -------
    ndarray
        The TQI (dimensionless).
    """
    m = Bipod(1.0, *_PROBE_STROKES)
    u = np.asarray(u, dtype=float)
    x, y, _ = m.fk(u, u)
    return m.tqi(x, y)


def bipod_t_readings(u, n_gauss: int = 24, n_edge: int = 201) -> dict:
    """Readings of the Bipod's T over the design variable ``u = q1min/b`` (b = 1,
    ``q_max = 1.6 q_min``): area mean (ours, exact), joint-space mean (Gauss-Legendre
    over the stroke box), minimum over the workspace (on the stroke box's boundary:
    ``cos gamma`` has no stationary point inside), TQI at the retracted and at the
    extended pose.

    Parameters
    ----------
    u : array_like
        ``q1_min / b``.
    n_gauss : int
        Gauss-Legendre nodes per side of the stroke box.
    n_edge : int
        Samples per edge of the stroke box.

    Returns
    -------
    dict
        ``{reading: ndarray}``.
    """
    u = np.asarray(u, dtype=float)
    one = np.ones_like(u)
    k = Q_MAX_OVER_Q_MIN
    m = Bipod(1.0, *_PROBE_STROKES)

    def tqi_q(q1, q2):
        x, y, ok = m.fk(q1, q2)
        if not np.all(ok):
            raise RuntimeError("a strut pair of the design range does not assemble")
        return m.tqi(x, y)

    t, w = gauss_legendre(n_gauss)
    mid, half = 0.5 * (1 + k) * u, 0.5 * (k - 1) * u
    q = mid[:, None] + half[:, None] * t[None, :]
    Q1, Q2 = np.broadcast_arrays(q[:, :, None], q[:, None, :])
    joint = np.einsum("nij,i,j->n", tqi_q(Q1, Q2), w, w) / 4.0
    s = np.linspace(0.0, 1.0, n_edge)
    e = u[:, None] * (1.0 + (k - 1.0) * s[None, :])
    lo, hi = np.broadcast_to(u[:, None], e.shape), np.broadcast_to(k * u[:, None], e.shape)
    edges = [tqi_q(lo, e), tqi_q(hi, e), tqi_q(e, lo), tqi_q(e, hi)]
    tmin = np.min(np.concatenate(edges, axis=1), axis=1)
    return {
        "area mean (ours)": (bipod_tqi_integral(one, u, k * u, u, k * u)
                             / bipod_workspace_area(one, u, k * u, u, k * u)),
        "joint-space mean": joint,
        "minimum over the workspace": tmin,
        "retracted pose q1 = q2 = q_min": tqi_q(u, u),
        "extended pose q1 = q2 = q_max": tqi_q(k * u, k * u),
    }


def _bipod_w_readings(u, paper_area):
    """Readings of W: ``(values, affine in the exact area)``."""
    k = Q_MAX_OVER_Q_MIN
    one = np.ones_like(u)
    inp = _inputs()
    b, qa = inp["b"], inp["q1_min"]  # sec. 5.1's base and shortest strut [mm]
    qc = inp["q_max_over_q_min"] * qa  # its longest strut by eq. (13)
    W = bipod_workspace_area(one, u, k * u, u, k * u)
    fixed = bipod_workspace_area(qa / u, qa * one, qc * one, qa * one, qc * one)
    return {
        f"W / W({inp['q1_min_over_b_upper']:g}) (ours)": (W / W[-1], True),
        "W [b^2], unnormalised": (W, True),
        f"W [mm^2] at b = {b:g} mm, unnormalised": (W * (b * b), True),
        f"W [mm^2] at b = {b:g} mm / {paper_area:g} mm^2": (W * (b * b) / paper_area, True),
        "(W - W_min) / (W_max - W_min)": ((W - W.min()) / np.ptp(W), True),
        "W / half annulus pi (q_max^2 - q_min^2) / 2": (W / (np.pi * (k * k - 1.0) * u * u / 2.0), False),
        f"W [mm^2] at q = {qa:g}-{qc:g} mm, b = {qa:g} mm/u, / its max": (fixed / fixed.max(), False),
    }


def _bipod_readings(s, tol, out):
    rec_area = _rec("bipod-sec5.1", "workspace_area")
    lo, hi = (_rec("bipod-eq12-13", q).value for q in ("q1_min_over_b_lower", "q1_min_over_b_upper"))
    u = np.linspace(lo, hi, s["n_readings"])
    Ts = bipod_t_readings(u)
    Ws = _bipod_w_readings(u, rec_area.value)
    rows = []
    for _, label, w1, w2 in _labels("table2"):
        paper = _rec(f"table2:{label}", "q1_over_b").value
        for tn, T in Ts.items():
            for wn, (W, affine) in Ws.items():
                x = float(u[np.argmax(w1 * T + w2 * W)])
                rows.append({"weights": label, "paper": paper, "T_reading": tn, "W_reading": wn,
                             "W_affine_in_area": affine, "optimum": x, "abs_diff": abs(x - paper),
                             "match": abs(x - paper) <= tol})
    pairs = pd.DataFrame(rows)
    _io.write_csv(pairs, out / "bipod_readings.csv")
    W_exact = Ws["W [b^2], unnormalised"][0]
    fam = []
    targets = [(label, _rec(f"table2:{label}", "q1_over_b").value)
               for _, label, w1, w2 in _labels("table2") if w1 > 0 and w2 > 0]
    for tn, T in Ts.items():
        opt = _reachable_optima(u, T, W_exact)
        row = {"T_reading": tn, "peak_of_T": float(u[np.argmax(T)]),
               "reachable_optima": _interval_text(opt, hi)}
        for label, v in targets:
            row[f"reaches_{v:g}"] = bool(np.min(np.abs(opt - v)) <= tol)
            row[f"nearest_to_{v:g}"] = float(opt[np.argmin(np.abs(opt - v))])
        fam.append(row)
    family = pd.DataFrame(fam)
    _io.write_csv(family, out / "bipod_reachable_optima.csv")
    return pairs, family, Ts, u


def _bipod_weighted_analysis(pairs, family, paper):
    """One sentence for a weighted Table 2 row: what the readings analysis found."""
    fam_txt = "; ".join(f"{r.T_reading}: {r.reachable_optima}" for r in family.itertuples())
    sel = pairs[np.isclose(pairs["paper"], paper)]
    hits = sel[sel["match"]]
    nonlin = sel[~sel["W_affine_in_area"]]
    hit_txt = ("; pairs that give it: " + ", ".join(f"T {r.T_reading} with {r.W_reading} ({r.optimum:.3f})"
                                                     for r in hits.itertuples())) if len(hits) else ""
    near = sel.iloc[int(np.argmin(sel["abs_diff"].to_numpy()))]
    nl = nonlin.groupby("W_reading", sort=False)["optimum"]
    nl_txt = "; ".join(f"{name}: {', '.join(f'{v:.3f}' for v in sorted(set(np.round(g, 3))))}"
                       for name, g in nl)
    upper = _inputs()["q1_min_over_b_upper"]
    area = _rec("bipod-sec5.1", "workspace_area").printed
    return (f"readings analysis (bipod_readings.csv, bipod_reachable_optima.csv): for every reading of "
            f"T and every W that is an increasing affine function of the exact area (normalised by "
            f"W({upper:g}), by its range or by {area} mm^2, or unnormalised in b^2 or mm^2), all "
            f"weightings together reach only these optima: {fam_txt}; so no such pair gives "
            f"{paper:g}. Of the {len(sel)} (T, W) pairs with these weights, {len(hits)} match"
            f"{hit_txt}; the nearest is {near.optimum:.3f} (T {near.T_reading}, {near.W_reading}); "
            f"the two non-affine W readings give, over the T readings: {nl_txt}")


# --- Biglide: the L1 reading and the scan -----------------------------------------------------
def _biglide_scan(s, span, paper):
    """Table 3's rows over a grid of L1 and strokes (``biglide_l1_scan.csv``); ``paper``
    maps ``(W1, W2)`` to the printed optimum's Record, each row's tolerance is that of
    its table row (:func:`mechopt.core.published.tolerance`, ``span`` the design range)."""
    tols = {k: tolerance(r, span=span) for k, r in paper.items()}
    val = {k: r.value for k, r in paper.items()}
    mixed = [k for k in paper if k[0] > 0 and k[1] > 0]
    (a1, a2), (b1, b2) = sorted(mixed, reverse=True)  # (0.7, 0.3), (0.3, 0.7)
    factor = (b2 / b1) / (a2 / a1)  # Z = W1 (T + (W2/W1) W_n/c): the lambdas of one c
    lam = _LAMBDAS[1:]
    rows = []
    for l1 in s["scan_l1"]:
        for stroke in s["scan_strokes"]:
            c = _curve(StanBiglide(l1=l1, q_min=0.0, q_max=stroke), s["scan_n"])
            x, T, Wn = (c[k].to_numpy() for k in ("value", "T", "W_n"))
            dT = np.diff(T)
            trend = "falls" if np.all(dT < 0) else ("rises" if np.all(dT > 0) else "mixed")
            row = {"L1": float(l1), "stroke": float(stroke), "T_trend": trend}
            ok = {}
            for (w1, w2), v in val.items():
                o = float(x[np.argmax(w1 * T + w2 * Wn)])
                row[f"opt[W1={w1:g},W2={w2:g}]"] = o
                ok[(w1, w2)] = abs(o - v) <= tols[(w1, w2)]
            row["rows_matching_W_n"] = int(sum(ok.values()))
            # any normalisation c of W (one c for both weightings)
            o1 = x[np.argmax(T[None, :] + (a2 / a1) * lam[:, None] * Wn[None, :], axis=1)]
            o2 = x[np.argmax(T[None, :] + factor * (a2 / a1) * lam[:, None] * Wn[None, :], axis=1)]
            both = ((np.abs(o1 - val[(a1, a2)]) <= tols[(a1, a2)])
                    & (np.abs(o2 - val[(b1, b2)]) <= tols[(b1, b2)]))
            row["some_c_gives_both_weighted"] = bool(both.any())
            row["some_c_gives_all_four"] = bool(both.any() and ok[(1.0, 0.0)] and ok[(0.0, 1.0)])
            rows.append(row)
    return pd.DataFrame(rows)


# --- notes ---------------------------------------------------------------------------------
def _convex_from(c):
    """Smallest grid value from which both W and T are convex (second differences > 0)."""
    ok = (np.diff(c["W"].to_numpy(), 2) > 0) & (np.diff(c["T"].to_numpy(), 2) > 0)
    bad = np.flatnonzero(~ok)
    x = c["value"].to_numpy()
    return float(x[1:-1][bad.max() + 1]) if bad.size else float(x[0])


def _tolerance_remark(rec, reproduced, span):
    """Say so when the printed-digit tolerance makes the status meaningless or fragile
    (``span``: the design range)."""
    tol = tolerance(rec, span=span)
    err = abs(reproduced - rec.value)
    if tol >= span:
        return (f"the paper prints {rec.value:g} with {rec.digits} decimals: its half-unit "
                f"tolerance {tol:g} is wider than the whole design range ({span:g}), so the "
                "status says nothing here")
    if abs(err - tol) <= 0.01 * tol:
        return (f"|ours - paper| = {err:.6g} sits on the edge of the printed-digit tolerance "
                f"{tol:g} (the paper prints {rec.value:g} with {rec.digits} decimal(s)): the "
                "status flips with the GA's last digits")
    return ""


def _ga_text(run):
    return (f"GA (the runner's 'ga', pymoo's default operators, see ga_crossover_rate; pop "
            f"{run['pop']}, {run['gen']} generations, seed {SEED}; rows '...;GA Table 1 rates]' use "
            "the paper's rates)")


def _bipod_note(w1, w2, ours, paper, curve, run, w_ref_var, analysis, t_peaks):
    var = curve["variable"].iloc[0]
    x, Wn, T = (curve[k].to_numpy() for k in ("value", "W_n", "T"))
    lo, hi = x[0], x[-1]
    i_t = int(np.argmax(T))
    parts = [f"{_ga_text(run)} optimum of Z = {w1:g} T + {w2:g} W_n, W_n = W/W({var} = {w_ref_var:g}) "
             f"(the paper does not state its normalisation of W); on our curves Z(ours) = "
             f"{_z(curve, w1, w2, ours):.4f}, Z(paper's {paper:g}) = {_z(curve, w1, w2, paper):.4f}"]
    label = f"W1={w1:g},W2={w2:g}"
    if w1 == 0:
        inp = _inputs()
        a, b = inp["q1_min"], inp["b"]
        parts.append(
            f"W grows monotonically with q1/b (W_n {Wn[0]:.3f} -> 1 over [{lo:g}, {hi:g}], "
            "curves.csv), so the W-only optimum is the upper bound of eq. (12) (claim row "
            f"{MAX_CLAIM}); the paper's own sec. 5.1 text gives {_comma(inp['q1_min_over_b'])} for the "
            f"maximum workspace, Table 2 prints {paper:g} (its design q1min = {a:g}, b = {b:g} has "
            f"q1min/b = {a / b:.3f}; row q1_over_b[{label};{DESIGN_TAG}] the b = {AREA_READING_B:g} mm "
            "reading)")
    elif w2 == 0:
        parts.append(
            f"our T (exact area mean of the TQI of eq. 9 over the y > 0 workspace) peaks at "
            f"q1/b = {x[i_t]:.3f} (T = {T[i_t]:.3f}); other readings of T peak at {t_peaks}; the "
            f"TQI at the retracted pose peaks at 1/sqrt(2) = 0.7071 and reproduces {paper:g} (row "
            f"q1_over_b[{label};{RETRACTED_TAG}]); this literal row keeps the workspace mean")
    else:
        parts.append(f"W and T are both convex in q1/b on [{_convex_from(curve):.3f}, {hi:g}] "
                     "(curves.csv grid)")
        parts.append(analysis)
    return "; ".join(parts)


def _biglide_note(w1, w2, curve, run, w_ref_var, l1_trend):
    var = curve["variable"].iloc[0]
    x, T = curve["value"].to_numpy(), curve["T"].to_numpy()
    lo, hi = x[0], x[-1]
    mono = bool(np.all(np.diff(curve["W"].to_numpy()) > 0) and np.all(np.diff(T) > 0))
    parts = [f"{_ga_text(run)} optimum of Z = {w1:g} T + {w2:g} W_n, W_n = W/W({var} = {w_ref_var:g})",
             "the paper gives neither L1 nor the strokes: literal setup L1 = 1, q in [0, 1] "
             "(problems/stan2008.py)",
             f"both W and T increase monotonically with L2 over [{lo:.4g}, {hi:g}] (curves.csv)"
             if mono else f"W and T over [{lo:.4g}, {hi:g}] in curves.csv"]
    if w1 > 0 and mono:
        t_only = _rec("table3:W1=1,W2=0", "L2").value
        parts.append(f"so every weighting gives the bound {w_ref_var:g}; the paper's T-only optimum "
                     f"L2 = {t_only:g} needs T to fall with L2, which at the centre pose x = 0 needs "
                     "L2 > sqrt(2) L1: L1 = 1 contradicts that row by construction")
    if w2 == 0:
        parts.append(f"at L2 = L1 = 1 our workspace collapses to the line x = 0 (W = 0, T = {T[0]:.4f} "
                     f"at L2 = {lo:.7g})")
    parts.append(f"rows 'L2[...;L1={BIGLIDE_L1:g}]' show Table 3 under L1 = {BIGLIDE_L1:g} "
                 f"(T {l1_trend} with L2 there; module docstring)")
    return "; ".join(parts)


# --- rows ------------------------------------------------------------------------------------
def _default_ga_text(pop):
    """The operators of the runner's named GA (the literal rows' sweep), read off the object."""
    algo = make_algorithm("ga", pop, 1)
    cx, mut = algo.mating.crossover, algo.mating.mutation
    one = get(PROBLEMS["bipod"])
    return (f"SBX applied to a mating with probability {float(cx.prob.value):g}, each variable with "
            f"probability {float(cx.prob_var.value):g}; polynomial mutation of an individual with "
            f"probability {float(mut.prob.value):g}, each variable with probability "
            f"{float(mut.get_prob_var(one)):g}")


def _ga_rows(pop, gen, quick, rates, paper_runs):
    run_txt = ("quick run (quick=True): small sizes for a smoke test; the full run uses "
               "Table 1's value") if quick else "the full run uses Table 1's value"
    runs_txt = "; ".join(f"{k} W2={w:g}: {r[0]:.4f} ({r[1]} evaluations)"
                         for k, res in paper_runs.items() for w, r in res.items())
    p_cx, p_mut = rates
    ga_txt = (f"pymoo 0.6 GA with Table 1's rates (experiments.stan2008.paper_ga): binary tournament, "
              f"elitist fitness survival, SBX crossover (eta 15) applied to a mating with probability "
              f"{p_cx:g}, its one variable always crossed; polynomial mutation (eta 20) of an individual "
              f"with probability {p_mut:g}, its one variable always mutated (n_var = 1: the rate per "
              f"individual is the rate per variable); no duplicate elimination (GAOT keeps copies). "
              f"Run with mechopt.run.runner.optimize(WeightedSum(problem, W2), algorithm=paper_ga(...), "
              f"gen={gen}, seed={SEED}) (an algorithm object: the same run as "
              f"pymoo.optimize.minimize with that seed). The GAOT operators are not named in the "
              f"paper; the rates are applied as these probabilities. Results (rows "
              f"'...;GA Table 1 rates]'): {runs_txt}. The literal Table 2/3 rows use the runner's "
              f"'ga' with pymoo's default operators ({_default_ga_text(pop)})")
    ours = {
        "population": (pop, run_txt if quick else "population of every GA and NSGA-II run"),
        "generations": (gen, run_txt if quick else "generations of every GA and NSGA-II run"),
        "crossover_rate": (p_cx, ga_txt),
        "mutation_rate": (p_mut, "the rate run, see ga_crossover_rate: polynomial mutation of an "
                                 f"individual with probability {p_mut:g} (= per variable, n_var = 1)"),
    }
    return [compare(_rec("table1", q), float(v), kind="setting", quantity=f"ga_{q}", note=note)
            for q, (v, note) in ours.items()]


def _claim_rows(curves, problems):
    rows = []
    c = curves["bipod"]
    x, W = c["value"].to_numpy(), c["W"].to_numpy()
    rec = _rec("bipod-sec5.1", "q1_min_over_b")
    up = problems["bipod"].xu[0]
    inc = bool(np.all(np.diff(W) > 0))
    at_top = bool(np.argmax(W) == len(W) - 1 and np.isclose(x[-1], rec.value))
    uu = np.linspace(x[0], x[-1], len(x))
    inp = _inputs()
    b, qa, ratio = inp["b"], inp["q1_min"], inp["q_max_over_q_min"]
    # sec. 5.1's shortest strut with its longest by eq. (13) and as printed
    fixed = {qm: bipod_workspace_area(qa / uu, qa, qm, qa, qm) for qm in (ratio * qa, inp["q1_max"])}
    def trend(v):
        return "increasing" if np.all(np.diff(v) > 0) else f"not monotone, smallest at {uu[np.argmin(v)]:.3f}"

    fixed_txt = "; ".join(f"with fixed struts {qa:g}-{qm:g} mm and b = {qa:g} mm/(q1min/b) the area is largest "
                          f"at q1min/b = {uu[np.argmax(v)]:.3f} ({v.max():.2f} mm^2; {trend(v)})"
                          for qm, v in fixed.items())
    rows.append(claim_row(
        MAX_CLAIM, rec.citation, inc and at_top,
        f"the W of eq. (11)-(13) (b = 1, q_max = {ratio:g} q_min, exact y > 0 area) rises strictly over "
        f"all {len(x)} points of [{x[0]:g}, {x[-1]:g}] (curves.csv; W from {W[0]:.4f} to {W[-1]:.4f} b^2, "
        f"smallest step {np.min(np.diff(W)):.2e}), so the maximum workspace of the design range is at "
        f"its upper bound q1min/b = {up:g}, as printed (at fixed b every strut length grows with "
        f"q1min/b, and so does the area); {fixed_txt}. The design the same sentence uses "
        f"(q1min = {qa:g}, b = {b:g} mm) has q1min/b = {qa / b:.3f}, not {rec.value:g}"))
    q_lo, q_hi = _rec("bipod-sec5.1", "q1_min").value, _rec("bipod-sec5.1", "q1_max").value
    sec51 = Bipod(b, q_lo, q_hi)
    wide = Bipod(b, 1.0, q_hi)  # the figures print no strokes: any strokes reaching the pose
    poses = {f: (_rec(f, "x_p").value, _rec(f, "y_p").value) for f in ("fig9", "fig10")}
    for fig, (xp, yp) in poses.items():
        other = poses["fig10" if fig == "fig9" else "fig9"]
        q1, q2 = (float(v) for v in wide.strut_lengths(xp, yp))
        cls = str(np.ravel(wide.classify_singularity(xp, yp))[0])
        t2 = float(np.ravel(wide.type2_function(xp, yp))[0])
        tq = float(np.ravel(wide.tqi(xp, yp))[0])
        cls51 = str(np.ravel(sec51.classify_singularity(xp, yp))[0])
        mirror = np.isclose(xp + other[0], b) and np.isclose(yp, other[1])
        mirror_txt = (f"Its mirror image about x = b/2 = {b / 2:g} mm is the other figure's pose (q1, q2 "
                      f"swapped), which supports b = {b:g} mm in Figs. 9-10. " if mirror else "")
        rows.append(claim_row(
            f"claim:{fig}_pose_regular", _rec(fig, "x_p").citation, cls == "none",
            f"the text shows P = ({xp:g}, {yp:g}) mm as a Bipod configuration of the inverse-kinematics "
            f"GUI (Fig. 8); it says nothing about singularity (the Biglide's singular configurations "
            f"are Figs. 26-28, without coordinates). Check on the sec. 5.1 base b = {b:g} mm: eq. (6) "
            f"gives q1 = {q1:.2f}, q2 = {q2:.2f} mm; with strokes reaching them "
            f"classify_singularity = '{cls}', type2_function = sin(angle between struts) = {t2:.4f}, "
            f"TQI = {tq:.4f}: a regular pose (the Bipod's only singular locus is y = 0, the type-I "
            f"locus needs a zero strut length), for every b. "
            f"{mirror_txt}"
            f"Under the sec. 5.1 strokes [{q_lo:g}, {q_hi:g}] mm the pose is '{cls51}' (both struts "
            f"shorter than q_min = {q_lo:g} mm): Figs. 9-10 use strokes the paper does not print"))
    return rows


# --- figures ---------------------------------------------------------------------------------
def _tqi_map(m, n, title, equal, unit):
    box = m.bounding_box()
    grid = grid_over(box, min(box[1] - box[0], box[3] - box[2]) / n)
    X, Y = grid.points()
    ok = m.reachable(X, Y)
    T = np.where(ok, m.tqi(X, Y), np.nan)
    fig = Figure(figsize=(6.4, 4.6))
    ax = fig.add_subplot()
    levels = MaxNLocator(20).tick_values(float(np.nanmin(T)), float(np.nanmax(T)))
    cs = ax.contourf(X, Y, np.ma.masked_invalid(T), levels=levels, cmap="viridis")
    labelled_colorbar(fig, cs, ax, "TQI (Stan eq. 9) [-]", shrink=0.8 if equal else 1.0)
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    ax.xaxis.set_major_locator(MaxNLocator(6))
    if equal:
        ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    return fig


def _tradeoff_figure(key, curve, paper_opt, ours_opt):
    var = curve["variable"].iloc[0]
    x, Wn, T = (curve[k].to_numpy() for k in ("value", "W_n", "T"))
    fig = Figure(figsize=(10, 4))
    a1, a2 = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    a1.plot(x, Wn, label="W_n = W / W(upper bound)")
    a1.plot(x, T, label="T (area mean of TQI)")
    for i, ((w1, w2), xp) in enumerate(paper_opt.items()):
        a1.axvline(xp, color=f"C{i + 2}", ls="--", lw=1, label=f"paper W1={w1:g}, W2={w2:g}: {xp:g}")
        a2.plot(np.interp(xp, x, Wn), np.interp(xp, x, T), "o", color=f"C{i + 2}", mfc="none",
                ms=9, label=f"paper W1={w1:g}, W2={w2:g}")
        xo = ours_opt[(w1, w2)]
        a1.plot(xo, np.interp(xo, x, T), "x", color=f"C{i + 2}", ms=8)
        a2.plot(np.interp(xo, x, Wn), np.interp(xo, x, T), "x", color=f"C{i + 2}", ms=8)
    a1.set_xlabel(f"{var} [-]")
    a1.set_ylabel("W_n, T [-]")
    a1.legend(fontsize=7)
    a1.set_title(f"Stan 2008 {key}: W_n and T over {var} (x: our GA optima)", fontsize=9)
    a2.plot(Wn, T, color="0.4")
    a2.set_xlabel("W_n [-]")
    a2.set_ylabel("T [-]")
    a2.legend(fontsize=7)
    a2.set_title("trade-off T vs W_n (o paper's optima on our curve, x ours)", fontsize=9)
    fig.tight_layout()
    return fig


# --- the experiment --------------------------------------------------------------------------
def run(out: Path, quick: bool = False) -> pd.DataFrame:
    """Every published number of ``mechopt/data/stan2008.csv`` against ours, the readings
    beside them and the checked claims; files into ``out``.

    Parameters
    ----------
    out : Path
        The paper's results folder.
    quick : bool
        Smaller runs (every row and file is still produced).

    Returns
    -------
    DataFrame
        The table (table.csv's columns).

    Raises
    ------
    RuntimeError
        When the weighting sweep lacks a weight a row needs (a programming error).
    """
    out = _io.prepare_out_dir(out)
    s = SETTINGS[bool(quick)]
    inputs = _inputs()
    rates = (_rec("table1", "crossover_rate").value, _rec("table1", "mutation_rate").value)
    table_w = {key: [w2 for _, _, _, w2 in _labels(tid)] for key, tid, _ in OPTIMA}

    jobs = [(key, _io.prepare_out_dir(out / key), s["pop"], s["gen"], table_w[key], rates)
            for key in PROBLEMS]
    results = dict(zip(PROBLEMS, parallel_map(_optimise_mechanism, jobs, n_jobs=1 if quick else 2)))
    tables = {k: r[0] for k, r in results.items()}
    paper_runs = {k: r[1] for k, r in results.items()}

    problems = {key: get(name) for key, name in PROBLEMS.items()}
    curves = {key: _curve(p, s["n_curve"]) for key, p in problems.items()}
    _io.write_csv(pd.concat([c.assign(mechanism=k) for k, c in curves.items()], ignore_index=True)
                  [["mechanism", "variable", "value", "W", "W_n", "T"]], out / "curves.csv")

    rows = []
    # workspace area of sec. 5.1, literal and the b = 62 mm reading
    b, a, c = inputs["b"], inputs["q1_min"], inputs["q1_max"]
    bip = Bipod(b, a, c, inputs["q2_min"], inputs["q2_max"])
    area_rows, _ = _area_rows(bip, inputs, s["raster_steps"], out)
    rows += area_rows

    # readings of the Bipod's T and W, the Biglide's L1
    span = {k: _span(p) for k, p in problems.items()}
    pairs, family, t_read, u_read = _bipod_readings(s, ACCURACY["ga_optimum"].absolute(span["bipod"]), out)
    t_peaks = ", ".join(f"{u_read[np.argmax(v)]:.3f} ({k})" for k, v in t_read.items()
                        if "ours" not in k)
    t_aggr = ", ".join(f"{u_read[np.argmax(v)]:.3f} ({k})" for k, v in t_read.items()
                       if "mean" in k or "minimum" in k)
    paper3 = {(w1, w2): _rec(d, "L2") for d, _, w1, w2 in _labels("table3")}
    scan = _biglide_scan(s, span["biglide"], paper3)
    _io.write_csv(scan, out / "biglide_l1_scan.csv")
    gl_read = StanBiglide(l1=BIGLIDE_L1, q_min=BIGLIDE_STROKES[0], q_max=BIGLIDE_STROKES[1])
    c_read = _curve(gl_read, s["n_curve"])
    dT = np.diff(c_read["T"].to_numpy())
    l1_trend = "falls" if np.all(dT < 0) else ("rises" if np.all(dT > 0) else "is not monotone")
    # Table 3's weighted rows (0.7/0.3, then 0.3/0.7) and its T-only row
    mixed = sorted((k for k in paper3 if k[0] > 0 and k[1] > 0), reverse=True)
    t_only = next(r for (w1, w2), r in paper3.items() if w2 == 0)

    # Tables 2-3
    for key, table_id, qname in OPTIMA:
        tab, curve, p = tables[key], curves[key], problems[key]
        var = p.var_names[0]
        paper_opt, ours_opt = {}, {}
        for design, label, w1, w2 in _labels(table_id):
            rec = _rec(design, qname)

            def reading(x, tag, note, rec=rec, label=label, key=key, qname=qname):
                """A reading of the row's printed optimum, within the row's tolerance."""
                rows.append(compare(rec, x, span=span[key], kind="reading",
                                    quantity=f"{qname}[{label};{tag}]", note=note))

            best = tab[np.isclose(tab["weight"], w2)]
            if len(best) != 1:
                raise RuntimeError(f"the sweep has no weight {w2} for {key}")
            x_opt = float(best.iloc[0][var])
            paper_opt[(w1, w2)], ours_opt[(w1, w2)] = float(rec.value), x_opt
            if key == "bipod":
                analysis = _bipod_weighted_analysis(pairs, family, rec.value) if w1 and w2 else ""
                note = _bipod_note(w1, w2, x_opt, rec.value, curve, s, float(p.xu[0]), analysis,
                                   t_peaks)
            else:
                note = _biglide_note(w1, w2, curve, s, float(p.xu[0]), l1_trend)
            remark = _tolerance_remark(rec, x_opt, span[key])
            note = f"{note}; {remark}" if remark else note
            rows.append(compare(rec, x_opt, span=span[key], quantity=f"{qname}[{label}]", note=note))
            # the same problem with Table 1's GA rates
            x_ga, n_ga, x_first, n_distinct = paper_runs[key][w2]
            reading(x_ga, "GA Table 1 rates",
                    f"the literal problem of row {qname}[{label}] solved by a GA with Table 1's rates "
                    f"(crossover {rates[0]:g}, mutation {rates[1]:g}; pop {s['pop']}, {s['gen']} "
                    f"generations, seed {SEED}, {n_ga} evaluations; operators in row "
                    f"ga_crossover_rate): {x_ga:.4f}, {x_ga - x_opt:+.4f} from the default-operator GA's "
                    f"{x_opt:.4f}. The best initial design was {x_first:.4f}; with so few crossovers "
                    f"and mutations the population fills with copies of its best designs "
                    f"({n_distinct} distinct in the final population) and moves only by the rare "
                    "variations")
            # readings of the optimum
            if key == "bipod" and w2 == 0:
                lo, hi = float(p.xl[0]), float(p.xu[0])
                u_ret = _maximise(lambda t: float(retracted_pose_tqi(t)), lo, hi, 84)
                reading(u_ret, RETRACTED_TAG,
                        f"reading: T = TQI at the retracted pose q1 = q2 = q_min (struts and base an "
                        f"isosceles triangle, cos gamma = 1 - 1/(2 (q1min/b)^2)), maximised over "
                        f"[{lo:g}, {hi:g}] (grid + bounded Brent): {u_ret:.6f} = 1/sqrt(2), the struts "
                        f"perpendicular (TQI = 1). Reproduces the printed {rec.value:g} to its digits; "
                        f"plausible as the TQI of the home pose of the design (eq. 9 is a pose index and "
                        f"the paper never states how T is aggregated), while every workspace aggregate of "
                        f"the TQI peaks lower ({t_aggr}; bipod_readings.csv). The literal row "
                        f"q1_over_b[{label}] keeps the workspace mean and its status")
            if key == "bipod" and w1 == 0:
                ratio = a / AREA_READING_B
                reading(ratio, DESIGN_TAG,
                        f"reading: Table 2's W-only entry as q1min/b of the design whose area sec. 5.1 "
                        f"prints, under the b = {AREA_READING_B:g} mm reading (row "
                        f"{AREA_READING}): {a:g}/{AREA_READING_B:g} = {ratio:.4f}, {rec.value:g} to the "
                        f"printed decimal. Not discriminating: the printed design's {a:g}/{b:g} = "
                        f"{a / b:.3f} and the bound {inputs['q1_min_over_b_upper']:g} are also within half "
                        f"a unit ({printed_half_unit(rec.digits):g}) of {rec.value:g}")
            if key == "biglide":
                x_r = _problem_optimum(gl_read, w1, w2, s["n_curve"])
                sc = scan[np.isclose(scan["stroke"], BIGLIDE_STROKES[1])]
                t_ok = sc[sc["T_trend"] == "falls"]["L1"]
                l1_falls = t_ok.max() if len(t_ok) else float("nan")
                reading(x_r, f"L1={BIGLIDE_L1:g}",
                        f"reading: Biglide with L1 = {BIGLIDE_L1:g} (guides 2 L1 = 1 apart, L2 in units of "
                        f"the guide distance as the Bipod's q1min/b is in units of b), strokes q in "
                        f"[{BIGLIDE_STROKES[0]:g}, {BIGLIDE_STROKES[1]:g}], mode '--'; exact optimum of "
                        f"Z = {w1:g} T + {w2:g} W_n on the problem's curve (grid + bounded Brent, no GA); "
                        f"T {l1_trend} with L2 here. Chosen because the T-only row needs T to fall with L2 "
                        f"(centre pose: L2 > sqrt(2) L1, i.e. L1 < 0.707; workspace mean, stroke "
                        f"{BIGLIDE_STROKES[1]:g}: T falls for the scan's L1 <= "
                        f"{l1_falls:g}; biglide_l1_scan.csv), not fitted "
                        f"to the weighted rows: no (L1, stroke, normalisation) of the scan gives "
                        f"{paper3[mixed[0]].value:g} and {paper3[mixed[1]].value:g} together with "
                        f"L2 = {t_only.value:g} (column some_c_gives_all_four: "
                        f"{int(scan['some_c_gives_all_four'].sum())} of {len(scan)})")
        _io.save_figure(_tradeoff_figure(key, curve, paper_opt, ours_opt), out / f"tradeoff_{key}.png")
    # Table 1
    rows += _ga_rows(s["pop"], s["gen"], quick, rates, paper_runs)
    # claims of sec. 5.1 and Figs. 9-10
    rows += _claim_rows(curves, problems)

    # Figs. 29-30 redrawn; Fig. 30 at the middle of sec. 5.2's design range of L2
    gl = problems["biglide"]
    _io.save_figure(_tqi_map(bip, s["n_map"], f"Fig. 29 redrawn: TQI of the Bipod\n(b = {b:g} mm, "
                             f"q in [{a:g}, {c:g}] mm, y > 0)", equal=True, unit="mm"),
                    out / "fig29_tqi_bipod.png")
    l2 = 0.5 * (_rec("biglide-sec5.2", "L2_lower").value + _rec("biglide-sec5.2", "L2_upper").value)
    big = Biglide(gl.l1, l2, gl.q_min, gl.q_max)
    _io.save_figure(_tqi_map(big, s["n_map"], f"Fig. 30 redrawn: TQI of the Biglide (L1 = {gl.l1:g}, "
                             f"L2 = {l2:g}, q in [{gl.q_min:g}, {gl.q_max:g}], mode '--'): constant "
                             "along y", equal=False, unit="L"),
                    out / "fig30_tqi_biglide.png")
    return pd.DataFrame(rows, columns=list(TABLE_COLUMNS))


if __name__ == "__main__":  # pragma: no cover
    import sys
    import time

    t0 = time.perf_counter()
    df = run(Path(sys.argv[1] if len(sys.argv) > 1 else "results/stan2008"),
             quick="--quick" in sys.argv)
    with pd.option_context("display.width", 250, "display.max_colwidth", 120):
        print(df.to_string(index=False))
    print(f"{time.perf_counter() - t0:.1f} s")
