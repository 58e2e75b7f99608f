"""``mechopt reproduce --quick``: every paper, the table schema, every required row."""
import re

import pandas as pd
import pytest

from mechopt.cli import main
from mechopt.core.published import TABLE_COLUMNS

REQUIRED = {
    "le2013": ["rho_star", "a_max", "a_max_at_paper_rho", "lci_min_in_square", "lci_max_in_square"],
    "stan2008": ["workspace_area", *(f"q1_over_b[W1={a},W2={b}]" for a, b in
                                     (("0.7", "0.3"), ("0.3", "0.7"), ("1", "0"), ("0", "1"))),
                 *(f"L2[W1={a},W2={b}]" for a, b in (("0.7", "0.3"), ("0.3", "0.7"), ("1", "0"), ("0", "1"))),
                 "ga_population", "ga_generations", "ga_crossover_rate", "ga_mutation_rate"],
    "liu2006": ["r_mic", "gci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min",
                "usable_area", "gcw_area", "gcw_gci", "gcw_gsi_max", "gcw_gsi_min", "gcw_D",
                "gcw_R1", "gcw_R2", "gcw_R3", "gcw_gsi_max_scaled", "gcw_gsi_min_scaled",
                "theta1_lo_deg", "theta1_hi_deg", "theta2_lo_deg", "theta2_hi_deg",
                "gcw_square_side", "square_D", "square_R1", "square_R2", "square_R3",
                "square_theta1_lo_deg", "square_theta1_hi_deg", "square_theta2_lo_deg",
                "square_theta2_hi_deg"],
    "wu2008": ["d1[theta_1S=15deg]", "l[theta_1S=15deg]", "stroke[theta_1S=15deg]", "d1[table1]",
               "l[table1]", "stroke[table1]", "k_av[table1]", "k_av_alternative[table1]",
               "eta_d[built]", "eta_d[symmetric]", "kappa_d_min[built]", "kappa_d_max[built]"],
}
FILES = {
    "le2013": ["curve.csv", "fig5_a_max.png", "fig6_lci_square.png", "front/front.csv", "sweep/sweep.csv"],
    "stan2008": ["fig29_tqi_bipod.png", "fig30_tqi_biglide.png", "bipod/front.csv", "bipod/sweep.csv",
                 "biglide/sweep.csv"],
    "liu2006": ["figs08-16_examples.png", "figs25-28_gcw_square.png", "fig02_atlas_gci.png",
                "fig13_region_w-gci-gsi.png", "atlas.csv", "regions.csv", "front/front.csv",
                "sweep/sweep.csv"],
    "wu2008": ["fig2_workspace.png", "fig4_driving_forces.png", "front/front.csv", "sweep/sweep.csv"],
}


#: every figure the quick reproduction saves, as (path, matplotlib Figure)
FIGURES = []


@pytest.fixture(scope="module")
def results(quick_reproduction):
    """``mechopt reproduce all --quick`` (tests/conftest.py: run once per session, in
    this process, every figure it saves captured)."""
    FIGURES[:] = quick_reproduction.figures
    return quick_reproduction.out


def _text_boxes(fig):
    """Window extents of every title, axis label, legend and suptitle (laid out with
    Agg: ``draw_without_rendering`` places every artist as a draw does, without
    rasterising)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    fig.draw_without_rendering()
    r = canvas.get_renderer()
    items = []
    for ax in fig.axes:
        if not ax.axison:
            continue
        for t in (ax.title, ax.xaxis.label, ax.yaxis.label):
            if t.get_text() and t.get_visible():
                items.append((t.get_window_extent(r), ax, t.get_text()))
        if ax.get_legend() is not None:
            items.append((ax.get_legend().get_window_extent(r), ax, "legend"))
    if fig._suptitle is not None:
        items.append((fig._suptitle.get_window_extent(r), None, "suptitle"))
    return items, r


def test_every_figure_has_labelled_axes_with_units_and_no_overlapping_text(results):
    """Every axis names its quantity and unit ([-] when dimensionless), every colour bar
    its quantity, and no title, label or legend overlaps another text or another axes."""
    assert len(FIGURES) >= 30
    for path, fig in FIGURES:
        for ax in fig.axes:
            if not ax.axison:
                continue
            xl, yl = ax.get_xlabel(), ax.get_ylabel()
            if ax.get_label() == "<colorbar>":
                assert xl or yl, f"{path}: unlabelled colour bar"
                continue
            for lab in (xl, yl):
                assert "[" in lab and "]" in lab, f"{path}: axis label {lab!r} without a unit"
        items, r = _text_boxes(fig)
        for i, (box, ax, text) in enumerate(items):
            for box2, _, text2 in items[i + 1:]:
                assert not box.overlaps(box2) or text == text2 == "legend", (path, text, text2)
            for other in fig.axes:
                if other is ax or text == "legend":
                    continue
                assert not box.overlaps(other.get_window_extent(r)), (path, text, other.get_label())


@pytest.mark.parametrize("paper", list(REQUIRED))
def test_table_schema_and_required_rows(results, paper):
    table = pd.read_csv(results / paper / "table.csv")
    assert list(table.columns[: len(TABLE_COLUMNS)]) == list(TABLE_COLUMNS)
    assert set(table["status"]) <= {"match", "differs", "not-reported", "holds", "fails"}
    missing = set(REQUIRED[paper]) - set(table["quantity"])
    assert not missing, missing
    for f in FILES[paper]:
        assert (results / paper / f).is_file(), f
    assert (results / paper / "table.md").read_text().startswith("# ")


@pytest.mark.parametrize("paper", list(REQUIRED))
def test_match_rows_are_within_their_tolerance_and_differs_rows_explained(results, paper):
    table = pd.read_csv(results / paper / "table.csv")
    for rec in table.itertuples():
        if rec.status == "match":
            tol = float(re.search(r"tol ([0-9.eE+-]+)", rec.note).group(1))
            assert abs(rec.reproduced - rec.paper) <= tol * (1 + 1e-9), rec
        if rec.status == "differs":
            # a reason beyond the labels the table code writes itself: the tolerance
            # statement and the quadrature / raster label
            reason = re.sub(r";? ?tol [^;]*$", "", rec.note)
            reason = re.sub(r"^(quadrature (area|polar)|raster area mean)(; )?", "", reason)
            assert len(reason.strip()) > 10, rec


def test_summary_readme(results):
    text = (results / "README.md").read_text()
    for title in ("Le, Kang, Doan", "Stan, Maties", "Liu, Wang", "Wu, Wang"):
        assert title in text
    assert "Where we differ, and why" in text


def test_unknown_paper(capsys, tmp_path):
    assert main(["reproduce", "smith1999", "--out", str(tmp_path / "r")]) == 2
    assert "paper must be one of" in capsys.readouterr().err
    assert not (tmp_path / "r").exists()


def test_counts_are_over_computed_rows_only(results):
    """match/differs count only what the paper computed and we recompute; settings,
    readings and claims are counted apart (mechopt.core.published.counts)."""
    from mechopt.core.published import KINDS, counts

    total = {"computed": 0, "match": 0, "differs": 0}
    for paper in REQUIRED:
        table = pd.read_csv(results / paper / "table.csv")
        assert set(table["kind"]) <= set(KINDS)
        c = counts(table)
        comp = table[table["kind"] == "computed"]
        assert c["match"] == int((comp["status"] == "match").sum())
        assert c["match"] + c["differs"] == c["computed"]
        # an echoed setting never counts as a match
        assert c["settings"] == int((table["kind"] == "setting").sum())
        for k in total:
            total[k] += c[k]
    text = (results / "README.md").read_text()
    assert "| total |" in text
    row = next(line for line in text.splitlines() if line.startswith("| total |")).split("|")
    assert [int(v) for v in row[2:5]] == [total["computed"], total["match"], total["differs"]]


def test_mirror_angle_rows_have_the_same_status(results):
    """theta2 = 180 deg - theta1 over the symmetric GCW (Liu 2006 sec. 3.2.3): the
    mirror-image rows carry the same error, so they must carry the same status."""
    t = pd.read_csv(results / "liu2006" / "table.csv").set_index("quantity")
    for a, b in (("theta1_lo_deg", "theta2_hi_deg"), ("theta1_hi_deg", "theta2_lo_deg"),
                 ("square_theta1_lo_deg", "square_theta2_hi_deg"),
                 ("square_theta1_hi_deg", "square_theta2_lo_deg")):
        assert t.loc[a, "status"] == t.loc[b, "status"], (a, b)
        assert abs(t.loc[a, "reproduced"] + t.loc[b, "reproduced"] - 180.0) < 1e-6


def test_liu_readings_and_claims(results):
    """The D = 6.6 readings recomputed from the printed numbers; the claim rows carry
    holds/fails with evidence; Fig. 20's four tangent points counted by an SVD of J."""
    import numpy as np

    from mechopt import FiveBar
    from mechopt.analysis.workspace import mic

    t = pd.read_csv(results / "liu2006" / "table.csv").set_index("quantity")
    for i, (r, printed) in enumerate(((0.85, 5.61), (1.6, 10.56), (0.55, 3.63)), 1):
        row = t.loc[f"gcw_R{i}[D=6.6]"]
        assert row["kind"] == "reading" and row["reproduced"] == pytest.approx(6.6 * r, abs=1e-12)
        assert row["status"] == "match" and row["paper"] == printed
    assert t.loc["gcw_gsi_max_scaled[D=6.6, paper's eta]", "reproduced"] == pytest.approx(6.6 ** 2 * 0.7656)
    claims = t[t["kind"] == "claim"]
    assert len(claims) >= 10 and set(claims["status"]) <= {"holds", "fails"}
    assert all(len(n) > 10 for n in claims["note"])
    # Fig. 20: four points of the MIC rim are singular (smallest singular value of J -> 0)
    fb = FiveBar(1.1, 1.65, 0.25)
    m = mic(fb)
    phi = np.linspace(0.0, 2 * np.pi, 20000, endpoint=False)
    r = m.radius * (1 - 1e-9)
    s = np.linalg.svd(fb.jacobian(r * np.cos(phi), m.center_y + r * np.sin(phi)), compute_uv=False)
    k = s[:, 1] / s[:, 0]
    minima = (k < np.roll(k, 1)) & (k <= np.roll(k, -1)) & (k < 1e-3)
    assert minima.sum() == 4
    assert t.loc["claim:four_tangent_points_fig20", "status"] == "holds"
    assert t.loc["claim:no_gcw_for_0.4/2.33/0.27", "status"] == "holds"


def test_a_quick_paper_is_recomputed_by_a_full_run(tmp_path, capsys, monkeypatch):
    """reproduce --quick then reproduce: the second recomputes (the first was quick)."""
    from mechopt.workflows import reproduce as rep

    calls = []

    def fake_run(out, quick):
        calls.append(quick)
        return pd.DataFrame([{"quantity": "q", "source": "s", "paper": 1.0, "reproduced": 1.0,
                              "unit": "-", "rel_error": 0.0, "status": "match",
                              "kind": "computed", "note": "tol 0.5"}])

    import mechopt.experiments.wu2008 as wu

    monkeypatch.setattr(wu, "run", fake_run)
    monkeypatch.setattr(wu, "PARTS", ())
    out = tmp_path / "r"
    rep.reproduce("wu2008", out=out, quick=True, log=lambda m: None)
    rep.reproduce("wu2008", out=out, quick=True, log=lambda m: None)
    assert calls == [True]  # same kind: skipped
    log = []
    rep.reproduce("wu2008", out=out, quick=False, log=log.append)
    assert calls == [True, False]
    assert any("was quick" in m and "recomputing" in m for m in log)


# --- the reproduction's fast paths give the same numbers, bit for bit ---------------------
def test_finished_papers_are_skipped_unless_forced_and_workers_write_the_same_files(results, tmp_path, monkeypatch,
                                                                                     capsys):
    """On a copy of the quick reproduction's folder: a finished paper is skipped, and
    ``--force`` recomputes it. The forced run is ``reproduce all`` of two papers mapped
    over worker processes (default_jobs): it rewrites every file of each paper, and every
    file equals the serial run's (tables, fronts, sweeps, curves, figures), byte for byte;
    only run.json / manifest.json (wall times, run ids) and the log differ. (One forced
    run serves both checks: it was a forced serial run of wu2008 and a fresh parallel
    run of both papers.)"""
    import shutil

    from mechopt.workflows import reproduce as rep

    copy = tmp_path / "results"
    shutil.copytree(results, copy)  # copy2: the serial run's modification times too
    before = (copy / "wu2008" / "table.csv").stat().st_mtime_ns
    assert main(["reproduce", "wu2008", "--quick", "--out", str(copy)]) == 0
    assert "skipped" in capsys.readouterr().err
    assert (copy / "wu2008" / "table.csv").stat().st_mtime_ns == before

    two = ("le2013", "wu2008")
    monkeypatch.setattr(rep, "PAPERS", two)
    reproduce, calls = rep.reproduce, []

    def on_two_processes(*args, **kw):  # the command's own call, on two worker processes
        calls.append(kw)
        table = reproduce(*args, **{**kw, "n_jobs": 2})
        calls.append(table)
        return table

    monkeypatch.setattr(rep, "reproduce", on_two_processes)
    assert main(["reproduce", "all", "--quick", "--force", "--out", str(copy)]) == 0
    assert calls[0]["force"] is True and calls[0]["quick"] is True
    log = [line for line in capsys.readouterr().err.splitlines() if not line.startswith("reproduce: ")]
    assert any("on 2 processes" in m for m in log)
    assert sorted(m.split(":")[0] for m in log if m.startswith("[")) == ["[1/2] le2013", "[2/2] wu2008"]
    assert list(dict.fromkeys(calls[1]["paper"])) == list(two)
    for paper in two:
        ours = {p.relative_to(results / paper) for p in (results / paper).rglob("*") if p.is_file()}
        theirs = {p.relative_to(copy / paper) for p in (copy / paper).rglob("*") if p.is_file()}
        assert ours == theirs, paper
        for rel in sorted(ours):
            # every file was written anew by the forced run (none left from the copy)
            assert (copy / paper / rel).stat().st_mtime_ns != (results / paper / rel).stat().st_mtime_ns, \
                (paper, rel)
            if rel.name in ("run.json", "manifest.json"):
                continue
            assert (results / paper / rel).read_bytes() == (copy / paper / rel).read_bytes(), (paper, rel)


def test_progress_lines_per_stage(tmp_path, capsys, monkeypatch):
    """With ``progress`` (the CLI's default) each finished work unit (a paper's table or
    one of its parts) prints one plain line on a pipe, naming the paper and the stage,
    counted over all stages; the paper's summary line comes after its last stage."""
    from mechopt.workflows import reproduce as rep

    import mechopt.experiments.wu2008 as wu

    def fake_run(out, quick, parts=True):
        return pd.DataFrame([{"quantity": "q", "source": "s", "paper": 1.0, "reproduced": 1.0,
                              "unit": "-", "rel_error": 0.0, "status": "match",
                              "kind": "computed", "note": "tol 0.5"}])

    stages = []
    monkeypatch.setattr(wu, "run", fake_run)
    monkeypatch.setattr(wu, "run_part", lambda out, quick, part: stages.append(part))
    log = []
    rep.reproduce("wu2008", out=tmp_path, quick=True, log=log.append, progress=True)
    err = capsys.readouterr().err.splitlines()
    units = rep._units("wu2008")
    assert stages == list(units[1:]) and len(units) >= 2
    lines = [line for line in err if line.startswith("reproduce: ")]
    assert len(lines) == len(units), err
    for k, line in enumerate(lines, 1):
        assert line.startswith(f"reproduce: {k}/{len(units)} (") and " wu2008 " in line, line
    assert {line.split(" wu2008 ")[1].split()[0] for line in lines} == set(units)
    assert log[-1].startswith("[1/1] wu2008: 1 of 1 computed match")


def test_default_jobs_and_bad_n_jobs(tmp_path):
    import os

    from mechopt.workflows import reproduce as rep

    assert rep.default_jobs(1) == 1 and rep.default_jobs(0) == 1
    assert rep.default_jobs(4) == min(4, os.cpu_count() or 1)
    units = {(paper, None if part == rep.TABLE else part) for paper in rep.PAPERS for part in rep._units(paper)}
    assert set(rep.COST[True]) == set(rep.COST[False]) == units
    with pytest.raises(ValueError, match="no part"):
        rep._run_paper(("wu2008", str(tmp_path / "w"), True, "nope"))
    with pytest.raises(ValueError, match="n_jobs"):
        rep.reproduce("wu2008", out=tmp_path, quick=True, n_jobs=0, log=lambda m: None)


def test_liu_indices_remembered_equal_new_evaluations():
    """problems/liu2006.py remembers the designs a GA meets again: a remembered row is
    the kernels' row of a fresh evaluation, bit for bit, whatever the batch around it."""
    import numpy as np

    from mechopt.run.atlas import RESULT_COLUMNS, evaluate_designs
    from mechopt.problems import liu2006 as P

    rng = np.random.default_rng(2006)
    X = np.column_stack([rng.uniform(P.U_MIN, 1 - P.U_MIN, 120), rng.uniform(0.0, P.R3_MAX, 120)])
    X = np.vstack([X, X[:40], X[80:20:-1], [[0.5, 0.0]], [[0.5, -0.0]]])
    for quadrature in ("polar", "area"):
        P._MEMO.clear()
        first = P.liu_indices(*P.designs(X[:60]), quadrature)
        again = P.liu_indices(*P.designs(X), quadrature)
        fresh = evaluate_designs(*P.designs(X), quadrature=quadrature)
        for j, name in enumerate(RESULT_COLUMNS):
            if name not in again:
                continue
            ref = np.where(fresh[:, j] > 0, fresh[:, j], np.nan) if name == "r_mic" else fresh[:, j]
            assert np.asarray(again[name]).tobytes() == ref.tobytes(), (quadrature, name)
            assert np.asarray(first[name]).tobytes() == ref[:60].tobytes(), (quadrature, name)
        assert len(P._MEMO) == 122  # 120 designs, r3 = 0.0 and -0.0 apart


def test_atlas_figures_reuse_the_triangulation(tmp_path):
    """Every atlas figure is drawn on the same points: the Delaunay triangulation is
    computed once (mechopt.run.atlas._triangulation) and the PNG is the same bytes as with
    a fresh triangulation."""
    import matplotlib.tri as mtri

    from mechopt.run import atlas
    from mechopt.run import io as _io

    table = atlas.compute_atlas(step=0.1, indices="gci", n_jobs=1)
    atlas._TRIANGULATIONS.clear()
    _io.save_figure(atlas.draw_atlas(table, "gci"), tmp_path / "a.png")
    assert len(atlas._TRIANGULATIONS) == 1
    cached = atlas._triangulation(table["s"].to_numpy(), table["t"].to_numpy())
    fresh = mtri.Triangulation(table["s"].to_numpy(), table["t"].to_numpy())
    assert (cached.triangles == fresh.triangles).all() and (cached.neighbors == fresh.neighbors).all()
    assert cached.is_delaunay and cached is not atlas._triangulation(table["s"].to_numpy(), table["t"].to_numpy())
    _io.save_figure(atlas.draw_atlas(table, "gci"), tmp_path / "b.png")
    atlas._TRIANGULATIONS.clear()
    _io.save_figure(atlas.draw_atlas(table, "gci", region=table["gci"] > 0.5, where="gci > 0.5"), tmp_path / "c.png")
    _io.save_figure(atlas.draw_atlas(table, "gci", region=table["gci"] > 0.5, where="gci > 0.5"), tmp_path / "d.png")
    assert (tmp_path / "a.png").read_bytes() == (tmp_path / "b.png").read_bytes()
    assert (tmp_path / "c.png").read_bytes() == (tmp_path / "d.png").read_bytes()


def test_mic_radius_on_the_sorted_cloud_equals_the_full_scan():
    """mechopt.mechanisms.five_bar.kernels: the MIC's coarse and golden-section radii visit the type-II cloud
    sorted by y and stop where dy^2 alone exceeds the best distance; the value must be
    the full scan's, bit for bit (clouds with invalid points, ties, empty clouds)."""
    import numpy as np

    from mechopt.mechanisms.five_bar import kernels as K

    if not K.HAVE_NUMBA:
        pytest.skip("the compiled kernels")
    rng = np.random.default_rng(3)
    ay = np.array([np.nan, 1.3, np.nan, -0.2])
    for trial in range(60):
        n = int(rng.integers(0, 300))
        qx = rng.normal(0.0, rng.uniform(0.05, 2.0), n)
        qy = rng.normal(1.0, rng.uniform(0.05, 2.0), n)
        if n:
            qx[rng.random(n) < 0.2] = np.inf
            qy[: n // 10] = qy[0]  # ties in y
        sx2, sy = np.empty(max(n, 1)), np.empty(max(n, 1))
        m = K._sort_cloud_nb(qx, qy, n, sx2, sy)
        assert m == int(np.isfinite(qx).sum())
        hint = -1
        for y in np.linspace(-0.5, 3.0, 37):
            ref = K._radius_nb(1.1, 1.4, 0.3, qx, qy, n, ay, y)
            got, hint = K._radius_sorted_nb(1.1, 1.4, 0.3, sx2, sy, m, ay, y, hint)
            assert np.float64(got).tobytes() == np.float64(ref).tobytes(), (trial, y)


# --- published numbers come from the data files only (issue "architecture") -------------------
def _significant(value: float, digits: int) -> int:
    """Significant digits of ``value`` printed with ``digits`` decimals, trailing zeros
    dropped (240 -> 2, 5.0 -> 1, 36.40 -> 3, 0.005 -> 1)."""
    text = f"{abs(value):.{digits}f}"
    if "." in text:
        text = text.rstrip("0").rstrip(".")
    if "." not in text:
        text = text.rstrip("0")
    return len(text.replace(".", "").lstrip("0"))


#: a line whose number equals a printed one by coincidence (a grey level "0.85") says so
MARKER = "# not a printed number"


def published_literals(source: str, paper: str) -> list:
    """``(line, literal, [design:quantity, ...])`` of every number in ``source`` (Python)
    that equals, in absolute value, a printed number of ``mechopt/data/<paper>.csv`` with
    two or more significant digits: numeric constants of the code and numbers inside its
    strings (f-strings included). Docstrings and comments are documentation and are not
    read, nor the ``if __name__ == "__main__"`` block (it prints, it reproduces nothing);
    inside strings the data file's design keys (``"0.85/1.6/0.55"``,
    ``"table2:W1=0.7,W2=0.3"``) are names of its rows and ``eq. (15)``, ``Fig. 25``,
    ``sec. 3.2.3``, ``Table 1`` places in the paper, not numbers. A line that carries
    :data:`MARKER` is left out (a number equal to a printed one by coincidence)."""
    import ast

    from mechopt.core.published import records

    recs = records(paper)
    lines = source.splitlines()
    printed = {}
    for r in recs:
        if _significant(r.value, r.digits) >= 2:
            printed.setdefault(abs(r.value), []).append(f"{r.design}:{r.quantity}")
    keys = sorted({r.design for r in recs}, key=len, reverse=True)
    tree = ast.parse(source)
    docstrings = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                docstrings.add(id(body[0].value))
    # the command-line entry of a script prints a table, it reproduces nothing
    for node in tree.body:
        if (isinstance(node, ast.If) and isinstance(node.test, ast.Compare)
                and isinstance(node.test.left, ast.Name) and node.test.left.id == "__name__"):
            docstrings.update(id(n) for n in ast.walk(node))
    number = re.compile(r"(?<![\w.])\d+(?:[.,]\d+)?(?![\w])")
    # references into the paper: "eq. (14)-(15)", "Figs. 9-10", "sec. 3.2.3", "Table 1"
    where = re.compile(r"\b(?:eqs?|Figs?|Tables?|secs?)\.?\s*\(?\d+(?:\.\d+)*\)?"
                       r"(?:\s*[-,/]\s*\(?\d+(?:\.\d+)*\)?)*")
    found = []
    for node in ast.walk(tree):
        if not isinstance(node, ast.Constant) or id(node) in docstrings or isinstance(node.value, bool):
            continue
        if isinstance(node.value, (int, float)):
            tokens = [(abs(float(node.value)), repr(node.value))]
        elif isinstance(node.value, str):
            text = node.value
            for k in keys:
                text = text.replace(k, " ")
            text = where.sub(" ", text)
            tokens = [(float(m.group().replace(",", ".")), m.group()) for m in number.finditer(text)]
        else:
            continue
        if MARKER in lines[node.lineno - 1]:
            continue
        for value, literal in tokens:
            if value in printed:
                found.append((node.lineno, literal, printed[value]))
    return found


def test_the_published_literal_check_finds_literals():
    """The check below can fail: a printed number typed as a constant, in a string or in
    an f-string is found; the same number in a docstring, a comment, a design key, the
    command-line block or a line marked as a coincidence, or a number the paper does not
    print, is not."""
    planted = (
        '"""Le 2013 prints a_MAX = 1.3142."""\n'
        "A = 1.3142  # rho* = 1.9721\n"
        "def f(x):\n"
        '    """rho* = 1.9721"""\n'
        '    return f"the printed {x} beside 1.9721", "1.9628", -60, "eq. (22)-(23)"\n'
        'if __name__ == "__main__":\n'
        '    print(1.3142)\n'
        f'grey = "1.3142"  {MARKER}\n'
    )
    found = published_literals(planted, "le2013")
    assert [(line, lit) for line, lit, _ in found] == [(2, "1.3142"), (5, "1.9721")]
    assert found[0][2] == ["example:a_max"]
    assert published_literals('K = "0.85/1.6/0.55"\n', "liu2006") == []
    assert [lit for _, lit, _ in published_literals('K = (0.85, 1.6, 0.55)\n', "liu2006")] == ["0.85"]
    assert [lit for _, lit, _ in published_literals('n = "W(1,35)"\n', "stan2008")] == ["1,35"]


@pytest.mark.parametrize("script", ["le2013", "liu2006", "liu2006_figures", "stan2008", "wu2008"])
def test_no_experiment_types_a_published_number(script):
    """Every printed number an experiment uses or quotes (values, inputs, the numbers in
    its notes, titles and row names) comes from its data file through
    mechopt.core.published (lookup/records), none is typed in the script."""
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "experiments" / f"{script}.py"
    found = published_literals(path.read_text(), script.split("_")[0])
    assert not found, "\n".join(f"{path.name}:{line}: {lit} is {', '.join(rows)}"
                                for line, lit, rows in found)


def test_every_data_row_names_an_accuracy_class_and_every_class_is_used():
    """The ``accuracy`` column of each data file names a class of ACCURACY (the one place
    of tolerances beyond the printed digits), each with its reason; none is unused."""
    from mechopt.core.published import ACCURACY, load, records

    used = set()
    for paper in ("le2013", "liu2006", "stan2008", "wu2008"):
        df = load(paper)
        assert list(df.columns) == ["design", "quantity", "value", "unit", "digits", "source", "accuracy"]
        assert set(df["accuracy"]) <= set(ACCURACY), paper
        assert [r.accuracy for r in records(paper)] == list(df["accuracy"])
        used |= set(df["accuracy"])
    assert all(a.reason for a in ACCURACY.values())
    # "propagated" is a reading's class (Liu 2006's eta_D from the printed D and mean)
    assert used | {"propagated"} == set(ACCURACY)


def test_the_record_api():
    """lookup -> Record (value, unit, digits, source, accuracy); tolerance and compare use
    the record's class, a span where the class needs one, or the class a reading names."""
    from mechopt.core.published import compare, lookup, not_reported, records, tolerance

    rec = lookup("stan2008", "q1_over_b", "table2:W1=0,W2=1")
    assert (rec.value, rec.unit, rec.digits, rec.accuracy) == (1.3, "-", 1, "ga_optimum")
    assert rec.source == "Table 2, Z = W2 W" and rec.citation == "Stan 2008 Table 2, Z = W2 W"
    assert rec.printed == "1.3" and lookup("stan2008", "workspace_area").printed == "4693.33"
    assert rec in records("stan2008")
    with pytest.raises(ValueError, match="4 rows"):
        lookup("stan2008", "q1_over_b", None)
    with pytest.raises(ValueError, match="0 rows"):
        lookup("stan2008", "q1_over_b", "table9")
    with pytest.raises(ValueError, match="data file"):
        lookup("nobody1999", "x")
    # 1 % of the design range 0.83 is below half the printed digit 0.05
    assert tolerance(rec, span=0.83) == pytest.approx(0.05)
    with pytest.raises(ValueError, match="span"):
        tolerance(rec)
    fine = lookup("stan2008", "L2", "table3:W1=0.3,W2=0.7")  # 1.1556, 4 decimals
    assert tolerance(fine, span=0.2) == pytest.approx(0.002)
    assert tolerance(fine, accuracy="printed") == pytest.approx(5e-5)
    row = compare(fine, 1.157, span=0.2, note="ours")
    assert row["status"] == "match" and row["paper"] == 1.1556 and row["unit"] == "-"
    assert row["note"] == "ours; tol 0.002 - (max of half last digit 5e-05, 0.002 -)"
    assert compare(fine, 1.157, accuracy="printed")["status"] == "differs"
    area = lookup("stan2008", "workspace_area")  # raster: 1 %
    assert compare(area, 4700.0)["note"] == "tol 46.9 mm^2 (max of half last digit 0.005, 1.0%)"
    with pytest.raises(ValueError, match="accuracy"):
        compare(area, 1.0, accuracy="roughly")
    with pytest.raises(ValueError, match="kind"):
        compare(area, 1.0, kind="guess")
    nr = not_reported("eta_d", "Wu 2008 eq. (44)", 0.5, "-", note="map only")
    assert nr["status"] == "not-reported" and pd.isna(nr["paper"]) and nr["unit"] == "-"


def test_experiments_set_no_tolerance_and_build_no_row_of_their_own():
    """Tolerances come from ACCURACY (by the data file's column or a class name): no
    experiment passes a tolerance number, defines a REL_TOL/ABS_TOL or an Accuracy, or
    builds a row other than through compare / not_reported / claim_row."""
    import ast
    from pathlib import Path

    forbidden_kw = {"tol_rel", "tol_abs", "rel_tol", "abs_tol"}
    for path in sorted((Path(__file__).resolve().parents[1] / "experiments").glob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            if isinstance(node, ast.keyword):
                assert node.arg not in forbidden_kw, f"{path.name}:{node.value.lineno}: {node.arg}="
            if isinstance(node, ast.Name):
                assert not any(t in node.id for t in ("REL_TOL", "ABS_TOL", "TOL_DEG")), (path.name, node.id)
                assert node.id not in ("Accuracy", "comparison_row"), (path.name, node.lineno, node.id)
            if isinstance(node, ast.Dict):  # a table row written by hand
                keys = {k.value for k in node.keys if isinstance(k, ast.Constant)}
                assert not {"status", "rel_error"} <= keys, (path.name, node.lineno)


def test_every_compared_row_quotes_its_record(results):
    """The paper value, unit and source of every row with a printed value are those of a
    record of the paper's data file (value, unit, citation), as the quick run wrote them."""
    import numpy as np

    from mechopt.core.published import records

    for paper in ("le2013", "liu2006", "stan2008", "wu2008"):
        recs = {(r.value, r.unit, r.citation) for r in records(paper)}
        table = pd.read_csv(results / paper / "table.csv")
        compared = table[table["paper"].notna()]
        assert len(compared) >= 9, paper
        for row in compared.itertuples():
            assert (row.paper, row.unit, row.source) in recs, (paper, row.quantity)
        others = table[table["paper"].isna()]
        assert set(others["status"]) <= {"not-reported", "holds", "fails"}, paper
        assert np.isfinite(compared["rel_error"]).all(), paper
