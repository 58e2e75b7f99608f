"""Speed: the platform speed guaranteed in every direction, a requirement
``--min-speed`` and an objective ``speed``; the reading of the actuators' limits
(``--actuator-norm``) shared with :mod:`mechopt.requirements.force` and
:mod:`mechopt.requirements.torque`.

With ``q_dot = J p_dot`` (``J`` in rad/L for revolute, 1 for prismatic actuators),
moving the platform at speed ``v`` in the unit direction ``u`` needs ``q_dot = v J u``.
Two readings of the rate limits ``w`` (rad/s or L/s; one value for both actuators
or one each, ``--actuator-speed 3,2.5``):

``box`` (the default: real motors, each limited on its own, ``|q_dot_i| <= w_i``)
    ``v = min_i w_i / ||row_i(J)||`` at a pose (exact: Cauchy-Schwarz, the proof in
    :mod:`mechopt.core.actuators`), over the task ``min_i w_i min_T 1/||row_i(J)||``
    [L/s].
``2`` (Liu 2006 eq. 10: one Euclidean budget, ``||diag(w)^-1 q_dot||_2 <= 1``)
    ``v = 1 / s_max(diag(w)^-1 J)``, for equal limits ``w / s_max(J)`` (Liu's ``|V|min``
    per unit rate), over the task ``1 / max_T s_max`` [L/s]. The box contains the
    ball: ``v_2 <= v_box``.

The minima over the task (:func:`box_extremes`, :func:`liu_extremes`) are located on
the samples and refined by zooming (:mod:`mechopt.analysis.sampling`); each is the
minimum of a smooth function of the pose (the minimum over two actuators is taken
after the search, not inside it).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core.indices import box_rows_of_matrix
from mechopt.core.jit import Twin
from mechopt.analysis.sampling import bad_to
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["MinSpeed", "SpeedObjective", "singular_value_extremes", "liu_extremes", "box_extremes", "limits",
           "reading", "extremes_known", "speed", "MEMBERS"]

#: the search leaves the guaranteed speed (and force, :mod:`mechopt.requirements.force`)
#: unrefined when the samples' value is at least ``1 + SETTLE`` times the required one
#: (:meth:`MinSpeed.settled`): refinement lowered them by at most 2.1e-4 relative on 900
#: designs near feasible ones of a gantry, five-bars, a Biglide and a Bipod, both readings
SETTLE = 0.05


def limits(value) -> np.ndarray:
    """The two actuators' limits of a per-actuator option's checked value (one number
    for both, or a pair), shape ``(2,)``.

    Parameters
    ----------
    value : float or (float, float)
        The checked value [rad/s, L/s, N m or N].

    Returns
    -------
    ndarray
        Shape ``(2,)``: actuator 1's limit, actuator 2's (a new array) [the value's unit].
    """
    return np.broadcast_to(np.asarray(value, dtype=float), (2,)).copy()


def reading(ctx):
    """The reading of the actuators' limits of the requirements: ``"box"`` or ``2``.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    str or int
        ``"box"`` (also when ``--actuator-norm`` is not given) or ``2``.
    """
    from mechopt.core.actuators import actuator_norm

    return actuator_norm(ctx.req.actuator_norm or "box")


def _extremes(sv):
    """``-s_max`` and ``s_min`` as rows (both minimised over the task; one SVD for the two)."""
    return np.stack([bad_to(-sv[0], -np.inf), bad_to(sv[1], 0.0)])


def _key(name, refine):
    """The memo key of a search's result: ``name``, or with ``refine=False`` the samples'
    value under its own key (a settled requirement's, :meth:`MinSpeed.settled`)."""
    return name if refine is not False else (name, "sampled")


def singular_value_extremes(ctx, refine=None) -> tuple:
    """``(max_T s_max(J), min_T s_min(J))`` over the task, searched together.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    refine : bool, optional
        Refine by zooming (default ``ctx.refine``); False: the samples' extremes.

    Returns
    -------
    s_max, s_min : float
        ``max_T s_max(J)`` and ``min_T s_min(J)`` (the unit of ``J``), memoised in ``ctx``.
    """
    def compute():
        neg_smax, smin = ctx.region_mins(
            lambda x, y: _extremes(_ix.singular_values(ctx.mech.jacobian(*ctx.to_mech(x, y)))),
            _extremes(_ix.singular_values(ctx.jacobian)), refine)
        return -neg_smax, smin
    return ctx.memo(_key("singular_value_extremes", refine), compute)


def liu_extremes(ctx, w=None, t=None, refine=None) -> tuple:
    """``(max_T s_max(diag(w)^-1 J), min_T s_min(diag(t) J))`` (Liu 2006 eq. 10, 13 with
    per-actuator budgets ``w``, ``t``: ``(2,)`` arrays, default ones); equal limits reuse
    :func:`singular_value_extremes` (the singular values scale with a common factor).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    w : ndarray, optional
        The rate limits, shape ``(2,)`` [rad/s or L/s] (default: ones).
    t : ndarray, optional
        The effort limits, shape ``(2,)`` [N m or N] (default: ones).
    refine : bool, optional
        Refine by zooming (default ``ctx.refine``); False: the samples' extremes.

    Returns
    -------
    s_max, s_min : float
        ``max_T s_max(diag(w)^-1 J)`` [s/L with ``w`` in rad/s or L/s] and
        ``min_T s_min(diag(t) J)`` [the unit of ``t`` times that of ``J``], memoised in ``ctx``.
    """
    w = np.ones(2) if w is None else w
    t = np.ones(2) if t is None else t
    if w[0] == w[1] and t[0] == t[1]:
        smax, smin = singular_value_extremes(ctx, refine)
        return smax / w[0], smin * t[0]

    def rows(J):
        return np.stack([bad_to(-_ix.singular_values(J / w[:, None])[0], -np.inf),
                         bad_to(_ix.singular_values(J * t[:, None])[1], 0.0)])

    def compute():
        neg_smax, smin = ctx.region_mins(lambda x, y: rows(ctx.mech.jacobian(*ctx.to_mech(x, y))),
                                         rows(ctx.jacobian), refine)
        return -neg_smax, smin
    return ctx.memo(_key(("liu_extremes", tuple(w), tuple(t)), refine), compute)


def _box_rows(J):
    """``1/||row_1||, 1/||row_2||, |det J|/||row_1||, |det J|/||row_2||`` (0 where unreachable)."""
    if Twin.compiled():
        flat = np.ascontiguousarray(J).reshape(-1, 2, 2)
        out = np.empty((4, flat.shape[0]))
        _BOX_ROWS_TWIN(flat, out)
        return out.reshape((4,) + J.shape[:-2])
    a, b = np.hypot(J[..., 0, 0], J[..., 0, 1]), np.hypot(J[..., 1, 0], J[..., 1, 1])
    det = np.abs(J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0])
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.stack([bad_to(1.0 / a, 0.0), bad_to(1.0 / b, 0.0), bad_to(det / a, 0.0), bad_to(det / b, 0.0)])


def _box_rows_loop(J, out):
    """:func:`_box_rows` matrix by matrix (compiled, :class:`mechopt.core.jit.Twin`;
    :func:`mechopt.core.indices.box_rows_of_matrix`)."""
    for i in range(J.shape[0]):
        out[0, i], out[1, i], out[2, i], out[3, i] = box_rows_of_matrix(J[i, 0, 0], J[i, 0, 1], J[i, 1, 0], J[i, 1, 1])


_BOX_ROWS_TWIN = Twin(_box_rows_loop)


def box_extremes(ctx, refine=None) -> np.ndarray:
    """The minima over the task of ``1/||row_1(J)||, 1/||row_2(J)||, |det J|/||row_1||,
    |det J|/||row_2||``, searched together: under per-actuator limits the guaranteed
    speed is ``min(w_1 m_0, w_2 m_1)`` and the guaranteed force ``min(t_2 m_2, t_1 m_3)``
    (:mod:`mechopt.core.actuators`); independent of the limits, so shared.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    refine : bool, optional
        Refine by zooming (default ``ctx.refine``); False: the samples' minima.

    Returns
    -------
    ndarray
        Shape ``(4,)``: ``m_0, m_1`` [the inverse of the unit of ``J``] and ``m_2, m_3``
        [the unit of ``J``], 0 where unreachable; memoised in ``ctx``.
    """
    def compute():
        return np.array(ctx.quantity_mins("box", lambda x, y: _box_rows(ctx.mech.jacobian(*ctx.to_mech(x, y))),
                                          _box_rows(ctx.jacobian), refine))
    return ctx.memo(_key("box_extremes", refine), compute)


def extremes_known(ctx, w=None, t=None) -> bool:
    """True when another member already searched the minima the reading needs.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    w : ndarray, optional
        The rate limits, shape ``(2,)`` [rad/s or L/s] (default: ones).
    t : ndarray, optional
        The effort limits, shape ``(2,)`` [N m or N] (default: ones).

    Returns
    -------
    bool
        Whether ``ctx`` holds them (:func:`box_extremes`, :func:`singular_value_extremes`
        or :func:`liu_extremes` of these limits).
    """
    if reading(ctx) == "box":
        return ctx.has("box_extremes")
    w = np.ones(2) if w is None else w
    t = np.ones(2) if t is None else t
    equal = w[0] == w[1] and t[0] == t[1]
    return ctx.has("singular_value_extremes" if equal else ("liu_extremes", tuple(w), tuple(t)))


def speed(ctx, refine=None) -> float:
    """The guaranteed speed over the task [L/s] under the reading :func:`reading` (module
    docstring); 0 where unbounded or unreachable.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.
    refine : bool, optional
        Refine by zooming (default ``ctx.refine``); False: over the samples alone.

    Returns
    -------
    float
        The speed guaranteed in every direction over the task [L/s].
    """
    w = limits(ctx.req.actuator_speed)
    if reading(ctx) == "box":
        m = box_extremes(ctx, refine)
        return float(min(w[0] * m[0], w[1] * m[1]))
    smax = liu_extremes(ctx, w=w, refine=refine)[0]
    return 1.0 / smax if smax > 0 and math.isfinite(smax) else 0.0


def _motors_option(value, spec):
    from mechopt.core.actuators import read_motors

    return read_motors(value)


def _norm_option(value, spec):
    from mechopt.core.actuators import actuator_norm

    return actuator_norm(value)


class MinSpeed(Requirement):
    name = "speed"
    options = (Option("min_speed", "guaranteed speed in every direction [unit/s, or with a unit: 0.5m/s]", kind="speed"),
               Option("actuator_speed", "actuator speed limit, one for both or one per actuator (3,2.5) "
                                        "[rad/s or unit/s, or with a unit: 30rpm, 0.5m/s]",
                      kind="rate", per_actuator=True, metavar="W[,W2]"),
               Option("actuator_norm", "reading of the actuators' speed and torque limits: box (default: "
                                       "each actuator within its own limits) or 2 (Liu 2006 eq. 10, 13: one "
                                       "Euclidean budget shared by both, as in the paper)",
                      check=_norm_option, parse=str, metavar="box|2"),
               Option("actuator", "the actuators' datasheet: key=value,... (both; two separated by ;) or a "
                                  ".json/.toml file; keys rated_torque, peak_torque [N m], max_speed [rad/s, or "
                                  "3000rpm], gear_ratio [-, rad/m for a screw], rotor_inertia [kg m^2]; gives "
                                  "--actuator-speed (max_speed/ratio), --actuator-torque (rated x ratio), "
                                  "with --cycle-time --max-torque (peak x ratio) and --max-rms-torque "
                                  "(rated x ratio), unless given; "
                                  "and adds the reflected rotor inertia to the motion's dynamics",
                      check=_motors_option, parse=str, metavar="SPEC|FILE"))
    needs_options = ("actuator_speed",)
    needs = ("points", "jacobian", "singular_values")
    margin_text = ("`--min-speed`: guaranteed speed minus the required one (per-actuator limits, or Liu eq. 10 "
                   "with `--actuator-norm 2`)")
    margin_unit = "{L}/s"
    certificate = ("boundary and interior critical points of 1/||row_i(J)|| (per-actuator limits) or s_max(J) "
                   "(--actuator-norm 2) located on the samples and refined by zooming (mechopt.analysis.sampling)")

    def implied(self, values, spec, unit) -> dict:
        """The actuators' limits at the output from ``--actuator``'s datasheet
        (:class:`mechopt.core.actuators.Motor`): rates [rad/s, or the task's unit per
        second for sliders], continuous (rated) torque for the guaranteed force (a force
        held for as long as needed), peak and rated torque for the motion's peak and RMS
        limits [N m or N]; one value when both actuators are alike.

        Parameters
        ----------
        values : dict
            ``{option: checked value}`` of every option (None where not given).
        spec : mechopt.core.design_spec.DesignSpec
            The mechanism's design spec.
        unit : str
            The task's length unit.

        Returns
        -------
        dict
            ``actuator_speed`` [rad/s or L/s] and ``actuator_torque`` [N m or N], with
            ``cycle_time`` also ``max_torque`` and ``max_rms_torque`` [N m or N]; each a
            float or a pair; empty without ``--actuator``.
        """
        motors = values.get("actuator")
        if motors is None:
            return {}
        from mechopt.analysis.task import UNITS

        per_s = 1.0 if spec.angular else 1.0 / UNITS[unit]  # [m/s] -> [L/s] for sliders

        def pair(f):
            a, b = (float(f(m)) for m in motors)
            return a if a == b else (a, b)
        out = {"actuator_speed": pair(lambda m: m.speed * per_s), "actuator_torque": pair(lambda m: m.torque)}
        if values.get("cycle_time") is not None:  # the motion's limits apply along a timed cycle
            out.update(max_torque=pair(lambda m: m.peak), max_rms_torque=pair(lambda m: m.torque))
        return out

    def describe(self, req, unit) -> str:
        how = "one Euclidean budget, Liu 2006" if (req.actuator_norm or "box") in (2, "2") else "per actuator"
        return f"guaranteed speed >= {req.min_speed} {unit}/s ({how})"

    def settled(self, ctx) -> bool:
        # the speed objective reads the refined value: never settled with it
        return "speed" not in ctx.objectives and speed(ctx, False) >= (1.0 + SETTLE) * ctx.req.min_speed

    def evaluate(self, ctx):
        need, v = ctx.req.min_speed, speed(ctx, False if self.name in ctx.settled else None)
        return v - need, (need - v) / need

    def report(self, ctx) -> dict:
        if ctx.req.actuator_speed is None:
            return {}
        return {"speed": speed(ctx)} if extremes_known(ctx, w=limits(ctx.req.actuator_speed)) else {}


class SpeedObjective(Objective):
    name = "speed"
    sense = -1
    unit = "{L}/s"
    description = ("guaranteed platform speed in every direction, min_i w_i / max ||row_i(J)|| (per actuator; "
                   "--actuator-norm 2: w / max s_max(J))")
    requires = ("actuator_speed",)
    needs = ("points", "jacobian", "singular_values")

    def value(self, ctx) -> float:
        return speed(ctx)

    def bounds(self, ev):
        # a reference range: a crank of length <= max_length turning at w moves its tip
        # at w * max_length [L/s]; a slider at w [L/s]
        return (0.0, 2.0 * float(np.max(ev.req.actuator_speed)) * (ev.max_length if ev.spec.angular else 1.0))

    def invalid_value(self, ev, lengths) -> float:
        return 0.0


MEMBERS = (MinSpeed(), SpeedObjective())
