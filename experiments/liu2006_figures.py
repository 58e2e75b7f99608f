"""Liu 2006 figures redrawn from mechopt's numbers (thin: evaluators + matplotlib).

Figs. 8-16 (example designs with MIC and usable workspace), 17-28 (LCI and index
maps, usable workspaces, GCW, the maximal square). The atlases (Figs. 2-6) and
optimum regions (Figs. 7, 9, 11, 13, 15) come from :mod:`mechopt.run.atlas`. Designs
are named by their keys ``"r1/r2/r3"`` in ``mechopt/data/liu2006.csv``.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Circle, Rectangle

from mechopt import FiveBar
from mechopt.run import io as _io
from mechopt.run.plotting import INDEX_LABELS, labelled_colorbar, workspace_axes
from mechopt.analysis.workspace import gcw, largest_square, mic, usable_region

__all__ = ["draw_all", "atlas_figures", "design_figures", "EXAMPLES", "fig_examples", "fig_lci_usable", "fig_usable_pair",
           "fig_extremes_on_miw", "fig_gcw_and_square"]

#: sec. 3.1.1-3.1.5: the example design (its key in liu2006.csv) of each optimum region
EXAMPLES = {
    "W-GCI (Fig. 8)": "1.1/1.65/0.25",
    "W-GCI-GVI (Fig. 10)": "1.5/1.2/0.3",
    "W-GCI-GPI (Fig. 12)": "0.7/1.7/0.6",
    "W-GCI-GSI (Fig. 14)": "0.85/1.6/0.55",
    "All (Fig. 16)": "1.17/1.45/0.38",
}
#: sec. 3.2: the design of the GCW and its square (Figs. 17, 23-28), of Fig. 20 and of
#: Figs. 21-22, and the pair of usable workspaces of Figs. 18-19
GCW_EXAMPLE, FIG20, FIGS21_22 = "0.85/1.6/0.55", "1.1/1.65/0.25", "1.5/1.2/0.3"
USABLE_PAIR = ("0.4/2.33/0.27", "0.65/1.62/0.73")


def _lengths(key: str) -> tuple:
    """``(r1, r2, r3)`` of a design key ``"r1/r2/r3"``."""
    return tuple(float(v) for v in key.split("/"))


def _mechanism_lines(ax, fb, m):
    """The mechanism drawn at the MIC centre, base joints and links."""
    x, y = 0.0, m.center_y
    b1x, b1y, b2x, b2y, _ = fb.elbows(x, y)
    ax.plot([-fb.r3, float(b1x), x, float(b2x), fb.r3], [0, float(b1y), y, float(b2y), 0], "k-o", ms=3, lw=1.2)


def _map(ax, fb, region, values, title, label, levels=12):
    """A local index (``label``: its colour-bar text) over a region, in the base frame."""
    X, Y = region.grid.points()
    V = np.where(region.mask, values, np.nan)
    cs = ax.contourf(X, Y, V, levels=levels)
    labelled_colorbar(ax.figure, cs, ax, label, shrink=0.8)
    workspace_axes(ax)
    ax.set_title(title, fontsize=9)
    return cs


def _disk_region(fb, m, radius, step):
    from mechopt.core.quadrature import grid_over
    from mechopt.analysis.workspace import Region

    g = grid_over((-radius, radius, m.center_y - radius, m.center_y + radius), step)
    X, Y = g.points()
    return Region(g, np.hypot(X, Y - m.center_y) <= radius)


def fig_examples(step):
    """The usable workspace of each example design of Liu 2006 sec. 3.1 (Figs. 8-14),
    with its MIC.

    Parameters
    ----------
    step : float
        Raster step (non-dimensional, Liu's lengths sum to 3).

    Returns
    -------
    Figure
        The figure (not saved).
    """
    fig = Figure(figsize=(16, 3.6), layout="constrained")
    for k, (name, key) in enumerate(EXAMPLES.items()):
        r = _lengths(key)
        fb = FiveBar(*r)
        m = mic(fb)
        u = usable_region(fb, step=step, center=(0.0, m.center_y))
        ax = fig.add_subplot(1, 5, k + 1)
        X, Y = u.grid.points()
        ax.contourf(X, Y, u.mask.astype(float), levels=[0.5, 1.5], colors=["0.85"])  # not a printed number
        ax.add_patch(Circle((0, m.center_y), m.radius, fill=False, color="C3", lw=1.2))
        _mechanism_lines(ax, fb, m)
        workspace_axes(ax)
        ax.set_title(f"{name}\nr = {r}, r_MIC = {m.radius:.4f}", fontsize=8)
    return fig


def fig_lci_usable(fb, step, title):
    """The LCI over the usable workspace of one design.

    Parameters
    ----------
    fb : FiveBar
        The design.
    step : float
        Raster step (non-dimensional, Liu's lengths sum to 3).
    title : str
        The figure's title.

    Returns
    -------
    Figure
        The figure (not saved).
    """
    u = usable_region(fb, step=step)
    X, Y = u.grid.points()
    fig = Figure(figsize=(6, 4), layout="constrained")
    _map(fig.add_subplot(), fb, u, fb.lci(X, Y), title, INDEX_LABELS["lci"])
    return fig


def fig_usable_pair(step):
    """The LCI over the usable workspaces of the two designs of :data:`USABLE_PAIR`.

    Parameters
    ----------
    step : float
        Raster step (non-dimensional, Liu's lengths sum to 3).

    Returns
    -------
    Figure
        The figure (not saved).
    """
    fig = Figure(figsize=(11, 4), layout="constrained")
    for k, r in enumerate(_lengths(key) for key in USABLE_PAIR):
        fb = FiveBar(*r)
        u = usable_region(fb, step=step)
        X, Y = u.grid.points()
        _map(fig.add_subplot(1, 2, k + 1), fb, u, fb.lci(X, Y),
             f"Figs. 18-19: r = {r}\nusable area {u.area:.4f}, LCI", INDEX_LABELS["lci"])
    return fig


def fig_extremes_on_miw(fb, names, step, title):
    """Local indices over the MIC of one design, one panel each (clipped at the 98th
    percentile).

    Parameters
    ----------
    fb : FiveBar
        The design.
    names : sequence of str
        Local index names (:data:`mechopt.core.indices.LOCAL_INDEX_NAMES`).
    step : float
        Raster step (non-dimensional, Liu's lengths sum to 3).
    title : str
        The figure's title.

    Returns
    -------
    Figure
        The figure (not saved).
    """
    from mechopt.core import indices as ix

    m = mic(fb)
    reg = _disk_region(fb, m, m.radius, step)
    X, Y = reg.grid.points()
    loc = ix.local_indices(fb.jacobian(X, Y))
    fig = Figure(figsize=(5.8 * len(names), 4.2), layout="constrained")
    for k, name in enumerate(names):
        v = loc[name]
        hi = np.nanpercentile(np.where(reg.mask, v, np.nan), 98)
        _map(fig.add_subplot(1, len(names), k + 1), fb, reg, np.clip(v, None, hi),
             f"{title}:\n{name} (clipped at 98th percentile)", INDEX_LABELS[name])
    return fig


def fig_gcw_and_square(fb, step):
    """The GCW (LCI >= 0.5) of one design and the largest square in it (Liu 2006 sec.
    3.2.3, Fig. 25).

    Parameters
    ----------
    fb : FiveBar
        The design.
    step : float
        Raster step (non-dimensional, Liu's lengths sum to 3).

    Returns
    -------
    Figure
        The figure (not saved).
    """
    from mechopt.core import indices as ix

    u = usable_region(fb, step=step)
    g = gcw(fb, 0.5, u)
    side, cy = largest_square(g)
    X, Y = g.grid.points()
    loc = ix.local_indices(fb.jacobian(X, Y))
    fig = Figure(figsize=(15, 4), layout="constrained")
    ax = fig.add_subplot(1, 3, 1)
    _map(ax, fb, g, fb.lci(X, Y), f"Figs. 25/28: GCW (LCI >= 0.5), area {g.area:.4f}",
         INDEX_LABELS["lci"])
    ax.add_patch(Rectangle((-side / 2, cy - side / 2), side, side, fill=False, color="k", lw=1.2))
    _map(fig.add_subplot(1, 3, 2), fb, g, loc["d_max"], "Fig. 26(a): |D|max on the GCW",
         INDEX_LABELS["d_max"])
    _map(fig.add_subplot(1, 3, 3), fb, g, loc["d_min"], "Fig. 26(b): |D|min on the GCW",
         INDEX_LABELS["d_min"])
    return fig


#: Figs. 2-6: the atlas columns and their figure numbers
ATLAS_FIGURES = {"gci": "fig02", "mci": "fig03", "gvi_max": "fig04a", "gvi_min": "fig04b",
                 "gpi_max": "fig05a", "gpi_min": "fig05b", "gsi_max": "fig06a", "gsi_min": "fig06b",
                 "r_mic": "ref19_fig19"}
#: Figs. 7, 9, 11, 13, 15: each optimum region with the example design of its section
REGION_FIGURES = {"w-gci": ("fig07a", None), "w-gci-prime": ("fig07b", EXAMPLES["W-GCI (Fig. 8)"]),
                  "w-gci-gvi": ("fig09", EXAMPLES["W-GCI-GVI (Fig. 10)"]),
                  "w-gci-gpi": ("fig11", EXAMPLES["W-GCI-GPI (Fig. 12)"]),
                  "w-gci-gsi": ("fig13", EXAMPLES["W-GCI-GSI (Fig. 14)"]),
                  "all": ("fig15", EXAMPLES["All (Fig. 16)"])}


def atlas_figures(out, quick: bool = False):
    """Figs. 2-6 (atlases, polar means as in the paper) and the optimum regions of
    Figs. 7-15 with their example designs; writes ``atlas.csv`` and ``regions.csv``.

    Parameters
    ----------
    out : Path
        The folder.
    quick : bool
        Smaller runs (every row and file is still produced).
    """
    import pandas as pd

    from mechopt.run.atlas import compute_atlas, draw_atlas, plane_coordinates
    from mechopt.core.conditions import parse_condition
    from mechopt.problems.liu2006 import REGIONS, liu_indices

    table = compute_atlas(step=0.1 if quick else 0.01, quadrature="polar")
    _io.write_csv(table, out / "atlas.csv")
    for col, fig_id in ATLAS_FIGURES.items():
        _io.save_figure(draw_atlas(table, col, quadrature="polar"), out / f"{fig_id}_atlas_{col}.png")
    rows = []
    for name, (fig_id, key) in REGION_FIGURES.items():
        example = None if key is None else _lengths(key)
        where = " and ".join(f"{q} {op} {t}" for q, op, t in REGIONS[name])
        mask = parse_condition(where, names=tuple(table.columns)).evaluate(table)
        fig = draw_atlas(table, "gci", region=mask, where=where, quadrature="polar")
        if example is not None:
            s, t = plane_coordinates(*example)
            fig.axes[0].plot([s], [t], "r*", ms=12, label=f"example r = {example}")
            fig.axes[0].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.3), ncol=2)
        _io.save_figure(fig, out / f"{fig_id}_region_{name}.png")
        inside = ""
        if example is not None:
            # the paper's claim: its example design lies in the region (our indices, polar)
            ex = liu_indices([example[0]], [example[1]], [example[2]])
            ex = pd.DataFrame({**{k: v for k, v in ex.items()},
                               **dict(zip(("s", "t"), plane_coordinates(*example)))})
            inside = bool(parse_condition(where, names=tuple(ex.columns)).evaluate(ex)[0])
        rows.append({"region": name, "condition": where, "n_designs": int(mask.sum()),
                     "example": "" if example is None else "/".join(map(str, example)),
                     "example_inside": inside})
    _io.write_csv(pd.DataFrame(rows), out / "regions.csv")


def draw_all(out, quick: bool = False):
    """Write every figure of this module into ``out``.

    Parameters
    ----------
    out : Path
        The folder.
    quick : bool
        Smaller runs (every row and file is still produced).
    """
    out = Path(out)
    atlas_figures(out, quick)
    design_figures(out, quick)


def design_figures(out, quick: bool = False):
    """Figs. 8-28 of single designs (everything but the atlases and their regions).

    Parameters
    ----------
    out : Path
        The folder.
    quick : bool
        Smaller runs (every row and file is still produced).
    """
    out = Path(out)
    step = 0.02 if quick else 0.005
    r_opt, r20, r21 = _lengths(GCW_EXAMPLE), _lengths(FIG20), _lengths(FIGS21_22)
    opt = FiveBar(*r_opt)
    _io.save_figure(fig_examples(step), out / "figs08-16_examples.png")
    _io.save_figure(fig_lci_usable(opt, step, f"Figs. 17/23: LCI on the usable workspace, r = {r_opt}"),
                    out / "fig17_23_lci_usable.png")
    _io.save_figure(fig_usable_pair(step), out / "figs18-19_usable.png")
    _io.save_figure(fig_extremes_on_miw(FiveBar(*r20), ["lci"], step, f"Fig. 20, r = {r20}"),
                    out / "fig20_lci_miw.png")
    _io.save_figure(fig_extremes_on_miw(FiveBar(*r21), ["v_max", "tau_min", "d_max"], step,
                                        f"Figs. 21-22, r = {r21}"), out / "figs21-22_extremes_miw.png")
    _io.save_figure(fig_extremes_on_miw(opt, ["d_max", "d_min"], step, f"Fig. 24, r = {r_opt}"),
                    out / "fig24_d_miw.png")
    _io.save_figure(fig_gcw_and_square(opt, step), out / "figs25-28_gcw_square.png")
