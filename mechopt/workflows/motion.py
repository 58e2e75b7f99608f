"""``mechopt motion DESIGN_DIR``: a design of ``mechopt design`` run along a timed motion.

Reads the chosen design (``design.json``: mechanism, lengths, mode, strokes, task
placement) and its task (``run.json``, ``design.task``), builds the mechanism, times a
path (:mod:`mechopt.core.motion`: the task's pick-and-place cycle, a straight segment or
a CSV polyline) within the cycle time, gives every body its masses
(:func:`mechopt.analysis.dynamics.mass_model`: the stated law, or a JSON file) and
computes each actuator's position, rate, acceleration, effort and power
(:func:`mechopt.analysis.dynamics.motion_efforts`). Writes, all after the computation
and each file under a temporary name then renamed: ``motion.csv``, ``bodies.json``,
``motion.json`` (the extremes per actuator and the settings) and ``motion.png`` (effort
and rate of each actuator over time, with the given limits drawn). docs/outputs.md lists
every column and key with its unit.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from mechopt.analysis import dynamics as _dyn
from mechopt.core import motion as _mo
from mechopt.core import validation as _v

__all__ = ["load_design", "design_motion", "run_motion", "plot_motion", "PATH_KINDS"]

#: ``--path``: the task's pick-and-place cycle, ``segment:x0,y0,x1,y1`` [unit] or ``csv:FILE``
PATH_KINDS = ("pick-place", "segment:X0,Y0,X1,Y1", "csv:FILE")


def _read_json(path):
    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ValueError(f"{str(path)!r} is not a readable JSON file: {getattr(e, 'strerror', None) or e}") from None


def _task(task: dict, placement: dict, unit: str):
    """The task of ``run.json`` (:class:`mechopt.analysis.task.Task`) at its placement."""
    from mechopt.analysis.task import Task

    try:
        if task["kind"] == "circle":
            t = Task.circle(task["radius"], task["center"], unit)
        elif task["kind"] == "points":
            t = Task.points(task["points"], unit)
        else:
            t = Task.polygon(task["vertices"], unit)
    except (KeyError, TypeError):
        raise ValueError("run.json's design.task is not a task (kind, vertices, center/radius or points)") from None
    return t.moved_to(placement["task_x"], placement["task_y"])


def load_design(folder):
    """``(spec, mech, unit, length_unit, task)`` of the design in ``folder``: its design
    specification, the mechanism, the length unit's name and metres per unit, and the
    placed task (:class:`mechopt.analysis.task.Task`, None without run.json).

    Parameters
    ----------
    folder : str or Path
        A design run folder.

    Returns
    -------
    spec : mechopt.core.design_spec.DesignSpec
        Its design spec.
    mech : PlanarMechanism
        The mechanism [unit].
    unit : str
        The length unit's name.
    length_unit : float
        Metres per unit [m/L].
    task : mechopt.analysis.task.Task or None
        The placed task.

    Raises
    ------
    ValueError
        One line, for a folder without a readable design.
    """
    from mechopt.analysis.task import UNITS
    from mechopt.mechanisms import registry

    folder = Path(folder)
    if not (folder / "design.json").is_file():
        raise ValueError(f"{str(folder)!r} holds no design.json (a folder written by mechopt design)")
    rec = _read_json(folder / "design.json")
    info = _read_json(folder / "run.json") if (folder / "run.json").is_file() else {}
    try:
        name, unit = rec["mechanism_name"], rec["unit"]
        variables, placement = rec["variables"], rec["task_placement"]
    except (KeyError, TypeError):
        raise ValueError(f"{str(folder / 'design.json')!r} lacks mechanism_name, unit, variables "
                         "or task_placement") from None
    cls = registry().get(name)
    if cls is None or cls.design_spec is None:
        raise ValueError(f"unknown mechanism {name!r} in design.json")
    spec = cls.design_spec()
    strokes = rec.get("strokes")
    mech = spec.build(variables, variables["mode"], strokes=strokes)
    task = (info.get("design") or {}).get("task")
    return spec, mech, unit, UNITS[unit], (_task(task, placement, unit) if task else None)


def design_motion(path, task, cycle_time, profile="cycloidal", samples=401, **shape):
    """The timed motion [unit] of a ``--path`` (:data:`PATH_KINDS`) for the placed ``task``
    (the pick-and-place cycle within it, as the ``--max-torque`` requirement runs it).

    Parameters
    ----------
    path : str
        One of :data:`PATH_KINDS`.
    task : mechopt.analysis.task.Task
        The placed task.
    cycle_time : float
        Duration [s].
    profile : str
        The profile (:func:`mechopt.core.motion.profile`).
    samples : int
        Time samples.
    **shape : 
        ``accel_fraction``, ``jerk_fraction``.

    Returns
    -------
    dict
        The timed motion (:func:`mechopt.core.motion.timed_motion`).

    Raises
    ------
    ValueError
        One line, for an unknown path or invalid settings.
    """
    if path == "pick-place":
        if task is None or not task.is_region:
            raise ValueError("the pick-and-place cycle needs a task region (run.json of the design)")
        pieces = _mo.pick_and_place_path(task.bbox, task.contains)
    elif isinstance(path, str) and path.startswith("segment:"):
        v = [float(s) for s in path[len("segment:"):].split(",")] if path[8:] else []
        if len(v) != 4:
            raise ValueError(f"--path segment:X0,Y0,X1,Y1 needs four numbers, got {path!r}")
        pieces = _mo.segment_path(v[:2], v[2:])
    elif isinstance(path, str) and path.startswith("csv:"):
        pieces = _mo.polyline_path(_mo.read_path_csv(path[4:]))
    else:
        raise ValueError(f"--path must be one of {', '.join(PATH_KINDS)}, got {path!r}")
    return _mo.timed_motion(pieces, cycle_time, profile, samples, **shape)


def _limits(name, v):
    """``(l1, l2)`` from one positive number (both actuators) or two; None stays None."""
    if v is None:
        return None
    if isinstance(v, str):
        v = v.split(",")
    vals = [v] if np.ndim(v) == 0 else list(v)
    vals = _v.finite_numbers(name, vals * 2 if len(vals) == 1 else vals, 2, "one or two positive numbers")
    if not all(x > 0 for x in vals):
        raise ValueError(f"{name} must be one or two positive numbers, got {_v.show(v)}")
    return vals


def plot_motion(table, summary, joint_names, angular, max_speed=None, max_torque=None, rms_limit=None):
    """Effort and rate of each actuator over the motion (one column per actuator), the
    limits drawn as dashed lines; units on every axis.

    Parameters
    ----------
    table : DataFrame
        motion.csv.
    summary : dict
        motion.json.
    joint_names : tuple of str
        The actuators' names.
    angular : bool
        Cranks (N m, rad/s) or sliders (N, L/s).
    max_speed, max_torque, rms_limit : float, optional
        Limits to draw.

    Returns
    -------
    Figure
        The figure.
    """
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10, 6), layout="constrained")
    axes = fig.subplots(2, 2, sharex=True)
    t = table["t"]
    tu, ru = ("N m", "rad/s") if angular else ("N", "m/s")
    for i in (0, 1):
        a, b = axes[0, i], axes[1, i]
        a.plot(t, table[f"tau_{i + 1}"], color="tab:blue")
        if max_torque is not None:
            for sgn in (1, -1):
                a.axhline(sgn * max_torque[i], color="tab:red", ls="--", lw=1,
                          label="peak limit" if sgn > 0 else None)
        if rms_limit is not None:
            a.axhline(rms_limit[i], color="tab:orange", ls=":", lw=1, label="RMS limit")
        a.axhline(summary["tau_rms"][i], color="tab:green", ls="-.", lw=1, label="RMS")
        a.set_ylabel(f"effort {joint_names[i]} [{tu}]")
        a.set_title(f"actuator {i + 1} ({joint_names[i]}): peak {summary['tau_peak'][i]:.4g} {tu}, "
                    f"RMS {summary['tau_rms'][i]:.4g} {tu}", fontsize=9)
        a.legend(fontsize=8, loc="best")
        b.plot(t, table[f"qd_{i + 1}"], color="tab:purple")
        if max_speed is not None:
            for sgn in (1, -1):
                b.axhline(sgn * max_speed[i], color="tab:red", ls="--", lw=1,
                          label="speed limit" if sgn > 0 else None)
            b.legend(fontsize=8, loc="best")
        b.set_ylabel(f"rate {joint_names[i]} [{ru}]")
        b.set_xlabel("time [s]")
    return fig


def run_motion(folder, out=None, path="pick-place", profile="cycloidal", cycle_time=0.5,
               samples=401, masses=None, gravity="down", max_speed=None, max_torque=None,
               rms_limit=None, accel_fraction=1.0 / 3.0, jerk_fraction=0.25, actuator=None) -> dict:
    """Compute and write the motion of the design in ``folder`` (module docstring) into
    ``out`` (default ``folder``). Returns the summary (``motion.json``). ``actuator``: a
    datasheet (:func:`mechopt.core.actuators.read_motors`): its reflected rotor inertia
    ``I_r N^2`` replaces the mass model's, and its output-side max speed, peak and rated
    torque are the limits not given.

    Parameters
    ----------
    folder : str or Path
        A design run folder (design.json, run.json).
    out : str or Path, optional
        The output folder (default: ``folder``).
    path : str
        One of :data:`PATH_KINDS` (coordinates [unit of the design]).
    profile : str
        The timing of each piece, one of :data:`mechopt.core.motion.PROFILES`.
    cycle_time : float
        Duration of the whole path [s].
    samples : int
        Time samples along the motion.
    masses : str or Path, optional
        A mass model JSON file (:func:`mechopt.analysis.dynamics.load_mass_model`);
        default :func:`mechopt.analysis.dynamics.mass_model`.
    gravity : str or tuple
        ``"down"``, ``"off"``, ``"gx,gy"`` or a pair [m/s^2]
        (:func:`mechopt.analysis.dynamics.parse_gravity`).
    max_speed : float or (float, float), optional
        Actuator rate limit(s) drawn and checked [rad/s or m/s].
    max_torque : float or (float, float), optional
        Peak effort limit(s) drawn and checked [N m or N].
    rms_limit : float or (float, float), optional
        RMS effort limit(s) drawn and checked [N m or N].
    accel_fraction : float
        Trapezoidal and s-curve profiles: fraction of each piece's time spent
        accelerating, in (0, 0.5].
    jerk_fraction : float
        S-curve profile: fraction of the acceleration time at constant jerk, in [0, 0.5].
    actuator : str, Path, dict or list, optional
        The motors' datasheet: inline, a .json/.toml file or the same as Python objects
        (:func:`mechopt.core.actuators.read_motors`).

    Returns
    -------
    dict
        The summary written to ``motion.json``: the extremes per actuator, the settings,
        the limits and ``within_limits``.
    """
    from mechopt.run import io

    _v.choice("profile", profile, _mo.PROFILES)
    spec, mech, unit, length_unit, task = load_design(folder)
    shape = {} if profile == "cycloidal" else {"accel_fraction": accel_fraction}
    if profile == "s-curve":
        shape["jerk_fraction"] = jerk_fraction
    motion = design_motion(path, task, cycle_time, profile, samples, **shape)
    model = (_dyn.load_mass_model(mech, masses, length_unit) if masses is not None
             else _dyn.mass_model(mech, length_unit=length_unit))
    if actuator is not None:
        from dataclasses import replace

        from mechopt.core.actuators import read_motors

        motors = read_motors(actuator)
        model = replace(model, actuator_inertia=tuple(m.reflected_inertia for m in motors))
        max_speed = [m.speed for m in motors] if max_speed is None else max_speed
        max_torque = [m.peak for m in motors] if max_torque is None else max_torque
        rms_limit = [m.torque for m in motors] if rms_limit is None else rms_limit
    grav = _dyn.parse_gravity(gravity, model.g)
    table, summary = _dyn.motion_efforts(mech, motion, model, grav, length_unit,
                                         to_mech=lambda x, y: spec.to_mech(mech, x, y))
    ms, mt, mr = _limits("max_speed", max_speed), _limits("max_torque", max_torque), _limits("rms_limit", rms_limit)
    # the table's positions in metres like every other column
    table["x"], table["y"] = table["x"] * length_unit, table["y"] * length_unit
    summary.update(mechanism=spec.name, unit=unit, path=path, profile=profile, samples=int(samples),
                   gravity=list(grav), mass_source=model.source,
                   limits={"max_speed": ms, "max_torque": mt, "rms_limit": mr},
                   within_limits=bool((ms is None or all(p <= l for p, l in zip(summary["qd_peak"], ms)))
                                      and (mt is None or all(p <= l for p, l in zip(summary["tau_peak"], mt)))
                                      and (mr is None or all(p <= l for p, l in zip(summary["tau_rms"], mr)))))
    fig = plot_motion(table, summary, mech.joint_names, spec.angular, ms, mt, mr)
    out = io.prepare_out_dir(folder if out is None else out)
    import pandas as pd

    io.write_csv(pd.DataFrame(table), out / "motion.csv")
    io.write_json(model.as_dict(), out / "bodies.json")
    io.write_json(summary, out / "motion.json")
    io.save_figure(fig, out / "motion.png")
    return summary
