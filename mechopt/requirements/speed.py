"""Speed: the platform speed guaranteed in every direction (Liu 2006 eq. 10, with
units), a requirement ``--min-speed`` and an objective ``speed``.

With ``q_dot = J p_dot`` (``J`` in rad/L for revolute, 1 for prismatic actuators):
moving the platform at speed ``v`` in the unit direction ``u`` needs ``q_dot = v J
u``; with the actuator rates bounded by ``|q_dot|_2 <= w`` (rad/s or L/s) the speed
reachable in EVERY direction is ``v = w / max_u |J u| = w / s_max(J)`` [L/s] (Liu
eq. 10, ``|V|min = 1/s_max`` per unit rate), and over the task ``w / max_T
s_max(J)``. Bounding each actuator separately (``|q_dot_i| <= w``) allows at least
this value (``|.|_inf <= |.|_2``): a safe guarantee. The largest ``s_max`` and the
smallest ``s_min`` over the task (:func:`singular_value_extremes`, shared with
:mod:`mechopt.requirements.force` and :mod:`mechopt.requirements.torque`) are
located on the samples and refined by zooming (:mod:`mechopt.analysis.sampling`).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import indices as _ix
from mechopt.analysis.sampling import bad_to
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MinSpeed", "SpeedObjective", "singular_value_extremes", "speed", "MEMBERS"]


def _extremes(sv):
    """``-s_max`` and ``s_min`` as rows (both minimised over the task; one SVD for the two)."""
    return np.stack([bad_to(-sv[0], -np.inf), bad_to(sv[1], 0.0)])


def singular_value_extremes(ctx) -> tuple:
    """``(max_T s_max(J), min_T s_min(J))`` over the task, searched together.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    s_max, s_min : float
        ``max_T s_max(J)`` and ``min_T s_min(J)`` (the unit of ``J``), memoised in ``ctx``.
    """
    def compute():
        neg_smax, smin = ctx.region_mins(
            lambda x, y: _extremes(_ix.singular_values(ctx.mech.jacobian(*ctx.to_mech(x, y)))),
            _extremes(_ix.singular_values(ctx.jacobian)))
        return -neg_smax, smin
    return ctx.memo("singular_value_extremes", compute)


def speed(ctx) -> float:
    """The guaranteed speed ``w / max_T s_max(J)`` [L/s] (0 where unbounded).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The speed [L/s].
    """
    smax = singular_value_extremes(ctx)[0]
    return ctx.req.actuator_speed / smax if smax > 0 and math.isfinite(smax) else 0.0


class MinSpeed(Requirement):
    name = "speed"
    options = (Option("min_speed", "guaranteed speed in every direction [unit/s, or with a unit: 0.5m/s]", kind="speed"),
               Option("actuator_speed", "actuator speed limit [rad/s or unit/s, or with a unit: 30rpm, 0.5m/s]", kind="rate"))
    needs_options = ("actuator_speed",)
    needs = ("points", "singular_values")
    margin_text = "`--min-speed`: guaranteed speed minus the required one (Liu eq. 10)"
    margin_unit = "{L}/s"
    certificate = ("boundary and interior critical points of s_max(J) located on the samples and refined by "
                   "zooming (mechopt.analysis.sampling)")

    def describe(self, req, unit) -> str:
        return f"guaranteed speed >= {req.min_speed} {unit}/s"

    def evaluate(self, ctx):
        need, v = ctx.req.min_speed, speed(ctx)
        return v - need, (need - v) / need

    def report(self, ctx) -> dict:
        known = ctx.has("singular_value_extremes") and ctx.req.actuator_speed is not None
        return {"speed": speed(ctx)} if known else {}


class SpeedObjective(Objective):
    name = "speed"
    sense = -1
    unit = "{L}/s"
    description = "guaranteed platform speed in every direction, w / max s_max(J)"
    requires = ("actuator_speed",)
    needs = ("points", "singular_values")

    def value(self, ctx) -> float:
        return speed(ctx)

    def bounds(self, ev):
        # a reference range: a crank of length <= max_length turning at w moves its tip
        # at w * max_length [L/s]; a slider at w [L/s]
        return (0.0, 2.0 * ev.req.actuator_speed * (ev.max_length if ev.spec.angular else 1.0))

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


MEMBERS = (MinSpeed(), SpeedObjective())
