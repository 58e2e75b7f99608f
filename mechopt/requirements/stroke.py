"""Stroke: the longest actuator stroke over the task is at most ``max_stroke``
(mechanisms with sliders or struts).

The strokes are not searched: the smallest stroke that covers the task is the range
of each actuator coordinate over it, attained on ``dT`` (no interior critical point
in a singularity-free region); the evaluator derives them for every such design.
"""
from __future__ import annotations

from mechopt.core import validation as _v
from mechopt.requirements.base import Option, Requirement

__all__ = ["Stroke", "MEMBERS"]


class Stroke(Requirement):
    name = "stroke"
    options = (Option("max_stroke", "longest actuator stroke [unit, or with a unit: 0.2m] (sliders)",
                      check=lambda v, spec: _v.positive_length("max_stroke", v), kind="length"),)
    needs = ("strokes",)
    instead = "joint_limits"
    margin_text = "`--max-stroke`: the limit minus the longest stroke"
    margin_unit = "{L}"
    certificate = "extremes on the task's boundary (no interior critical point), boundary samples refined by zooming"

    def applies(self, spec) -> bool:
        return not spec.angular

    def describe(self, req, unit) -> str:
        return f"stroke <= {req.max_stroke} {unit}"

    def evaluate(self, ctx):
        m = ctx.req.max_stroke - ctx.derived["stroke"]
        return m, -m / ctx.req.max_stroke


MEMBERS = (Stroke(),)
