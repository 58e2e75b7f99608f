"""benchmarks/bench_design_floor.py's accounting, on a small version of its tutorial case:
every design evaluation is counted once, in the stage that asked for it; the compiled
loops' time is part of the evaluations' time; the floors lie below the total; and the
functions the meter wraps are put back (the figures of the issue's floor analysis rest
on this accounting)."""
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def floor():
    sys.path.insert(0, str(ROOT / "benchmarks"))
    try:
        import bench_design_floor
    finally:
        sys.path.remove(str(ROOT / "benchmarks"))
    return bench_design_floor


def test_meter_accounts_a_small_design_run(floor):
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.core.jit import HAVE_NUMBA, Twin
    from mechopt.workflows import design as wd

    wrapped = (DesignEvaluator.evaluate, Twin.__call__, wd._polish_front, wd.certify)
    pop = 16
    m = floor.measure("tutorial", ["--pop", str(pop), "--gen", "6"], warm=False)
    assert (DesignEvaluator.evaluate, Twin.__call__, wd._polish_front, wd.certify) == wrapped
    s = floor.summarise(m, start=0.0)
    n = {k: count for k, (count, _) in s["evals"].items()}
    # the search's own evaluations (run.json) plus at most one per row of its final
    # population for the front's table
    search = n[("search", "search (settled)")]
    assert m["search_evaluations"] <= search <= m["search_evaluations"] + pop
    # the polish evaluates with the certification's sampling (SLSQP, COBYLA) and with it
    # settled (the direct search); the certification with the fine one
    assert n[("polish", "fine")] > 0 and n[("polish", "fine (settled)")] > 0
    assert n[("certification", "fine")] > 0
    assert 0.0 < s["eval_cpu"] <= s["total"]
    assert sum(s["stages"].values()) == pytest.approx(s["total"])
    if HAVE_NUMBA:  # a population loads the compiled twins: they run inside the evaluations
        assert 0.0 < s["compiled_in_evaluations"] < s["eval_cpu"]
    else:
        assert s["compiled_in_evaluations"] == 0.0
    free, compiled = s["floors"]["free evaluations"], s["floors"]["compiled only"]
    assert 0.0 < free <= compiled <= s["total"]
