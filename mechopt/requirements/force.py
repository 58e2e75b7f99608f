"""Force: the platform force guaranteed in every direction (Liu 2006 eq. 13, with
units), a requirement ``--min-force`` and an objective ``force``.

By virtual work ``tau . q_dot = F . p_dot``, i.e. ``F = J^T tau``: resisting a force
``f u`` needs ``tau = f J^-T u``, so with ``|tau|_2 <= t`` (N m or N) the force
guaranteed in every direction is ``f = t / s_max(J^-T) = t s_min(J)`` [N] (Liu eq.
13, ``|tau|min = s_min`` per unit effort), over the task ``t min_T s_min(J)``. ``J``
is in rad/L for cranks: a torque in N m gives ``t / u_m`` N per rad/L with ``u_m``
the task's unit in metres. Bounding each actuator separately allows at least this
value. The minimum over the task is
:func:`mechopt.requirements.speed.singular_value_extremes`.
"""
from __future__ import annotations

from mechopt.analysis.task import UNITS
from mechopt.requirements.base import Objective, Option, Requirement
from mechopt.requirements.speed import singular_value_extremes

__all__ = ["MinForce", "ForceObjective", "effort_factor", "force", "MEMBERS"]


def effort_factor(ctx_or_ev) -> float:
    """N m -> N per (rad/L) for cranks (``1 / u_m``), 1 for sliders.

    Parameters
    ----------
    ctx_or_ev : DesignContext or DesignEvaluator
        Gives the mechanism's spec and the task's unit.

    Returns
    -------
    float
        The factor.
    """
    return 1.0 / UNITS[ctx_or_ev.unit] if ctx_or_ev.spec.angular else 1.0


def force(ctx) -> float:
    """The guaranteed force ``t min_T s_min(J)`` [N].

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The force [N].
    """
    return ctx.req.actuator_torque * effort_factor(ctx) * singular_value_extremes(ctx)[1]


class MinForce(Requirement):
    name = "force"
    options = (Option("min_force", "guaranteed force in every direction [N, or with a unit: 2kN]", kind="force"),
               Option("actuator_torque", "actuator torque limit [N m or N, or with a unit: 2Nm, 500Nmm]", kind="effort"))
    needs_options = ("actuator_torque",)
    needs = ("points", "singular_values")
    margin_text = "`--min-force`: guaranteed force minus the required one (Liu eq. 13)"
    margin_unit = "N"
    certificate = ("boundary and interior critical points of s_min(J) located on the samples and refined by "
                   "zooming (mechopt.analysis.sampling)")

    def describe(self, req, unit) -> str:
        return f"guaranteed force >= {req.min_force} N"

    def precheck(self, req, spec, unit) -> None:
        """Speed and force together: for every ``J``, ``v f = w t s_min(J) / s_max(J) <= w t``
        (Liu 2006 eq. 10 and 13; in SI for cranks: ``v`` in m/s, ``t`` in N m, ``w`` in
        rad/s), so ``min_speed x min_force`` above the actuators' ``w x t`` is met by no
        geometry.

        Parameters
        ----------
        req : mechopt.requirements.Requirements
            The checked requirements.
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.
        unit : str
            The task's length unit.

        Raises
        ------
        ValueError
            One line, when ``min_speed x min_force`` exceeds the actuators' ``w x t``.
        """
        if req.min_speed is None or req.min_force is None:
            return
        u_m = UNITS[unit] if spec.angular else 1.0  # [m/L]: the speed in m/s for cranks
        need, have = req.min_speed * u_m * req.min_force, req.actuator_speed * req.actuator_torque
        if need > have:
            w_unit, t_unit = ("rad/s", "N m") if spec.angular else (f"{unit}/s", "N")
            p_unit = "W" if spec.angular else f"N {unit}/s"
            raise ValueError(
                f"no {spec.name} meets --min-speed {req.min_speed:g} {unit}/s and --min-force {req.min_force:g} N "
                f"together: speed x force = {need:.4g} {p_unit} exceeds the actuators' {req.actuator_speed:g} "
                f"{w_unit} x {req.actuator_torque:g} {t_unit} = {have:.4g} {p_unit} (for every geometry "
                f"speed x force <= w t s_min/s_max <= w t, Liu 2006 eq. 10, 13); relax one or choose "
                f"stronger or faster actuators")

    def evaluate(self, ctx):
        need, f = ctx.req.min_force, force(ctx)
        return f - need, (need - f) / need

    def report(self, ctx) -> dict:
        known = ctx.has("singular_value_extremes") and ctx.req.actuator_torque is not None
        return {"force": force(ctx)} if known else {}


class ForceObjective(Objective):
    name = "force"
    sense = -1
    unit = "N"
    description = "guaranteed platform force in every direction, t * min s_min(J)"
    requires = ("actuator_torque",)
    needs = ("points", "singular_values")

    def value(self, ctx) -> float:
        return force(ctx)

    def bounds(self, ev):
        # a reference range: s_min(J) of a crank of length L is about 1/L [rad/L], at
        # least 1/max_length; ten times the effort over the shortest link allowed
        return (0.0, 10.0 * ev.req.actuator_torque * effort_factor(ev) / (ev.min_length if ev.spec.angular else 1.0))

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


MEMBERS = (MinForce(), ForceObjective())
