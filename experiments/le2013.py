"""Le, Kang, Doan (2013): the a_MAX(rho) curve, its optimum, and the paper's numbers.

Thin script over :mod:`mechopt.problems.le2013` and the runner. Writes ``curve.csv``
(a_MAX, r_MIC, MIC centre, LCI range over rho), ``fig5_a_max.png``,
``fig6_lci_square.png``, the GA run (``front/``), the relaxed run (``relaxed/``),
the (square side, gamma) front and its weighting sweep (``sweep/``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib.figure import Figure

from mechopt import FiveBar
from mechopt import io as _io
from mechopt.parallel import parallel_map
from mechopt.problems import get
from mechopt.problems.le2013 import GAMMA, square_side, tied_half_base
from mechopt.published import comparison_row, load
from mechopt.runner import optimize, parse_weights, sweep

__all__ = ["run", "REL_TOL"]

#: acceptance for lengths from the square search: our own sampling accuracy of a_MAX
#: (257 points per edge, bisection to 1e-6) is about 1e-4 relative
REL_TOL = 1e-3


def _row_for_rho(rho):
    return {"rho": rho, "l0": tied_half_base(rho), **square_side(1.0, rho, tied_half_base(rho))}


def _curve(step):
    rhos = np.round(np.arange(1.2, 4.0 + 1e-9, step), 6)
    return pd.DataFrame(parallel_map(_row_for_rho, list(rhos), n_jobs=2))


def _fig5(curve, paper_rho, paper_a, ours):
    fig = Figure(figsize=(6, 4))
    ax = fig.add_subplot()
    ax.plot(curve["rho"], curve["a_max"], "-", lw=1.5, label=r"$a_{MAX}(\rho)$, mechopt")
    ax.plot([paper_rho], [paper_a], "rs", label=f"paper: rho*={paper_rho}, a={paper_a}")
    ax.plot([ours["rho"]], [ours["a_max"]], "k^", label=f"mechopt GA: rho*={ours['rho']:.4f}, a={ours['a_max']:.4f}")
    ax.set_xlabel(r"$\rho = l_2/l_1$")
    ax.set_ylabel(r"$a_{MAX}$ [$l_1$]")
    ax.set_title(r"Le 2013 Fig. 5 redrawn: $\gamma$ = 0.5, $\theta \in [-\pi/3, 4\pi/3]$")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def _fig6(rho):
    fb = FiveBar(1.0, rho, tied_half_base(rho))
    res = square_side(1.0, rho, tied_half_base(rho))
    a, cy = res["a_max"], res["mic_center_y"]
    s = np.linspace(-a / 2, a / 2, 161)
    X, Y = np.meshgrid(s, cy + s)
    fig = Figure(figsize=(5, 4.4))
    ax = fig.add_subplot()
    cs = ax.contourf(X, Y, fb.lci(X, Y), levels=np.linspace(0.5, 1.0, 11))
    fig.colorbar(cs, ax=ax, label="LCI = 1/kappa")
    ax.set_aspect("equal")
    ax.set_title(f"Le 2013 Fig. 6 redrawn: LCI in the square, rho = {rho:.4f}")
    ax.set_xlabel("x [l1]")
    ax.set_ylabel("y [l1]")
    return fig


def run(out: Path, quick: bool = False) -> pd.DataFrame:
    out = Path(out)
    pub = load("le2013").set_index("quantity")
    paper_rho, paper_a = float(pub.loc["rho_star", "value"]), float(pub.loc["a_max", "value"])
    curve = _curve(0.2 if quick else 0.02)
    _io.write_csv(curve, out / "curve.csv")

    ga = dict(pop=6, gen=3) if quick else {}
    best = optimize(get("le2013"), seed=1, out=out / "front", progress=False, **ga).front.iloc[0]
    relaxed = optimize(get("le2013-relaxed"), seed=1, out=out / "relaxed", progress=False,
                       **ga).front.iloc[0]
    sweep(get("le2013-gamma"), parse_weights("0,0.5,1" if quick else "0:1:0.1"), seed=1,
          out=out / "sweep", progress=False, **(dict(pop=6, gen=2) if quick else {}))
    at_paper = square_side(1.0, paper_rho, tied_half_base(paper_rho))
    _io.save_figure(_fig5(curve, paper_rho, paper_a, best), out / "fig5_a_max.png")
    _io.save_figure(_fig6(paper_rho), out / "fig6_lci_square.png")

    src = lambda q: f"Le 2013 {pub.loc[q, 'source']}"  # noqa: E731
    why_opt = (
        "the LCI >= 0.5 constraint binds at the square's top corners for 1.55 < rho < 1.97 and at "
        "its bottom corners above; a_MAX(rho) (curve.csv, fig5) peaks near rho = 1.55 and the "
        "paper's rho* sits exactly at the switch of the binding corners, where our curve gives "
        f"{at_paper['a_max']:.4f}; the paper's text says a_MAX grows up to rho ~ 2, which no "
        "reading we tried (lower half, boundary only, other working modes) reproduces"
    )
    rows = [
        comparison_row("rho_star", src("rho_star"), paper_rho, best["rho"], "-", 4, REL_TOL,
                       "GA (runner, seed 1) on le2013; " + why_opt),
        comparison_row("a_max", src("a_max"), paper_a, best["a_max"], "l1", 4, REL_TOL,
                       "best square side of our GA; " + why_opt),
        comparison_row("a_max_at_paper_rho", src("a_max"), paper_a, at_paper["a_max"], "l1", 4, REL_TOL,
                       "our a_MAX evaluated at the paper's rho* = 1.9721 (l0 by eq. 24, MIC centre)"),
        comparison_row("lci_min_in_square", src("lci_min_in_square"), 0.5, at_paper["lci_min"], "-", 1,
                       REL_TOL, "min LCI on a 81 x 81 grid of the square at the paper's rho*"),
        comparison_row("lci_max_in_square", src("lci_max_in_square"), 1.0, at_paper["lci_max"], "-", 0,
                       REL_TOL, "max LCI on a 81 x 81 grid of the square at the paper's rho*"),
        comparison_row("a_max_relaxed", "Le 2013 eq. (24) dropped (mechopt variant)", None,
                       relaxed["a_max"], "l1", 4, REL_TOL, kind="reading", note=
                       f"l0 free: best a = {relaxed['a_max']:.4f} at rho = {relaxed['rho']:.4f}, "
                       f"l0 = {relaxed['l0']:.4f}; with eq. (24): {best['a_max']:.4f} "
                       f"({(relaxed['a_max'] / best['a_max'] - 1):+.2%})"),
    ]
    return pd.DataFrame(rows)
