"""Collisions: links that keep clear of each other, joints that do not fold, a machine that
stays out of a zone, a base wide enough for its motors; the objective ``clearance``.

The bodies are the capsules each design spec declares (:meth:`DesignSpec.links
<mechopt.core.design_spec.DesignSpec.links>`), sized by ``--link-width``,
``--motor-diameter`` and ``--carriage-length`` (defaults: 20 mm links, 60 mm motor
housings, 60 mm carriages, :data:`mechopt.core.bodies.MM_DEFAULTS`, in the task's unit);
the measures are those of :mod:`mechopt.analysis.collisions`.

clearance (``--min-clearance C`` [L])
    The smallest capsule clearance of two bodies that share no joint (and are not both
    fixed) stays >= C over the task: margin = minimum over the task - C.
joint_angle (``--min-joint-angle A`` [deg])
    Two links that share a joint (the five-bar's crank and distal link at the elbow,
    the two distal links at the tool) keep an angle >= A between them.
keep_out (``--keep-out task|polygon:x1,y1;...|above:Y|below:Y``)
    Every body's capsule stays outside the zone (``task``: the task itself, sparing the
    links that carry the tool); margin = the smallest signed distance [L].
base (``--min-base B`` [L] and/or ``--motor-diameter D`` [L])
    The distance between the fixed bodies' axes (the five-bar's ``2 r3``, the
    Biglide's ``2 l1``) >= B; with ``--motor-diameter`` the housings clear each other by
    ``--min-clearance`` (0 if not given): ``2 r3 >= D + C``. Exact: no pose enters.

The minima over the task are located on the samples and refined by zooming, as the
LCI's (:mod:`mechopt.analysis.sampling`); the reported ``clearance_bound`` (and
``keep_out_bound``, ``joint_angle_bound``) is the certified lower bound of
:func:`mechopt.analysis.collisions.lipschitz_bound` from the same samples: sampled
values less the bodies' speed bounds times the covering radius (the argument is in
:mod:`mechopt.analysis.collisions`).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.analysis import collisions as _c
from mechopt.analysis.sampling import bad_to
from mechopt.core import validation as _v
from mechopt.core.bodies import Shapes
from mechopt.requirements.base import Objective, Option, Requirement

__all__ = ["Clearance", "JointAngle", "KeepOut", "Base", "ClearanceObjective", "shapes_of", "collisions",
           "clearance_min", "joint_angle_min", "keep_out_min", "zone_of", "drawn", "worst_pose", "DRAWN_BY",
           "MEMBERS"]

#: a design whose sampled margin is below ``-SCREEN * D`` is not refined (far from feasible)
SCREEN = 0.05


def _nonneg(name):
    return lambda v, spec: _v.nonnegative_length(name, v)


def _pos(name):
    return lambda v, spec: _v.positive_length(name, v)


def _zone_text(value, spec):
    """The ``--keep-out`` text, its syntax checked (``task`` is resolved per evaluation)."""
    if not isinstance(value, str):
        raise ValueError(f"keep_out must be task, polygon:x1,y1;..., above:Y or below:Y, got {_v.show(value)}")
    if value.strip().lower() != "task":
        _c.parse_zone(value)
    return value.strip()


def _angle(value, spec):
    a = _v.finite_number("min_joint_angle", value)
    if not 0.0 < a < math.pi:
        raise ValueError(f"min_joint_angle must lie in (0, pi) rad (0 to 180 deg), got {_v.show(value)}")
    return a


def shapes_of(req, unit) -> Shapes:
    """The bodies' sizes [unit] of the requirements ``req``: the given ``link_width``,
    ``motor_diameter`` and ``carriage_length``, the others :meth:`Shapes.default
    <mechopt.core.bodies.Shapes.default>`.

    Parameters
    ----------
    req : mechopt.requirements.Requirements
        The requirements.
    unit : str
        The task's length unit.

    Returns
    -------
    mechopt.core.bodies.Shapes
        The sizes [unit].
    """
    given = {k: getattr(req, o) for k, o in (("link_width", "link_width"), ("housing_diameter", "motor_diameter"),
                                              ("carriage_length", "carriage_length"))
             if getattr(req, o) is not None}
    return Shapes.default(unit, **given)


def collisions(ctx) -> _c.Collisions:
    """The design's :class:`~mechopt.analysis.collisions.Collisions` (once per evaluation).

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    mechopt.analysis.collisions.Collisions
        The collision geometry.
    """
    return ctx.memo("collisions", lambda: _c.Collisions(ctx.spec, ctx.mech, shapes_of(ctx.req, ctx.unit)))


def _radius(ctx) -> float:
    """The covering radius [L] of the evaluation's samples."""
    s = ctx.samples
    return _c.covering_radius_of(ctx.task, s["gap"], s["tb"].size, s["step"])


def _at_samples(ctx, key, rows):
    """``rows(x, y)`` at the evaluation's samples, computed once (the screen and the
    minimum share them)."""
    s = ctx.samples
    return ctx.memo(key + "_samples", lambda: rows(s["allx"], s["ally"]))


def _minimum(ctx, key, rows, rates):
    """``(refined minimum, certified bound)`` over the task of the smallest row of
    ``rows(x, y)`` (shape ``(m, N)``), ``rates(x, y, radius)`` their Lipschitz bounds;
    the pose ``(x, y)`` where the minimum was found is kept as ``key + "_where"``
    (:func:`worst_pose`)."""
    def compute():
        s = ctx.samples
        x, y = s["allx"], s["ally"]
        vals = _at_samples(ctx, key, rows)
        if vals.size == 0:
            return math.inf, math.inf
        bound = _c.lipschitz_bound(vals, rates(x, y, _radius(ctx)), _radius(ctx))
        seen = []  # every (x, y, value) evaluated: the minimum is one of them

        def low(px, py):
            v = bad_to(np.min(rows(px, py), axis=0), -ctx.diameter)
            seen.append((px, py, v))
            return v[None]

        sampled = bad_to(np.min(vals, axis=0), -ctx.diameter)  # low(x, y)
        seen.append((x, y, sampled))
        m = float(ctx.region_mins(low, sampled[None])[0] if ctx.is_region else sampled.min())
        px, py, v = (np.concatenate(c) for c in zip(*seen))
        k = int(np.flatnonzero(v == m)[0])
        ctx.memo(key + "_where", lambda: (float(px[k]), float(py[k])))
        return m, min(bound, m)
    return ctx.memo(key, compute)


def clearance_min(ctx):
    """``(minimum, certified bound)`` [L] of the capsule clearance over the task.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    minimum, bound : float
        [L].
    """
    col = collisions(ctx)
    return _minimum(ctx, "clearance_min", col.pair_clearances, col.clearance_lipschitz)


def joint_angle_min(ctx):
    """``(minimum, certified bound)`` [rad] of the adjacent links' joint angles over the task.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    minimum, bound : float
        [rad].
    """
    col = collisions(ctx)
    return _minimum(ctx, "joint_angle_min", col.joint_angles, col.angle_lipschitz)


def zone_of(ctx):
    """The ``--keep-out`` zone (:class:`~mechopt.analysis.collisions.Zone`) of the
    evaluation, ``task`` resolved to its placed task; None without ``--keep-out``.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    mechopt.analysis.collisions.Zone or None
        The zone [L, task frame], or None without ``--keep-out``.
    """
    if ctx.req.keep_out is None:
        return None
    return ctx.memo("keep_out_zone", lambda: _c.parse_zone(ctx.req.keep_out, ctx.task))


def keep_out_min(ctx):
    """``(minimum, certified bound)`` [L] of the bodies' margins to the ``--keep-out`` zone.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    minimum, bound : float
        [L].
    """
    col, zone = collisions(ctx), zone_of(ctx)
    return _minimum(ctx, "keep_out_min", lambda x, y: col.keep_out(x, y, zone),
                    lambda x, y, r: col.keep_out_lipschitz(x, y, zone, r))


#: the options after which a design's figures draw its bodies (:func:`drawn`)
DRAWN_BY = ("min_clearance", "link_width", "carriage_length", "min_joint_angle", "keep_out", "min_base",
            "motor_diameter")


def drawn(req, objectives=()) -> bool:
    """True when the figures of a design (design.png, the explorer) draw its bodies as
    capsules, its keep-out zone and its worst-clearance pose: a collision requirement
    or a body size (:data:`DRAWN_BY`) is given, or ``clearance`` is an objective.

    Parameters
    ----------
    req : mechopt.requirements.Requirements or dict
        The requirements (a dict: run.json's ``design.requirements``).
    objectives : sequence of str
        The objectives.

    Returns
    -------
    bool
    """
    get = req.get if isinstance(req, dict) else (lambda k: getattr(req, k, None))
    return "clearance" in tuple(objectives or ()) or any(get(k) is not None for k in DRAWN_BY)


def worst_pose(ctx, what="clearance"):
    """Where the minimum over the task that a design's ``clearance`` (``what="clearance"``,
    :func:`clearance_min`) or ``keep_out`` (``"keep_out"``, :func:`keep_out_min`) margin
    rests on was found: the pose evaluated at that value.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's evaluation (its sampling: :meth:`Sampling.fine
        <mechopt.analysis.sampling.Sampling.fine>` for the values of front.csv and design.json).
    what : str
        ``"clearance"`` or ``"keep_out"``.

    Returns
    -------
    dict or None
        ``value`` [L] (the refined minimum, as reported), ``x, y`` [L, task frame] (the
        platform there) and ``which`` (the two bodies of the closest pair, or the body
        closest to the zone); None when nothing is measured (no pair, no zone) or the
        pose is out of reach.

    Raises
    ------
    ValueError
        When ``what`` is neither ``"clearance"`` nor ``"keep_out"``.
    """
    col = collisions(ctx)
    if what == "clearance":
        value, _ = clearance_min(ctx)
        rows, names = col.pair_clearances, col.pair_names()
    elif what == "keep_out":
        zone = zone_of(ctx)
        if zone is None:
            return None
        value, _ = keep_out_min(ctx)
        rows, names = (lambda x, y: col.keep_out(x, y, zone)), col.zone_bodies(zone)
    else:
        raise ValueError(f"what must be 'clearance' or 'keep_out', got {what!r}")
    if not names or not math.isfinite(value):
        return None
    x, y = ctx.memo(f"{what}_min_where", lambda: None)
    at = rows(np.array([x]), np.array([y]))[:, 0]
    if not np.any(np.isfinite(at)):
        return None
    return dict(value=value, x=x, y=y, which=names[int(np.nanargmin(at))])


class Clearance(Requirement):
    name = "clearance"
    options = (Option("min_clearance", "smallest clearance between links that share no joint [unit] "
                      "(capsules; 0: they may touch)", check=_nonneg("min_clearance")),
               Option("link_width", "width of every link's capsule [unit] (default 20 mm)",
                      check=_pos("link_width")),
               Option("carriage_length", "length of a slider's carriage along its guide [unit] "
                      "(default 60 mm)", check=_nonneg("carriage_length")))
    needs = ("points",)
    margin_text = "`--min-clearance`: the smallest capsule clearance over the task minus the required one"
    margin_unit = "{L}"
    certificate = ("minimum located on the samples and refined by zooming (mechopt.analysis.sampling); "
                   "clearance_bound: sampled clearance - (k_a + k_b) rho (Lipschitz, mechopt.analysis.collisions)")

    def describe(self, req, unit) -> str:
        return f"clearance >= {req.min_clearance} {unit} between links"

    def screen(self, ctx) -> bool:
        c = _at_samples(ctx, "clearance_min", collisions(ctx).pair_clearances)
        return float(np.nanmin(c, initial=math.inf)) >= ctx.req.min_clearance - SCREEN * ctx.diameter

    def evaluate(self, ctx):
        m = clearance_min(ctx)[0] - ctx.req.min_clearance
        return m, -m / ctx.diameter

    def report(self, ctx) -> dict:
        if not ctx.has("clearance_min"):
            return {}
        m, bound = clearance_min(ctx)
        return {"clearance_min": m, "clearance_bound": bound}


class JointAngle(Requirement):
    name = "joint_angle"
    options = (Option("min_joint_angle", "smallest angle between two links that share a joint [deg]",
                      check=_angle, parse=lambda t: math.radians(_v.finite_number("--min-joint-angle", t)),
                      metavar="DEG"),)
    needs = ("points",)
    margin_text = "`--min-joint-angle`: the smallest angle between adjacent links over the task minus the limit"
    margin_unit = "rad"
    certificate = ("minimum located on the samples and refined by zooming; joint_angle_bound: sampled angle - "
                   "rate bound x rho (Lipschitz, mechopt.analysis.collisions)")

    def describe(self, req, unit) -> str:
        return f"angle >= {math.degrees(req.min_joint_angle):g} deg between adjacent links"

    def evaluate(self, ctx):
        m = joint_angle_min(ctx)[0] - ctx.req.min_joint_angle
        return m, -m / math.pi

    def report(self, ctx) -> dict:
        if not ctx.has("joint_angle_min"):
            return {}
        m, bound = joint_angle_min(ctx)
        return {"joint_angle_min": m, "joint_angle_bound": bound}


class KeepOut(Requirement):
    name = "keep_out"
    options = (Option("keep_out", "a zone no body may enter: task (the task; the links carrying the tool "
                      "excepted), polygon:x1,y1;x2,y2;... [unit], above:Y or below:Y [unit]",
                      check=_zone_text, parse=str, metavar="ZONE"),)
    needs = ("points",)
    margin_text = "`--keep-out`: the smallest distance of a body's capsule to the zone over the task"
    margin_unit = "{L}"
    certificate = ("minimum located on the samples and refined by zooming; keep_out_bound: sampled margin - "
                   "body speed x rho (Lipschitz, mechopt.analysis.collisions)")

    def describe(self, req, unit) -> str:
        return f"no body in the zone {req.keep_out}"

    def evaluate(self, ctx):
        m = keep_out_min(ctx)[0]
        return m, -m / ctx.diameter

    def report(self, ctx) -> dict:
        if not ctx.has("keep_out_min"):
            return {}
        m, bound = keep_out_min(ctx)
        return {"keep_out_min": m, "keep_out_bound": bound}


class Base(Requirement):
    name = "base"
    options = (Option("min_base", "smallest distance between the base joints or guides [unit] "
                      "(the five-bar's 2 r3)", check=_nonneg("min_base")),
               Option("motor_diameter", "diameter of each motor housing at a base joint [unit] (default 60 mm; "
                      "given, the housings must clear each other by --min-clearance)",
                      check=_nonneg("motor_diameter")))
    proven = True
    margin_text = ("`--min-base`, `--motor-diameter`: the base distance minus the required one, or the "
                   "housings' clearance minus `--min-clearance`, whichever is smaller")
    margin_unit = "{L}"
    certificate = "exact: the fixed bodies do not move"

    def active(self, req, spec) -> bool:
        return req.min_base is not None or req.motor_diameter is not None

    def describe(self, req, unit) -> str:
        parts = ([f"base >= {req.min_base} {unit}"] if req.min_base is not None else []) + \
                ([f"housings of {req.motor_diameter} {unit} clear"] if req.motor_diameter is not None else [])
        return " and ".join(parts)

    def evaluate(self, ctx):
        col, req = collisions(ctx), ctx.req
        m = math.inf
        if req.min_base is not None:
            m = min(m, col.base_distance() - req.min_base)
        if req.motor_diameter is not None:
            m = min(m, col.base_margin() - (req.min_clearance or 0.0))
        return m, -m / ctx.diameter


class ClearanceObjective(Objective):
    name = "clearance"
    sense = -1
    unit = "{L}"
    description = "smallest clearance between links that share no joint, over the task (capsules)"
    needs = ("points",)

    def value(self, ctx) -> float:
        return clearance_min(ctx)[0]

    def bounds(self, ev):
        return (-ev.max_length, ev.max_length)

    def invalid_value(self, ev, lengths) -> float:
        return -ev.max_length

    def report(self, ctx) -> dict:
        return Clearance.report(self, ctx)


MEMBERS = (Clearance(), JointAngle(), KeepOut(), Base(), ClearanceObjective())
