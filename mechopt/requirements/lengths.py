"""Lengths: derived lengths that are links too (the bipod's struts at full extension)
are at most ``max_length`` (the design variables have bounds ``[min_length,
max_length]`` of their own). Exact: the struts' longest extension is their derived
stroke's end.
"""
from __future__ import annotations

from mechopt.requirements.base import Requirement

__all__ = ["Lengths", "MEMBERS"]


class Lengths(Requirement):
    name = "lengths"
    always = True
    needs = ("strokes",)
    margin_text = "bipod: `--max-length` minus the longest strut at full extension"
    margin_unit = "{L}"
    certificate = "exact: the longest strut extension is the end of its derived stroke"

    def applies(self, spec) -> bool:
        return spec.length_constraint

    def describe(self, req, unit) -> str:
        return "the link-length bounds"

    def evaluate(self, ctx):
        qmax = max(ctx.mech.q1_max, ctx.mech.q2_max)
        return ctx.max_length - qmax, (qmax - ctx.max_length) / ctx.max_length


MEMBERS = (Lengths(),)
