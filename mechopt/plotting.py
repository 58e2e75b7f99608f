"""Figures of runs: Pareto fronts, convergence curves, weighting sweeps.

Figures are built with :class:`matplotlib.figure.Figure` (no global pyplot
state, no display needed) and saved through :func:`mechopt.io.save_figure`.
"""
from __future__ import annotations

from matplotlib.figure import Figure

__all__ = ["plot_front", "plot_sweep"]


def _label(ob):
    return f"{ob.name} [{ob.unit}] ({'max' if ob.sense < 0 else 'min'})"


def plot_front(problem, front, history) -> Figure:
    """The front of a 2-3 objective run (pairs of objectives for more), or the
    best-so-far curve of a single-objective run."""
    obs = problem.objectives
    if len(obs) == 1:
        fig = Figure(figsize=(5, 3.5))
        ax = fig.add_subplot()
        ax.plot(history["generation"], history[f"best_{obs[0].name}"], marker="o")
        ax.set_xlabel("generation")
        ax.set_ylabel(_label(obs[0]))
        ax.set_title(problem.name)
        return fig
    pairs = [(0, 1)] if len(obs) == 2 else [(i, j) for i in range(len(obs)) for j in range(i + 1, len(obs))][:6]
    fig = Figure(figsize=(4.5 * min(len(pairs), 3), 3.8 * ((len(pairs) + 2) // 3)))
    for k, (i, j) in enumerate(pairs):
        ax = fig.add_subplot((len(pairs) + 2) // 3, min(len(pairs), 3), k + 1)
        ax.scatter(front[obs[i].name], front[obs[j].name], s=14)
        ax.set_xlabel(_label(obs[i]))
        ax.set_ylabel(_label(obs[j]))
    fig.suptitle(f"{problem.name}: {len(front)} non-dominated designs")
    fig.tight_layout()
    return fig


def plot_sweep(problem, front, sweep) -> Figure:
    """Weighted-sum optima (labelled by weight) over the NSGA-II front."""
    a, b = problem.objectives[:2]
    fig = Figure(figsize=(5.5, 4))
    ax = fig.add_subplot()
    ax.scatter(front[a.name], front[b.name], s=12, color="0.6", label="NSGA-II front")
    ax.scatter(sweep[a.name], sweep[b.name], s=30, color="C3", marker="x", label="weighted-sum optima")
    for rec in sweep.itertuples():
        ax.annotate(f"{rec.weight:g}", (getattr(rec, a.name), getattr(rec, b.name)), fontsize=7,
                    xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel(_label(a))
    ax.set_ylabel(_label(b))
    ax.legend(fontsize=8)
    ax.set_title(f"{problem.name}: weighting sweep")
    return fig
