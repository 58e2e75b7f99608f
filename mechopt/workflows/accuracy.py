"""The accuracy budget of a design made by ``mechopt design``: the proven worst-case
position error over its task, its Monte Carlo check and the error map.

:func:`load_design` rebuilds the chosen mechanism and its placed task from a design
folder (``design.json``, ``run.json``); :func:`accuracy` evaluates
:func:`mechopt.analysis.accuracy.pose_error` at the task samples of ``mechopt design``
(:func:`~mechopt.analysis.accuracy.task_points`), runs
:func:`~mechopt.analysis.accuracy.monte_carlo` there and, with ``figure``, draws the
bound over the task (:func:`plot_error_map`, colour bar in micrometres).
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from mechopt.analysis import accuracy as _acc

__all__ = ["load_design", "accuracy", "plot_error_map", "ACCURACY_KEYS"]

#: the keys of :func:`accuracy`'s result, in order (docs/outputs.md)
ACCURACY_KEYS = ("mechanism", "unit", "poses", "bound_um", "task_max_um", "linear_um", "remainder_um", "worst_x_um",
                 "worst_y_um", "at", "mc_max_um", "ratio", "samples", "draw", "seed", "unbounded_poses")


def _read_json(path: Path) -> dict:
    try:
        return json.loads(path.read_text())
    except OSError as exc:
        raise ValueError(f"cannot read {str(path)!r} ({exc.strerror}): is it a `mechopt design` folder?") from None
    except ValueError as exc:
        raise ValueError(f"unreadable {str(path)!r}: {' '.join(str(exc).split())}") from None


def _task_of(d: dict):
    from mechopt.analysis.task import Task

    return Task.from_dict(d)


def load_design(folder):
    """``(mech, task, spec, record)`` of the design folder ``folder``: the chosen
    mechanism (rebuilt by its design spec from ``design.json``'s variables and strokes,
    checked against its recorded ``repr``), the task placed where the design put it,
    in the task frame (``spec.to_mech`` maps it to the mechanism's), the design spec and
    the ``design.json`` record.

    Parameters
    ----------
    folder : str or Path
        A design run folder.

    Returns
    -------
    mech : PlanarMechanism
        The mechanism.
    task : mechopt.analysis.task.Task
        The placed task.
    spec : mechopt.core.design_spec.DesignSpec
        Its design spec.
    record : dict
        design.json.

    Raises
    ------
    ValueError
        One line, for a folder without a readable design, or a rebuilt mechanism that is not
        the recorded one.
    """
    from mechopt.mechanisms import design_spec

    folder = Path(folder)
    rec = _read_json(folder / "design.json")
    run = _read_json(folder / "run.json")
    try:
        spec = design_spec(rec["mechanism_name"])
        v = dict(rec["variables"])
        mode = v.pop("mode")
        kw = {"strokes": [tuple(s) for s in rec["strokes"]]} if spec.derived_strokes else {}
        mech = spec.build(v, mode, **kw)
        task = _task_of(run["design"]["task"])
        place = rec["task_placement"]
        task = task.moved_to(place["task_x"], place["task_y"])
    except (KeyError, TypeError) as exc:
        raise ValueError(f"{str(folder)!r} is not a complete `mechopt design` folder (missing {exc})") from None
    if repr(mech) != rec.get("repr"):
        raise ValueError(f"design.json in {str(folder)!r}: the rebuilt mechanism {mech!r} is not the recorded "
                         f"{rec.get('repr')!r}")
    return mech, task, spec, rec


def accuracy(folder, model, samples: int = 1000, seed: int = 1, draw: str = "vertices", figure=None,
             n_boundary: int = 192, n_interior: int = 13) -> dict:
    """The accuracy budget of the design in ``folder`` under ``model``.

    Parameters
    ----------
    folder : path
        A ``mechopt design`` output folder.
    model : ErrorModel
        The tolerances (:class:`mechopt.analysis.accuracy.ErrorModel`).
    samples : int
        Monte Carlo draws per task sample (exact perturbed forward kinematics).
    seed : int
        Seed of the draws.
    draw : {"vertices", "uniform"}
        Where the draws lie in the tolerance box (:func:`~mechopt.analysis.accuracy.monte_carlo`).
    figure : path, optional
        Where to write the error map (:func:`plot_error_map`).
    n_boundary, n_interior : int
        The task samples (those of one evaluation of ``mechopt design``).

    Returns
    -------
    dict
        The keys :data:`ACCURACY_KEYS`: the largest proven bound over the samples and its
        parts [um], ``task_max_um`` the maximum over the task refined from the samples by
        zooming (:func:`~mechopt.analysis.accuracy.task_max_error`, what ``--max-error``
        checks) (``linear_um``, ``remainder_um`` at that pose; ``worst_x_um``,
        ``worst_y_um`` the largest first-order error along each axis), ``at`` the task
        point [unit] of the largest bound, the Monte Carlo maximum ``mc_max_um`` and
        ``ratio`` = bound / Monte Carlo maximum, ``unbounded_poses`` (samples without a
        proof: unreachable or too near a type-II singularity).
    """
    from mechopt.core import validation as _v

    mech, task, spec, rec = load_design(folder)
    unit = task.unit
    um = _acc.UM_PER_UNIT[unit]
    from mechopt.analysis.sampling import Sampling, samples as task_samples

    s = task_samples(task, Sampling(_v.integer("n_boundary", n_boundary, 8), _v.integer("n_interior", n_interior, 2)))
    tx, ty = s["allx"], s["ally"]
    mx, my = spec.to_mech(mech, tx, ty)
    pe = _acc.pose_error(mech, model, mx, my, unit)
    b = np.where(np.isnan(pe["bound"]), np.inf, pe["bound"])
    top = _acc.task_max_error(mech, model, s, lambda x, y: spec.to_mech(mech, x, y), unit, vals=-b)
    i = int(np.argmax(b))
    mc = _acc.monte_carlo(mech, model, mx, my, samples, unit, seed, draw)
    mc_max = float(np.nanmax(mc)) if np.any(np.isfinite(mc)) else math.nan
    out = {"mechanism": repr(mech), "unit": unit, "poses": int(tx.size), "bound_um": float(b[i] * um),
           "task_max_um": float(top * um),
           "linear_um": float(pe["linear"][i] * um), "remainder_um": float(pe["remainder"][i] * um),
           "worst_x_um": float(np.nanmax(pe["x"]) * um), "worst_y_um": float(np.nanmax(pe["y"]) * um),
           "at": [float(tx[i]), float(ty[i])], "mc_max_um": mc_max * um,
           "ratio": float(b[i] / mc_max) if mc_max > 0 else math.nan, "samples": int(samples), "draw": draw,
           "seed": int(seed), "unbounded_poses": int(np.count_nonzero(~np.isfinite(b)))}
    if figure is not None:
        from mechopt.run import io as _io

        _io.save_figure(plot_error_map(mech, task, spec, model, rec), figure)
    return {k: out[k] for k in ACCURACY_KEYS}


def plot_error_map(mech, task, spec, model, rec=None, n: int = 81):
    """The proven worst-case position error over the task [um]: the bound of
    :func:`~mechopt.analysis.accuracy.pose_error` on an ``n x n`` grid over the task's box
    (cells outside the task left blank; a point task: its points), the task's outline
    and the pose of the largest bound; returns the matplotlib figure.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism.
    task : mechopt.analysis.task.Task
        The placed task.
    spec : mechopt.core.design_spec.DesignSpec
        Its design spec.
    model : object
        The error model (:mod:`mechopt.analysis.accuracy`).
    rec : dict, optional
        design.json (for the title).
    n : int
        Grid nodes per side.

    Returns
    -------
    Figure
        The figure.
    """
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.figure import Figure

    unit = task.unit
    um = _acc.UM_PER_UNIT[unit]
    fig = Figure(figsize=(6.4, 4.8))
    ax = fig.add_subplot(111)
    if task.is_region:
        x0, x1, y0, y1 = task.bbox
        X, Y = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
        mx, my = spec.to_mech(mech, X, Y)
        Z = _acc.pose_error(mech, model, mx, my, unit)["bound"] * um
        Z = np.ma.masked_where(~task.contains(X, Y) | ~np.isfinite(Z), Z)
        art = ax.pcolormesh(X, Y, Z, shading="auto", cmap="viridis")
        ox, oy = task.outline()
        ax.plot(ox, oy, "k-", lw=1)
        k = np.unravel_index(np.argmax(Z.filled(-np.inf)), Z.shape) if Z.count() else None
        if k is not None:
            ax.plot(X[k], Y[k], "rx", ms=8, label=f"max {Z[k]:.3g} um")
            ax.legend(loc="upper right", fontsize=8)
    else:
        px, py = task.pts[:, 0], task.pts[:, 1]
        mx, my = spec.to_mech(mech, px, py)
        art = ax.scatter(px, py, c=_acc.pose_error(mech, model, mx, my, unit)["bound"] * um, cmap="viridis", s=12)
    fig.colorbar(art, ax=ax, shrink=0.8, label="worst-case position error bound [um]")
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{unit}]")
    ax.set_ylabel(f"y [{unit}]")
    name = rec["mechanism_name"] if rec else type(mech).__name__
    ax.set_title(f"{name}: proven position error over the task", fontsize=10)
    return fig
