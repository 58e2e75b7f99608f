"""Collision runs of ``mechopt design`` checked on dense grids, and what their figures draw
(issue 31).

Independent checks, for every front design of a run:

* the five-bar with ``--min-base 60 --min-clearance 0`` (objectives size and clearance):
  ``2 r3 >= 60``; the capsule clearance over a 201 x 201 grid of the task with a segment
  distance written in ``tests/test_collisions.py`` (Ericson's closest points, not the
  library's), no intersecting pair, and front.csv's ``clearance`` equal to that grid
  minimum within 1e-6 of the task size;
* the laser-table Biglide (400 x 300 mm, free-y, size) with ``--keep-out task
  --min-clearance 0``: every guide and carriage kept out of the placed table, measured by
  shapely (the distance of each capsule's axis to the table polygon less its half width,
  and the capsules as polygons) on a 201 x 201 grid: no intersection, and
  ``margin_keep_out`` equal to the grid minimum within 1e-6 of the task size; the
  bodies clear of each other as the five-bar's (``--keep-out task`` alone lets the
  smallest design put its two 40 mm carriages on guides 4.4 mm apart);
* what design.png and the explorer draw: the worst-clearance pose is where the reported
  minimum lies (the independent distance of the named pair there equals it), the
  capsule outlines lie at half a width from their axes, the zone is the placed task.

The runs here are small (``--pop 12 --gen 3`` and ``--pop 8 --gen 2``, ``--no-polish``);
the default runs, with the polish, and the explorer page in a browser are behind
``slow`` (the default runs take 10-20 min on a loaded 2-core machine).
"""
from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
import shapely

from mechopt.analysis.collisions import Collisions
from mechopt.analysis.sampling import Sampling
from mechopt.analysis.task import Task
from mechopt.cli import main
from mechopt.core.bodies import Shapes, capsule_outline
from mechopt.mechanisms import design_spec
from mechopt.requirements import collisions as rc
from test_collisions import _grid, ends, ericson_distance
# the browser of the report's and the explorer's tests (skips, saying why, without one)
from test_report import _browser, artifacts, browser  # noqa: F401

FIVE_TASK = Task.rect(100, 60, (0, 250))
FIVE = ["design", "five-bar", "--task", "rect:100,60@0,250", "--min-base", "60", "--min-clearance", "0",
        "--objectives", "size,clearance"]
LASER_TASK = Task.rect(400, 300, (0, 400))
LASER = ["design", "biglide", "--task", "rect:400,300@0,400", "--place", "free-y", "--objectives", "size"]
KEEP_OUT = ["--keep-out", "task", "--min-clearance", "0"]
#: small runs that find a feasible design
SMALL_FIVE = ["--pop", "12", "--gen", "3", "--no-polish", "--seed", "1"]
SMALL_LASER = ["--pop", "8", "--gen", "2", "--no-polish", "--seed", "2"]
#: the zone's bodies of a Biglide: all but the links, which carry the tool
OFF_TABLE = ("guide1", "carriage1", "guide2", "carriage2")


def _run(tmp_path_factory, name, args):
    out = tmp_path_factory.mktemp(name)
    assert main([*args, "--out", str(out)]) == 0
    return out


@pytest.fixture(scope="module")
def five_bar_run(tmp_path_factory):
    return _run(tmp_path_factory, "five", FIVE + SMALL_FIVE)


@pytest.fixture(scope="module")
def laser_run(tmp_path_factory):
    return _run(tmp_path_factory, "laser", LASER + KEEP_OUT + SMALL_LASER)


def _mechanism(spec, row, pad=1e-6):
    """The mechanism of a front.csv row; its strokes (printed to 10 digits) widened by
    ``pad`` [mm] so that the task's corners, where they end, stay within them."""
    v = {n: float(getattr(row, n)) for n in spec.lengths}
    if spec.derived_strokes:
        strokes = [(float(getattr(row, f"q{i}_min")), float(getattr(row, f"q{i}_max"))) for i in (1, 2)]
        return spec.build(v, row.mode, strokes=strokes, pad=pad)
    return spec.build(v, row.mode)


def _pair_clearances(col, x, y):
    """Every checked pair's capsule clearance at the poses (Ericson's distance)."""
    b = col.bodies(x, y)
    return np.stack([ericson_distance(*ends(b[i]), *ends(b[j])) - 0.5 * (b[i].width + b[j].width)
                     for i, j in col.pairs])


def _clearance_gap(col, task, reported, n):
    """|reported clearance - the n x n grid's minimum| / task size, after checking that no
    pair intersects at any grid pose (Ericson's distance)."""
    x, y = _grid(task, n)
    c = _pair_clearances(col, x, y)
    assert np.isfinite(c).all()  # the whole grid reached
    assert int(np.sum(c < 0)) == 0  # no intersecting pair at any grid pose
    return abs(reported - float(c.min())) / task.diameter


def check_five_bar(folder, n=201):
    """The five-bar front of ``folder`` on an n x n grid (module docstring); returns the
    largest |clearance - grid minimum| over the task size and the designs checked."""
    front = pd.read_csv(folder / "front.csv", dtype={"mode": str})
    spec, shapes = design_spec("five-bar"), Shapes.default("mm")
    assert len(front) >= 1 and {"clearance", "margin_clearance", "margin_base"} <= set(front.columns)
    worst = 0.0
    for row in front.itertuples():
        tol = 1e-6 + 2e-9 * row.r3  # front.csv prints 10 significant digits
        assert 2 * row.r3 >= 60 - tol and row.margin_base == pytest.approx(2 * row.r3 - 60, abs=tol)
        assert row.margin_clearance == pytest.approx(row.clearance, abs=1e-6)
        col = Collisions(spec, _mechanism(spec, row), shapes)
        worst = max(worst, _clearance_gap(col, FIVE_TASK.moved_to(row.task_x, row.task_y), row.clearance, n))
    assert worst <= 1e-6
    return worst, len(front)


def check_laser(folder, n=201):
    """The keep-out and the clearance of the Biglide front of ``folder`` on an n x n grid
    (module docstring); returns the largest |margin - grid minimum| over the task size,
    the number of designs and their sizes."""
    front = pd.read_csv(folder / "front.csv", dtype={"mode": str})
    spec, shapes = design_spec("biglide"), Shapes.default("mm")
    assert len(front) >= 1 and {"margin_keep_out", "margin_clearance"} <= set(front.columns)
    worst = 0.0
    for row in front.itertuples():
        task = LASER_TASK.moved_to(row.task_x, row.task_y)
        table = shapely.Polygon(task.vertices)
        col = Collisions(spec, _mechanism(spec, row), shapes)
        x, y = _grid(task, n)
        bodies = {b.name: b for b in col.bodies(x, y)}
        margins = []
        for name in OFF_TABLE:
            b = bodies[name]
            axes = shapely.linestrings(np.stack([np.c_[b.x0, b.y0], np.c_[b.x1, b.y1]], 1))
            margins.append(shapely.distance(axes, table) - 0.5 * b.width)
            caps = shapely.buffer(axes[:: max(1, len(axes) // 500)], 0.5 * b.width, quad_segs=16)
            assert not shapely.intersects(caps, table).any()
        dense = float(np.min(margins))
        assert dense > 0  # guides and carriages outside the table at every grid pose
        worst = max(worst, abs(row.margin_keep_out - dense) / task.diameter,
                    _clearance_gap(col, task, row.margin_clearance, n))
        # guides and sliders below or beside the table (the guides' capsules outside it)
        for g in ("guide1", "guide2"):
            b = bodies[g]
            assert (max(b.y0[0], b.y1[0]) + b.width / 2 < task.bbox[2] or
                    abs(b.x0[0]) - b.width / 2 > task.bbox[1])
    assert worst <= 1e-6
    return worst, len(front), front["size"].tolist()


def test_five_bar_with_a_base_width_on_a_201_grid(five_bar_run):
    check_five_bar(five_bar_run)


def test_laser_table_biglide_kept_off_the_table_on_a_201_grid(laser_run):
    check_laser(laser_run)


@pytest.mark.slow
@pytest.mark.parametrize("which", ["five-bar", "laser"])
def test_default_runs_on_a_201_grid(which, tmp_path_factory):
    """The default runs (population, generations and polish of the CLI)."""
    if which == "five-bar":
        worst, n = check_five_bar(_run(tmp_path_factory, "five-full", FIVE + ["--seed", "1"]))
        print(f"five-bar --min-base 60: {n} designs, |clearance - grid min| <= {worst:.2e} D")
    else:
        free = _run(tmp_path_factory, "laser-free", LASER + ["--seed", "1"])
        worst, n, sizes = check_laser(_run(tmp_path_factory, "laser-full", LASER + KEEP_OUT + ["--seed", "1"]))
        size_free = pd.read_csv(free / "front.csv")["size"].min()
        print(f"laser-table Biglide: {size_free:.1f} mm without --keep-out, {min(sizes):.1f} mm with "
              f"({n} designs, |margin - grid min| <= {worst:.2e} D)")
        assert min(sizes) > size_free


# --------------------------------------------------------------------------- what is drawn
def _context(folder):
    """The evaluation (certification's sampling) of the chosen design of a run (its
    variables as design.json has them, in full), with the run's collision requirements,
    and its front.csv row."""
    from mechopt.workflows.explore import _evaluator, _task_from

    settings = json.loads((folder / "run.json").read_text())["design"]
    spec = design_spec(settings["mechanism"])
    ev = _evaluator(settings, _task_from(settings["task"]), spec)
    chosen = json.loads((folder / "design.json").read_text())
    row = pd.read_csv(folder / "front.csv", dtype={"mode": str}).iloc[chosen["index"]]
    return ev.context({**chosen["variables"], **chosen["task_placement"]}, Sampling.fine()), row


def test_worst_pose_is_where_the_reported_minimum_lies(five_bar_run, laser_run):
    ctx, row = _context(five_bar_run)
    w = rc.worst_pose(ctx, "clearance")
    record = json.loads((five_bar_run / "design.json").read_text())
    assert w["value"] == record["values"]["clearance_min"]  # the number design.json reports
    assert w["value"] == pytest.approx(row["clearance"], rel=1e-9)
    x0, x1, y0, y1 = ctx.task.bbox  # a pose of the task (a rectangle: its box)
    eps = 1e-9 * ctx.task.diameter
    assert x0 - eps <= w["x"] <= x1 + eps and y0 - eps <= w["y"] <= y1 + eps
    col = rc.collisions(ctx)
    b = {k.name: k for k in col.bodies(np.array([w["x"]]), np.array([w["y"]]))}
    a, c = (b[n] for n in w["which"])
    independent = ericson_distance(*ends(a), *ends(c))[0] - 0.5 * (a.width + c.width)
    assert independent == pytest.approx(w["value"], abs=1e-9 * ctx.task.diameter)
    # the keep-out zone's closest body: shapely's distance to the placed table
    ctx, row = _context(laser_run)
    w = rc.worst_pose(ctx, "keep_out")
    assert w["which"] in OFF_TABLE and w["value"] == pytest.approx(row["margin_keep_out"], rel=1e-9)
    b = {k.name: k for k in rc.collisions(ctx).bodies(np.array([w["x"]]), np.array([w["y"]]))}[w["which"]]
    axis = shapely.LineString([(b.x0[0], b.y0[0]), (b.x1[0], b.y1[0])])
    table = shapely.Polygon(ctx.task.vertices)
    assert axis.distance(table) - b.width / 2 == pytest.approx(w["value"], abs=1e-9 * ctx.task.diameter)


@pytest.mark.parametrize("seg", [(0.0, 0.0, 30.0, 40.0, 10.0), (5.0, -2.0, 5.0, -2.0, 60.0), (-3.0, 1.0, -3.0, 9.0, 4.0)])
def test_capsule_outline_lies_on_the_capsule(seg):
    x0, y0, x1, y1, w = seg
    x, y = capsule_outline(x0, y0, x1, y1, w, n=12)
    axis = shapely.LineString([(x0, y0), (x1, y1)]) if (x0, y0) != (x1, y1) else shapely.Point(x0, y0)
    d = shapely.distance(shapely.points(x, y), axis)
    np.testing.assert_allclose(d, w / 2, rtol=1e-12)
    poly = shapely.Polygon(np.c_[x, y])
    assert poly.is_valid and (x[0], y[0]) == (x[-1], y[-1])
    exact = math.pi * w * w / 4 + w * math.hypot(x1 - x0, y1 - y0)
    assert exact * 0.95 < poly.area <= exact  # inscribed in the capsule, nearly all of it


def test_design_png_draws_the_capsules_the_zone_and_the_worst_pose(laser_run, five_bar_run):
    from matplotlib.figure import Figure

    from mechopt.run.plotting import draw_collisions

    for folder, zone in ((laser_run, True), (five_bar_run, False)):
        ctx, row = _context(folder)
        ax = Figure().add_subplot()
        ax.plot([-1000, 1000], [-1000, 1000])
        handles = draw_collisions(ax, ctx, (float(row["task_x"]), float(row["task_y"])), "mm")
        labels = [h.get_label() for h in handles]
        hatched = [p for p in ax.patches if p.get_hatch()]
        assert (len(hatched) == 1) == zone and ("keep-out zone: task" in labels) == zone
        w = rc.worst_pose(ctx, "clearance")
        assert any(lb.startswith(f"worst clearance: {w['value']:.5g} mm") for lb in labels)
        if zone:  # the hatched zone is the placed table
            np.testing.assert_allclose(hatched[0].get_xy()[:4], ctx.task.vertices, atol=1e-9)
            k = rc.worst_pose(ctx, "keep_out")
            assert any(lb.startswith(f"closest to the keep-out zone: {k['value']:.5g} mm") for lb in labels)
        n_bodies = len(rc.collisions(ctx).names)
        assert len([p for p in ax.patches if not p.get_hatch()]) == n_bodies  # every capsule filled


def test_drawn_only_with_a_collision_option():
    from mechopt.requirements import Requirements

    assert not rc.drawn(Requirements(min_lci=0.3), ("size", "min-lci"))
    assert not rc.drawn({"singularity_margin": 1e-3}, ("size",))
    assert rc.drawn({"min_base": 60.0}, ("size",)) and rc.drawn({}, ("size", "clearance"))
    assert rc.drawn(Requirements(link_width=25.0), ("size",))


def test_explorer_page_data_draws_the_capsules(laser_run):
    from mechopt.workflows.explore import page_data

    data = page_data(laser_run)
    front = pd.read_csv(laser_run / "front.csv", dtype={"mode": str})
    spec = design_spec("biglide")
    for i, row in enumerate(front.itertuples()):
        B = data["designs"][i]["bodies"]
        assert B["names"] == ["guide1", "carriage1", "link1", "guide2", "carriage2", "link2"]
        assert B["widths"] == [20.0, 40.0, 20.0, 20.0, 40.0, 20.0]
        # the zone is the placed table; the carriages are centred on the sliders, whose
        # height is the Biglide's inverse kinematics written here: q_i = y - sqrt(l2^2 - (x - g_i)^2)
        task = LASER_TASK.moved_to(row.task_x, row.task_y)
        np.testing.assert_allclose(np.c_[B["zone"]["x"], B["zone"]["y"]][:4], task.vertices, rtol=1e-5)  # 6 digits
        path = data["designs"][i]["path"]
        for k in range(0, len(path["x"]), 7):
            px, py = path["x"][k], path["y"][k]
            gs = [B["segments"][k][j][0] for j in (0, 3)]  # the guides' x: +-l1
            assert sorted(gs) == pytest.approx([-row.l1, row.l1], rel=1e-5)  # 6 digits
            for j, g in ((1, gs[0]), (4, gs[1])):
                x0, y0, x1, y1 = B["segments"][k][j]
                q = py - math.sqrt(row.l2 ** 2 - (px - g) ** 2)
                tol = 1e-5 * (abs(py) + row.l2)  # the page's numbers have 6 digits
                assert (x0, 0.5 * (y0 + y1), y1 - y0) == pytest.approx((g, q, 60.0), abs=tol)
        worst = {w["what"]: w for w in B["worst"]}
        assert worst["keep_out"]["value"] == pytest.approx(row.margin_keep_out, rel=1e-8)


@pytest.mark.slow  # a page load, about 10 s (the page data are checked unmarked above)
def test_explorer_draws_the_capsules_in_a_browser(browser, laser_run, artifacts, tmp_path):
    """The page's own capsule outlines (JavaScript) lie half a width from the page data's
    axes (shapely), the zone and the worst poses are drawn and named with their values."""
    from mechopt.workflows.explore import page_data, write_page
    from test_explore import _chains, _load, _no_console_error, _trace

    data = page_data(laser_run)
    path = write_page(laser_run, out=tmp_path / "explore-collisions.html")
    _load(browser, path)
    i, k = browser.execute_script("var c = window.mechoptExplorer.current; return [c.i, c.k];")
    B = data["designs"][i]["bodies"]
    names = browser.execute_script("return document.getElementById('mech').data.map(function (t) { return t.name; });")
    for kinds, trace in ((("guide",), "guides"), (("carriage",), "carriages"), (("distal",), "links (capsules)")):
        polygons = _chains(_trace(browser, "mech", trace))
        segs = [(s, w) for s, w, kind in zip(B["segments"][k], B["widths"], B["kinds"]) if kind in kinds]
        assert len(polygons) == len(segs) == 2
        for poly, (s, w) in zip(polygons, segs):
            axis = shapely.LineString([s[:2], s[2:]])
            d = shapely.distance(shapely.points(np.array(poly, float)), axis)
            np.testing.assert_allclose(d, w / 2, rtol=1e-9)
    zone = _trace(browser, "mech", "keep-out zone: task")
    assert zone[0] == B["zone"]["x"] and zone[1] == B["zone"]["y"]
    worst = {w["what"]: w for w in B["worst"]}
    shown = f"{worst['keep_out']['value']:.6g}"  # the page's fmt: 6 significant digits
    assert f"closest to the keep-out zone: {shown} mm ({worst['keep_out']['which'][0]})" in names, names
    assert any(n.startswith("worst clearance: ") for n in names)
    _no_console_error(browser)
    shot = artifacts / "explore-collisions.png"
    assert browser.find_element("id", "mech").screenshot(str(shot))


def test_a_half_plane_zone_spans_the_view_without_moving_it(five_bar_run):
    """``--keep-out below:Y``: a hatched band from Y down past the view; the axes' limits
    are those of the drawing without it."""
    from matplotlib.figure import Figure
    from matplotlib.patches import Rectangle

    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.requirements import Requirements
    from mechopt.run.plotting import draw_collisions

    chosen = json.loads((five_bar_run / "design.json").read_text())
    ev = DesignEvaluator("five-bar", FIVE_TASK, Requirements(keep_out="below:-40"), ("size",), mode="+-")
    ctx = ev.context({**chosen["variables"], **chosen["task_placement"]}, Sampling.fine())
    limits = []
    for draw in (False, True):
        ax = Figure().add_subplot()
        ax.plot([-300, 300], [-100, 400])
        handles = draw_collisions(ax, ctx, (0.0, 250.0), "mm") if draw else []
        ax.autoscale_view()
        limits.append((ax.get_xlim(), ax.get_ylim()))
    band = [a for a in ax.patches if isinstance(a, Rectangle) and a.get_hatch()]
    (y0, y1) = limits[1][1]
    assert len(band) == 1 and band[0].get_y() == -40
    assert band[0].get_y() + band[0].get_height() < y0 - 5 * (y1 - y0)  # far below the view
    assert "keep-out zone: below:-40" in [h.get_label() for h in handles]
    # the housings (60 mm discs about y = 0) are the lowest bodies: 10 mm above the zone
    w = rc.worst_pose(ctx, "keep_out")
    assert w["which"] in ("housing1", "housing2") and w["value"] == pytest.approx(10.0, abs=1e-9)
    assert limits[0][1][0] <= limits[1][1][0] and limits[1][1][0] > -1e3  # the view not stretched by the band
