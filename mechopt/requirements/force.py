"""Force: the platform force guaranteed in every direction, a requirement
``--min-force`` and an objective ``force``.

By virtual work ``tau . q_dot = F . p_dot``, i.e. ``F = J^T tau``: resisting a force
``f u`` needs ``tau = f J^-T u``. Two readings of the effort limits ``t`` (N m or N;
one value for both actuators or one each, ``--actuator-torque 8,6``), as
``--actuator-norm`` says (:mod:`mechopt.requirements.speed`):

``box`` (the default: ``|tau_i| <= t_i``)
    the inradius of the parallelogram ``J^T [-t_1, t_1] x [-t_2, t_2]``,
    ``f = min(t_2 |det J| / ||row_1(J)||, t_1 |det J| / ||row_2(J)||)`` (exact; the
    proof, a linear function's maximum over a box at a vertex, in
    :mod:`mechopt.core.actuators`), over the task the minimum of each term.
``2`` (Liu 2006 eq. 13: ``||diag(t)^-1 tau||_2 <= 1``)
    ``f = s_min(diag(t) J)``, for equal limits ``t s_min(J)`` (Liu's ``|tau|min`` per
    unit effort), over the task ``min_T``. The ball lies in the box: ``f_2 <= f_box``.

``J`` is in rad/L for cranks: a torque in N m gives ``t / u_m`` N per rad/L with
``u_m`` the task's unit in metres (:func:`effort_factor`).
"""
from __future__ import annotations

import numpy as np

from mechopt.analysis.task import UNITS
from mechopt.requirements.base import Objective, Option, Requirement
from mechopt.requirements.speed import SETTLE, box_extremes, extremes_known, limits, liu_extremes, reading

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


def force(ctx, refine=None) -> float:
    """The guaranteed force over the task [N] under the reading
    :func:`~mechopt.requirements.speed.reading` (module docstring).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    refine : bool, optional
        Refine by zooming (default ``ctx.refine``); False: over the samples alone.

    Returns
    -------
    float
        The force guaranteed in every direction over the task [N].
    """
    t = limits(ctx.req.actuator_torque)
    if reading(ctx) == "box":
        m = box_extremes(ctx, refine)
        return float(min(t[1] * m[2], t[0] * m[3])) * effort_factor(ctx)
    return float(liu_extremes(ctx, t=t, refine=refine)[1]) * effort_factor(ctx)


class MinForce(Requirement):
    name = "force"
    options = (Option("min_force", "guaranteed force in every direction [N, or with a unit: 2kN]", kind="force"),
               Option("actuator_torque", "actuator torque (force) limit, one for both or one per actuator "
                                         "(8,6) [N m or N, or with a unit: 2Nm, 500Nmm]",
                      kind="effort", per_actuator=True, metavar="T[,T2]"))
    needs_options = ("actuator_torque",)
    needs = ("points", "jacobian", "singular_values")
    margin_text = ("`--min-force`: guaranteed force minus the required one (per-actuator limits, or Liu eq. 13 "
                   "with `--actuator-norm 2`)")
    margin_unit = "N"
    certificate = ("boundary and interior critical points of |det J|/||row_i(J)|| (per-actuator limits) or "
                   "s_min(J) (--actuator-norm 2) located on the samples and refined by zooming "
                   "(mechopt.analysis.sampling)")

    def describe(self, req, unit) -> str:
        return f"guaranteed force >= {req.min_force} N"

    def precheck(self, req, spec, unit) -> None:
        """Speed and force together: at every pose ``v f <= min_i w_i t_i``, so
        ``min_speed x min_force`` above ``min_i w_i t_i`` is met by no geometry (in SI for
        cranks: ``v`` in m/s, ``t`` in N m, ``w`` in rad/s).

        Proof, per-actuator limits: with ``a_i = ||row_i(J)||`` and ``D = |det J| <= a_1
        a_2`` (Hadamard), ``v = min_i w_i / a_i`` and ``f = min(t_2 D / a_1, t_1 D / a_2)``
        (:mod:`mechopt.core.actuators`), so ``v f <= (w_1 / a_1)(t_1 D / a_2) <= w_1 t_1``
        and ``v f <= (w_2 / a_2)(t_2 D / a_1) <= w_2 t_2``. The bound is attained (rows
        orthogonal, ``a_2 / a_1`` between ``t_1 / t_2`` and ``w_2 / w_1`` when ``w_1 t_1 <=
        w_2 t_2``). Liu 2006 eq. 10, 13 (``--actuator-norm 2``): its speed and force are
        at most the box's (the ball lies in the box), so the same bound holds; for equal
        limits it is Liu's ``v f = w t s_min / s_max <= w t``. Over the task the minima
        of ``v`` and ``f`` are at most their values at any one pose.

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
            One line, when ``min_speed x min_force`` exceeds ``min_i w_i t_i`` of the
            actuators' limits.
        """
        if req.min_speed is None or req.min_force is None:
            return
        u_m = UNITS[unit] if spec.angular else 1.0  # [m/L]: the speed in m/s for cranks
        w, t = limits(req.actuator_speed), limits(req.actuator_torque)
        need, have = req.min_speed * u_m * req.min_force, float(np.min(w * t))
        if need > have:
            w_unit, t_unit = ("rad/s", "N m") if spec.angular else (f"{unit}/s", "N")
            p_unit = "W" if spec.angular else f"N {unit}/s"
            i = int(np.argmin(w * t))
            whose = "the actuators'" if w[0] == w[1] and t[0] == t[1] else f"actuator {i + 1}'s"
            raise ValueError(
                f"no {spec.name} meets --min-speed {req.min_speed:g} {unit}/s and --min-force {req.min_force:g} N "
                f"together: speed x force = {need:.4g} {p_unit} exceeds {whose} {w[i]:g} "
                f"{w_unit} x {t[i]:g} {t_unit} = {have:.4g} {p_unit} (for every geometry "
                f"speed x force <= min_i w_i t_i); relax one or choose stronger or faster actuators")

    def settled(self, ctx) -> bool:
        # the force objective reads the refined value: never settled with it
        return "force" not in ctx.objectives and force(ctx, False) >= (1.0 + SETTLE) * ctx.req.min_force

    def evaluate(self, ctx):
        need, f = ctx.req.min_force, force(ctx, False if self.name in ctx.settled else None)
        return f - need, (need - f) / need

    def report(self, ctx) -> dict:
        if ctx.req.actuator_torque is None:
            return {}
        return {"force": force(ctx)} if extremes_known(ctx, t=limits(ctx.req.actuator_torque)) else {}


class ForceObjective(Objective):
    name = "force"
    sense = -1
    unit = "N"
    description = ("guaranteed platform force in every direction, min(t_2 |det J|/||row_1||, t_1 |det J|/||row_2||) "
                   "(per actuator; --actuator-norm 2: t * min s_min(J))")
    requires = ("actuator_torque",)
    needs = ("points", "jacobian", "singular_values")

    def value(self, ctx) -> float:
        return force(ctx)

    def bounds(self, ev):
        # a reference range: s_min(J) of a crank of length L is about 1/L [rad/L], at
        # least 1/max_length; ten times the effort over the shortest link allowed
        t = float(np.max(ev.req.actuator_torque))
        return (0.0, 10.0 * t * effort_factor(ev) / (ev.min_length if ev.spec.angular else 1.0))

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


MEMBERS = (MinForce(), ForceObjective())
