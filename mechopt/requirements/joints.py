"""Joints: the crank angles stay within their limits over the task (mechanisms with
cranks).

An actuator coordinate has no critical point inside a singularity-free region (its
gradient is a row of ``J``, never zero), so its extremes over the task lie on ``dT``:
the boundary samples refined by the boundary zoom (:mod:`mechopt.analysis.sampling`).
The crank ranges themselves are derived for every design with cranks (the
evaluator's ``joint_ranges``).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v
from mechopt.requirements.base import Option, Requirement

__all__ = ["Joints", "MEMBERS"]

#: the search leaves the crank ranges unrefined when the samples' ranges lie at least
#: ``SETTLE`` [rad] inside the limits (:meth:`Joints.settled`): refinement widened them
#: by at most 6e-5 rad on 800 random five-bar designs of a rectangle and a star polygon
SETTLE = 0.01


def _check(value, spec):
    jl = np.asarray(value, float)
    if jl.shape == (2,):
        jl = np.vstack([jl, jl])
    if jl.shape != (2, 2) or not np.all(np.isfinite(jl)) or not np.all(jl[:, 1] > jl[:, 0]):
        raise ValueError(f"joint_limits must be (lo, hi) or ((lo1, hi1), (lo2, hi2)) with lo < hi, "
                         f"got {_v.show(value)}")
    return tuple(map(tuple, jl.tolist()))


def _parse(text):
    """``LO,HI[,LO2,HI2]`` [deg] -> ``((lo1, hi1), (lo2, hi2))`` [rad] (two values: both cranks)."""
    vals = [math.radians(_v.finite_number("--joint-limits (deg)", v)) for v in str(text).split(",")]
    if len(vals) not in (2, 4):
        raise ValueError(f"--joint-limits (deg) must be 2 or 4 comma-separated numbers, got {text!r}")
    return (vals[:2], vals[2:] if len(vals) == 4 else vals[:2])


class Joints(Requirement):
    name = "joints"
    options = (Option("joint_limits", "crank angle limits [deg]", check=_check, parse=_parse,
                      metavar="LO,HI[,LO2,HI2]"),)
    needs = ("points", "ik")
    instead = "max_stroke"
    margin_text = "`--joint-limits`: smallest distance of the crank ranges to their limits"
    margin_unit = "rad"
    certificate = "extremes on the task's boundary (no interior critical point), boundary samples refined by zooming"

    def applies(self, spec) -> bool:
        return spec.angular

    def describe(self, req, unit) -> str:
        return "the joint limits " + ", ".join(f"[{math.degrees(a):g}, {math.degrees(b):g}] deg"
                                               for a, b in req.joint_limits)

    def settled(self, ctx) -> bool:
        return _margin(ctx.joint_ranges(refine=False), ctx.req.joint_limits) >= SETTLE

    def evaluate(self, ctx):
        m = _margin(ctx.derived["joint_ranges"], ctx.req.joint_limits)
        m = m if math.isfinite(m) else -math.pi
        return m, -m / math.pi


def _margin(ranges, limits) -> float:
    """The smallest distance of the crank ranges to their limits [rad]."""
    return min(min(q_lo - lim_lo, lim_hi - q_hi) for (q_lo, q_hi), (lim_lo, lim_hi) in zip(ranges, limits))


MEMBERS = (Joints(),)
