"""Size and footprint: the objectives ``size`` (the sum of the link lengths each design
spec states, :meth:`~mechopt.core.design_spec.DesignSpec.size`) and ``footprint``
(the radius about the base midpoint of every joint over the task's samples, and of
the task itself).
"""
from __future__ import annotations

import numpy as np

from mechopt.requirements.base import Objective

__all__ = ["SizeObjective", "FootprintObjective", "size", "footprint", "MEMBERS"]


def size(ctx) -> float:
    """The design's size [L].

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The size [L] as the mechanism's design spec defines it (its ``size``).
    """
    return ctx.memo("size", lambda: float(ctx.spec.size(ctx.mech, ctx.derived)))


def footprint(ctx) -> float:
    """The largest distance [L] of any joint (at the task's samples) or task sample from
    the base midpoint.

    Parameters
    ----------
    ctx : mechopt.analysis.design_context.DesignContext
        The design's sample context.

    Returns
    -------
    float
        The footprint radius [L].
    """
    def compute():
        s = ctx.samples
        allx, ally = s["allx"], s["ally"]
        fp = 0.0
        # DesignSpec.joints takes task points and gives joints in the task frame (the
        # bipod's base joints at -+b/2; mechanism-frame points put them at -b and 0)
        for jx, jy in ctx.spec.joints(ctx.mech, allx, ally):
            r = np.hypot(np.asarray(jx), np.asarray(jy))
            fp = max(fp, float(np.nanmax(r)) if np.any(np.isfinite(r)) else 0.0)
        return max(fp, float(np.hypot(allx, ally).max()))
    return ctx.memo("footprint", compute)


class SizeObjective(Objective):
    name = "size"
    unit = "{L}"
    description = "sum of the link lengths (mechanism docstring of each spec)"

    def value(self, ctx) -> float:
        return size(ctx)

    def bounds(self, ev):
        return (0.0, ev.spec.size_bound(ev.max_length))

    def report(self, ctx) -> dict:
        return {"size": size(ctx)}

    def invalid_value(self, ev, lengths) -> float:
        return 2.0 * sum(lengths.values())


class FootprintObjective(Objective):
    name = "footprint"
    unit = "{L}"
    description = "radius about the base midpoint of every joint over the task"

    def value(self, ctx) -> float:
        return footprint(ctx)

    def bounds(self, ev):
        x0, x1, y0, y1 = ev.task.bbox
        return (0.0, ev.spec.size_bound(ev.max_length) + float(np.abs([x0, x1, y0, y1]).max()))

    def report(self, ctx) -> dict:
        return {"footprint": footprint(ctx)} if ctx.has("footprint") else {}

    def invalid_value(self, ev, lengths) -> float:
        return 2.0 * sum(lengths.values())


MEMBERS = (SizeObjective(), FootprintObjective())
