"""Reach: the whole task lies in the reachable set of one working mode (always required).

Certified, not sampled. ``serial_clearance`` is the exact distance to the boundary
``dR`` of the reachable set ``R``, inside ``R`` (1-Lipschitz), so ``clearance >= c``
at boundary samples gives ``>= c - h_b/2`` on all of ``dT`` (``h_b`` the largest gap
between boundary samples). Inside ``T`` the distance to ``dR`` has no local minimum
(moving toward the nearest boundary point of ``R`` lowers it), so once ``dT`` is in
``R`` a point of ``T`` outside ``R`` can only belong to a bounded component (a hole)
of the complement of ``R``; for every mechanism here each hole contains a base joint
(five-bar, bipod: the disks ``|P - A_i| < |r1 - r2|`` or ``< q_min``, for the
asymmetric five-bar ``< |a_i - c_i|``; the biglide's and gantry's leg regions are
simply connected, their complements unbounded; a spec's
:meth:`~mechopt.core.design_spec.DesignSpec.holes` names them), so "no base joint in
``T``" closes the argument. Margin: ``c - h_b/2`` [L] > 0. A path (a polyline) is
covered by its samples in the same way (every point of it within ``h_b/2`` of one, and
a disk of radius ``c`` about a sample lies in ``R``): margin ``c - h_b/2``. A point task
is checked at its points exactly.
"""
from __future__ import annotations

from mechopt.core import validation as _v
from mechopt.requirements.base import Requirement

__all__ = ["Reach", "MEMBERS"]

#: a design whose reach margin is below ``-SCREEN * D`` is not refined (far from feasible)
SCREEN = 0.05


class Reach(Requirement):
    name = "reach"
    always = True
    proven = True
    needs = ("points", "clearance")
    margin_text = ("the whole task reachable in one working mode: certified clearance (sampled minimum "
                   "minus half the boundary gap)")
    margin_unit = "{L}"
    certificate = "certified: clearance >= sampled minimum - boundary_gap/2 (1-Lipschitz), no base joint in the task"

    def describe(self, req, unit) -> str:
        return "reachability of the whole task in one working mode"

    def margin(self, ctx) -> float:
        """The certified margin [L] (module docstring).

        Parameters
        ----------
        ctx : mechopt.analysis.design_context.DesignContext
            The design's sample context.

        Returns
        -------
        float
            The certified clearance to the boundary of the reachable set [L]: the sampled
            minimum minus half the boundary gap (1-Lipschitz).
        """
        return ctx.memo("reach_margin", lambda: self._margin(ctx))

    @staticmethod
    def _margin(ctx) -> float:
        clr = ctx.clearance
        if ctx.task.is_path:
            return float(clr.min()) - 0.5 * ctx.samples["gap"]
        if not ctx.is_region:
            return float(clr.min())
        D = ctx.diameter
        margin = min(float(clr[:ctx.n_boundary].min()) - 0.5 * ctx.samples["gap"], float(clr.min()))
        x0, x1, y0, y1 = ctx.task.bbox
        far = 2.0 * _v.ROUNDING * D
        for hx, hy in ctx.spec.holes(ctx.mech):
            if hx < x0 - far or hx > x1 + far or hy < y0 - far or hy > y1 + far:
                continue  # farther than 2 ROUNDING D from the task's box: depth < -ROUNDING D below
            depth = float(ctx.task.signed_distance(hx, hy))
            if depth >= -_v.ROUNDING * D:
                margin = min(margin, -max(depth, _v.RESOLUTION * D))
        return margin

    def screen(self, ctx) -> bool:
        return self.margin(ctx) > -SCREEN * ctx.diameter

    def evaluate(self, ctx):
        m, D = self.margin(ctx), ctx.diameter
        return m, (-m / D if m > 0 else -m / D + _v.RESOLUTION)


MEMBERS = (Reach(),)
