"""Wu, Wang, Wang, Shao (2008): the 2-DOF gantry, side by side with the published values.

``run(out, quick)`` reproduces the dimensional synthesis (sec. 4.2 and Table 1),
the global velocity output ratio ``k_av`` (eq. 6-7) under the literal and an
alternative reading, and the dynamic manipulability of sec. 5-6 (``kappa_D``
eq. 43, ``eta_D`` eq. 44, inertia ellipses, Table 3 driving forces), writes the
Pareto fronts of the problems ``wu2008`` and ``wu2008-dynamic``, the weighting
sweep of ``wu2008``, and redraws Figs 2, 4, 5, 6 and 7 from our numbers.

Thin script: every number comes from :mod:`mechopt.mechanisms.gantry`,
:mod:`mechopt.mechanisms.gantry_dynamics`, the problems registry and :mod:`mechopt.run.runner`; the
code below only picks evaluation points, draws and writes (through
:mod:`mechopt.run.io`). The paper prints no number for Figs 4-7, so those rows are
``not-reported`` and carry the checks of the text's qualitative statements.

Every printed number (value, unit, digits, source; the inputs b, h, theta_1S too) comes
from ``mechopt/data/wu2008.csv`` through :func:`mechopt.core.published.lookup`; the
tolerance is half a unit of the last printed digit, for ``k_av`` the class
``global_mean`` of :data:`mechopt.core.published.ACCURACY` (its quadrature is unstated).

Modelling assumptions (stated in the notes of the rows they affect): the links'
mass centres sit at mid-link (Table 2 prints no ``s_i2``); link ``A3B3`` loads the
machine like ``A1B1`` (eq. 36-37); the symmetric variant of sec. 6.3 copies the
left chain to the right (:meth:`mechopt.mechanisms.gantry_dynamics.GantryInertia.symmetric_variant`);
the task rectangle sits at ``y in [300, 700]`` mm (no index depends on it).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import colormaps
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Ellipse, Rectangle
from scipy.optimize import brentq

from mechopt.core import validation as _v
from mechopt.run import io as _io
from mechopt import problems
from mechopt.run import runner
from mechopt.mechanisms.gantry_dynamics import (GantryDynamics, GantryInertia, rectangle_rule,
                              wu2008_driving_forces)
from mechopt.mechanisms.gantry import (Gantry, dimensional_synthesis, k_av_literal_of_design,
                                       wu2008_gantry)
from mechopt.core.published import TABLE_COLUMNS, cite, claim_row, compare, lookup, not_reported

__all__ = ["run", "run_part", "PARTS", "ALTERNATIVE_READING", "QUANTITIES"]

PAPER = "wu2008"

#: the reading of eq. (6)-(7) reported as ``k_av_alternative`` (see its note)
ALTERNATIVE_READING = "max_speed"

#: every quantity of the table, in order
QUANTITIES = (
    "d1[theta_1S=15deg]", "l[theta_1S=15deg]", "stroke[theta_1S=15deg]",
    "d1[table1]", "l[table1]", "stroke[table1]",
    "k_av[table1]", "k_av_alternative[table1]",
    "eta_d[built]", "eta_d_std[built]", "eta_d[symmetric]",
    "kappa_d_min[built]", "kappa_d_max[built]", "kappa_d_centre[built]",
    "kappa_d_min[symmetric]", "kappa_d_max[symmetric]",
    "driving_force_peak_1", "driving_force_peak_2",
    "theta_2L[table1]", "claim:counterweights_half_moving_mass", "claim:a_s_gives_T0_0.15s",
    "claim:2l_greater_than_2d1", "claim:k_av_descends_with_theta",
)


def _rec(design: str, quantity: str):
    return lookup(PAPER, quantity, design)


#: the task rectangle [mm] of sec. 4.2-4.3 (the same for both designs)
B_MM, H_MM = _rec("table1", "b").value, _rec("table1", "h").value
#: theta_1S [deg] of the two designs: sec. 4.2's and Table 1's
DESIGNS = {d: _rec(d, "theta_1S").value for d in ("theta_1S=15deg", "table1")}
THETA_TABLE1 = DESIGNS["table1"]
MASS_NOTE = "links' mass centres at mid-link (Table 2 prints no s_i2), A3B3 loads like A1B1 (eq. 36-37)"


def _sym_note() -> str:
    sym = GantryInertia.wu2008().symmetric_variant()
    return ("symmetric variant of sec. 6.3: right slider, link and extra link A4B4 copy the left "
            f"chain, counterweights half the moving mass ({sym.m21:g}/{sym.m22:g}/{sym.m5:g} kg, "
            f"{sym.m13:g} kg each)")


SYM_NOTE = _sym_note()


# --- sec. 4.2 and Table 1: dimensional synthesis ---------------------------------------------
def _synthesis_rows() -> list[dict]:
    rows = []
    for design, deg in DESIGNS.items():
        _, d1, l, stroke = dimensional_synthesis(B_MM, H_MM, math.radians(deg))
        for q, v in (("d1", d1), ("l", l), ("stroke", stroke)):
            note = f"eq. (14)-(16) with b = {B_MM:g}, h = {H_MM:g} mm, theta_1S = {deg:g} deg"
            rows.append(compare(_rec(design, q), v, quantity=f"{q}[{design}]", note=note))
    return rows


# --- eq. (6)-(7): k_av ------------------------------------------------------------------------
def _k_av_curve(thetas_deg) -> pd.DataFrame:
    rows = []
    for deg in thetas_deg:
        th = math.radians(deg)
        g = Gantry.from_synthesis(B_MM, H_MM, th)
        xs, ys, w = rectangle_rule(g.task_workspace, 16)
        v_max, _ = g.velocity_extremes(xs, ys)
        _, d1, l, _ = dimensional_synthesis(B_MM, H_MM, th)
        rows.append({"theta_1S_deg": deg,
                     "k_av_literal": float(k_av_literal_of_design(th)),
                     "k_av_max_speed": g.k_av(reading="max_speed"),
                     "k_av_displacement": g.k_av(reading="displacement"),
                     "mean_v_max": float(np.sum(w * v_max)),
                     "l_mm": l, "d1_mm": d1})
    return pd.DataFrame(rows)


def _theta_where(reading: str, value: float) -> float:
    """theta_1S [deg] at which the reading of k_av equals ``value`` (monotone in theta_1S)."""
    def f(deg):
        return Gantry.from_synthesis(B_MM, H_MM, math.radians(deg)).k_av(reading=reading) - value
    return brentq(f, 1.0, 44.9, xtol=1e-6)


def _k_av_rows(out: Path, quick: bool) -> list[dict]:
    rec = _rec("table1", "k_av")
    value = rec.value
    g = wu2008_gantry(THETA_TABLE1)
    literal = g.k_av(reading="literal")
    alt = g.k_av(reading=ALTERNATIVE_READING)
    displacement = g.k_av(reading="displacement")
    xs, ys, w = rectangle_rule(g.task_workspace, 48)
    v_max = float(np.sum(w * g.velocity_extremes(xs, ys)[0]))
    th_lit = _theta_where("literal", value)
    th_alt = _theta_where(ALTERNATIVE_READING, value)
    deg15 = DESIGNS["theta_1S=15deg"]
    g15 = wu2008_gantry(deg15)
    note_lit = (
        "literal reading: x-mean over [-b/2, b/2] (eq. 17-18) of k_v(1) = |x_dot/q_dot_1| = "
        "|cot theta_1| at y_dot = 0 (sec. 3.3), closed form; k_av(1) = k_av(2). Other readings "
        f"tried on the Table 1 design: max_speed {alt:.3f}, mean of Liu's velocity index "
        f"|V|max = 1/s_min(J) over W_t {v_max:.3f}, x travel / slider travel {displacement:.3f} "
        "(exactly 1 for every design of eq. 13), theta-mean of cot 1.420, geometric x-mean 1.362, "
        f"median 1.407 (tests/test_gantry.py); none gives {value:g}. The literal value is {value:g} only at "
        f"theta_1S = {th_lit:.1f} deg ({deg15:g} deg design: {g15.k_av():.3f})")
    note_alt = (
        f"reading '{ALTERNATIVE_READING}': x-mean of |x_dot| over the mean slider speed "
        "(|q_dot_1| + |q_dot_2|)/2 at y_dot = 0, i.e. 2/|tan theta_1 - tan theta_2| (equally: the "
        "largest |x_dot| with both sliders at unit speed). Sec. 3.3 compares 'the average output "
        "velocity' with 'the average input velocity', and with y_dot = 0 both sliders move; it "
        f"exceeds 1 and descends with theta_1S as sec. 4.3 says. It gives {value:g} at theta_1S = "
        f"{th_alt:.1f} deg ({deg15:g} deg design: {g15.k_av(reading=ALTERNATIVE_READING):.3f}). Liu's "
        f"|V|max mean ({v_max:.3f}) is as far off and ignores the y_dot = 0 condition")
    rows = [compare(rec, literal, quantity="k_av[table1]", note=note_lit),
            compare(rec, alt, quantity="k_av_alternative[table1]", note=note_alt, kind="reading")]

    thetas = np.linspace(1.0, 44.0, 44 if quick else 431)
    curve = _k_av_curve(thetas)
    _io.write_csv(curve, out / "k_av_vs_theta.csv")
    _io.save_figure(_plot_k_av(curve, value), out / "k_av_vs_theta.png")
    return rows


def _plot_k_av(curve: pd.DataFrame, printed: float) -> Figure:
    fig = Figure(figsize=(6, 4))
    ax = fig.add_subplot()
    th = curve["theta_1S_deg"]
    ax.plot(th, curve["k_av_literal"], label="literal: x-mean of |cot theta_1| (eq. 6-7)")
    ax.plot(th, curve["k_av_max_speed"], label="alternative: |x_dot| / mean slider speed")
    ax.plot(th, curve["mean_v_max"], ls="--", label="mean |V|max = 1/s_min(J) (Liu 2006)")
    ax.plot(th, curve["k_av_displacement"], ls=":", label="x travel / slider travel")
    ax.axhline(printed, color="k", lw=0.8)
    ax.axvline(THETA_TABLE1, color="0.5", lw=0.8, ls="--")
    ax.annotate(f"Table 1: k_av = {printed:g} at theta_1S = {THETA_TABLE1:g} deg", (THETA_TABLE1 + 0.5, printed),
                xytext=(12, 2.6), fontsize=8, arrowprops=dict(arrowstyle="->", lw=0.6))
    ax.set_ylim(0.5, 3.5)
    ax.set_xlabel("theta_1S [deg]")
    ax.set_ylabel("k_av [-]")
    ax.set_title("Wu 2008: readings of the global velocity output ratio")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


# --- Fig. 2: workspace -----------------------------------------------------------------------
def _plot_workspace() -> Figure:
    fig = Figure(figsize=(11, 5.5))
    for k, (design, deg) in enumerate(DESIGNS.items()):
        g = wu2008_gantry(deg)
        ax = fig.add_subplot(1, 2, k + 1)
        lo_x, hi_x = g.x_range
        x = np.linspace(lo_x, hi_x, 801)
        lo, hi = g.y_interval(x)
        ax.fill_between(x, lo, hi, where=np.isfinite(lo), color="C0", alpha=0.2,
                        label="reachable workspace")
        ax.plot(x, lo, color="C0", lw=1)
        ax.plot(x, hi, color="C0", lw=1)
        base = g.l2 / 2.0
        for xb in g.column_x:  # the four arcs of Fig. 2 (centres B', B'')
            for q in (g.q_min, g.q_max):
                ax.add_patch(Circle((xb, q + base), g.l, fill=False, lw=0.5, ls=":", color="0.5"))
            ax.plot([xb, xb], [g.q_min, g.q_max], color="0.3", lw=4, alpha=0.4,
                    solid_capstyle="butt")
        xmin, xmax, ymin, ymax = g.task_workspace
        ax.add_patch(Rectangle((xmin, ymin), xmax - xmin, ymax - ymin, fill=False, color="C3",
                               lw=1.5, label="task workspace W_t"))
        for name, (px, py) in {"Q1": (xmin, ymax), "Q2": (xmin, ymin), "Q3": (xmax, ymin),
                               "Q4": (xmax, ymax)}.items():
            ax.annotate(name, (px, py), xytext=(-14 if px < 0 else 4, 4), textcoords="offset points",
                        fontsize=8, color="C3")
        # the machine at the centre of W_t (eq. 2), with the parallelogram link A3B3
        px, py = 0.5 * (xmin + xmax), 0.5 * (ymin + ymax)
        q1, q2, _ = g.ik(px, py)
        ay = py - base
        for xb, q in zip(g.column_x, (float(q1), float(q2))):
            ax.plot([xb, px], [q, ay], color="k", lw=1.5)
        ax.plot([g.column_x[0], px], [float(q1) + g.l2, ay + g.l2], color="k", lw=1, ls="--")
        ax.plot([px], [py], "ko", ms=4)
        ax.annotate("O'", (px, py), xytext=(4, 4), textcoords="offset points", fontsize=8)
        bx = g.bounding_box()
        ax.set_xlim(-g.l - 50, g.l + 50)
        ax.set_ylim(min(g.q_min, bx[2]) - 50, bx[3] + 100)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_title(f"{design}: d1 = {g.d1:.0f}, l = {g.l:.1f}, stroke = {g.stroke:.0f} mm\n"
                     f"reachable area {g.workspace_area() / 1e6:.3f} m^2, W_t "
                     f"{g.task_workspace_area() / 1e6:.2f} m^2", fontsize=9)
        ax.legend(fontsize=7, loc="lower center")
    fig.suptitle("Wu 2008 Fig. 2 redrawn: workspace and task rectangle Q1Q2Q3Q4 "
                 "(machine drawn at the centre of W_t)")
    fig.tight_layout()
    return fig


# --- sec. 6: kappa_D, eta_D, ellipses --------------------------------------------------------
def _dynamics(kind: str) -> GantryDynamics:
    inertia = GantryInertia.wu2008()
    if kind == "symmetric":
        inertia = inertia.symmetric_variant()
    return GantryDynamics(wu2008_gantry(THETA_TABLE1, unit="m"), inertia)


def _kappa_profile(dyn: GantryDynamics, n: int = 2001):
    """kappa_D along x over the closed task rectangle (it depends on x only)."""
    xmin, xmax, ymin, ymax = dyn.gantry.task_workspace
    x = np.linspace(xmin, xmax, n)
    return x, dyn.kappa_d(x, np.full_like(x, 0.5 * (ymin + ymax)))


def _dynamics_rows() -> list[dict]:
    rows = []
    built, sym = _dynamics("built"), _dynamics("symmetric")
    xmin, xmax, ymin, ymax = built.gantry.task_workspace
    centre = (0.5 * (xmin + xmax), 0.5 * (ymin + ymax))
    src6, src7 = cite(PAPER, "eq. (43)-(44), Fig. 6 (map only)"), cite(PAPER, "sec. 6.3, Fig. 7 (map only)")

    x, k = _kappa_profile(built)
    i_min, i_max = int(np.argmin(k)), int(np.argmax(k))
    kc = float(built.kappa_d(*centre))
    edge_l, edge_r = float(k[0]), float(k[-1])
    iso = ("consistent with 'more isotropic in the centre than at the peripheries' (sec. 6.2)"
           if max(float(k[i_min]), kc) < min(edge_l, edge_r) else
           "NOT consistent with 'more isotropic in the centre' (sec. 6.2)")
    xs_note = "kappa_D depends on x only; over the closed task rectangle (2001 abscissae)"
    rows.append(not_reported(
        "eta_d[built]", cite(PAPER, "eq. (44), Fig. 6"), built.eta_d(n=48), "-",
        f"area mean of kappa_D over W_t (48 x 48 Gauss-Legendre); {MASS_NOTE}; the paper prints "
        "no value"))
    rows.append(not_reported(
        "eta_d_std[built]", cite(PAPER, "abstract, sec. 7 item 2 (formula not printed)"),
        built.eta_d_std(n=48), "-",
        "area standard deviation of kappa_D over W_t: our reading of the second global index the "
        f"abstract announces (its formula is not printed); {MASS_NOTE}"))
    rows.append(not_reported(
        "eta_d[symmetric]", cite(PAPER, "sec. 6.3, Fig. 7"), sym.eta_d(n=48), "-",
        f"area mean of kappa_D over W_t; {SYM_NOTE}; {MASS_NOTE}"))
    rows.append(not_reported(
        "kappa_d_min[built]", src6, float(k[i_min]), "-",
        f"at x = {1e3 * x[i_min]:.0f} mm (left of the centre: the machine is asymmetric, sec. 7 "
        f"item 2); {xs_note}; {iso}"))
    rows.append(not_reported(
        "kappa_d_max[built]", src6, float(k[i_max]), "-",
        f"at x = {1e3 * x[i_max]:.0f} mm (edges: left {edge_l:.3f}, right {edge_r:.3f}), where "
        f"a link is {_rec('table1', 'theta_2L').value:g} deg from the vertical (theta_1 at x = +b/2, -theta_2 at x = -b/2); "
        f"{xs_note}"))
    rows.append(not_reported(
        "kappa_d_centre[built]", src6, kc, "-",
        f"at the centre of W_t (0, {1e3 * centre[1]:.0f}) mm; {MASS_NOTE}"))

    xs, ks = _kappa_profile(sym)
    j_min, j_max = int(np.argmin(ks)), int(np.argmax(ks))
    asym = float(np.nanmax(np.abs(ks - ks[::-1])))
    _, _, angle = sym.inertia_ellipse(0.0, centre[1])
    lam = sym.inertia_matrix(0.0, centre[1])  # force per unit acceleration along x and y
    fx, fy = (float(np.linalg.norm(lam[:, c])) for c in (0, 1))
    rows.append(not_reported(
        "kappa_d_min[symmetric]", src7, float(ks[j_min]), "-",
        f"at x = {1e3 * xs[j_min]:.1f} mm: on the y axis and symmetric (max |kappa(x) - "
        f"kappa(-x)| = {asym:.1e}), as sec. 6.3 says. At x = 0 our acceleration ellipse "
        f"{{a : |(J^T)^-1 M a| <= 1}} has its major (easiest) axis at {math.degrees(float(angle)):.0f} "
        f"deg, i.e. along x (|Lambda e_x| = {fx:.0f} < |Lambda e_y| = {fy:.0f} N per m/s^2), "
        "whereas the text says acceleration is maximum along y: that holds for the ellipse with "
        "semi-axes sigma_i of Lambda = (J^T)^-1 M, whose major axis is the hardest direction; "
        f"{SYM_NOTE}"))
    rows.append(not_reported(
        "kappa_d_max[symmetric]", src7, float(ks[j_max]), "-",
        f"at x = {1e3 * xs[j_max]:.0f} mm (both edges equal); {xs_note}; {SYM_NOTE}"))
    return rows


def _kappa_levels(maps) -> np.ndarray:
    hi = max(float(np.nanmax(K)) for K in maps)
    lo = min(float(np.nanmin(K)) for K in maps)
    return np.geomspace(lo, hi, 16)


def _plot_kappa_map(dyn: GantryDynamics, X, Y, K, levels, title: str) -> Figure:
    fig = Figure(figsize=(6.2, 4.6))
    ax = fig.add_subplot()
    cs = ax.contourf(1e3 * X, 1e3 * Y, K, levels=levels, cmap="viridis_r", extend="both")
    cl = ax.contour(1e3 * X, 1e3 * Y, K, levels=levels[::3], colors="k", linewidths=0.5)
    ax.clabel(cl, fmt="%.2f", fontsize=7)
    fig.colorbar(cs, ax=ax, label="kappa_D = sigma_2 / sigma_1 [-]", format="%.2f")
    mid = K.shape[0] // 2  # kappa_D depends on x only: mark its minimum as a vertical line
    j = int(np.nanargmin(K[mid]))
    ax.axvline(1e3 * X[mid, j], color="r", lw=1, ls="--",
               label=f"min {K[mid, j]:.3f} at x = {1e3 * X[mid, j]:.0f} mm")
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.legend(fontsize=8, loc="upper center")
    ax.set_title(f"{title}\neta_D = {dyn.eta_d(n=48):.4f} over W_t (mid-link mass centres)",
                 fontsize=9)
    fig.tight_layout()
    return fig


def _plot_ellipses(quick: bool) -> Figure:
    fig = Figure(figsize=(11, 4.8))
    nx, ny = (5, 4) if quick else (9, 7)
    for k, kind in enumerate(("built", "symmetric")):
        dyn = _dynamics(kind)
        xmin, xmax, ymin, ymax = dyn.gantry.task_workspace
        # poses at cell centres: the corners Q1, Q4 lie on the reachable boundary
        X, Y = np.meshgrid(xmin + (np.arange(nx) + 0.5) * (xmax - xmin) / nx,
                           ymin + (np.arange(ny) + 0.5) * (ymax - ymin) / ny)
        major, minor, angle = dyn.inertia_ellipse(X, Y)
        kap = dyn.kappa_d(X, Y)
        # semi-axes are accelerations per unit force [(m/s^2)/N]: scale the largest to
        # 45 % of the grid spacing
        spacing = min((xmax - xmin) / nx, (ymax - ymin) / ny)
        scale = 0.45 * spacing / float(np.nanmax(major))
        ax = fig.add_subplot(1, 2, k + 1)
        norm_lo, norm_hi = float(np.nanmin(kap)), float(np.nanmax(kap))
        cmap = colormaps["viridis_r"]
        for xx, yy, a, b, phi, kk in zip(X.ravel(), Y.ravel(), major.ravel(), minor.ravel(),
                                         angle.ravel(), kap.ravel()):
            c = cmap((kk - norm_lo) / max(norm_hi - norm_lo, _v.ROUNDING))
            ax.add_patch(Ellipse((1e3 * xx, 1e3 * yy), 2e3 * scale * a, 2e3 * scale * b,
                                 angle=math.degrees(phi), facecolor=c, edgecolor="k", lw=0.5,
                                 alpha=0.8))
        ax.add_patch(Rectangle((1e3 * xmin, 1e3 * ymin), 1e3 * (xmax - xmin), 1e3 * (ymax - ymin),
                               fill=False, color="C3", lw=1))
        pad = 1e3 * spacing * 0.2
        ax.set_xlim(1e3 * xmin - pad, 1e3 * xmax + pad)
        ax.set_ylim(1e3 * ymin - pad, 1e3 * ymax + pad)
        ax.set_aspect("equal")
        ax.set_xlabel("x [mm]")
        ax.set_ylabel("y [mm]")
        ax.set_title(f"{'built machine (Table 1-2)' if kind == 'built' else 'symmetric variant (sec. 6.3)'}"
                     f"\n1 mm drawn = {1.0 / (1e3 * scale):.3g} (m/s^2)/N; colour: kappa_D "
                     f"{norm_lo:.2f} (light) to {norm_hi:.2f} (dark)", fontsize=9)
    fig.suptitle("Wu 2008 Fig. 5 redrawn: acceleration ellipses {a : |(J^T)^-1 M a| <= 1 N} "
                 "(major axis = easiest direction)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.93))  # room for the suptitle above the panel titles
    return fig


def _figures_5_to_7(out: Path, quick: bool):
    n = 61 if quick else 201
    built, sym = _dynamics("built"), _dynamics("symmetric")
    mb, ms = built.kappa_d_map(n=n), sym.kappa_d_map(n=n)
    levels = _kappa_levels([mb[2], ms[2]])
    _io.save_figure(_plot_kappa_map(built, *mb, levels,
                                    "Wu 2008 Fig. 6 redrawn: kappa_D over W_t, built machine"),
                    out / "fig6_kappa_d_built.png")
    _io.save_figure(_plot_kappa_map(sym, *ms, levels,
                                    "Wu 2008 Fig. 7 redrawn: kappa_D, symmetric variant (A4B4 added)"),
                    out / "fig7_kappa_d_symmetric.png")
    _io.save_figure(_plot_ellipses(quick), out / "fig5_inertia_ellipses.png")


# --- Fig. 4: driving forces along the Table 3 trajectory -------------------------------------
def _driving_force_rows(out: Path, quick: bool) -> list[dict]:
    tr = wu2008_driving_forces(wu2008_gantry(THETA_TABLE1, unit="m"), n=651)
    dyn = _dynamics("built")
    F1g, F2g = dyn.driving_forces(tr["x"], tr["y"], tr["xd"], tr["yd"], tr["xdd"], tr["ydd"],
                                  gravity=False)
    data = pd.DataFrame({k: tr[k] for k in ("t", "x", "y", "xd", "yd", "xdd", "ydd", "F1", "F2")})
    data["F1_no_gravity"], data["F2_no_gravity"] = F1g, F2g
    _io.write_csv(data, out / "driving_forces.csv")
    _io.save_figure(_plot_forces(data, tr["T0"], tr["Tf"]), out / "fig4_driving_forces.png")
    rows = []
    x1 = _rec("table3", "x1").value
    for i in (1, 2):
        F = data[f"F{i}"].to_numpy()
        j = int(np.argmax(np.abs(F)))
        rows.append(not_reported(
            f"driving_force_peak_{i}", cite(PAPER, "Fig. 4, Tables 2-3 (curves only)"),
            float(np.abs(F[j])), "N",
            f"max |F{i}| over the Table 3 motion (651 instants, trapezoidal profile, T0 = "
            f"{tr['T0']:.3f} s, Tf = {tr['Tf']:.3f} s), at t = {data['t'].iloc[j]:.3f} s, x = "
            f"{1e3 * data['x'].iloc[j]:.0f} mm (F{i} = {F[j]:.0f} N); gravity included (sec. 5.2); "
            f"{MASS_NOTE}; Table 3's x1 '{x1:g} mm' read as {x1:g} m. Our forces jump at t = T0 and "
            "Tf - T0, where the trapezoidal profile's acceleration jumps; the text calls the "
            "paper's curves smooth"))
    return rows


def _plot_forces(data: pd.DataFrame, T0: float, Tf: float) -> Figure:
    fig = Figure(figsize=(7, 6))
    ax = fig.add_subplot(2, 1, 1)
    t = data["t"]
    ax.plot(t, data["F1"] / 1e3, label="F1 (left slider)")
    ax.plot(t, data["F2"] / 1e3, label="F2 (right slider)")
    ax.plot(t, data["F1_no_gravity"] / 1e3, ls=":", color="C0", lw=0.8, label="F1 without gravity")
    ax.plot(t, data["F2_no_gravity"] / 1e3, ls=":", color="C1", lw=0.8, label="F2 without gravity")
    for tt in (T0, Tf - T0):
        ax.axvline(tt, color="0.6", lw=0.6, ls="--")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_ylabel("driving force [kN]")
    ax.set_xlabel("t [s]")
    ax.set_title("Wu 2008 Fig. 4 redrawn: driving forces along Table 3 (Table 2 masses)", fontsize=10)
    ax.legend(fontsize=7)
    ax2 = fig.add_subplot(2, 1, 2, sharex=ax)
    ax2.plot(t, 1e3 * data["x"], color="C2", label="x [mm]")
    ax2.set_ylabel("x [mm]")
    ax3 = ax2.twinx()
    ax3.plot(t, data["xd"], color="C4", label="x_dot [m/s]")
    ax3.set_ylabel("x_dot [m/s]")
    ax3.set_xlabel("t [s]")
    ax2.set_xlabel("t [s]")
    ax2.legend(loc="upper left", fontsize=7)
    ax3.legend(loc="lower right", fontsize=7)
    fig.tight_layout()
    return fig


# --- fronts and sweep ------------------------------------------------------------------------
# --- printed claims and derived settings (issue: every printed claim a row) -------------------
def _claim_rows(curve: pd.DataFrame) -> list[dict]:
    """theta_2L, the counterweight rule, a_s and T0, 2l > 2d1, and k_av's descent."""
    rows = []
    # theta_2L: the largest angle of link 2 over the task rectangle of the Table 1 design
    g = wu2008_gantry(THETA_TABLE1)
    xmin, xmax, ymin, ymax = g.task_workspace
    _, th2 = g.link_angles(np.array([xmin, xmin]), np.array([ymin, ymax]))
    rec = _rec("table1", "theta_2L")
    rows.append(compare(rec, float(np.degrees(np.max(np.abs(th2)))), quantity="theta_2L[table1]",
                        note="largest |theta_2| over W_t of the Table 1 design (at x = -b/2); "
                             "eq. (11)-(13) make theta_1S + theta_2L = 90 deg"))
    # counterweights: "each is half of the masses of all moving parts" (sec. 6.2)
    def pub(design, quantity):
        return _rec(design, quantity).value

    parts = [pub("table2", k) for k in ("m11", "m21", "m12", "m22", "m4", "mN")]
    moving = sum(parts)
    cw = pub("table2", "m13")
    rows.append(claim_row("claim:counterweights_half_moving_mass", cite(PAPER, "sec. 6.2, Table 2"),
                          cw == moving / 2 == pub("table2", "m23"),
                          f"moving parts {' + '.join(f'{m:g}' for m in parts)} = {moving:g} kg, half "
                          f"{moving / 2:g} kg; Table 2 prints m13 = m23 = {cw:g} kg"))
    # a_s = 6.67 m/s^2: accelerating time T0 = v_max / a_s (eq. 45 with equal phases)
    a_rec = _rec("table3", "a_s")
    v, a = pub("table3", "v_max"), a_rec.value
    length = abs(pub("table3", "x1") - pub("table3", "x0"))
    T0, Tf = v / a, v / a + length / v
    rows.append(claim_row("claim:a_s_gives_T0_0.15s", cite(PAPER, "eq. (45), Table 3"),
                          round(1.0 / 0.15, a_rec.digits) == a,
                          f"T0 = v_max / a_s = {T0:.4f} s, Tf = T0 + |q1 - q0| / v_max = {Tf:.4f} s; "
                          f"{a_rec.printed} is 1/0.15 = {1 / 0.15:.4f} rounded to the printed "
                          f"{a_rec.digits} decimals, so the paper's T0 = 0.15 s, Tf = 0.65 s"))
    # 2l > 2d1 (sec. 3.1): no combined singularity
    ok = all(dimensional_synthesis(B_MM, H_MM, math.radians(t))[2]
             > dimensional_synthesis(B_MM, H_MM, math.radians(t))[1] for t in np.linspace(1, 44, 44))
    _, d1, l, _ = dimensional_synthesis(B_MM, H_MM, math.radians(THETA_TABLE1))
    rows.append(claim_row("claim:2l_greater_than_2d1", cite(PAPER, "sec. 3.1"), ok,
                          f"Table 1: 2l = {2 * l:.1f} mm > 2d1 = {2 * d1:.1f} mm; eq. (14)-(15) give "
                          f"l > d1 for every theta_1S in [1, 44] deg (checked at 1 deg steps)"))
    # "k_av descends as theta_1 goes from 0 to 90 deg" (sec. 4.3)
    lit = curve["k_av_literal"].to_numpy()
    alt = curve["k_av_max_speed"].to_numpy()
    desc = bool(np.all(np.diff(lit) < 0) and np.all(np.diff(alt) < 0))
    rows.append(claim_row("claim:k_av_descends_with_theta", cite(PAPER, "sec. 4.3, Fig. 3"), desc,
                          f"on {len(curve)} designs theta_1S in [{curve['theta_1S_deg'].min():g}, "
                          f"{curve['theta_1S_deg'].max():g}] deg (k_av_vs_theta.csv) both the literal "
                          f"({lit[0]:.3f} -> {lit[-1]:.3f}) and the max_speed reading "
                          f"({alt[0]:.3f} -> {alt[-1]:.3f}) descend strictly; locally k_v = |cot theta| "
                          "falls on (0, 90) deg"))
    return rows


def _runs(out: Path, quick: bool):
    # the paper's folder is reproduce's: a run of the other mode (quick or full) is replaced
    kw = dict(seed=1, progress=False, n_jobs=1 if quick else 2, overwrite=True)
    small = dict(pop=8, gen=3) if quick else {}
    runner.optimize(problems.get("wu2008"), out=out / "front", **small, **kw)
    runner.optimize(problems.get("wu2008-dynamic"), out=out / "front_dynamic",
                    **(small or dict(pop=40, gen=40)), **kw)
    weights = runner.parse_weights("0,0.5,1" if quick else "0:1:0.1")
    runner.sweep(problems.get("wu2008"), weights, out=out / "sweep", **small, **kw)


#: pieces of :func:`run` that only write files (no row depends on them), which
#: ``mechopt reproduce`` may run in another process beside the rest (:func:`run_part`)
PARTS = ("runs",)


def run_part(out: Path, quick: bool, name: str) -> None:
    """One piece of :data:`PARTS` into ``out``: ``"runs"``, the fronts of ``wu2008`` and
    ``wu2008-dynamic`` and the weighting sweep (``front/``, ``front_dynamic/``, ``sweep/``).

    Parameters
    ----------
    out : Path
        The paper's results folder.
    quick : bool
        Smaller runs (every row and file is still produced).
    name : str
        A key of :data:`PARTS`.

    Raises
    ------
    ValueError
        For an unknown part.
    """
    if name != "runs":
        raise ValueError(f"wu2008 has no part {name!r} (parts: {', '.join(PARTS)})")
    _runs(_io.prepare_out_dir(out), quick)


def run(out: Path, quick: bool = False, parts: bool = True) -> pd.DataFrame:
    """Reproduce Wu 2008 into ``out``; returns the table (columns :data:`TABLE_COLUMNS`).

    ``quick`` shrinks the optimiser runs, the sweep and the figure grids; every row and
    every file is still produced (the rows' values do not depend on it). ``parts=False``
    leaves out the files of :data:`PARTS` (written by :func:`run_part`).

    Parameters
    ----------
    out : Path
        The paper's results folder.
    quick : bool
        Smaller runs (every row and file is still produced).
    parts : bool
        Also write the files of :data:`PARTS`.

    Returns
    -------
    DataFrame
        The table (table.csv's columns).

    Raises
    ------
    RuntimeError
        When the rows are out of order (a programming error).
    """
    out = _io.prepare_out_dir(out)
    rows = _synthesis_rows()
    rows += _k_av_rows(out, quick)
    rows += _dynamics_rows()
    rows += _driving_force_rows(out, quick)
    rows += _claim_rows(pd.read_csv(out / "k_av_vs_theta.csv"))
    _io.save_figure(_plot_workspace(), out / "fig2_workspace.png")
    _figures_5_to_7(out, quick)
    if parts:
        run_part(out, quick, "runs")
    table = pd.DataFrame(rows, columns=list(TABLE_COLUMNS))
    if tuple(table["quantity"]) != QUANTITIES:  # pragma: no cover (a programming error)
        raise RuntimeError(f"wu2008 rows out of order: {list(table['quantity'])}")
    return table


if __name__ == "__main__":  # pragma: no cover
    import sys
    import time

    t0 = time.perf_counter()
    target = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("results/wu2008")
    df = run(target, quick="--quick" in sys.argv)
    with pd.option_context("display.width", 250, "display.max_colwidth", 80):
        print(df.to_string(index=False))
    print(f"{time.perf_counter() - t0:.1f} s")
