"""experiments/stan2008.py (installed as mechopt.experiments.stan2008): the quick run
produces every published quantity, a valid table, every file, and the physics it
rests on."""
import json

import numpy as np
import pandas as pd
import pytest

from mechopt.experiments import stan2008
from mechopt.core.published import TABLE_COLUMNS

WEIGHT_LABELS = ("W1=0.7,W2=0.3", "W1=0.3,W2=0.7", "W1=1,W2=0", "W1=0,W2=1")
QUANTITIES = (
    ["workspace_area", "workspace_area[b=62mm]"]
    + [f"q1_over_b[{w}]" for w in WEIGHT_LABELS]
    + [f"q1_over_b[{w};GA Table 1 rates]" for w in WEIGHT_LABELS]
    + ["q1_over_b[W1=1,W2=0;retracted pose]", "q1_over_b[W1=0,W2=1;design 80/62]"]
    + [f"L2[{w}]" for w in WEIGHT_LABELS]
    + [f"L2[{w};GA Table 1 rates]" for w in WEIGHT_LABELS]
    + [f"L2[{w};L1=0.5]" for w in WEIGHT_LABELS]
    + ["ga_population", "ga_generations", "ga_crossover_rate", "ga_mutation_rate"]
    + ["claim:max_workspace_at_q1min/b=1.35", "claim:fig9_pose_regular", "claim:fig10_pose_regular"]
)
RUN_FILES = ("front.csv", "history.csv", "run.json", "front.png", "sweep.csv", "sweep.png")
TOP_FILES = ("fig29_tqi_bipod.png", "fig30_tqi_biglide.png", "tradeoff_bipod.png",
             "tradeoff_biglide.png", "curves.csv", "area_search.csv", "bipod_readings.csv",
             "bipod_reachable_optima.csv", "biglide_l1_scan.csv")


@pytest.fixture(scope="module")
def quick(quick_reproduction):
    """``stan2008.run(out, quick=True)`` as the quick reproduction ran it (tests/conftest.py)."""
    out, table, _ = quick_reproduction.runs["stan2008"]
    return out, table


def test_table_columns_and_quantities(quick):
    _, df = quick
    assert list(df.columns) == list(TABLE_COLUMNS)
    assert sorted(df["quantity"]) == sorted(QUANTITIES)  # each exactly once


def test_statuses_valid_and_differs_explained(quick):
    _, df = quick
    assert set(df["status"]) <= {"match", "differs", "not-reported", "holds", "fails"}
    assert set(df["kind"]) <= {"computed", "setting", "reading", "claim"}
    for rec in df[df["status"].isin(["differs", "holds", "fails"])].itertuples():
        assert isinstance(rec.note, str) and rec.note.strip(), rec.quantity
    # every compared row also names its tolerance (published.compare) and has a finite value
    compared = df[df["kind"] != "claim"]
    assert compared["note"].str.contains("tol ").all()
    assert set(df[df["kind"] == "claim"]["status"]) <= {"holds", "fails"}
    assert np.all(np.isfinite(df["reproduced"].to_numpy(float)))
    # the Table rows are computed, the GA settings settings
    assert (df[df["quantity"].isin([f"q1_over_b[{w}]" for w in WEIGHT_LABELS])]["kind"] == "computed").all()
    assert (df[df["quantity"].str.startswith("ga_")]["kind"] == "setting").all()


def test_files_exist(quick):
    out, _ = quick
    for mech in ("bipod", "biglide"):
        for name in RUN_FILES:
            f = out / mech / name
            assert f.is_file() and f.stat().st_size > 0, f
        run = json.loads((out / mech / "run.json").read_text())
        assert run["problem"] == f"stan2008-{mech}" and run["algorithm"]["name"] == "nsga2"
        sweep = pd.read_csv(out / mech / "sweep.csv")
        np.testing.assert_allclose(sweep["weight"], np.round(np.arange(11) * 0.1, 12))
    for name in TOP_FILES:
        f = out / name
        assert f.is_file() and f.stat().st_size > 0, f
    curves = pd.read_csv(out / "curves.csv")
    assert list(curves.columns) == ["mechanism", "variable", "value", "W", "W_n", "T"]
    assert set(curves["mechanism"]) == {"bipod", "biglide"}
    assert set(curves["variable"]) == {"q1_min_over_b", "L2"}


def _row(df, q):
    return df[df["quantity"] == q].iloc[0]


def test_exact_bipod_area(quick):
    _, df = quick
    r = _row(df, "workspace_area")
    assert r["reproduced"] == pytest.approx(4863.88, rel=1e-6)
    assert r["paper"] == 4693.33 and r["status"] == "differs"


def test_bipod_w_only_optimum_at_upper_bound(quick):
    out, df = quick
    assert _row(df, "q1_over_b[W1=0,W2=1]")["reproduced"] == pytest.approx(1.35, abs=1e-3)
    # because W grows monotonically with q1/b over the whole range (curves.csv)
    c = pd.read_csv(out / "curves.csv")
    bip = c[c["mechanism"] == "bipod"]
    assert np.all(np.diff(bip["W"]) > 0)
    assert bip["value"].iloc[-1] == pytest.approx(1.35) and bip["W_n"].iloc[-1] == pytest.approx(1.0)


def test_t_only_optimum_is_the_peak_of_the_t_curve(quick):
    out, df = quick
    c = pd.read_csv(out / "curves.csv")
    bip = c[c["mechanism"] == "bipod"]
    u_peak = bip["value"].iloc[int(np.argmax(bip["T"]))]
    step = np.diff(bip["value"]).max()
    assert _row(df, "q1_over_b[W1=1,W2=0]")["reproduced"] == pytest.approx(u_peak, abs=step)


def test_ga_settings_rows(quick):
    _, df = quick
    s = stan2008.SETTINGS[True]
    assert _row(df, "ga_population")["reproduced"] == s["pop"]
    assert _row(df, "ga_generations")["reproduced"] == s["gen"]
    # the rates actually run (Table 1's), with the operators named
    assert _row(df, "ga_crossover_rate")["reproduced"] == pytest.approx(0.08)
    assert _row(df, "ga_mutation_rate")["reproduced"] == pytest.approx(0.005)
    assert "SBX" in _row(df, "ga_crossover_rate")["note"]
    assert "polynomial mutation" in _row(df, "ga_mutation_rate")["note"]
    assert stan2008.SETTINGS[False]["pop"] == 50 and stan2008.SETTINGS[False]["gen"] == 100


@pytest.mark.slow
def test_full_run_uses_table1_sizes(tmp_path):
    df = stan2008.run(tmp_path, quick=False)
    assert _row(df, "ga_population")["status"] == "match"
    assert _row(df, "ga_generations")["status"] == "match"
    assert _row(df, "q1_over_b[W1=0,W2=1]")["reproduced"] == pytest.approx(1.35, abs=1e-6)
    assert _row(df, "ga_crossover_rate")["status"] == "match"
    assert _row(df, "workspace_area[b=62mm]")["status"] == "match"


@pytest.mark.parametrize("setup", [{}, {"l1": 0.5}, {"l1": 0.3, "q_max": 0.25}, {"l1": 1.0, "q_max": 4.0},
                                   {"l1": 0.64, "q_max": 2.0}])
def test_biglide_population_evaluation_equals_one_design_at_a_time(setup):
    """problems/stan2008.py evaluates a whole population at once (the GA runs' cost): W
    and T must equal Biglide(...).workspace_area() and .gtqi(method="gauss") of each
    design bit for bit, for the literal setup and those of the L1 reading and scan."""
    from mechopt.mechanisms.biglide import Biglide
    from mechopt.problems.stan2008 import StanBiglide

    p = StanBiglide(**{"q_min": 0.0, **setup})
    rng = np.random.default_rng(2008)
    l2 = np.concatenate([rng.uniform(p.xl[0], p.xu[0], 150), np.linspace(p.xl[0], p.xu[0], 41)])
    W, T = p._indices(l2)
    for v, w, t in zip(l2, W, T):
        m = Biglide(p.l1, v, p.q_min, p.q_max)
        assert np.float64(w).tobytes() == np.float64(m.workspace_area()).tobytes(), v
        assert np.float64(t).tobytes() == np.float64(m.gtqi(method="gauss")).tobytes(), v
    # the problem's columns (describe) come from the same numbers, and W_n from the cached W_ref
    cols = p.describe(l2[:5, None])
    np.testing.assert_array_equal(cols["W"], W[:5])
    assert p.w_ref == Biglide(p.l1, p.xu[0], p.q_min, p.q_max).workspace_area()


def test_bipod_population_evaluation_equals_one_design_at_a_time():
    from mechopt.mechanisms.bipod import Bipod
    from mechopt.problems.stan2008 import Q_MAX_OVER_Q_MIN, StanBipod

    p = StanBipod()
    rng = np.random.default_rng(5)
    u = np.concatenate([rng.uniform(p.xl[0], p.xu[0], 300), [p.xl[0], p.xu[0]]])
    W, T = p._indices(u[::-1].copy()[::-1])  # a strided view too
    for v, w, t in zip(u, W, T):
        m = Bipod(1.0, v, Q_MAX_OVER_Q_MIN * v)
        assert np.float64(w).tobytes() == np.float64(m.workspace_area()).tobytes(), v
        assert np.float64(t).tobytes() == np.float64(m.gtqi()).tobytes(), v
