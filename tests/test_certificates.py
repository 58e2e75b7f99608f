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


# ----------------------------------------------------------------- 2. placement
SHAPE_TASK = dict(shape=(1.2, 0.8, 0.6), max_length=100, seed=1, pop=12, gen=6, n_jobs=1, polish=False)


def _grid_check(mech, task, gamma, n=61):
    """Own check on an n x n grid of the placed square task: every point reachable, one
    sign of the type-II function, the smallest LCI (mechopt.FiveBar's kinematics)."""
    x0, x1, y0, y1 = task.bbox
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    x, y = gx.ravel(), gy.ravel()
    if not mech.reachable(x, y).all():
        return False, 0.0
    f = mech.type2_function(x, y)
    lci = mech.lci(x, y)
    return bool((np.all(f > 0) or np.all(f < 0)) and lci.min() >= gamma - 1e-9), float(lci.min())


@pytest.fixture(scope="module")
def shape_runs():
    from mechopt.analysis.task import Task
    from mechopt.workflows.design import design

    task, req = Task.rect(10, 10), Requirements(min_lci=0.5)
    return task, {place: design("five-bar", task, req, ("size",), place=place, mode="+-", **SHAPE_TASK)
                  for place in ("free-y", "free")}


def test_free_y_searches_below_the_base_line(shape_runs):
    """Mode +-, shape (1.2, 0.8, 0.6), a 10 mm square, LCI >= 0.5: the design found lies
    below the base line, holds on a 61 x 61 grid (own check), and at its size no height
    above the line works in mode +- (a scan of 300 heights, each on the grid): the
    search above only could not have found it. Its mirror image is the same design in
    mode -+ above the line."""
    import mechopt

    task, runs = shape_runs
    best = runs["free-y"].front.iloc[0]
    assert best["task_y"] < 0
    mech = mechopt.FiveBar(best["r1"], best["r2"], best["r3"], mode="+-")
    ok, lmin = _grid_check(mech, task.moved_to(best["task_x"], best["task_y"]), 0.5)
    assert ok, lmin
    mirror = mechopt.FiveBar(best["r1"], best["r2"], best["r3"], mode="-+")
    ok_m, lmin_m = _grid_check(mirror, task.moved_to(best["task_x"], -best["task_y"]), 0.5)
    assert ok_m and lmin_m == pytest.approx(lmin, rel=1e-12, abs=1e-12)
    D = best["D"]
    above = [_grid_check(mech, task.moved_to(0.0, y), 0.5, n=21) for y in np.linspace(0.01 * D, 3 * D, 300)]
    assert not any(ok for ok, _ in above)


def test_free_contains_free_y(shape_runs):
    """``--place free`` on the same seed and budget ends no worse than ``free-y``: every
    free-y front design is on free's front or dominated by one of its designs."""
    _, runs = shape_runs
    fy, fr = runs["free-y"], runs["free"]
    assert fr.info["other_designs"] == len(fy.front) >= 1 and fy.info["other_designs"] >= 1
    assert fr.front["size"].min() <= fy.front["size"].min()
    for s in fy.front["size"]:
        assert (fr.front["size"] <= s).any()


# ----------------------------------------------------------------- 3. certificate.json, mechopt check
RUN_ARGS = dict(seed=1, pop=12, gen=6, n_jobs=1, max_length=200, polish=False)
RUN_TASK, RUN_GAMMA = "rect:60,40@0,150", 0.4


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    from mechopt.workflows.design import design

    out = tmp_path_factory.mktemp("certs") / "run"
    design("five-bar", parse_task(RUN_TASK), Requirements(min_lci=RUN_GAMMA), ("size", "min-lci"), out=out,
           **RUN_ARGS)
    return out


def test_front_csv_reads_back_as_design_json(run_dir):
    """Re-reading front.csv gives exactly design.json's lengths, placement and margins."""
    front = pd.read_csv(run_dir / "front.csv", dtype={"mode": str})
    chosen = json.loads((run_dir / "design.json").read_text())
    row = front.iloc[chosen["index"]]
    for k, val in chosen["variables"].items():
        assert row[k] == val, k
    for k, val in chosen["task_placement"].items():
        assert row[k] == val, k
    for k, val in chosen["margins"].items():
        assert row[f"margin_{k}"] == val, k
    # and the re-read lengths re-evaluate to the same, feasible margins
    ev = DesignEvaluator("five-bar", parse_task(RUN_TASK), Requirements(min_lci=RUN_GAMMA), ("size", "min-lci"),
                         max_length=200)
    for _, r in front.iterrows():
        res = certify(ev, {k: r[k] for k in ("r1", "r2", "r3", "mode", "task_x", "task_y")})
        assert res["feasible"] and all(res["margin"][k] == r[f"margin_{k}"] for k in res["margin"])


def test_certificate_json_records_every_front_design(run_dir):
    from mechopt.export.source import design_digest

    cert = json.loads((run_dir / "certificate.json").read_text())
    chosen = json.loads((run_dir / "design.json").read_text())
    front = pd.read_csv(run_dir / "front.csv", dtype={"mode": str})
    manifest = json.loads((run_dir / "manifest.json").read_text())
    assert "certificate.json" in manifest["files"]
    assert len(cert["designs"]) == len(front) >= 2 and cert["chosen"] == chosen["index"]
    # the chosen design's digest is design.json's
    assert cert["designs"][cert["chosen"]]["digest"] == design_digest(chosen)
    assert len({d["digest"] for d in cert["designs"]}) == len(front)
    assert cert["sampling"]["n_boundary"] >= 1000 and cert["settings"]["mechanism"] == "five-bar"
    for d, (_, row) in zip(cert["designs"], front.iterrows()):
        assert set(d["requirements"]) == {"reach", "singular", "lci"}
        assert d["requirements"]["reach"]["method"] == "proven"
        # LCI is proven where its interval bound meets the level (designs off the LCI edge)
        b = d["requirements"]["lci"]["bound"]
        assert b["lower_bound"] <= b["estimate"] and b["gap"] <= 0.01
        assert d["requirements"]["lci"]["method"] == ("proven" if b["proven_margin"] >= 0 else "refined-sampled")
        for name, e in d["requirements"].items():
            assert e["margin"] == row[f"margin_{name}"] and e["holds"] and e["g"] <= 0
        assert all(d["variables"][k] == row[k] for k in ("r1", "r2", "r3"))


def test_certificate_bounds_in_lock_step_are_each_designs_alone(run_dir):
    """certificate.json's bounds (every front design's searches in lock-step) are, bit for
    bit, those of each design bounded alone (proven_bounds, one design at a time)."""
    from mechopt.workflows.certificate import proven_bounds

    cert = json.loads((run_dir / "certificate.json").read_text())
    ev = DesignEvaluator("five-bar", parse_task(RUN_TASK), Requirements(min_lci=RUN_GAMMA), ("size", "min-lci"),
                         max_length=RUN_ARGS["max_length"])
    for d in cert["designs"][:3]:
        reqs = d["requirements"]
        alone = proven_bounds(ev, {**d["variables"], **d["task_placement"]}, {k: e["margin"] for k, e in reqs.items()})
        assert set(alone) == {"singular", "lci"}
        for name, b in alone.items():
            got = reqs[name]["bound"]
            assert (got["lower_bound"], got["cells"]) == (b["lower_bound"], b["cells"]), name


def _main(argv, capsys):
    from mechopt.cli import main

    code = main(argv)
    cap = capsys.readouterr()
    return code, cap.out, cap.err


def test_check_cli_exit_statuses(run_dir, capsys, tmp_path):
    design_json = str(run_dir / "design.json")
    code, out, _ = _main(["check", design_json], capsys)
    assert code == 0 and "all requirements hold" in out and "lci: margin" in out
    assert "certificate.json records this design.json" in out
    chosen = json.loads((run_dir / "design.json").read_text())
    # the margin printed is design.json's (6 digits)
    assert f"{chosen['margins']['lci']:.6g}" in out
    # links of 10 mm: the task (150 mm away) leaves the workspace; named
    r1 = chosen["variables"]["r1"]
    code, out, _ = _main(["check", design_json, "--lengths", "r1=10,r2=10"], capsys)
    assert code == 1 and "fails: reach" in out and "reach: margin -" in out
    # a hand-edited design.json (rounded lengths, 2 decimals) in another folder with its run.json
    edited = tmp_path / "edited"
    edited.mkdir()
    rec = dict(chosen, variables={k: (round(v, 2) if k != "mode" else v) for k, v in chosen["variables"].items()})
    (edited / "design.json").write_text(json.dumps(rec))
    (edited / "run.json").write_text((run_dir / "run.json").read_text())
    (edited / "certificate.json").write_text((run_dir / "certificate.json").read_text())
    code, out, _ = _main(["check", str(edited / "design.json"), "--json"], capsys)
    rep = json.loads(out)
    # edited: the certificate does not vouch (and claims nothing about it)
    assert rep["certificate"] == {"index": None, "chosen": False, "disagrees": []}
    assert code == (0 if rep["holds"] else 1)
    assert rep["variables"]["r1"] == round(r1, 2)
    ev = DesignEvaluator("five-bar", parse_task(RUN_TASK), Requirements(min_lci=RUN_GAMMA), ("size",), max_length=200)
    own = certify(ev, {**rep["variables"]})
    assert {k: e["margin"] for k, e in rep["requirements"].items()} == pytest.approx(own["margin"], rel=0, abs=0)
    # bad input: exit 2, one line
    for argv in (["check", str(tmp_path / "none.json")], ["check", design_json, "--lengths", "r9=3"],
                 ["check", design_json, "--tolerance", "0"], ["check", design_json, "--lengths", "r1"],
                 ["check", str(run_dir / "front.csv")]):
        code, out, err = _main(argv, capsys)
        assert code == 2 and len(err.strip().splitlines()) == 1 and err.startswith("mechopt: error:"), (argv, err)


# ----------------------------------------------------------------- 4. tolerance boxes
def _write_knife(folder):
    ev = _knife_evaluator()
    folder.mkdir()
    rec = {"mechanism_name": "five-bar", "unit": "mm", "variables": {k: KNIFE[k] for k in ("r1", "r2", "r3", "mode")},
           "task_placement": {"task_x": KNIFE["task_x"], "task_y": KNIFE["task_y"]}}
    (folder / "design.json").write_text(json.dumps(rec))
    (folder / "run.json").write_text(json.dumps({"problem": "design", "design": _io.plain_json(ev.settings())}))
    return folder / "design.json"


def test_knife_edge_design_holds_but_not_within_a_tolerance(tmp_path, capsys):
    """The knife-edge design holds as it is (exit 0) and fails with --tolerance 0.01 mm,
    naming LCI; with its r3 at 10 digits it fails (exit 1)."""
    path = str(_write_knife(tmp_path / "k"))
    code, out, _ = _main(["check", path], capsys)
    assert code == 0, out
    code, out, _ = _main(["check", path, "--tolerance", "0.01"], capsys)
    assert code == 1 and "fails: lci (within +-0.01 mm)" in out and "sampled at 44 mechanisms" in out
    code, out, _ = _main(["check", path, "--lengths", f"r3={KNIFE['r3']:.10g}"], capsys)
    assert code == 1 and "fails: lci" in out


def test_tolerance_box_that_holds_holds_on_a_dense_own_check(run_dir):
    """A box the check says holds (the knee design, +-0.05 mm): 300 random mechanisms
    inside it, each on a 61 x 61 grid of the placed task with mechopt.FiveBar's own
    kinematics, all reach the task in one assembly mode with LCI >= gamma; the box's
    smallest LCI margin is no lower than the sampled one by more than the grid's
    resolution would explain (it is a sampled minimum, not a bound)."""
    import mechopt
    from mechopt.workflows.certificate import check

    rep = check(run_dir / "design.json", tolerance=0.05)
    assert rep["holds"] and rep["box"]["evaluated"] == 8 + 4 + 32
    # the interval bound over the task and the whole box proves it (the five-bar's enclosure
    # takes length intervals): every requirement proven, each bound below every dense value
    assert rep["box"]["method"] == "proven" and set(rep["box"]["methods"].values()) == {"proven"}
    v = rep["variables"]
    task = parse_task(RUN_TASK).moved_to(v["task_x"], v["task_y"])
    rng = np.random.default_rng(11)
    worst = np.inf
    for off in rng.uniform(-0.05, 0.05, size=(300, 3)):
        mech = mechopt.FiveBar(v["r1"] + off[0], v["r2"] + off[1], max(v["r3"] + off[2], 0.0), mode=v["mode"])
        ok, lmin = _grid_check(mech, task, RUN_GAMMA)
        assert ok, (off, lmin)
        worst = min(worst, lmin - RUN_GAMMA)
    assert rep["box"]["min_margin"]["lci"] <= worst + 1e-3
    assert 0 <= rep["box"]["proven"]["lci"]["proven_margin"] <= worst


def test_check_fails_on_a_tampered_certificate(run_dir, tmp_path, capsys):
    """The certificate.json beside an untouched design.json, with one claimed margin
    raised (or a verdict turned): the re-check finds another number, and the check
    fails (exit 1) naming it; the untampered copy passes."""
    chosen = json.loads((run_dir / "design.json").read_text())
    cert = json.loads((run_dir / "certificate.json").read_text())
    k = cert["chosen"]
    name = next(iter(cert["designs"][k]["requirements"]))
    for tamper in ("margin", "holds"):
        folder = tmp_path / tamper
        folder.mkdir()
        for f in ("design.json", "run.json"):
            (folder / f).write_text((run_dir / f).read_text())
        bad = json.loads(json.dumps(cert))
        entry = bad["designs"][k]["requirements"][name]
        if tamper == "margin":
            entry["margin"] = entry["margin"] + 1.0
        else:
            entry["holds"] = not entry["holds"]
        (folder / "certificate.json").write_text(json.dumps(bad))
        code, out, _ = _main(["check", str(folder / "design.json")], capsys)
        assert code == 1 and f"certificate.json: {name} (certificate.json claims margin" in out, out
        (folder / "certificate.json").write_text(json.dumps(cert))
        code, out, _ = _main(["check", str(folder / "design.json")], capsys)
        assert code == (0 if all(m >= 0 for m in chosen["margins"].values()) else 1), out
        assert "certificate.json records this design.json" in out


def test_check_reverifies_a_certificate(run_dir, tmp_path, capsys, monkeypatch):
    """``mechopt check DIR/certificate.json``: every recorded design re-certified from the
    certificate alone (exit 0, one line per design); a certificate with a raised claimed
    margin, one claiming proven what the check does not prove, one whose design was moved
    (r1 0.1 mm shorter): exit 1 naming the design and what fails; options of a
    design.json, a broken file: one line, exit 2."""
    cert = json.loads((run_dir / "certificate.json").read_text())
    n = len(cert["designs"])
    code, out, _ = _main(["check", str(run_dir / "certificate.json")], capsys)
    assert code == 0 and f"{n} certified designs re-checked" in out and f"all {n} designs hold" in out, out
    assert out.count("holds, every claim found again") == n
    k = min(range(n), key=lambda i: cert["designs"][i]["requirements"]["lci"]["margin"])  # nearest the edge
    cases = {name: json.loads(json.dumps(cert)) for name in ("raised", "moved")}
    cases["raised"]["designs"][k]["requirements"]["singular"]["margin"] += 0.5
    cases["moved"]["designs"][k]["variables"]["r1"] -= 0.1
    expect = {"raised": (k, "certificate.json: singular (certificate.json claims margin"),
              "moved": (k, "certificate.json: lci (certificate.json claims margin")}
    for what, bad in cases.items():
        path = tmp_path / f"{what}.json"
        path.write_text(json.dumps(bad))
        code, out, _ = _main(["check", str(path)], capsys)
        idx, phrase = expect[what]
        assert code == 1 and f"design {idx}: " in out.splitlines()[-1] and phrase in out, (what, out)
    # a claim of "proven" the re-check cannot make (its bounds withheld): every such claim named
    import mechopt.workflows.certificate as cert_module

    proven = [(i, r) for i, d in enumerate(cert["designs"]) for r, e in d["requirements"].items()
              if e["method"] == "proven" and r in cert_module.BOUNDED]
    assert proven
    monkeypatch.setattr(cert_module, "proven_bounds", lambda *a, **kw: {})
    code, out, _ = _main(["check", str(run_dir / "certificate.json")], capsys)
    assert code == 1, out
    for i, r in proven:
        assert f"design {i}: certificate.json: {r} (certificate.json claims it proven, the check does not prove it)" \
            in out.splitlines()[-1], (i, r, out)
    monkeypatch.undo()
    for argv in (["check", str(run_dir / "certificate.json"), "--lengths", "r1=80"],
                 ["check", str(run_dir / "certificate.json"), "--tolerance", "0.05"]):
        code, out, err = _main(argv, capsys)
        assert code == 2 and len(err.strip().splitlines()) == 1 and "applies to a design.json" in err, err
    broken = tmp_path / "broken.json"
    broken.write_text(json.dumps({"certificate_version": 1, "designs": "none"}))
    code, out, err = _main(["check", str(broken)], capsys)
    assert code == 2 and len(err.strip().splitlines()) == 1 and "is not a certificate.json" in err, err
