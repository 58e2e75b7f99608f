"""Certificates that hold (issue 28): full-precision CSV, placement on both sides of the
base line, certificate.json and ``mechopt check`` (with tolerance boxes).

The knife-edge design below was found by bisection on r3 from a polished front design
(rect:40,30@0,150, LCI >= 0.4): at full precision its LCI margin is >= 0 (5.6e-17),
at r3 rounded to 10 significant digits it is -2.7e-12 (the assertions check both).
"""
from __future__ import annotations

import io
import json

import numpy as np
import pandas as pd
import pytest

from mechopt.analysis.design_eval import DesignEvaluator, certify
from mechopt.analysis.task import parse_task
from mechopt.requirements import Requirements
from mechopt.run import io as _io

KNIFE_TASK = "rect:40,30@0,150"
KNIFE = dict(r1=124.36986838734104, r2=45.953153080330914, r3=3.175029087666897, mode="+-",
             task_x=0.0, task_y=150.0)


def _knife_evaluator():
    return DesignEvaluator("five-bar", parse_task(KNIFE_TASK), Requirements(min_lci=0.4), ("size", "min-lci"),
                           max_length=250)


# ----------------------------------------------------------------- 1. full precision
def test_write_csv_round_trips_every_double(tmp_path):
    """Any double written by write_csv reads back (pandas' default parser) bit for bit;
    10 significant digits (the former format) would not."""
    rng = np.random.default_rng(5)
    x = rng.normal(size=5000) * 10.0 ** rng.integers(-12, 12, 5000)
    x[:4] = [0.1, 1 / 3, -0.0, 5e-324]
    df = pd.DataFrame({"a": x, "b": np.nextafter(x, np.inf), "mode": ["+-"] * len(x)})
    _io.write_csv(df, tmp_path / "f.csv")
    back = pd.read_csv(tmp_path / "f.csv", dtype={"mode": str})
    assert np.array_equal(back["a"].to_numpy(), x) and np.array_equal(back["b"].to_numpy(), df["b"].to_numpy())
    assert np.array_equal(np.signbit(back["a"].to_numpy()), np.signbit(x))
    rounded = pd.read_csv(io.StringIO(df.to_csv(index=False, float_format="%.10g")))
    assert not np.array_equal(rounded["a"].to_numpy(), x)  # the check can fail


def test_front_row_of_a_knife_edge_design_reads_back_feasible(tmp_path):
    """A design whose LCI margin is 5.6e-17: its front.csv row, re-read, has the very
    lengths and margins, and re-evaluating the re-read lengths violates nothing; the
    same row at 10 digits violates LCI (what the issue found in front.csv)."""
    ev = _knife_evaluator()
    res = certify(ev, KNIFE)
    assert res["feasible"] and 0 <= res["margin"]["lci"] < 1e-15
    row = ev.row(KNIFE, res)
    _io.write_csv(pd.DataFrame([row]), tmp_path / "front.csv")
    back = pd.read_csv(tmp_path / "front.csv", dtype={"mode": str}).iloc[0].to_dict()
    for k, val in row.items():
        assert back[k] == val, k
    again = certify(ev, {k: back[k] for k in KNIFE})
    assert again["feasible"] and again["margin"] == res["margin"]
    rounded = {k: float(f"{val:.10g}") if isinstance(val, float) else val for k, val in KNIFE.items()}
    assert not certify(ev, rounded)["feasible"]
