"""Torque: the actuator effort needed to hold a payload force in the worst direction,
the objective ``torque`` (``--payload``).

Holding ``f`` newtons in the direction ``u`` needs ``tau = f J^-T u``. Under
per-actuator limits (the default ``--actuator-norm box``) the value is the largest
effort of one actuator: ``tau_i = f (J^-1 e_i) . u``, largest over ``u`` at ``f
||J^-1 e_i||``, and for a 2 x 2 matrix ``J^-1 e_1 = (J_22, -J_21) / det J``, ``J^-1 e_2
= (-J_12, J_11) / det J``, so actuator 1 needs ``f ||row_2(J)|| / |det J|`` and
actuator 2 ``f ||row_1(J)|| / |det J|``; over the task ``f / min_T min_i |det J| /
||row_i(J)||`` (the minima of :func:`mechopt.requirements.speed.box_extremes`). With
``--actuator-norm 2`` (Liu 2006 eq. 13 inverted) it is the Euclidean norm of the two,
``|tau|_2 = f / s_min(J)``, over the task ``f / min_T s_min(J)``. [N m for cranks, N
for sliders.] Undefined (NaN) where the design has no force capacity (``s_min = 0``
somewhere: a type-I singularity in the task), which the reach requirement already
makes infeasible (its certified clearance to the type-I loci is then not positive).
"""
from __future__ import annotations

import math

from mechopt.analysis.task import UNITS
from mechopt.requirements.base import Objective, Option
from mechopt.requirements.force import effort_factor
from mechopt.requirements.speed import box_extremes, extremes_known, reading, singular_value_extremes

__all__ = ["TorqueObjective", "torque", "MEMBERS"]


def torque(ctx) -> float:
    """``payload / min_T min_i |det J| / ||row_i(J)||`` (per actuator) or ``payload /
    min_T s_min(J)`` (``--actuator-norm 2``) [N m or N], NaN without force capacity.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The effort needed to hold the payload in the worst direction [N m or N]: the
        larger actuator's, or the two's Euclidean norm with ``--actuator-norm 2`` (NaN
        without force capacity).
    """
    smin = float(min(box_extremes(ctx)[2:])) if reading(ctx) == "box" else singular_value_extremes(ctx)[1]
    return ctx.req.payload / smin / effort_factor(ctx) if smin > 0 else math.nan


class TorqueObjective(Objective):
    name = "torque"
    sense = 1
    unit = "{T}"
    description = ("largest actuator torque (force) to hold the payload in the worst direction (--actuator-norm 2: "
                   "the Euclidean norm of the two)")
    options = (Option("payload", "payload force [N] for the torque objective", kind="force"),)
    requires = ("payload",)
    needs = ("points", "jacobian", "singular_values")

    def value(self, ctx) -> float:
        return torque(ctx)

    def bounds(self, ev):
        # a reference range: s_min(J) >= 1/(4 max_length) on the designs of interest
        return (0.0, 4.0 * ev.req.payload * (ev.max_length * UNITS[ev.unit] if ev.spec.angular else 1.0))

    def report(self, ctx) -> dict:
        return {"torque": torque(ctx)} if ctx.req.payload is not None and extremes_known(ctx) else {}


MEMBERS = (TorqueObjective(),)
