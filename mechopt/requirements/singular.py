"""Singular: no type-II singularity over the task (always required).

``s0 * type2_function`` (the sine of the angle between the legs, ``s0`` its sign at
the task's reference point: the centre of its box, or the first point of a point task
or path; where that point is out of reach or singular, the sign at the reachable
sample farthest from the type-II locus) stays above ``singularity_margin``. A path is
connected too: one sign along it means it never crosses the type-II locus. ``T`` is connected, so one sign means one
connected singularity-free piece, one assembly mode. The minimum over the task is
located on the samples and refined (:mod:`mechopt.analysis.sampling`). Implied by
``LCI >= gamma > 0``.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core import validation as _v
from mechopt.analysis.sampling import bad_to
from mechopt.requirements.base import Option, Requirement

__all__ = ["Singular", "MEMBERS"]

#: a design whose sampled type-II minimum is below ``-SCREEN`` is not refined
SCREEN = 0.05
#: the search leaves the type-II minimum unrefined when the samples' minimum is at
#: least ``singularity_margin + SETTLE`` (:meth:`Singular.settled`): refinement lowered
#: it by at most 0.0008 on 800 random five-bar designs of a rectangle and a star polygon
SETTLE = 0.05


def _margin_check(value, spec):
    m = _v.finite_number("singularity_margin", value)
    if not 0 <= m < 1:
        raise ValueError(f"singularity_margin must lie in [0, 1), got {m!r}")
    return m


class Singular(Requirement):
    name = "singular"
    always = True
    options = (Option("singularity_margin", "smallest |sine of the angle between the legs| allowed",
                      check=_margin_check, default=1e-3, cli=False),)
    needs = ("points", "type2")
    margin_text = ("no type-II singularity over the task: smallest sine of the angle between the legs "
                   "minus the singularity margin")
    certificate = ("boundary and interior critical points located on the samples and refined by zooming "
                   "(mechopt.analysis.sampling)")

    def describe(self, req, unit) -> str:
        return "no type-II singularity over the task (one assembly mode)"

    @staticmethod
    def sign(ctx) -> float:
        """``s0``: the sign of the type-II function at the task's reference point; where
        that is out of reach (NaN) or singular (0), at the reachable sample with the
        largest ``|type2_function|`` (the assembly mode of a reachable task point: a task
        whose samples all share one sign gets that sign whatever its reference point);
        +1 when no sample is reachable.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        float
            ``s0``, +1 or -1.
        """
        def compute():
            s = ctx.samples
            rx, ry = ctx.task.reference if ctx.is_region else ctx.task.pts[0]
            s0 = float(np.sign(ctx.mech.type2_function(*ctx.to_mech(np.float64(rx), np.float64(ry)))))
            if not (math.isfinite(s0) and s0):
                f = ctx.type2_raw[np.isfinite(ctx.type2_raw)]
                s0 = float(np.sign(f[np.argmax(np.abs(f))])) if f.size else 1.0
            return s0 or 1.0
        return ctx.memo("type2_sign", compute)

    def samples(self, ctx):
        """``s0 * type2_function`` at the samples (-1 where unreachable).

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        ndarray
            ``s0 * type2_function`` at each sample (dimensionless, -1 where unreachable).
        """
        return ctx.memo("type2_samples", lambda: bad_to(self.sign(ctx) * ctx.type2_raw, -1.0))

    def minimum(self, ctx) -> float:
        """The minimum of ``s0 * type2_function`` over the task.

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        float
            The minimum (dimensionless), the samples' minimum refined by zooming; memoised
            in ``ctx``.
        """
        def compute():
            s0 = self.sign(ctx)
            return ctx.quantity_min("type2", self.samples(ctx), s0, -1.0, ctx.refines(self.name))
        return ctx.memo("type2_min", compute)

    def screen(self, ctx) -> bool:
        return float(self.samples(ctx).min()) > -SCREEN

    def settled(self, ctx) -> bool:
        return float(self.samples(ctx).min()) >= ctx.req.singularity_margin + SETTLE

    def evaluate(self, ctx):
        t2, m = self.minimum(ctx), ctx.req.singularity_margin
        return t2 - m, (m - t2 if t2 < m else -(t2 - m))

    def report(self, ctx) -> dict:
        return {"type2_min": self.minimum(ctx)}


MEMBERS = (Singular(),)
