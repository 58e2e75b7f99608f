"""Figures of runs: Pareto fronts, convergence curves, weighting sweeps; a design's
bodies, keep-out zone and worst-clearance pose (:func:`draw_collisions`).

Figures are built with :class:`matplotlib.figure.Figure` (no global pyplot
state, no display needed) and saved through :func:`mechopt.run.io.save_figure`.
A run without any feasible design has no front: its figure is the final
population in design space, coloured by constraint violation
(:func:`plot_population`).
"""
from __future__ import annotations

from matplotlib.figure import Figure

import numpy as np

__all__ = ["plot_front", "plot_sweep", "plot_population", "INDEX_LABELS", "workspace_axes",
           "labelled_colorbar", "draw_collisions", "BODY_COLOURS", "WORST_STYLES"]

#: axis and colour-bar labels of the local indices (Liu 2006 eq. 2, 10, 13, 18), with
#: units for a mechanism in length unit L and angular joints: speeds per unit joint
#: rate, forces per unit joint torque, compliance with unit actuator stiffness
INDEX_LABELS = {
    "lci": "LCI = 1/kappa [-]",
    "tqi": "TQI [-]",
    "v_max": "|V|max [L/rad]", "v_min": "|V|min [L/rad]",
    "tau_max": "|tau|max [1/L]", "tau_min": "|tau|min [1/L]",
    "d_max": "|D|max [L^2]", "d_min": "|D|min [L^2]",
}


def workspace_axes(ax, unit: str = "L"):
    """Label an axes of the base frame: x, y in ``unit``, equal aspect (the one style
    of every workspace map).

    Parameters
    ----------
    ax : Axes
        The axes.
    unit : str
        The length unit.
    """
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    ax.set_aspect("equal")


def labelled_colorbar(fig, mappable, ax, label: str, **kw):
    """A colour bar with its quantity and unit (``INDEX_LABELS`` for local indices).

    Parameters
    ----------
    fig : Figure
        The figure.
    mappable : matplotlib.cm.ScalarMappable
        What is coloured.
    ax : Axes
        The axes.
    label : str
        The quantity's name (or a local index's).
    **kw : 
        Passed to ``fig.colorbar``.

    Returns
    -------
    matplotlib.colorbar.Colorbar
        The colour bar.
    """
    cb = fig.colorbar(mappable, ax=ax, **kw)
    cb.set_label(label)
    return cb


def _plain_ticks(ax):
    """Tick labels as plain numbers: no offset (``1e-5+1.329``) nor scientific factor
    above the axis; a reader reads the value at a tick directly."""
    for axis in (ax.xaxis, ax.yaxis):
        fmt = axis.get_major_formatter()
        if hasattr(fmt, "set_useOffset"):
            fmt.set_useOffset(False)


def _single_point(ax, x, y):
    """A front of one design: a large marker labelled with its value, and axes of
    +-5 % about it (a one-point autoscale is degenerate)."""
    ax.scatter([x], [y], s=60, color="C0", zorder=3)
    ax.annotate(f"({x:.6g}, {y:.6g})", (x, y), xytext=(6, 6), textcoords="offset points", fontsize=8)
    _widen(ax, [x], [y])


def _widen(ax, xs, ys):
    """Axes of +-5 % about a coordinate whose values all coincide to 1e-4 of their size
    (one design, or a sweep whose optima are one point up to the search's resolution),
    where an autoscale would be degenerate or spread a single point over the axes."""
    for v, setter in ((xs, ax.set_xlim), (ys, ax.set_ylim)):
        v = np.asarray(v, float)
        v = v[np.isfinite(v)]
        if v.size and np.ptp(v) <= 1e-4 * np.abs(v).max():
            c = 0.5 * (v.min() + v.max())
            h = 0.05 * abs(c) if c else 1.0
            setter(c - h, c + h)


def _label(ob):
    return f"{ob.name} [{ob.unit}] ({'max' if ob.sense < 0 else 'min'})"


def plot_front(problem, front, history, population=None, info=None, chosen=None) -> Figure:
    """The front of a 2-3 objective run (pairs of objectives for more), or the
    best-so-far curve of a single-objective run; with an empty front (no feasible
    design) and the final ``population``, :func:`plot_population` instead. ``chosen``
    (a row index of ``front``) is marked and labelled.

    Parameters
    ----------
    problem : mechopt.run.problem.MechoptProblem
        The problem.
    front : DataFrame
        front.csv.
    history : DataFrame
        history.csv.
    population : DataFrame, optional
        The final population.
    info : dict, optional
        run.json (for the title).
    chosen : int, optional
        A row of ``front`` to mark.

    Returns
    -------
    Figure
        The figure.
    """
    obs = problem.objectives
    if len(front) == 0 and population is not None:
        n_eval = (info or {}).get("evaluations")
        within = f" in {n_eval} evaluations" if n_eval is not None else ""
        return plot_population(problem, population, f"{problem.name}: no feasible design{within}")
    if len(obs) == 1:
        fig = Figure(figsize=(5, 3.5))
        ax = fig.add_subplot()
        ax.plot(history["generation"], history[f"best_{obs[0].name}"], marker="o")
        ax.set_xlabel("generation [-]")
        from matplotlib.ticker import MaxNLocator

        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_ylabel(_label(obs[0]))
        ax.set_title(problem.name)
        _plain_ticks(ax)
        return fig
    pairs = [(0, 1)] if len(obs) == 2 else [(i, j) for i in range(len(obs)) for j in range(i + 1, len(obs))][:6]
    fig = Figure(figsize=(4.5 * min(len(pairs), 3), 3.8 * ((len(pairs) + 2) // 3)))
    for k, (i, j) in enumerate(pairs):
        ax = fig.add_subplot((len(pairs) + 2) // 3, min(len(pairs), 3), k + 1)
        if len(front) == 1:
            _single_point(ax, float(front[obs[i].name].iloc[0]), float(front[obs[j].name].iloc[0]))
        else:
            ax.scatter(front[obs[i].name], front[obs[j].name], s=14)
        if chosen is not None:
            ax.scatter([front[obs[i].name].iloc[chosen]], [front[obs[j].name].iloc[chosen]], s=90,
                       facecolors="none", edgecolors="C3", linewidths=1.5, label="chosen design")
            ax.legend(fontsize=7)
        ax.set_xlabel(_label(obs[i]))
        ax.set_ylabel(_label(obs[j]))
        _plain_ticks(ax)
    many = f"{len(front)} non-dominated designs" if len(front) != 1 else "one non-dominated design"
    fig.suptitle(f"{problem.name}: {many}")
    fig.tight_layout()
    return fig


def plot_sweep(problem, front, sweep, population=None, info=None) -> Figure:
    """Weighted-sum optima (labelled by weight) over the NSGA-II front. Weights
    without a feasible optimum (``feasible`` False in ``sweep``) are listed, not
    drawn; when nothing at all is feasible, the runs' final ``population``
    coloured by constraint violation (:func:`plot_population`).

    Parameters
    ----------
    problem : mechopt.run.problem.MechoptProblem
        The problem.
    front : DataFrame
        The NSGA-II front.
    sweep : DataFrame
        sweep.csv.
    population : DataFrame, optional
        The final populations.
    info : dict, optional
        run.json.

    Returns
    -------
    Figure
        The figure.
    """
    a, b = problem.objectives[:2]
    ok = sweep["feasible"].astype(bool) if "feasible" in sweep else np.ones(len(sweep), bool)
    if len(front) == 0 and not ok.any() and population is not None:
        n_eval = (info or {}).get("evaluations")
        within = f" in {n_eval} evaluations" if n_eval is not None else ""
        return plot_population(problem, population,
                               f"{problem.name} weighting sweep: no feasible design{within}")
    fig = Figure(figsize=(5.5, 4))
    ax = fig.add_subplot()
    ax.scatter(front[a.name].astype(float), front[b.name].astype(float), s=12, color="0.6",
               label="NSGA-II front")
    best = sweep[ok]
    ax.scatter(best[a.name].astype(float), best[b.name].astype(float), s=30, color="C3", marker="x",
               label="weighted-sum optima")
    for w, x, y in zip(best["weight"], best[a.name].astype(float), best[b.name].astype(float)):
        if np.isfinite(x) and np.isfinite(y):
            ax.annotate(f"{w:g}", (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    _widen(ax, np.r_[front[a.name].astype(float), best[a.name].astype(float)],
           np.r_[front[b.name].astype(float), best[b.name].astype(float)])
    ax.set_xlabel(_label(a))
    ax.set_ylabel(_label(b))
    ax.legend(fontsize=8)
    _plain_ticks(ax)
    title = f"{problem.name}: weighting sweep"
    if not ok.all():
        title += "\nno feasible design for w = " + ", ".join(f"{w:g}" for w in sweep["weight"][~ok])
    ax.set_title(title, fontsize=9 if not ok.all() else None)
    return fig


def plot_population(problem, population, title=None) -> Figure:
    """The final population of a run without a feasible design, in design space
    (first two variables; a single variable against the violation), coloured by
    its constraint violation (``violation`` = sum of max(0, g)); the
    least-violating design is starred.

    Parameters
    ----------
    problem : mechopt.run.problem.MechoptProblem
        The problem.
    population : DataFrame
        The final population.
    title : str, optional
        The title.

    Returns
    -------
    Figure
        The figure.
    """
    from matplotlib.colors import LogNorm, Normalize

    names = list(problem.var_names)
    v = population["violation"].to_numpy(float)
    finite = np.isfinite(v)
    lo, hi = (v[finite].min(), v[finite].max()) if finite.any() else (0.0, 1.0)
    norm = LogNorm(lo, hi) if lo > 0 and hi > 100 * lo else Normalize(lo, hi if hi > lo else lo + 1.0)
    x = population[names[0]].to_numpy(float)
    y = population[names[1]].to_numpy(float) if len(names) > 1 else v
    fig = Figure(figsize=(5.8, 4))
    ax = fig.add_subplot()
    sc = ax.scatter(x, y, c=np.where(finite, v, hi), cmap="viridis_r", norm=norm, s=22,
                    edgecolors="0.3", linewidths=0.4)
    fig.colorbar(sc, ax=ax, label="constraint violation (sum of max(0, g))")
    if finite.any():
        k = int(np.argmin(np.where(finite, v, np.inf)))
        ax.scatter([x[k]], [y[k]], marker="*", s=160, color="C3", edgecolors="k", linewidths=0.5,
                   label=f"least violation {v[k]:.3g}", zorder=3)
        ax.legend(fontsize=8)
    ax.set_xlabel(names[0])
    ax.set_ylabel(names[1] if len(names) > 1 else "constraint violation (sum of max(0, g)) [-]")
    if len(names) == 1 and isinstance(norm, LogNorm):
        ax.set_yscale("log")
    if len(names) > 1:
        ax.set_xlim(problem.xl[0], problem.xu[0])
        ax.set_ylim(problem.xl[1], problem.xu[1])
    ax.set_title(title or f"{problem.name}: population, no feasible design", fontsize=9)
    return fig


#: fill colours of the bodies by kind (:data:`mechopt.core.bodies.KINDS`)
BODY_COLOURS = {"housing": "#7f7f7f", "guide": "#b0b0b0", "carriage": "#c49a6c", "proximal": "#4a7fb5",
                "distal": "#4a7fb5", "platform": "#4a7fb5"}
#: the styles of the worst poses of :func:`draw_collisions`: outline colour, line style
WORST_STYLES = {"clearance": ("tab:orange", "--"), "keep_out": ("tab:pink", ":")}


def draw_collisions(ax, ctx, pose, unit: str = "L") -> list:
    """Draw on ``ax`` the bodies of a design as capsules with their widths (housings as
    discs, carriages and guides as their capsules), filled, at the platform pose
    ``pose = (x, y)`` [unit]; its ``--keep-out`` zone hatched (a half-plane across the
    view); and its worst poses in
    outline (:data:`WORST_STYLES`): where the clearance between bodies that share no
    joint is smallest over the task (the two bodies of that pair drawn heavier, the
    platform there marked x) and, with a zone, where a body comes closest to it, each
    with its value in the legend.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    ctx : mechopt.analysis.design_context.DesignContext
        The design's evaluation (:mod:`mechopt.requirements.collisions`: the bodies, the
        zone, :func:`~mechopt.requirements.collisions.worst_pose`).
    pose : tuple of float
        The platform ``(x, y)`` of the filled drawing [unit, task frame].
    unit : str
        The length unit of the legend.

    Returns
    -------
    list
        The legend handles (bodies, zone, worst poses).
    """
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    from mechopt.core.bodies import capsule_outline
    from mechopt.requirements import collisions as _rc

    col = _rc.collisions(ctx)
    handles = []
    zone = _rc.zone_of(ctx)
    if zone is not None:
        style = dict(facecolor=(0.84, 0.15, 0.16, 0.08), edgecolor="tab:red", hatch="///", lw=1.0)
        if zone.kind in ("above", "below"):  # the half-plane across the whole view (no autoscale)
            from matplotlib.patches import Rectangle

            reach = 10.0 * (np.abs(ax.dataLim.get_points()).max() + abs(zone.level) + ctx.diameter)
            far = zone.level + (reach if zone.kind == "above" else -reach)  # beyond any view of the design
            ax.add_artist(Rectangle((0.0, zone.level), 1.0, far - zone.level, transform=ax.get_yaxis_transform(),
                                    zorder=1, **style))
        else:
            ax.fill(*zone.outline(None), zorder=1, **style)
        handles.append(Patch(**style, label=f"keep-out zone: {zone.label}"))

    def bodies_at(x, y):
        return [b for b in col.bodies(np.array([float(x)]), np.array([float(y)]))
                if np.isfinite([b.x0[0], b.y0[0], b.x1[0], b.y1[0]]).all()]

    kinds = []
    for b in bodies_at(*pose):
        cx, cy = capsule_outline(b.x0[0], b.y0[0], b.x1[0], b.y1[0], b.width)
        ax.fill(cx, cy, facecolor=BODY_COLOURS[b.kind], alpha=0.35, edgecolor=BODY_COLOURS[b.kind], lw=0.8,
                zorder=2)
        kinds.append(b.kind)
    for kind in dict.fromkeys(kinds):
        label = {"proximal": "links (capsules)", "distal": "links (capsules)", "platform": "links (capsules)",
                 "housing": "motor housings", "guide": "guides", "carriage": "carriages"}[kind]
        if label not in [h.get_label() for h in handles]:
            handles.append(Patch(facecolor=BODY_COLOURS[kind], alpha=0.35, edgecolor=BODY_COLOURS[kind], label=label))
    for what, text in (("clearance", "worst clearance"), ("keep_out", "closest to the keep-out zone")):
        w = _rc.worst_pose(ctx, what)
        if w is None:
            continue
        colour, ls = WORST_STYLES[what]
        which = set(w["which"]) if isinstance(w["which"], tuple) else {w["which"]}
        for b in bodies_at(w["x"], w["y"]):
            cx, cy = capsule_outline(b.x0[0], b.y0[0], b.x1[0], b.y1[0], b.width)
            ax.plot(cx, cy, color=colour, ls=ls, lw=1.8 if b.name in which else 0.8, zorder=4)
        ax.plot([w["x"]], [w["y"]], "x", color=colour, ms=7, zorder=4)
        names = " - ".join(w["which"]) if isinstance(w["which"], tuple) else w["which"]
        handles.append(Line2D([], [], color=colour, ls=ls, lw=1.8, marker="x",
                              label=f"{text}: {w['value']:.5g} {unit} ({names})"))
    return handles
