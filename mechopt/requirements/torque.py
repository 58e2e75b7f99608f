"""Torque: the actuator effort needed to hold a payload force in the worst direction,
the objective ``torque`` (``--payload``).

Holding ``f`` newtons in the worst direction needs ``|tau|_2 = f / s_min(J)`` (Liu
2006 eq. 13 inverted), over the task ``f / min_T s_min(J)`` [N m for cranks, N for
sliders]. Undefined (NaN) where the design has no force capacity (``s_min = 0``
somewhere: a type-I singularity in the task), which the reach requirement already
makes infeasible (its certified clearance to the type-I loci is then not positive).
"""
from __future__ import annotations

import math

from mechopt.analysis.task import UNITS
from mechopt.requirements.base import Objective, Option
from mechopt.requirements.force import effort_factor
from mechopt.requirements.speed import singular_value_extremes

__all__ = ["TorqueObjective", "torque", "MEMBERS"]


def torque(ctx) -> float:
    """``payload / min_T s_min(J)`` [N m or N], NaN without force capacity.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The torque [N m for cranks, N for sliders]; NaN when the design has no force
        capacity somewhere on the task (``min s_min(J) = 0``).
    """
    smin = singular_value_extremes(ctx)[1]
    return ctx.req.payload / smin / effort_factor(ctx) if smin > 0 else math.nan


class TorqueObjective(Objective):
    name = "torque"
    sense = 1
    unit = "{T}"
    description = "actuator torque (force) to hold the payload in the worst direction"
    options = (Option("payload", "payload force [N] for the torque objective", kind="force"),)
    requires = ("payload",)
    needs = ("points", "singular_values")

    def value(self, ctx) -> float:
        return torque(ctx)

    def bounds(self, ev):
        # a reference range: s_min(J) >= 1/(4 max_length) on the designs of interest
        return (0.0, 4.0 * ev.req.payload * (ev.max_length * UNITS[ev.unit] if ev.spec.angular else 1.0))

    def report(self, ctx) -> dict:
        known = ctx.has("singular_value_extremes") and ctx.req.payload is not None
        return {"torque": torque(ctx)} if known else {}


MEMBERS = (TorqueObjective(),)
