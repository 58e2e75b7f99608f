"""Capsule bodies (``DesignSpec.links``) and their checks (``mechopt.analysis.collisions``).

Independent checks:

* the segment distance against an independent algorithm written here (the clamped
  closest points of Ericson, Real-Time Collision Detection, 5.1.9), shapely's
  ``distance`` and a dense sampling of both segments (hypothesis);
* on a 201 x 201 grid of a task, for several designs of each mechanism: the geometry of
  the bodies (link lengths, ends on the joints of the inverse kinematics), every pair's
  clearance equal to the independent distance within 1e-6 of the task size, and no
  intersection of shapely's capsule polygons where the library says clearance > 0;
* keep-out margins against shapely (half-planes, discs, polygons), the base width;
* the joint speeds against finite differences, and the Lipschitz bound of the
  192-boundary + 13 x 13 sampling never above a much denser grid's minimum.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import shapely
from scipy.spatial import cKDTree
from hypothesis import given, settings
from hypothesis import strategies as st

from mechopt.analysis.collisions import (Collisions, Zone, covering_radius, lipschitz_bound, parse_zone,
                                         point_segment_distance, segment_distance, task_samples)
from mechopt.analysis.task import Task
from mechopt.mechanisms import design_spec as get_spec
from mechopt.core.bodies import Shapes
from mechopt.mechanisms.gantry import wu2008_gantry


# ------------------------------------------------------------- an independent distance
def ericson_distance(p1, q1, p2, q2):
    """Distance of segments p1q1, p2q2 (arrays (..., 2)) by the clamped closest points
    of Ericson (2005), 5.1.9, vectorised; a different algorithm from the library's."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a = (d1 * d1).sum(-1)
    e = (d2 * d2).sum(-1)
    f = (d2 * r).sum(-1)
    c = (d1 * r).sum(-1)
    b = (d1 * d2).sum(-1)
    eps = 1e-300
    A = np.where(a <= eps, 1.0, a)
    E = np.where(e <= eps, 1.0, e)
    denom = a * e - b * b
    with np.errstate(divide="ignore", invalid="ignore"):
        # general case: s on the infinite lines' closest pair (0 when parallel), t from s,
        # then t clamped and s recomputed
        s = np.where(denom > 1e-14 * a * e, np.clip((b * f - c * e) / np.where(denom > 0, denom, 1.0), 0, 1), 0.0)
    t = (b * s + f) / E
    s = np.where(t < 0, np.clip(-c / A, 0, 1), np.where(t > 1, np.clip((b - c) / A, 0, 1), s))
    t = np.clip(t, 0, 1)
    # degenerate segments (points)
    s = np.where(e <= eps, np.clip(-c / A, 0, 1), s)
    t = np.where(e <= eps, 0.0, t)
    t = np.where(a <= eps, np.clip(f / E, 0, 1), t)
    s = np.where(a <= eps, 0.0, s)
    c1 = p1 + d1 * s[..., None]
    c2 = p2 + d2 * t[..., None]
    return np.sqrt(((c1 - c2) ** 2).sum(-1))


def ericson_exact(p1, q1, p2, q2):
    """:func:`ericson_distance` of one pair in rational arithmetic (exact up to the final
    square root): no cancellation for nearly parallel segments."""
    from fractions import Fraction as F

    p1, q1, p2, q2 = ([F(float(v)) for v in p] for p in (p1, q1, p2, q2))
    d1 = [q1[0] - p1[0], q1[1] - p1[1]]
    d2 = [q2[0] - p2[0], q2[1] - p2[1]]
    r = [p1[0] - p2[0], p1[1] - p2[1]]
    dot = lambda u, v: u[0] * v[0] + u[1] * v[1]  # noqa: E731
    a, e, f = dot(d1, d1), dot(d2, d2), dot(d2, r)
    clamp = lambda v: min(max(v, F(0)), F(1))  # noqa: E731
    if a == 0 and e == 0:
        s = t = F(0)
    elif a == 0:
        s, t = F(0), clamp(f / e)
    else:
        c = dot(d1, r)
        if e == 0:
            s, t = clamp(-c / a), F(0)
        else:
            b = dot(d1, d2)
            denom = a * e - b * b
            s = clamp((b * f - c * e) / denom) if denom != 0 else F(0)
            t = (b * s + f) / e
            if t < 0:
                t, s = F(0), clamp(-c / a)
            elif t > 1:
                t, s = F(1), clamp((b - c) / a)
    dx = p1[0] + d1[0] * s - p2[0] - d2[0] * t
    dy = p1[1] + d1[1] * s - p2[1] - d2[1] * t
    return math.sqrt(dx * dx + dy * dy)


def ends(body):
    return (np.stack([body.x0, body.y0], -1), np.stack([body.x1, body.y1], -1))


# ------------------------------------------------------------- the segment distance
coord = st.floats(-100, 100, allow_nan=False, allow_infinity=False).map(lambda v: round(v, 6))  # GEOS: no 1e-189 segments


@st.composite
def segment_pairs(draw):
    pts = [draw(st.tuples(coord, coord)) for _ in range(4)]
    case = draw(st.sampled_from(["free", "point", "parallel", "collinear", "shared"]))
    (a0, a1, b0, b1) = [np.array(p) for p in pts]
    if case == "point":
        a1 = a0.copy()
    elif case == "parallel":
        b1 = b0 + (a1 - a0) * draw(st.floats(-2, 2))
    elif case == "collinear":
        b0 = a0 + (a1 - a0) * draw(st.floats(-2, 2))
        b1 = a0 + (a1 - a0) * draw(st.floats(-2, 2))
    elif case == "shared":
        b0 = a1.copy()
    return tuple(np.round(p, 6) for p in (a0, a1, b0, b1))  # GEOS: no 1e-300 long segments


@settings(max_examples=80, deadline=None)
@given(segment_pairs())
def test_segment_distance_against_dense_sampling_ericson_and_shapely(seg):
    a0, a1, b0, b1 = seg
    d = float(segment_distance(*a0, *a1, *b0, *b1))
    scale = 1.0 + max(np.abs(np.r_[a0, a1, b0, b1]).max(), 1.0)
    n = 151
    s = np.linspace(0, 1, n)[:, None]
    pa, pb = a0 + s * (a1 - a0), b0 + s * (b1 - b0)
    dense = np.sqrt(((pa[:, None, :] - pb[None, :, :]) ** 2).sum(-1)).min()
    # never above the true distance (a sampled pair is a pair), never below the dense
    # minimum by more than half a sample spacing of each segment
    assert d <= dense + 1e-12 * scale
    spacing = (np.linalg.norm(a1 - a0) + np.linalg.norm(b1 - b0)) / (n - 1) / 2
    assert dense <= d + spacing + 1e-12 * scale
    assert d == pytest.approx(ericson_exact(a0, a1, b0, b1), abs=1e-12 * scale)
    geom = [shapely.Point(p) if np.all(p == q) else shapely.LineString([p, q]) for p, q in ((a0, a1), (b0, b1))]
    assert d == pytest.approx(shapely.distance(*geom), abs=1e-9 * scale)
    assert float(point_segment_distance(*b0, *a0, *a1)) >= d - 1e-12 * scale


def test_segment_distance_broadcasts_and_crossing_segments_meet():
    d = segment_distance(-1.0, 0.0, 1.0, 0.0, np.zeros(3), np.array([-1.0, 0.5, 2.0]), np.zeros(3), 3.0)
    assert d.tolist() == [0.0, 0.5, 2.0]
    assert float(segment_distance(0, 0, 0, 0, 3, 4, 3, 4)) == 5.0  # two points


# ------------------------------------------------------------- the designs
def _build(name, v, mode, task, pad=1e-9):
    """The design ``v`` of spec ``name``, its strokes (if derived) the ranges over a dense
    grid, widened by ``pad`` times the task's size."""
    spec = get_spec(name)
    if not spec.derived_strokes:
        return spec, spec.build(v, mode)
    x, y = _grid(task, 201)
    q1, q2 = spec.positions(v, mode, x, y)
    strokes = [(float(np.nanmin(q)), float(np.nanmax(q))) for q in (q1, q2)]
    return spec, spec.build(v, mode, strokes=strokes, pad=pad * task.diameter)


def _grid(task, n):
    x0, x1, y0, y1 = task.bbox
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    keep = task.contains(gx, gy)
    return gx[keep], gy[keep]


# (mechanism, design, mode, task, link width): designs chosen so that some poses collide
DESIGNS = [
    ("five-bar", dict(r1=150, r2=250, r3=60), "+-", Task.rect(200, 120, (0, 230)), 20),
    ("five-bar", dict(r1=120, r2=200, r3=40), "+-", Task.rect(200, 80, (0, 130)), 40),
    ("five-bar", dict(r1=100, r2=220, r3=120), "-+", Task.rect(120, 80, (0, 200)), 30),
    ("asymmetric-five-bar", dict(a1=140, c1=230, a2=170, c2=260, r3=50), "+-", Task.rect(160, 100, (0, 200)), 30),
    ("biglide", dict(l1=100, l2=250), "--", Task.rect(200, 100, (0, 300)), 20),
    ("biglide", dict(l1=60, l2=260), "--", Task.rect(300, 120, (0, 300)), 20),
    ("gantry", dict(d1=150, l=300), "--", Task.rect(260, 120, (0, 300)), 20),
    ("gantry", dict(d1=120, l=280), "-+", Task.rect(200, 100, (0, 250)), 30),
    ("bipod", dict(b=100), "up", Task.rect(160, 60, (0, 100)), 20),
    ("bipod", dict(b=300), "up", Task.rect(250, 80, (0, 90)), 30),
]


def _ids():
    return [f"{d[0]}-{i}" for i, d in enumerate(DESIGNS)]


#: one design of each mechanism in the default run, the others behind ``slow``
FIRST = {0, 3, 4, 6, 8}
SPLIT = [pytest.param(d, id=i, marks=() if k in FIRST else pytest.mark.slow)
         for k, (d, i) in enumerate(zip(DESIGNS, _ids()))]


def _check_geometry(spec, mech, bodies, x, y):
    """The bodies sit on the mechanism's joints (independent of the distance code)."""
    by = {b.name: b for b in bodies}
    ok = np.isfinite(by[next(n for n in by if not by[n].ground)].x1)
    if spec.name in ("five-bar", "asymmetric-five-bar"):
        t1, t2, _ = mech.ik(x, y)  # law of cosines and atan2: not the circle intersection of links()
        legs = mech._legs()
        for i, (ax, th, (a, c, _)) in enumerate(((-mech.r3, t1, legs[0]), (mech.r3, t2, legs[1])), start=1):
            cr, di = by[f"crank{i}"], by[f"distal{i}"]
            np.testing.assert_allclose(cr.x0, ax) and np.testing.assert_allclose(cr.y0, 0.0)
            np.testing.assert_allclose(cr.x1[ok], (ax + a * np.cos(th))[ok], atol=1e-9 * a)
            np.testing.assert_allclose(cr.y1[ok], (a * np.sin(th))[ok], atol=1e-9 * a)
            np.testing.assert_allclose(np.hypot(di.x1 - di.x0, di.y1 - di.y0)[ok], c, rtol=1e-9)
            np.testing.assert_allclose(di.x1[ok], x[ok]) and np.testing.assert_allclose(di.y1[ok], y[ok])
            assert by[f"housing{i}"].width == by[f"housing{i}"].width and by[f"housing{i}"].x0[0] == ax
    elif spec.name in ("biglide", "gantry"):
        q1, q2, _ = mech.ik(*spec.to_mech(mech, x, y))
        L = mech.l2 if spec.name == "biglide" else mech.l
        for i, (g, q) in enumerate(zip(mech.guides, (q1, q2)), start=1):
            link, car, guide = by[f"link{i}"], by[f"carriage{i}"], by[f"guide{i}"]
            np.testing.assert_allclose(np.hypot(link.x1 - link.x0, link.y1 - link.y0)[ok], L, rtol=1e-9)
            np.testing.assert_allclose(link.y0[ok], q[ok]) and np.testing.assert_allclose(link.x0, g)
            np.testing.assert_allclose((0.5 * (car.y0 + car.y1))[ok], q[ok], atol=1e-9 * L)
            assert np.all(guide.y0[0] <= car.y0[ok] + 1e-9 * L) and np.all(car.y1[ok] <= guide.y1[0] + 1e-9 * L)
    else:  # bipod
        for i, ax in enumerate((-mech.b / 2, mech.b / 2), start=1):
            s = by[f"strut{i}"]
            np.testing.assert_allclose(s.x0, ax) and np.testing.assert_allclose(s.x1[ok], x[ok])
    return ok


@pytest.mark.parametrize("case", SPLIT)
def test_clearance_on_a_201_grid_against_independent_distance_and_shapely_polygons(case):
    name, v, mode, task, width = case
    spec, mech = _build(name, v, mode, task)
    col = Collisions(spec, mech, Shapes.default("mm", link_width=width))
    x, y = _grid(task, 201)
    bodies = col.bodies(x, y)
    ok = _check_geometry(spec, mech, bodies, x, y)
    assert ok.mean() > 0.99  # the task is in reach
    lib = col.pair_clearances(x, y, bodies)[:, ok]
    # independent: Ericson's closest points on each checked pair
    ind = np.stack([ericson_distance(*ends(bodies[i]), *ends(bodies[j]))[ok] - 0.5 * (bodies[i].width + bodies[j].width)
                    for i, j in col.pairs])
    tol = 1e-6 * task.diameter
    assert np.max(np.abs(lib - ind)) <= tol
    full = np.full(x.size, np.nan)
    full[ok] = ind.min(0)
    sub = np.arange(x.size)[::37]
    sub = sub[ok[sub]]  # the minimum over the pairs, on a subset of the poses
    np.testing.assert_allclose(col.clearance(x[sub], y[sub]), full[sub], atol=tol, rtol=0)
    # where the library says the capsules are apart, shapely's polygons of them (inscribed
    # in the true capsules) do not meet: the 150 closest such pose-pairs of this design
    pos = np.argwhere(lib > 0)
    closest = pos[np.argsort(lib[lib > 0])[:150]]
    idx = np.flatnonzero(ok)
    for r, c in closest:
        i, j = col.pairs[r]
        caps = [shapely.buffer(shapely.LineString([(b.x0[idx[c]], b.y0[idx[c]]), (b.x1[idx[c]], b.y1[idx[c]])])
                               if b.x0[idx[c]] != b.x1[idx[c]] or b.y0[idx[c]] != b.y1[idx[c]]
                               else shapely.Point(b.x0[idx[c]], b.y0[idx[c]]), b.width / 2, quad_segs=16)
                for b in (bodies[i], bodies[j])]
        assert not caps[0].intersects(caps[1])
    # and where it says they overlap, shapely's capsules (drawn a rounding wider) do
    neg = np.argwhere(lib < -1e-9 * task.diameter)
    for r, c in neg[:: max(1, len(neg) // 50)]:
        i, j = col.pairs[r]
        g = [shapely.LineString([(b.x0[idx[c]], b.y0[idx[c]]), (b.x1[idx[c]], b.y1[idx[c]])])
             if b.x0[idx[c]] != b.x1[idx[c]] or b.y0[idx[c]] != b.y1[idx[c]] else shapely.Point(b.x0[idx[c]], b.y0[idx[c]])
             for b in (bodies[i], bodies[j])]
        assert shapely.distance(*g) < 0.5 * (bodies[i].width + bodies[j].width)


def test_some_designs_collide_and_some_do_not():
    """The designs above exercise both answers (else the checks above prove little)."""
    fractions = []
    for name, v, mode, task, width in DESIGNS:
        spec, mech = _build(name, v, mode, task)
        x, y = _grid(task, 41)
        c = Collisions(spec, mech, Shapes.default("mm", link_width=width)).clearance(x, y)
        fractions.append(float(np.mean(c < 0)))
    assert sum(f == 0 for f in fractions) >= 2 and sum(0 < f < 1 for f in fractions) >= 3


# ------------------------------------------------------------- adjacency, angles, base
def test_adjacency_is_derived_from_joint_names():
    spec, mech = _build("five-bar", dict(r1=150, r2=250, r3=60), "+-", None)
    col = Collisions(spec, mech)
    assert set(col.angle_names()) == {("crank1", "distal1", "B1"), ("crank2", "distal2", "B2"),
                                      ("distal1", "distal2", "P")}
    checked = {frozenset(p) for p in col.pair_names()}
    assert frozenset(("crank1", "crank2")) in checked and frozenset(("crank1", "distal2")) in checked
    assert frozenset(("crank1", "distal1")) not in checked  # adjacent at B1
    assert frozenset(("housing1", "crank1")) not in checked  # adjacent at A1
    assert frozenset(("housing1", "housing2")) not in checked  # both fixed: the base width
    assert len(checked) == 9
    col2 = Collisions(spec, mech, ignore=[("crank1", "crank2")])
    assert len(col2.pairs) == 8
    with pytest.raises(ValueError, match="ignore names no body of five-bar: 'crank9'"):
        Collisions(spec, mech, ignore=[("crank9", "crank2")])


def test_joint_angles_against_the_law_of_cosines():
    spec, mech = _build("five-bar", dict(r1=150, r2=250, r3=60), "+-", None)
    col = Collisions(spec, mech)
    x, y = np.meshgrid(np.linspace(-80, 80, 9), np.linspace(150, 300, 9))
    x, y = x.ravel(), y.ravel()
    ang = dict(zip(col.angle_names(), col.joint_angles(x, y)))
    for i, ax in ((1, -60.0), (2, 60.0)):  # at the elbow: d^2 = r1^2 + r2^2 - 2 r1 r2 cos(angle)
        d = np.hypot(x - ax, y)
        expect = np.arccos((150 ** 2 + 250 ** 2 - d ** 2) / (2 * 150 * 250))
        np.testing.assert_allclose(ang[(f"crank{i}", f"distal{i}", f"B{i}")], expect, atol=1e-9)


def test_base_width_of_the_housings():
    spec, mech = _build("five-bar", dict(r1=150, r2=250, r3=45), "+-", None)
    col = Collisions(spec, mech, Shapes.default("mm", housing_diameter=70))
    assert col.base_margin() == pytest.approx(90 - 70, abs=1e-12)
    assert col.base_distance() == pytest.approx(90, abs=1e-12)
    spec, mech = _build("five-bar", dict(r1=150, r2=250, r3=0), "+-", None)  # both motors on one axis
    assert Collisions(spec, mech).base_margin() == pytest.approx(-60, abs=1e-12)
    task = Task.rect(100, 50, (0, 300))
    spec, mech = _build("biglide", dict(l1=100, l2=250), "--", task)
    col = Collisions(spec, mech, Shapes.default("m"))
    assert col.base_distance() == pytest.approx(200, abs=1e-9)
    assert col.base_margin() == pytest.approx(200 - 0.020, abs=1e-9)  # 20 mm rails, in metres


def test_shapes_and_zones_refuse_bad_input():
    with pytest.raises(ValueError, match="link_width"):
        Shapes(link_width=-1.0)
    with pytest.raises(ValueError, match="housing_diameter"):
        Shapes(housing_diameter=math.nan)
    with pytest.raises(ValueError, match="--keep-out must be task"):
        parse_zone("left:3")
    with pytest.raises(ValueError, match="above:Y needs one number"):
        parse_zone("above:x")
    with pytest.raises(ValueError, match="self-intersecting"):
        parse_zone("polygon:0,0;1,1;1,0;0,1")
    with pytest.raises(ValueError, match="point task"):
        parse_zone("task", Task.points([[0, 1], [1, 2]]))
    assert Shapes.default("m").link_width == pytest.approx(0.02)


# ------------------------------------------------------------- keep-out zones
def test_keep_out_margins_against_shapely():
    rng = np.random.default_rng(3)
    seg = rng.uniform(-100, 100, (400, 4))
    seg[:40, 2:] = seg[:40, :2]  # discs
    geoms = [shapely.Point(s[:2]) if np.all(s[:2] == s[2:]) else shapely.LineString([s[:2], s[2:]]) for s in seg]
    zones = [(parse_zone("polygon:-30,-20;40,-25;10,35;-5,0"), shapely.Polygon([(-30, -20), (40, -25), (10, 35), (-5, 0)])),
             (Zone.from_task(Task.rect(60, 40, (5, 10))), shapely.box(-25, -10, 35, 30)),
             (Zone.from_task(Task.circle(30, (10, -5))), shapely.Point(10, -5)),
             (parse_zone("above:20"), shapely.box(-1e4, 20, 1e4, 1e4)),
             (parse_zone("below:-10"), shapely.box(-1e4, -1e4, 1e4, -10))]
    for zone, poly in zones:
        m = zone.margin(seg[:, 0], seg[:, 1], seg[:, 2], seg[:, 3])
        if zone.kind == "disc":  # exact on both sides: the distance to the centre less the radius
            np.testing.assert_allclose(m, shapely.distance(geoms, poly) - 30, atol=1e-9)
            assert (m < 0).any() and (m > 0).any()
            continue
        dist = shapely.distance(geoms, poly.boundary)
        hits = shapely.intersects(geoms, poly)
        outside = ~hits
        np.testing.assert_allclose(m[outside], dist[outside], atol=1e-9)
        assert np.all(m[hits] <= 1e-9) and hits.any() and outside.any()
        if zone.kind in ("above", "below"):  # inside too: minus the depth of the deepest end
            deepest = [shapely.points(p) for p in (seg[:, :2], seg[:, 2:])]
            depth = np.maximum(*(np.where(shapely.within(d, poly), shapely.distance(d, poly.boundary), 0.0)
                                 for d in deepest))
            np.testing.assert_allclose(m[hits], -depth[hits], atol=1e-9)
    assert Zone.from_task(Task.rect(1, 1)).spares_tool and not parse_zone("below:0").spares_tool


def test_keep_out_task_spares_the_links_that_carry_the_tool():
    task = Task.rect(400, 300, (0, 400))
    spec, mech = _build("biglide", dict(l1=131, l2=340), "--", task)
    col = Collisions(spec, mech)
    zone = parse_zone("task", task)
    assert col.zone_bodies(zone) == ["guide1", "carriage1", "guide2", "carriage2"]
    res = col.certified_minimum(task, "keep_out", zone)
    assert res["sampled"] < 0 and res["which"] in ("guide1", "guide2", "carriage1", "carriage2")  # at x = +-131
    spec, mech = _build("biglide", dict(l1=240, l2=520), "--", task)
    col = Collisions(spec, mech)
    res = col.certified_minimum(task, "keep_out", zone)
    # guides at +-240 (rails 20 mm, carriages 40 mm wide): 20 mm clear of +-200, but the
    # design evaluation's sampling (192 + 13 x 13, radius 18 mm) cannot prove it; the
    # certification's (2048 + 61 x 61, radius 4.5 mm) does
    assert res["sampled"] == pytest.approx(20.0) and res["bound"] < 0
    fine = col.certified_minimum(task, "keep_out", zone, n_boundary=2048, n_interior=61)
    assert 0 < fine["bound"] < 20 and fine["radius"] < 5


# ------------------------------------------------------------- speeds and the certificate
@pytest.mark.parametrize("case", DESIGNS[::2], ids=_ids()[::2])
def test_joint_speeds_against_finite_differences(case):
    name, v, mode, task, width = case
    spec, mech = _build(name, v, mode, task, pad=0.2)  # the strokes reach beyond the task
    col = Collisions(spec, mech)
    x, y = _grid(task, 9)
    h = 1e-5 * task.diameter
    speeds = col.body_speeds(x, y)
    base = col.bodies(x, y)
    fd = np.zeros_like(speeds)
    for a in np.linspace(0, np.pi, 48, endpoint=False):
        moved = col.bodies(x + h * np.cos(a), y + h * np.sin(a))
        for k, (b0, b1) in enumerate(zip(base, moved)):
            e = np.maximum(np.hypot(b1.x0 - b0.x0, b1.y0 - b0.y0), np.hypot(b1.x1 - b0.x1, b1.y1 - b0.y1)) / h
            fd[k] = np.maximum(fd[k], e)
    np.testing.assert_allclose(fd, speeds, rtol=2e-3, atol=1e-6)
    # the bound over a disc holds the speeds at points of the disc
    r = 0.05 * task.diameter
    bound = col.body_speeds(x, y, r)
    for a in np.linspace(0, 2 * np.pi, 12, endpoint=False):
        for f in (0.5, 1.0):
            assert np.all(col.body_speeds(x + f * r * np.cos(a), y + f * r * np.sin(a)) <= bound * (1 + 1e-12))


def _dense_min(col, task, what, zone=None, n=193):
    x, y = _grid(task, n)
    tb, _ = task.boundary_params(8 * n)
    bx, by = task.boundary_at(tb)
    x, y = np.r_[x, bx], np.r_[y, by]
    if what == "clearance":
        v = col.pair_clearances(x, y)
    elif what == "angles":
        v = col.joint_angles(x, y)
    else:
        v = col.keep_out(x, y, zone)
    return float(np.nanmin(v))


@pytest.mark.parametrize("case", SPLIT)
def test_lipschitz_bound_never_above_a_dense_minimum(case):
    name, v, mode, task, width = case
    spec, mech = _build(name, v, mode, task)
    col = Collisions(spec, mech, Shapes.default("mm", link_width=width))
    zone = parse_zone(f"below:{task.bbox[2] - 20}")
    for what in ("clearance", "angles", "keep_out"):
        res = col.certified_minimum(task, what, zone)
        dense = _dense_min(col, task, what, zone)
        assert res["bound"] <= dense + 1e-9 * task.diameter, what
        if case is DESIGNS[0]:  # far from singularities: a useful bound (8 % of the task size below)
            assert dense - res["bound"] < 0.1 * task.diameter, what


def test_covering_radius_covers_the_task():
    for task in (Task.rect(100, 40, (3, 50)), Task.circle(30, (0, 80)),
                 Task.polygon([[0, 0], [100, 0], [100, 60], [50, 20], [0, 60]])):
        x, y, r = task_samples(task)
        assert r == pytest.approx(covering_radius(task))
        px, py = _grid(task, 301)
        tb, _ = task.boundary_params(3000)
        bx, by = task.boundary_at(tb)
        px, py = np.r_[px, bx], np.r_[py, by]
        far = cKDTree(np.c_[x, y]).query(np.c_[px, py])[0].max()
        assert r / 2 < far <= r  # covered, and not by a radius much larger than needed


def test_lipschitz_bound_function():
    assert lipschitz_bound([3.0, 5.0], [1.0, 4.0], 0.5) == 2.5
    assert lipschitz_bound([3.0, np.nan], 1.0, 0.5) == -math.inf
    assert lipschitz_bound([3.0], np.inf, 0.5) == -math.inf
    assert lipschitz_bound([3.0], np.inf, 0.0) == 3.0
    assert lipschitz_bound([], 1.0, 1.0) == math.inf


def test_gantry_with_a_platform_has_its_parallelogram():
    g = wu2008_gantry()  # l2 = 200 mm
    spec = get_spec("gantry")
    xmin, xmax, ymin, ymax = g.task_workspace
    x, y = np.meshgrid(np.linspace(xmin, xmax, 7), np.linspace(ymin, ymax, 7))
    x, y = x.ravel(), y.ravel()
    by = {b.name: b for b in spec.links(g, x, y)}
    l1, l3, pf = by["link1"], by["link3"], by["platform"]
    np.testing.assert_allclose(l3.x1 - l3.x0, l1.x1 - l1.x0) and np.testing.assert_allclose(l3.y0 - l1.y0, 200)
    np.testing.assert_allclose(pf.y1 - pf.y0, 200) and np.testing.assert_allclose(pf.x0, x)
    np.testing.assert_allclose(0.5 * (pf.y0 + pf.y1), y)  # O' halfway up the platform
    col = Collisions(spec, g)
    # parallel links l2 apart vertically: 200 |sin theta_1| apart (theta_1 from the vertical)
    theta1, _ = g.link_angles(x, y)
    c13 = col.pair_clearances(x, y)[col.pair_names().index(("link1", "link3"))]
    np.testing.assert_allclose(c13, 200 * np.abs(np.sin(theta1)) - 20, atol=1e-9)
    assert {"link3", "platform"} <= set(col.names)
    assert ("link3", "platform", "A3") in col.angle_names()
    assert np.all(np.isfinite(col.clearance(x, y)))


def test_the_sampled_minimum_alone_is_no_bound():
    """Between the samples the clearance or a joint angle dips below the sampled minimum
    (so the check above fails without the Lipschitz term: it did for 4 of the 10 designs
    when the bound was taken as the sampled minimum)."""
    name, v, mode, task, width = DESIGNS[3]
    spec, mech = _build(name, v, mode, task)
    col = Collisions(spec, mech, Shapes.default("mm", link_width=width))
    dips = [col.certified_minimum(task, what)["sampled"] - _dense_min(col, task, what) for what in ("clearance", "angles")]
    assert max(dips) > 1e-6
