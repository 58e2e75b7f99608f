"""Dynamics along the pick-and-place cycle: the requirements ``--max-torque`` (peak
actuator effort) and ``--max-rms-torque`` (RMS effort, the motor's rated torque) with
``--cycle-time``, and the objectives ``peak-torque``, ``rms-torque`` and ``moving-mass``.

The motion: the standard pick-and-place cycle (25 up, 305 across, 25 down [mm],
:func:`mechopt.core.motion.pick_and_place_path`) scaled to the placed task's width and
shrunk about its centre until its corners lie in the task, each piece cycloidal, the
whole in ``--cycle-time`` seconds, sampled at :data:`SAMPLES` times. The masses: the
mechanism's default mass model (:func:`mechopt.analysis.dynamics.mass_model`: 20 x 20 x 2
mm aluminium tubes, 0.5 kg motors, 0.2 kg payload, 0.3 kg carriages; Wu 2008 Table 2
for the gantry), with ``--actuator``'s reflected rotor inertias ``I_r N^2`` in place of
the law's; gravity ``--motion-gravity`` (default down, -y). The limits are per actuator
(one value for both or two; ``--actuator`` gives peak x N and rated x N): ``g`` is the
largest of the two actuators' relative excess, the margin the smaller of their margins. The efforts: the
inverse dynamics of :mod:`mechopt.analysis.dynamics` (exact, checked against a sympy
Lagrange derivation), the peak over the samples and the RMS by the trapezoidal rule.

Certificate: the efforts are exact at the samples; the peak between samples is not
bounded (with 101 samples of the cycloidal cycle the sampled peak was 0.9 % below the
peak over 2001 samples for a five-bar sized for a 300 x 200 mm task: leave that margin). A pose of the cycle out of
reach gives NaN, which fails the requirement (``g`` NaN) and is undefined for the
objectives.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from mechopt.analysis.task import UNITS
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MaxTorque", "MaxRmsTorque", "PeakTorqueObjective", "RmsTorqueObjective",
           "MovingMassObjective", "cycle_efforts", "SAMPLES", "MEMBERS"]

#: time samples of the cycle
SAMPLES = 101


def _gravity(text):
    from mechopt.analysis.dynamics import parse_gravity

    parse_gravity(text)  # checked here: one line when it is not a gravity
    return str(text)


def _cycle(task):
    """The pick-and-place path inside ``task`` (module docstring)."""
    from mechopt.core import motion as mo

    return mo.pick_and_place_path(task.bbox, task.contains if task.is_region else None)


def cycle_efforts(ctx) -> dict:
    """``{"peak": (2,), "rms": (2,), "moving_mass": kg}`` of the design along the cycle
    (memoised in the context); NaN efforts when a pose is out of reach.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    dict
        ``peak`` and ``rms``: arrays of the two actuators' efforts [N m or N];
        ``moving_mass`` [kg].
    """
    def compute():
        from mechopt.analysis import dynamics as dyn
        from mechopt.core import motion as mo

        unit = UNITS[ctx.unit]
        model = dyn.mass_model(ctx.mech, length_unit=unit)
        if ctx.req.actuator is not None:  # the datasheet's rotors replace the law's
            model = replace(model, actuator_inertia=tuple(m.reflected_inertia for m in ctx.req.actuator))
        if ctx.req.cycle_time is None:
            return {"peak": np.full(2, math.nan), "rms": np.full(2, math.nan),
                    "moving_mass": model.moving_mass}
        m = mo.timed_motion(_cycle(ctx.task), ctx.req.cycle_time, "cycloidal", SAMPLES)
        mx, my = ctx.to_mech(m["x"], m["y"])
        out = dyn.inverse_dynamics(ctx.mech, dict(m, x=mx, y=my), model, ctx.req.motion_gravity, unit)
        tau = out["tau"]
        if not np.all(np.isfinite(tau)):
            nan = np.full(2, math.nan)
            return {"peak": nan, "rms": nan, "moving_mass": model.moving_mass}
        return {"peak": np.max(np.abs(tau), 0),
                "rms": np.sqrt(np.trapezoid(tau ** 2, m["t"], axis=0) / m["t"][-1]),
                "moving_mass": model.moving_mass}
    return ctx.memo("cycle_efforts", compute)


def _cycle_time(value, spec):
    from mechopt.core import validation as _v

    v = _v.finite_number("cycle_time", value)
    if not v > 0:
        raise ValueError(f"cycle_time must be > 0 [s], got {value!r}")
    return v


class _EffortLimit(Requirement):
    key = ""
    label = ""
    needs_options = ("cycle_time",)
    needs = ("points",)
    margin_unit = "N m or N"
    certificate = (f"inverse dynamics exact at {SAMPLES} samples of the pick-and-place cycle "
                   "(mechopt.requirements.motion); not bounded between samples")

    def evaluate(self, ctx):
        from mechopt.requirements.speed import limits

        limit = limits(getattr(ctx.req, self.options[0].name))  # per actuator
        effort = cycle_efforts(ctx)[self.key]
        return float(np.min(limit - effort)), float(np.max((effort - limit) / limit))

    def describe(self, req, unit) -> str:
        return f"{self.label} effort <= {getattr(req, self.options[0].name)} along the {req.cycle_time} s cycle"

    def report(self, ctx) -> dict:
        if not ctx.has("cycle_efforts") or ctx.req.cycle_time is None:
            return {}
        e = cycle_efforts(ctx)
        return {f"{self.key}_torque": float(np.max(e[self.key]))}


class MaxTorque(_EffortLimit):
    name = "peak_torque"
    key = "peak"
    options = (Option("max_torque", "peak actuator effort along the pick-and-place cycle, one for both or one "
                                    "per actuator [N m or N, or with a unit]", kind="effort", per_actuator=True,
                      metavar="T[,T2]"),
               Option("cycle_time", "duration of the pick-and-place cycle [s] (dynamics requirements "
                                    "and objectives)", check=_cycle_time),
               Option("motion_gravity", "gravity of the dynamics: down (default, -y), off or GX,GY [m/s^2]",
                      check=lambda v, spec: _gravity(v), parse=_gravity, metavar="G"))
    label = "peak"
    margin_text = "`--max-torque`: the smaller of the two actuators' limit minus its peak effort along the cycle"


class MaxRmsTorque(_EffortLimit):
    name = "rms_torque"
    key = "rms"
    options = (Option("max_rms_torque", "RMS actuator effort over the pick-and-place cycle (the rated torque), "
                                        "one for both or one per actuator [N m or N, or with a unit]",
                      kind="effort", per_actuator=True, metavar="T[,T2]"),)
    label = "RMS"
    margin_text = "`--max-rms-torque`: the smaller of the two actuators' limit minus its RMS effort"


class PeakTorqueObjective(Objective):
    name = "peak-torque"
    unit = "{T}"
    description = "largest peak actuator effort along the pick-and-place cycle (--cycle-time)"
    requires = ("cycle_time",)
    needs = ("points",)

    def value(self, ctx) -> float:
        return float(np.max(cycle_efforts(ctx)["peak"]))

    def bounds(self, ev):
        return (0.0, 10.0)


class RmsTorqueObjective(PeakTorqueObjective):
    name = "rms-torque"
    description = "largest RMS actuator effort over the pick-and-place cycle (--cycle-time)"

    def value(self, ctx) -> float:
        return float(np.max(cycle_efforts(ctx)["rms"]))


class MovingMassObjective(Objective):
    name = "moving-mass"
    unit = "kg"
    description = "mass of the moving bodies of the default mass model (motors on the frame excluded)"
    needs = ()

    def value(self, ctx) -> float:
        from mechopt.analysis import dynamics as dyn

        return ctx.memo("moving_mass", lambda: dyn.mass_model(ctx.mech, length_unit=UNITS[ctx.unit]).moving_mass)

    def bounds(self, ev):
        return (0.0, 5.0)


MEMBERS = (MaxTorque(), MaxRmsTorque(), PeakTorqueObjective(), RmsTorqueObjective(), MovingMassObjective())
