"""Size a mechanism for a task: task-driven, multi-objective dimensional synthesis.

A designer starts from a task ("cover this 100 x 60 mm rectangle 180 mm in front
of the base with LCI >= 0.4 everywhere, links at most 250 mm"), not from a
non-dimensional atlas. This module states such a problem on the shared evaluators;
:func:`mechopt.workflows.design.design` solves it with the seeded runner:

* :class:`Task` - the region to cover (:meth:`Task.rect`, :meth:`Task.circle`,
  :meth:`Task.polygon`, :meth:`Task.points`), in the user's length unit, in the
  base frame (base midpoint at the origin, y away from the base). Its placement is
  ``"fixed"``, ``"free-y"`` (moved along y) or ``"free"`` (moved in x and y).
* :class:`Requirements` - inequality constraints that must hold over the WHOLE task.
* objectives (:data:`OBJECTIVES`) - any non-empty subset.
* :func:`mechopt.workflows.design.design` - builds :class:`mechopt.problems.design.DesignProblem`, runs it
  through :func:`mechopt.run.runner.optimize`, certifies every front design with a finer
  sampling (:func:`certify`) and returns a :class:`~mechopt.workflows.design.DesignResult` (front as a
  DataFrame, :meth:`~mechopt.workflows.design.DesignResult.pick`, ``knee``).

Mechanisms (:func:`mechanisms`) and their design variables, in the task's unit. Each
mechanism states them in its own module, as its
:attr:`~mechopt.core.protocol.PlanarMechanism.design_spec` (a
:class:`~mechopt.core.design_spec.DesignSpec`); :func:`get_spec` finds them through
:func:`mechopt.mechanisms.registry`:

===================  ====================================  ===========================================
name                 variables                             derived
===================  ====================================  ===========================================
asymmetric-five-bar  a1, c1, a2, c2, r3 (or D with         crank ranges
                     ``shape``), mode with ``mode="any"``
biglide              l1, l2 (mode ``"--"`` ... ``"-+"``)   strokes: the q range over the task
bipod                b (branch ``"up"``/``"down"``)        strut strokes: the q range over the task
five-bar             r1, r2, r3 (or D with ``shape``),     crank ranges
                     mode with ``mode="any"``
gantry               d1, l (mode ``"--"`` ...)             q_min, stroke: the q range over the task
===================  ====================================  ===========================================

For the slider/strut mechanisms the strokes are not searched: the smallest stroke
that covers the task is the range of each actuator coordinate over the task, and
that range is attained on the task's boundary (below).

Requirements and how "over the whole task" is certified
--------------------------------------------------------
The task ``T`` is a compact, simply connected region (rectangle, disk, simple
polygon) or a finite point set. Samples: ``n_boundary`` points along ``dT`` at
uniform arc length (every polygon vertex included; largest gap ``h_b``) and an
``n_interior`` x ``n_interior`` grid over its box, kept inside ``T``.

reach
    ``T`` lies in the reachable set ``R`` of one working mode. Certified, not
    sampled: ``serial_clearance`` is the exact distance to ``dR`` inside ``R``
    (1-Lipschitz), so ``clearance >= c`` at boundary samples gives ``>= c - h_b/2`` on
    all of ``dT``. Inside ``T`` the distance to ``dR`` has no local minimum (moving
    toward the nearest boundary point of ``R`` lowers it), so once ``dT`` is in ``R``
    a point of ``T`` outside ``R`` can only belong to a bounded component (a hole) of
    the complement of ``R``; for every mechanism here each hole contains a base
    joint (five-bar, bipod: the disks ``|P - A_i| < |r1 - r2|`` or ``< q_min``, for
    the asymmetric five-bar ``< |a_i - c_i|``; the biglide's and gantry's leg regions
    are simply connected, their complements unbounded; a spec's
    :meth:`~mechopt.core.design_spec.DesignSpec.holes` names them), so "no base joint
    in ``T``" closes the argument. Margin: ``c - h_b/2``
    [L] > 0. A point task is checked at its points exactly.
singular
    No type-II singularity in ``T``: ``s0 * type2_function`` (``s0`` its sign at the
    task's reference point; the sine of the angle between the legs) stays above
    ``singularity_margin``. ``T`` is connected, so one sign means one connected
    singularity-free piece, one assembly mode. Implied by ``LCI >= gamma > 0``.
lci, speed, force
    ``min_T LCI >= gamma``; guaranteed platform speed ``w / max_T s_max(J)`` and
    force ``t * min_T s_min(J)`` (below). The minimum of a continuous function over
    ``T`` is attained on ``dT`` or at an interior critical point: both are located on
    the samples and refined by zooming (boundary: 4 levels of 17 points around the 3
    lowest boundary samples, interior: 3 levels of 9 x 9 points around the 3 lowest
    grid samples, each level 4x (interior) or 8x (boundary) finer), which places the
    minimiser to ``h/64`` (interior) and ``h_b/2048`` (boundary). Stated tolerance:
    the grid resolves the basins of the minimum (no dip narrower than a grid cell);
    the value is then exact to the zoom resolution (about 1e-5 relative for LCI on
    the examples; the tests check every front design on a 200 x 200 grid).
joints, link_angle, stroke
    Actuator coordinates have no critical point inside a singularity-free region
    (``grad q_i`` is row ``i`` of ``J``, never zero), and the link angles of the
    biglide/gantry depend on x alone (``d/dy = 0``, no interior extremum of x), so
    their extremes lie on ``dT``: boundary samples plus the boundary zoom.
lengths
    Variables have bounds ``[min_length, max_length]`` (``r3``, the five-bar half
    base, from 0); derived lengths (bipod strut at full extension) are constrained
    to ``max_length``; ``l2 > l1`` (biglide) and ``l > d1`` (gantry) are constraints.

Constraints are ``G <= 0`` and normalised (lengths by the task diameter, angles by
pi, LCI by gamma, speed and force by their required values); an infeasible design
has finite objectives and ``G > 0`` telling how far it is from feasible.

Speed and force (Liu 2006 eq. 10 and 13, with units)
-----------------------------------------------------
With ``q_dot = J p_dot`` (``J`` in rad/L for revolute, 1 for prismatic actuators):
moving the platform at speed ``v`` in the unit direction ``u`` needs
``q_dot = v J u``; with the actuator rates bounded by ``|q_dot|_2 <= w`` (rad/s or
L/s) the speed reachable in EVERY direction is ``v = w / max_u |J u| = w / s_max(J)``
[L/s] (Liu eq. 10, ``|V|min = 1/s_max`` per unit rate). By virtual work
``tau . q_dot = F . p_dot``, i.e. ``F = J^T tau``: resisting a force ``f u`` needs
``tau = f J^-T u``, so with ``|tau|_2 <= t`` (N m or N) the force guaranteed in every
direction is ``f = t / s_max(J^-T) = t s_min(J)`` [N] (Liu eq. 13, ``|tau|min = s_min``
per unit effort), and holding a payload of ``f`` newtons in the worst direction
needs ``|tau|_2 = f / s_min(J)`` (the ``torque`` objective). Bounding each actuator
separately (``|q_dot_i| <= w``) allows at least these values (``|.|_inf <= |.|_2``):
they are safe guarantees. Inputs: ``actuator_speed`` in rad/s (revolute) or the
task's unit per second (prismatic); ``actuator_torque`` in N m (revolute) or N;
``payload`` in N; outputs: speed in [unit]/s, force in N, torque in N m or N.
"""
from __future__ import annotations

import math
from functools import cached_property, lru_cache
from dataclasses import asdict, dataclass, replace
from pathlib import Path

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v
from mechopt.core.design_spec import DesignSpec

__all__ = ["Task", "Requirements", "OBJECTIVES", "MECHANISMS", "PLACEMENTS", "DesignEvaluator",
           "NoFeasibleDesign", "Sampling", "certify", "feasible", "parse_task", "knee_index", "get_spec",
           "mechanisms"]

#: length units a task may be given in, and their value in metres
UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}
PLACEMENTS = ("fixed", "free-y", "free")

#: name -> (sense, unit template, description); sense -1 maximised
OBJECTIVES = {
    "size": (1, "{L}", "sum of the link lengths (mechanism docstring of each spec)"),
    "footprint": (1, "{L}", "radius about the base midpoint of every joint over the task"),
    "min-lci": (-1, "-", "minimum LCI over the task"),
    "mean-lci": (-1, "-", "mean LCI over the task (interior grid)"),
    "speed": (-1, "{L}/s", "guaranteed platform speed in every direction, w / max s_max(J)"),
    "force": (-1, "N", "guaranteed platform force in every direction, t * min s_min(J)"),
    "torque": (1, "{T}", "actuator torque (force) to hold the payload in the worst direction"),
}


class NoFeasibleDesign(ValueError):
    """No design satisfies the requirements; ``info`` holds the least-violating one."""

    def __init__(self, message, info=None):
        super().__init__(message)
        self.info = info or {}


# --------------------------------------------------------------------------- task
def _polygon_simple(v):
    """True when the closed polygon ``v`` (n, 2) has no two non-adjacent edges that
    meet and no two adjacent edges that fold back on each other."""
    n = len(v)
    a, b = v, np.roll(v, -1, axis=0)

    def orient(p, q, r):
        return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                       - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))

    for i in range(n):
        for j in range(i + 1, n):
            adjacent = j == i + 1 or (i == 0 and j == n - 1)
            p1, p2, p3, p4 = a[i], b[i], a[j], b[j]
            if adjacent:
                # the shared vertex is allowed; collinear overlap (a fold) is not
                shared = p2 if j == i + 1 else p1
                other_i = p1 if j == i + 1 else p2
                other_j = p4 if j == i + 1 else p3
                d1, d2 = other_i - shared, other_j - shared
                cross = d1[0] * d2[1] - d1[1] * d2[0]
                if abs(cross) <= _v.ROUNDING * (np.hypot(*d1) * np.hypot(*d2)) and np.dot(d1, d2) > 0:
                    return False
                continue
            o1, o2 = orient(p1, p2, p3), orient(p1, p2, p4)
            o3, o4 = orient(p3, p4, p1), orient(p3, p4, p2)
            if o1 != o2 and o3 != o4:
                return False

            def on(p, q, r):  # r on segment pq (collinear case)
                return (min(p[0], q[0]) <= r[0] <= max(p[0], q[0])
                        and min(p[1], q[1]) <= r[1] <= max(p[1], q[1]))

            if (o1 == 0 and on(p1, p2, p3)) or (o2 == 0 and on(p1, p2, p4)) or \
               (o3 == 0 and on(p3, p4, p1)) or (o4 == 0 and on(p3, p4, p2)):
                return False
    return True


def _as_xy(name, values, minimum):
    try:
        arr = np.asarray(values, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a list of (x, y) points, got {_v.show(values)}") from None
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must be a list of (x, y) points, got an array of shape {arr.shape}")
    if len(arr) < minimum:
        raise ValueError(f"{name} needs at least {minimum} points, got {len(arr)}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite (no NaN or inf), got {_v.show(values)}")
    if np.abs(arr).max() > _v.LENGTH_MAX:
        raise ValueError(f"{name} coordinates must lie within +-{_v.LENGTH_MAX:g}")
    return arr


@dataclass(frozen=True, eq=False)
class Task:
    """A region (or point set) to cover, in the base frame, lengths in ``unit``.

    Build it with :meth:`rect`, :meth:`circle`, :meth:`polygon` or :meth:`points`
    (or :func:`parse_task` from the CLI syntax). ``reference`` is the centre of its
    bounding box; :meth:`moved_to` translates the task so that it sits there.
    """

    kind: str
    vertices: np.ndarray | None = None   # rect, polygon (counter-clockwise)
    center: tuple | None = None          # circle
    radius: float | None = None          # circle
    pts: np.ndarray | None = None        # points
    unit: str = "mm"
    label: str = ""

    # --- constructors ---------------------------------------------------------------
    @classmethod
    def rect(cls, width, height, center=(0.0, 0.0), unit="mm"):
        """Axis-aligned ``width x height`` rectangle centred at ``center`` [unit]."""
        w = _v.positive_length("task width", width)
        h = _v.positive_length("task height", height)
        cx, cy = (_v.coordinate("task center", c) for c in _v.finite_numbers("task center", center, 2, "a point (x, y)"))
        v = np.array([[cx - w / 2, cy - h / 2], [cx + w / 2, cy - h / 2], [cx + w / 2, cy + h / 2],
                      [cx - w / 2, cy + h / 2]])
        return cls("rect", vertices=v, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"rect {w:g} x {h:g} {unit} at ({cx:g}, {cy:g})")

    @classmethod
    def circle(cls, radius, center=(0.0, 0.0), unit="mm"):
        """Disk of ``radius`` about ``center`` [unit]."""
        r = _v.positive_length("task radius", radius)
        cx, cy = (_v.coordinate("task center", c) for c in _v.finite_numbers("task center", center, 2, "a point (x, y)"))
        return cls("circle", center=(cx, cy), radius=r, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"circle r {r:g} {unit} at ({cx:g}, {cy:g})")

    @classmethod
    def polygon(cls, vertices, unit="mm"):
        """Simple polygon (no self-intersection, positive area), vertices in order."""
        v = _as_xy("polygon vertices", vertices, 3)
        if len(v) > 3 and np.allclose(v[0], v[-1]):
            v = v[:-1]  # closed explicitly
        keep = np.r_[True, np.any(np.diff(v, axis=0) != 0, axis=1)]
        v = v[keep]
        if len(v) < 3:
            raise ValueError("polygon needs at least 3 distinct vertices")
        area2 = float(np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1]))
        scale = float(np.ptp(v, axis=0).max())
        collinear = bool(np.all(np.abs((v[:, 0] - v[0, 0]) * (v[1:2, 1] - v[0, 1]) - (v[:, 1] - v[0, 1]) * (v[1:2, 0] - v[0, 0]))
                                <= _v.ROUNDING * scale * scale))
        if collinear or not scale > 0:
            raise ValueError("polygon is empty (zero area: collinear vertices)")
        if not _polygon_simple(v):
            raise ValueError("polygon is self-intersecting (edges cross); give the vertices in boundary order")
        if not abs(area2) > _v.ROUNDING * scale * scale:
            raise ValueError("polygon is empty (zero area)")
        if area2 < 0:
            v = v[::-1].copy()
        return cls("polygon", vertices=v, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"polygon of {len(v)} vertices [{unit}]")

    @classmethod
    def points(cls, array, unit="mm"):
        """A finite set of poses (a trajectory's way-points or a point cloud)."""
        p = _as_xy("task points", array, 1)
        return cls("points", pts=p, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"{len(p)} points [{unit}]")

    # --- geometry --------------------------------------------------------------------
    @property
    def is_region(self) -> bool:
        return self.kind != "points"

    @property
    def bbox(self):
        if self.kind == "circle":
            (cx, cy), r = self.center, self.radius
            return (cx - r, cx + r, cy - r, cy + r)
        p = self.vertices if self.vertices is not None else self.pts
        return (float(p[:, 0].min()), float(p[:, 0].max()), float(p[:, 1].min()), float(p[:, 1].max()))

    @property
    def reference(self):
        x0, x1, y0, y1 = self.bbox
        return (0.5 * (x0 + x1), 0.5 * (y0 + y1))

    @cached_property
    def diameter(self) -> float:
        """Largest distance between two points of the task (a length scale, > 0);
        computed once (:meth:`contains` needs it at every call)."""
        if self.kind == "circle":
            return 2.0 * self.radius
        p = self.vertices if self.vertices is not None else self.pts
        if len(p) > 2000:
            p = p[np.linspace(0, len(p) - 1, 2000).astype(int)]
        d = float(np.sqrt(((p[:, None, :] - p[None, :, :]) ** 2).sum(-1)).max())
        return d if d > 0 else 1.0

    @property
    def area(self) -> float:
        if self.kind == "circle":
            return math.pi * self.radius ** 2
        if self.kind == "points":
            return 0.0
        v = self.vertices
        return 0.5 * abs(float(np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1])))

    @property
    def perimeter(self) -> float:
        if self.kind == "circle":
            return 2 * math.pi * self.radius
        if self.kind == "points":
            return 0.0
        return float(np.hypot(*(np.roll(self.vertices, -1, 0) - self.vertices).T).sum())

    def moved_to(self, x, y) -> "Task":
        """The same task translated so that its :attr:`reference` is ``(x, y)``."""
        rx, ry = self.reference
        d = np.array([x - rx, y - ry], float)
        if not np.any(d):
            return self
        if self.kind == "circle":
            return replace(self, center=(self.center[0] + d[0], self.center[1] + d[1]))
        if self.kind == "points":
            return replace(self, pts=self.pts + d)
        return replace(self, vertices=self.vertices + d)

    def outline(self):
        """Closed outline ``(x, y)`` for plots (the points themselves for a point task)."""
        if self.kind == "circle":
            t = np.linspace(0, 2 * np.pi, 361)
            return self.center[0] + self.radius * np.cos(t), self.center[1] + self.radius * np.sin(t)
        if self.kind == "points":
            return self.pts[:, 0], self.pts[:, 1]
        v = np.vstack([self.vertices, self.vertices[:1]])
        return v[:, 0], v[:, 1]

    @cached_property
    def _edges(self):
        """The polygon's edges, computed once (the design evaluation asks for them at
        every boundary sample): ``(vx, vy, wy, ex, ey, L2, L, cum)`` with ``(vx, vy)``
        the vertices, ``wy`` the next vertex's y, ``(ex, ey) = w - v``, ``L2 = |e|^2``,
        ``L = |e|`` and ``cum`` the arc-length fractions of the vertices (``cum[-1] = 1``)."""
        v = self.vertices
        w = np.roll(v, -1, 0)
        e = w - v
        ex, ey = e[:, 0].copy(), e[:, 1].copy()
        L = np.hypot(ex, ey)
        return (v[:, 0].copy(), v[:, 1].copy(), w[:, 1].copy(), ex, ey, ex * ex + ey * ey, L,
                np.r_[0.0, np.cumsum(L)] / L.sum())

    def boundary_at(self, t):
        """Point at arc-length fraction ``t`` (mod 1) of the boundary, counter-clockwise."""
        t = np.mod(np.asarray(t, float), 1.0)
        if self.kind == "circle":
            a = 2 * np.pi * t
            return self.center[0] + self.radius * np.cos(a), self.center[1] + self.radius * np.sin(a)
        vx, vy, _, ex, ey, _, L, cum = self._edges
        k = np.clip(np.searchsorted(cum, t, side="right") - 1, 0, len(vx) - 1)
        s = (t - cum[k]) / np.where(L[k] > 0, (cum[k + 1] - cum[k]), 1.0)
        return vx[k] + s * ex[k], vy[k] + s * ey[k]

    def boundary_params(self, n):
        """Arc-length fractions of about ``n`` boundary samples, every vertex included;
        returns ``(t, gap)`` with ``gap`` the largest distance between neighbours [unit]."""
        n = max(int(n), 8)
        if self.kind == "circle":
            t = np.arange(n) / n
            return t, 2 * self.radius * math.sin(math.pi / n)
        v = self.vertices
        L = np.hypot(*(np.roll(v, -1, 0) - v).T)
        total = L.sum()
        cum = np.r_[0.0, np.cumsum(L)] / total
        ts, gap = [], 0.0
        for i, li in enumerate(L):
            m = max(1, int(math.ceil(n * li / total)))
            ts.append(cum[i] + (cum[i + 1] - cum[i]) * np.arange(m) / m)
            gap = max(gap, li / m)
        return np.concatenate(ts), gap

    def contains(self, x, y):
        """Points inside or on the boundary (to rounding)."""
        x, y = np.asarray(x, float), np.asarray(y, float)
        if self.kind == "circle":
            return np.hypot(x - self.center[0], y - self.center[1]) <= self.radius * (1 + _v.ROUNDING)
        if self.kind == "points":
            return np.zeros(np.broadcast(x, y).shape, bool)
        return self.signed_distance(x, y) >= -_v.ROUNDING * self.diameter

    def signed_distance(self, x, y):
        """Distance to the boundary, positive inside, negative outside [unit]."""
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if self.kind == "circle":
            return self.radius - np.hypot(x - self.center[0], y - self.center[1])
        if self.kind == "points":
            raise ValueError("a point task has no inside")
        vx, vy, wy, ex, ey, L2, _, _ = self._edges
        px, py = x[..., None], y[..., None]
        dx, dy = px - vx, py - vy
        s = np.clip((dx * ex + dy * ey) / L2, 0, 1)
        d = np.hypot(dx - s * ex, dy - s * ey).min(-1)
        # even-odd rule (the polygon is simple)
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = ((vy > py) != (wy > py)) & (px < ex * dy / ey + vx)
        inside = np.count_nonzero(cross, axis=-1) % 2 == 1
        return np.where(inside, d, -d)

    def grid(self, n):
        """``n x n`` grid over the bounding box (edges included), kept inside: ``(x, y, step)``."""
        if self.kind == "points":
            return self.pts[:, 0].copy(), self.pts[:, 1].copy(), 0.0
        x0, x1, y0, y1 = self.bbox
        gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
        keep = self.contains(gx, gy)
        return gx[keep], gy[keep], max(x1 - x0, y1 - y0) / (n - 1)

    def to_dict(self) -> dict:
        d = {"kind": self.kind, "unit": self.unit, "label": self.label}
        if self.kind == "circle":
            d.update(center=list(self.center), radius=self.radius)
        elif self.kind == "points":
            d["points"] = self.pts.tolist()
        else:
            d["vertices"] = self.vertices.tolist()
        return d


def _floats(text, what):
    try:
        vals = [float(v) for v in text.split(",")]
    except ValueError:
        raise ValueError(f"{what}: expected comma-separated numbers, got {text!r}") from None
    if not all(math.isfinite(v) for v in vals):
        raise ValueError(f"{what} must be finite numbers, got {text!r}")
    return vals


def parse_task(text: str, unit: str = "mm") -> Task:
    """A task from the CLI syntax: ``rect:W,H@X,Y``, ``circle:R@X,Y``,
    ``polygon:x1,y1;x2,y2;...`` or ``points:FILE.csv`` (two columns x, y; a header
    line is skipped). ``@X,Y`` (the centre) defaults to the origin."""
    if not isinstance(text, str) or ":" not in text:
        raise ValueError(f"--task must be rect:W,H@X,Y, circle:R@X,Y, polygon:x1,y1;x2,y2;... or "
                         f"points:FILE.csv, got {_v.show(text)}")
    kind, _, body = text.partition(":")
    kind = kind.strip().lower()
    if kind in ("rect", "circle"):
        size, _, at = body.partition("@")
        center = _floats(at, f"--task {kind} centre") if at.strip() else [0.0, 0.0]
        if len(center) != 2:
            raise ValueError(f"--task {kind} centre must be X,Y, got {at!r}")
        s = _floats(size, f"--task {kind} size")
        if kind == "rect":
            if len(s) != 2:
                raise ValueError(f"--task rect needs W,H, got {size!r}")
            return Task.rect(s[0], s[1], center, unit)
        if len(s) != 1:
            raise ValueError(f"--task circle needs one radius R, got {size!r}")
        return Task.circle(s[0], center, unit)
    if kind == "polygon":
        if not body.strip():
            raise ValueError("--task polygon is empty: give x1,y1;x2,y2;x3,y3;...")
        pts = [_floats(p, "--task polygon vertex") for p in body.split(";") if p.strip()]
        if any(len(p) != 2 for p in pts):
            raise ValueError(f"--task polygon vertices must be x,y pairs separated by ';', got {body!r}")
        return Task.polygon(pts, unit)
    if kind == "points":
        path = Path(body.strip())
        try:
            raw = path.read_text()
        except OSError as exc:
            raise ValueError(f"--task points: cannot read {str(path)!r} ({exc.strerror})") from None
        rows = []
        for k, line in enumerate(raw.splitlines()):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            parts = [p for p in line.replace(";", ",").replace("\t", ",").split(",") if p.strip()]
            try:
                rows.append([float(parts[0]), float(parts[1])])
            except (ValueError, IndexError):
                if rows or k > 0:
                    raise ValueError(f"--task points: line {k + 1} of {str(path)!r} is not x,y: {line!r}") from None
        if not rows:
            raise ValueError(f"--task points: {str(path)!r} holds no x,y rows")
        return Task.points(rows, unit)
    raise ValueError(f"--task kind must be rect, circle, polygon or points, got {kind!r}")


# ------------------------------------------------------------------- requirements
@dataclass(frozen=True)
class Requirements:
    """What must hold over the whole task (module docstring: how it is certified).

    Angles in rad, lengths in the task's unit. ``None`` switches a requirement off;
    reachability in one working mode without crossing a type-II singularity is
    always required.

    Parameters
    ----------
    min_lci : float, optional
        LCI >= gamma over the task, gamma in (0, 1).
    joint_limits : tuple, optional
        ``((lo1, hi1), (lo2, hi2))`` (or one ``(lo, hi)`` for both) crank angles
        [rad] of the five-bar, as :meth:`FiveBar.ik
        <mechopt.mechanisms.five_bar.model.FiveBar.ik>` returns them (unwrapped).
    link_angle : tuple, optional
        ``(lo, hi)`` [rad]: ``lo <= |theta_i| <= hi`` for the angle of each link from
        the slider direction (biglide, gantry; Wu 2008 eq. 1, 13).
    max_stroke : float, optional
        Largest actuator stroke [L] (biglide, bipod, gantry).
    min_speed : float, optional
        Guaranteed platform speed in every direction [L/s]; needs
        ``actuator_speed``.
    min_force : float, optional
        Guaranteed platform force in every direction [N]; needs
        ``actuator_torque``.
    actuator_speed : float, optional
        Actuator rate limit [rad/s for cranks, L/s for sliders].
    actuator_torque : float, optional
        Actuator effort limit [N m for cranks, N for sliders].
    payload : float, optional
        Force [N] to hold in the worst direction (the ``torque`` objective).
    singularity_margin : float
        Smallest ``|sine of the angle between the legs|`` allowed (default 1e-3).
    """

    min_lci: float | None = None
    joint_limits: tuple | None = None
    link_angle: tuple | None = None
    max_stroke: float | None = None
    min_speed: float | None = None
    min_force: float | None = None
    actuator_speed: float | None = None
    actuator_torque: float | None = None
    payload: float | None = None
    singularity_margin: float = 1e-3

    def checked(self, spec: DesignSpec) -> "Requirements":
        kw = {}
        if self.min_lci is not None:
            kw["min_lci"] = _v.open_unit_interval("min_lci", self.min_lci)
        if self.joint_limits is not None:
            if not spec.angular:
                cranked = [n for n in mechanisms() if get_spec(n).angular]
                raise ValueError(f"joint_limits (crank angles) apply to {' and '.join('the ' + n for n in cranked)}; "
                                 f"the {spec.name} has sliders: use max_stroke")
            jl = np.asarray(self.joint_limits, float)
            if jl.shape == (2,):
                jl = np.vstack([jl, jl])
            if jl.shape != (2, 2) or not np.all(np.isfinite(jl)) or not np.all(jl[:, 1] > jl[:, 0]):
                raise ValueError(f"joint_limits must be (lo, hi) or ((lo1, hi1), (lo2, hi2)) with lo < hi, "
                                 f"got {_v.show(self.joint_limits)}")
            kw["joint_limits"] = tuple(map(tuple, jl.tolist()))
        if self.link_angle is not None:
            if spec.link_angles is None:
                with_angles = [n for n in mechanisms() if get_spec(n).link_angles is not None]
                raise ValueError(f"link_angle applies to {' and '.join('the ' + n for n in with_angles)}, "
                                 f"not the {spec.name}")
            lo, hi = _v.finite_numbers("link_angle", self.link_angle, 2, "(lo, hi) in rad")
            if not 0 <= lo < hi <= math.pi / 2:
                raise ValueError(f"link_angle must satisfy 0 <= lo < hi <= 90 deg, got {_v.show(self.link_angle)}")
            kw["link_angle"] = (lo, hi)
        if self.max_stroke is not None:
            if spec.angular:
                raise ValueError(f"max_stroke applies to slider mechanisms; the {spec.name} has cranks: "
                                 f"use joint_limits")
            kw["max_stroke"] = _v.positive_length("max_stroke", self.max_stroke)
        for name, needs in (("min_speed", "actuator_speed"), ("min_force", "actuator_torque")):
            if getattr(self, name) is not None:
                kw[name] = _v.positive_length(name, getattr(self, name))
                if getattr(self, needs) is None:
                    raise ValueError(f"{name} needs {needs} (the actuators' limit)")
        for name in ("actuator_speed", "actuator_torque", "payload"):
            if getattr(self, name) is not None:
                kw[name] = _v.positive_length(name, getattr(self, name))
        m = _v.finite_number("singularity_margin", self.singularity_margin)
        if not 0 <= m < 1:
            raise ValueError(f"singularity_margin must lie in [0, 1), got {m!r}")
        kw["singularity_margin"] = m
        return replace(self, **kw)

    def names(self, spec) -> tuple[str, ...]:
        out = ["reach", "singular"]
        if self.min_lci is not None:
            out.append("lci")
        if self.joint_limits is not None:
            out.append("joints")
        if self.link_angle is not None:
            out.append("link_angle")
        if self.max_stroke is not None:
            out.append("stroke")
        if spec.length_constraint:
            out.append("lengths")
        if self.min_speed is not None:
            out.append("speed")
        if self.min_force is not None:
            out.append("force")
        return tuple(out)

    def describe(self, name, unit) -> str:
        """Human wording of one requirement (for messages)."""
        deg = math.degrees
        return {
            "reach": "reachability of the whole task in one working mode",
            "singular": "no type-II singularity over the task (one assembly mode)",
            "lci": f"LCI >= {self.min_lci} over the task",
            "joints": "the joint limits " + (", ".join(f"[{deg(a):g}, {deg(b):g}] deg" for a, b in self.joint_limits)
                                             if self.joint_limits else ""),
            "link_angle": (f"link angles within [{deg(self.link_angle[0]):g}, {deg(self.link_angle[1]):g}] deg"
                           if self.link_angle else ""),
            "stroke": f"stroke <= {self.max_stroke} {unit}",
            "lengths": "the link-length bounds",
            "speed": f"guaranteed speed >= {self.min_speed} {unit}/s",
            "force": f"guaranteed force >= {self.min_force} N",
        }[name]


# -------------------------------------------------------------- mechanism specs
# Each mechanism module defines its design spec next to its mechanism
# (PlanarMechanism.design_spec): the registry is the one list of them, so a new
# mechanism is sized without an edit here.
def mechanisms() -> tuple[str, ...]:
    """Names of the mechanisms ``mechopt design`` sizes: every mechanism of
    :func:`mechopt.mechanisms.registry` (in its order) with a
    :attr:`~mechopt.core.protocol.PlanarMechanism.design_spec`."""
    from mechopt import mechanisms as _mechanisms

    return tuple(n for n, cls in _mechanisms.registry().items() if cls.design_spec is not None)


#: the names of :func:`mechanisms` (computed on access: listing them imports every
#: mechanism module, which importing this module does not)
MECHANISMS: tuple[str, ...]


def __getattr__(name):
    if name == "MECHANISMS":
        return mechanisms()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def get_spec(name) -> DesignSpec:
    """The design specification of mechanism ``name`` (one of :func:`mechanisms`): its
    design variables, bounds, modes, size and joint positions over a task (a
    :class:`~mechopt.core.design_spec.DesignSpec`, the mechanism's
    :attr:`~mechopt.core.protocol.PlanarMechanism.design_spec`)."""
    from mechopt import mechanisms as _mechanisms

    return _mechanisms.registry()[_v.choice("mechanism", name, mechanisms())].design_spec()


# ------------------------------------------------------------------ evaluation
@dataclass(frozen=True)
class Sampling:
    """Sample counts of one evaluation: boundary points, interior grid per side."""

    n_boundary: int = 192
    n_interior: int = 13
    refine: bool = True

    @classmethod
    def fine(cls):
        """The certification of :func:`certify` (front designs, design.json)."""
        return cls(2048, 61, True)


def _bad(v, bad):
    """NaN (unreachable) replaced by ``bad``."""
    return np.where(np.isfinite(v), v, bad)


#: placements whose samples a :class:`DesignEvaluator` keeps (:meth:`DesignEvaluator._context`)
_CONTEXTS_KEPT = 8


def _readonly(*arrays):
    """``arrays``, made read-only (kept samples are shared by many evaluations)."""
    for a in arrays:
        a.setflags(write=False)
    return arrays


def _samples(task, s: Sampling) -> dict:
    """The samples of one evaluation of ``task`` (module doc): boundary parameters
    ``tb`` and points ``bx, by`` (largest gap ``gap``), interior grid ``ix, iy`` (step
    ``step``), and both together, ``allx, ally``. A point task's points are its
    boundary samples (contiguous copies: every sample set is a contiguous array)."""
    if task.is_region:
        tb, gap = task.boundary_params(s.n_boundary)
        bx, by = task.boundary_at(tb)
        ix, iy, step = task.grid(s.n_interior)
    else:
        tb, gap = np.zeros(0), 0.0
        bx, by = task.pts[:, 0].copy(), task.pts[:, 1].copy()
        ix, iy, step = np.zeros(0), np.zeros(0), 0.0
    allx, ally = np.concatenate([bx, ix]), np.concatenate([by, iy])
    _readonly(tb, bx, by, ix, iy, allx, ally)
    return dict(task=task, tb=tb, gap=gap, bx=bx, by=by, ix=ix, iy=iy, step=step, allx=allx, ally=ally)


@lru_cache(maxsize=None)
def _boundary_offsets(size, levels, n):
    """Parameter offsets of each level of the boundary zoom over ``size`` samples:
    ``n`` points over +-1.5 sample spacings, each level ``(n - 1) / 2`` times finer."""
    dt = 1.0 / size * 1.5
    out = []
    for _ in range(levels):
        out.append(np.linspace(-dt, dt, n))
        dt = 2.0 * dt / (n - 1)
    return _readonly(*out)


@lru_cache(maxsize=None)
def _interior_offsets(n):
    """The ``n x n`` offsets (in steps) of the interior zoom, ravelled: ``(GX, GY)``."""
    g = np.linspace(-1.0, 1.0, n)
    return _readonly(*(a.ravel() for a in np.meshgrid(g, g)))


def _lowest(vals, k):
    """``np.argsort(vals)[:k]``, the indices of the ``k`` lowest values, lowest first,
    without sorting them all: by a partition when the ``k + 1`` lowest values are
    distinct (their order is then unique); with ties (or NaN) by the full sort, whose
    choice among equal values the zoom has always started from."""
    if vals.size > k + 1:
        part = np.argpartition(vals, k)[:k + 1]  # the k + 1 lowest, in no order
        o = np.argsort(vals[part])
        low = vals[part][o]
        if np.all(low[1:] > low[:-1]):
            return part[o[:k]]
    return np.argsort(vals)[:k]


def _boundary_search(ctx, vals, refine, row=0, k=3, levels=4, n=17):
    """Minimum of a function over the task's boundary (``vals``: its values at the
    boundary samples), refined by zooming (module doc) around the ``k`` lowest
    samples. A generator run by :func:`_minimise`: it yields the boundary parameters
    of each zoom level and is sent the values there (row ``row`` of them); it returns
    the minimum."""
    if vals.size == 0:
        return math.inf
    best = float(np.min(vals))
    if not refine or ctx["tb"].size == 0:
        return best
    t = ctx["tb"][_lowest(vals, k)]
    for off in _boundary_offsets(ctx["tb"].size, levels, n):
        ts = t[:, None] + off[None, :]
        vv = (yield ts.ravel())[row].reshape(ts.shape)
        j = np.argmin(vv, axis=1)
        t = ts[np.arange(len(t)), j]
        best = min(best, float(vv.min()))
    return best


def _interior_search(ctx, vals, refine, row=0, k=3, levels=3, n=9):
    """Minimum of a function over the task's interior grid (``vals``: its values
    there), refined by zooming (module doc) around the ``k`` lowest grid points; a
    generator run by :func:`_minimise`, as :func:`_boundary_search`, that yields
    points ``(x, y)``."""
    if ctx["ix"].size == 0:
        return math.inf
    best = float(np.min(vals))
    if not refine:
        return best
    order = _lowest(vals, k)
    px, py = ctx["ix"][order], ctx["iy"][order]
    h = ctx["step"]
    task = ctx["task"]
    GX, GY = _interior_offsets(n)
    for _ in range(levels):
        X = px[:, None] + h * GX[None, :]
        Y = py[:, None] + h * GY[None, :]
        inside = task.contains(X, Y)
        vv = np.where(inside, (yield X.ravel(), Y.ravel())[row].reshape(X.shape), np.inf)
        j = np.argmin(vv, axis=1)
        px, py = X[np.arange(len(px)), j], Y[np.arange(len(py)), j]
        best = min(best, float(vv.min()))
        h = 2.0 * h / (n - 1)
    return best


def _minimise(F, searches, task):
    """Run the zoom ``searches`` (generators of :func:`_boundary_search` and
    :func:`_interior_search` on ``task``) together and return their minima: each
    round maps the boundary parameters they ask for to points in one call and passes
    all the points to ``F`` in one call (``F(x, y)``: the values of the searched
    functions as rows, shape ``(m, N)``), then sends each search its columns. A call of
    a mechanism's method on 50 points costs mostly its overhead: batching the searches
    of one evaluation saves most of its time."""
    out = [None] * len(searches)
    asks = {}

    def advance(i, values=None):
        try:
            asks[i] = searches[i].send(values)
        except StopIteration as stop:
            out[i] = stop.value

    for i in range(len(searches)):
        advance(i)
    while asks:
        ids, reqs = list(asks), list(asks.values())
        asks.clear()
        ts = [r for r in reqs if not isinstance(r, tuple)]  # boundary parameters
        bx, by = task.boundary_at(np.concatenate(ts)) if ts else (None, None)
        xs, ys, at = [], [], 0
        for r in reqs:
            if isinstance(r, tuple):
                xs.append(r[0])
                ys.append(r[1])
            else:
                xs.append(bx[at:at + r.size])
                ys.append(by[at:at + r.size])
                at += r.size
        V = F(np.concatenate(xs), np.concatenate(ys))
        at = 0
        for i, x in zip(ids, xs):
            advance(i, V[:, at:at + x.size])
            at += x.size
    return out


class DesignEvaluator:
    """Evaluates one design (a dict of variables) against a task: every requirement's
    margin, every objective, the derived strokes. Picklable (travels to workers)."""

    def __init__(self, mechanism, task: Task, requirements: Requirements, objectives, mode=None,
                 place="fixed", min_length=None, max_length=None, shape=None):
        self.spec = get_spec(mechanism)
        if not isinstance(task, Task):
            raise ValueError(f"task must be a mechopt.workflows.design.Task, got {type(task).__name__}")
        self.task = task
        self.unit = task.unit
        self.req = (requirements or Requirements()).checked(self.spec)
        objectives = (objectives,) if isinstance(objectives, str) else tuple(objectives)
        if not objectives:
            raise ValueError(f"objectives must name at least one of {', '.join(OBJECTIVES)}")
        for ob in objectives:
            _v.choice("objective", ob, tuple(OBJECTIVES))
        if len(set(objectives)) != len(objectives):
            raise ValueError(f"objectives must not repeat, got {', '.join(objectives)}")
        if "speed" in objectives and self.req.actuator_speed is None:
            raise ValueError("objective speed needs actuator_speed (--actuator-speed)")
        if "force" in objectives and self.req.actuator_torque is None:
            raise ValueError("objective force needs actuator_torque (--actuator-torque)")
        if "torque" in objectives and self.req.payload is None:
            raise ValueError("objective torque needs payload (--payload, N)")
        self.objectives = objectives
        self.place = _v.choice("place", place, PLACEMENTS)
        if mode in (None, ""):
            mode = self.spec.default_mode
        self.mode_any = mode == "any"
        self.mode = None if self.mode_any else _v.choice("mode", mode, self.spec.modes)
        D = task.diameter
        self.max_length = (_v.positive_length("max_length", max_length) if max_length is not None
                           else 4.0 * max(D, float(np.abs(task.bbox).max())))
        self.min_length = (_v.positive_length("min_length", min_length) if min_length is not None
                           else self.max_length / 1000.0)
        if not self.min_length < self.max_length:
            raise ValueError(f"min_length ({self.min_length:g}) must be below max_length ({self.max_length:g})")
        self.shape = None
        if shape is not None:
            s = _v.finite_numbers("shape", shape, len(self.spec.lengths),
                                  f"{len(self.spec.lengths)} ratios ({', '.join(self.spec.lengths)})")
            if not all(x >= 0 for x in s) or max(s) <= 0:
                raise ValueError(f"shape ratios must be >= 0 and not all 0, got {_v.show(shape)}")
            self.shape = s
        self._precheck()
        self._build_vars()
        self._contexts = {}  # placement -> samples (_context)

    # --- variables -------------------------------------------------------------------
    def _build_vars(self):
        """pymoo variables: each length ``L`` as ``ln_L = ln(L + c)`` with ``c = min_length``
        (a log scale: the optimiser resolves small and large designs alike, and a
        length may reach 0, e.g. the five-bar's half base), the mode index with
        ``mode="any"``, the task placement ``task_x``/``task_y`` when free."""
        lo = self.spec.lower_bounds(self.min_length)
        c = self._c = self.min_length
        names, xl, xu = [], [], []
        if self.shape is None:
            names += [f"ln_{n}" for n in self.spec.lengths]
            xl += [math.log(v + c) for v in lo]
            xu += [math.log(self.max_length + c)] * len(lo)
        else:
            names.append("ln_D")
            pos = [s for s in self.shape if s > 0]
            xl.append(math.log(self.min_length / min(pos) + c))
            xu.append(math.log(self.max_length / max(self.shape) + c))
        if self.mode_any:
            names.append("mode")
            xl.append(0.0)
            xu.append(len(self.spec.modes) - _v.RESOLUTION)
        # the placement relative to the design's own reach (spec.placement_scale):
        # task_y = y_lo + task_y_rel * scale, task_x = task_x_rel * scale
        x0, x1, y0, y1 = self.task.bbox
        self._y_lo = 0.5 * (y1 - y0) if self.spec.placement_above_base(self.mode) else None
        if self.place == "free":
            names.append("task_x_rel")
            xl.append(-1.0)
            xu.append(1.0)
        if self.place in ("free", "free-y"):
            names.append("task_y_rel")
            xl.append(0.0)
            xu.append(1.0)
        self.var_names = tuple(names)
        self.xl, self.xu = np.array(xl, float), np.array(xu, float)

    def _precheck(self):
        """A task no design within the length bounds can reach is an input error."""
        R = self.spec.reach_radius(self.max_length)
        Xr = self.spec.x_reach(self.max_length)
        t, D = self.task, self.task.diameter
        x0, x1, y0, y1 = t.bbox
        far = float(np.abs([x0, x1, y0, y1]).max())
        u = self.unit
        if self.place == "fixed":
            if t.kind == "circle":
                dmax = math.hypot(*t.center) + t.radius
            else:
                p = t.vertices if t.vertices is not None else t.pts
                dmax = float(np.hypot(p[:, 0], p[:, 1]).max())
            if dmax > R:
                raise ValueError(f"the task reaches {dmax:g} {u} from the base midpoint; no {self.spec.name} "
                                 f"with links <= {self.max_length:g} {u} reaches beyond {R:g} {u} "
                                 f"(raise --max-length or move the task)")
            if max(abs(x0), abs(x1)) > Xr:
                raise ValueError(f"the task spans x in [{x0:g}, {x1:g}] {u}; no {self.spec.name} with links "
                                 f"<= {self.max_length:g} {u} reaches |x| > {Xr:g} {u}")
        elif self.place == "free-y":
            if max(abs(x0), abs(x1)) > min(R, Xr):
                raise ValueError(f"the task spans x in [{x0:g}, {x1:g}] {u}; no {self.spec.name} with links "
                                 f"<= {self.max_length:g} {u} reaches |x| > {min(R, Xr):g} {u}")
        if D > 2 * min(R, Xr) and (D > 2 * R or (x1 - x0) > 2 * Xr):
            raise ValueError(f"the task is {D:g} {u} across; no {self.spec.name} with links <= "
                             f"{self.max_length:g} {u} has a workspace that wide (raise --max-length)")
        del far

    def decode(self, x) -> dict:
        """Variables of one row of X as a dict (lengths, ``mode`` string, placement)."""
        x = np.asarray(x, float)
        d = dict(zip(self.var_names, x))
        out = {}
        c = self._c
        if self.shape is None:
            for n in self.spec.lengths:
                out[n] = max(float(math.exp(d[f"ln_{n}"]) - c), 0.0)
        else:
            D = max(float(math.exp(d["ln_D"]) - c), 0.0)
            for n, s in zip(self.spec.lengths, self.shape):
                out[n] = D * s
            out["D"] = D
        if self.mode_any:
            k = int(np.clip(np.floor(d["mode"]), 0, len(self.spec.modes) - 1))
            out["mode"] = self.spec.modes[k]
        else:
            out["mode"] = self.mode
        rx, ry = self.task.reference
        scale = self.spec.placement_scale(out, self.max_length)
        out["task_x"] = float(d["task_x_rel"] * scale) if "task_x_rel" in d else float(rx)
        if "task_y_rel" in d:
            lo = self._y_lo if self._y_lo is not None else ry - scale
            span = scale if self._y_lo is not None else 2.0 * scale
            out["task_y"] = float(lo + d["task_y_rel"] * span)
        else:
            out["task_y"] = float(ry)
        return out

    def encode(self, v: dict) -> np.ndarray:
        row = []
        for n in self.var_names:
            if n == "mode":
                row.append(self.spec.modes.index(v["mode"]) + 0.5)
            elif n.startswith("ln_"):
                row.append(math.log(float(v[n[3:]]) + self._c))
            elif n in ("task_x_rel", "task_y_rel"):
                scale = self.spec.placement_scale(v, self.max_length)
                if n == "task_x_rel":
                    row.append(v["task_x"] / scale)
                else:
                    ry = self.task.reference[1]
                    lo = self._y_lo if self._y_lo is not None else ry - scale
                    span = scale if self._y_lo is not None else 2.0 * scale
                    row.append((v["task_y"] - lo) / span)
            else:
                row.append(float(v[n]))
        return np.array(row)

    # --- one design -------------------------------------------------------------------
    def mechanism(self, v: dict, sampling: Sampling | None = None):
        """The mechanism of the decoded design ``v`` (strokes derived from its task)."""
        return self._setup(v, sampling or Sampling.fine())[0]

    def _setup(self, v, s: Sampling):
        lengths = {n: v[n] for n in self.spec.lengths}
        ctx = self._context(v["task_x"], v["task_y"], s)
        derived = {}
        if self.spec.derived_strokes:
            strokes = []
            for lo, hi in self._leg_ranges(ctx, lambda x, y: self.spec.positions(lengths, v["mode"], x, y),
                                           s.refine):
                if not (math.isfinite(lo) and math.isfinite(hi)):
                    lo, hi = -1.0, 1.0  # some task point out of reach of the link: reach fails
                strokes.append((lo, max(hi, lo + _v.RESOLUTION * self.task.diameter)))
            derived["strokes"] = strokes
            mech = self.spec.build(lengths, v["mode"], strokes=strokes)
            # the clearance to the type-I loci alone (the strokes cover the task by construction)
            check = self.spec.build(lengths, v["mode"], strokes=strokes, pad=10.0 * self.task.diameter)
        else:
            mech = self.spec.build(lengths, v["mode"])
            check = mech
        return mech, check, ctx, derived

    def _context(self, x, y, s: Sampling) -> dict:
        """The samples of the task placed at ``(x, y)`` (:func:`_samples`). They do not
        depend on the design, and the polish evaluates hundreds of designs at one
        placement: the last few placements' samples are kept (read-only)."""
        key = (x, y, s.n_boundary, s.n_interior)
        ctx = self._contexts.get(key)
        if ctx is None:
            ctx = _samples(self.task.moved_to(x, y), s)
            if len(self._contexts) >= _CONTEXTS_KEPT:
                self._contexts.pop(next(iter(self._contexts), None), None)  # the oldest
            self._contexts[key] = ctx
        return ctx

    def __getstate__(self):  # the samples' cache stays behind (workers build their own)
        state = dict(self.__dict__)
        state.pop("_contexts", None)
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._contexts = {}

    def _leg_ranges(self, ctx, legs, refine, bad=(np.inf, np.inf)):
        """``[(lo1, hi1), (lo2, hi2)]``: the range over the task's boundary of each of the
        two values ``legs(x, y)`` returns (one per leg: actuator or link angle), NaN
        replaced by ``bad[0]`` for the minimum and ``bad[1]`` for the maximum: the
        boundary minima (:func:`_boundary_search`) of ``q1, -q1, q2, -q2``, searched
        together (:func:`_minimise`: one call of ``legs`` per round, not four)."""
        def rows(x, y):
            q1, q2 = legs(x, y)[:2]
            return np.stack([_bad(q1, bad[0]), _bad(-q1, bad[1]), _bad(q2, bad[0]), _bad(-q2, bad[1])])

        vals = rows(ctx["bx"], ctx["by"])
        m = _minimise(rows, [_boundary_search(ctx, vals[i], refine, i) for i in range(len(vals))], ctx["task"])
        return [(m[0], -m[1]), (m[2], -m[3])]

    @staticmethod
    def _region_mins(ctx, F, refine, vals):
        """Minimum over the task of each row of ``F(x, y)`` (functions evaluated by one
        call, shape ``(m, N)``): the boundary and interior searches of every row
        (:func:`_boundary_search`, :func:`_interior_search`) run together; ``vals`` is
        ``F`` at ``ctx["allx"], ctx["ally"]`` (the boundary samples, then the grid)."""
        nb = ctx["bx"].size
        searches = []
        for i, v in enumerate(vals):
            searches += [_boundary_search(ctx, v[:nb], refine, i), _interior_search(ctx, v[nb:], refine, i)]
        m = _minimise(F, searches, ctx["task"])
        return [min(m[2 * i], m[2 * i + 1]) for i in range(len(vals))]

    @classmethod
    def _region_min(cls, ctx, f, refine, vals):
        """Minimum of ``f`` over the task (:meth:`_region_mins` of one function)."""
        return cls._region_mins(ctx, lambda x, y: f(x, y)[None], refine, vals[None])[0]

    def evaluate(self, v: dict, sampling: Sampling | None = None) -> dict:
        """Every requirement's ``g`` (<= 0 feasible), margin, objective and derived value."""
        s = sampling or Sampling()
        D = self.task.diameter
        lengths = {n: v[n] for n in self.spec.lengths}
        names = self.req.names(self.spec)
        out = {"g": {}, "margin": {}, "values": {}, "derived": {}}
        validity = self.spec.validity(lengths, self.max_length)
        if validity > 0:
            return self._invalid(v, names, validity)
        mech, check, ctx, derived = self._setup(v, s)
        spec, req = self.spec, self.req
        allx, ally = ctx["allx"], ctx["ally"]
        nb = ctx["bx"].size

        def tm(x, y):
            return spec.to_mech(mech, x, y)

        # reach (certified: 1-Lipschitz clearance on the boundary + holes)
        clr = _bad(check.serial_clearance(*spec.to_mech(check, allx, ally)), -D)
        if self.task.is_region:
            c_b = float(clr[:nb].min())
            reach_margin = c_b - 0.5 * ctx["gap"]
            reach_margin = min(reach_margin, float(clr.min()))
            task = ctx["task"]
            for hx, hy in spec.holes(mech):
                depth = float(task.signed_distance(hx, hy))
                if depth >= -_v.ROUNDING * D:
                    reach_margin = min(reach_margin, -max(depth, _v.RESOLUTION * D))
        else:
            reach_margin = float(clr.min())
        out["margin"]["reach"] = reach_margin
        out["g"]["reach"] = -reach_margin / D if reach_margin > 0 else -reach_margin / D + _v.RESOLUTION

        # type II sign
        rx, ry = ctx["task"].reference if self.task.is_region else (allx.mean(), ally.mean())
        f_all = mech.type2_function(*tm(allx, ally))
        s0 = np.sign(mech.type2_function(*tm(np.float64(rx), np.float64(ry))))
        if not s0:
            med = np.nanmedian(f_all) if np.any(np.isfinite(f_all)) else 1.0
            s0 = np.sign(med) or 1.0

        def t2(x, y):
            return _bad(s0 * mech.type2_function(*tm(x, y)), -1.0)

        def lci(x, y):
            return _bad(_ix.lci(mech.jacobian(*tm(x, y))), 0.0)

        def svals(x, y):
            return _ix.singular_values(mech.jacobian(*tm(x, y)))

        # the sample values, computed once: the minima below start from them
        t2_s = _bad(s0 * f_all, -1.0)
        J_s = mech.jacobian(*tm(allx, ally))
        lci_s = _bad(_ix.lci(J_s), 0.0)
        sample_vals = dict(t2=float(t2_s.min()), lci=float(lci_s.min()))
        # decide whether to refine: only designs that are feasible or nearly so
        near = reach_margin > -0.05 * D and sample_vals["t2"] > -0.05 and \
            (req.min_lci is None or sample_vals["lci"] >= 0.9 * req.min_lci)
        refine = s.refine and near
        t2_min = self._region_min(ctx, t2, refine, t2_s) if self.task.is_region else sample_vals["t2"]
        out["values"]["type2_min"] = t2_min
        out["margin"]["singular"] = t2_min - req.singularity_margin
        out["g"]["singular"] = req.singularity_margin - t2_min if t2_min < req.singularity_margin \
            else -(t2_min - req.singularity_margin)
        need_lci = req.min_lci is not None or {"min-lci"} & set(self.objectives)
        lci_min = (self._region_min(ctx, lci, refine, lci_s) if self.task.is_region else float(lci_s.min())) \
            if need_lci else float(lci_s.min())
        out["values"]["lci_min"] = lci_min
        # over the interior grid (the boundary samples for a point task)
        out["values"]["lci_mean"] = float(np.mean(lci_s[nb:] if ctx["ix"].size else lci_s[:nb]))
        if req.min_lci is not None:
            out["margin"]["lci"] = lci_min - req.min_lci
            out["g"]["lci"] = (req.min_lci - lci_min) / req.min_lci

        # joint / stroke / link angle (boundary extremes; a point task's samples are its points)
        if spec.angular:
            rng = self._leg_ranges(ctx, lambda x, y: mech.ik(*tm(x, y)), refine)
            derived["joint_ranges"] = rng
            if req.joint_limits is not None:
                m = min(min(q_lo - lim_lo, lim_hi - q_hi)
                        for (q_lo, q_hi), (lim_lo, lim_hi) in zip(rng, req.joint_limits))
                m = m if math.isfinite(m) else -math.pi
                out["margin"]["joints"] = m
                out["g"]["joints"] = -m / math.pi
        else:
            st = derived["strokes"]
            strokes = [hi - lo for lo, hi in st]
            derived["stroke"] = max(strokes)
            if req.max_stroke is not None:
                m = req.max_stroke - max(strokes)
                out["margin"]["stroke"] = m
                out["g"]["stroke"] = -m / req.max_stroke
        if req.link_angle is not None:
            lo_req, hi_req = req.link_angle
            m = math.inf
            ranges = self._leg_ranges(ctx, lambda x, y: spec.link_angles(mech, x, y), refine, (0.0, -math.pi / 2))
            for leg, (lo, hi) in enumerate(ranges):
                derived[f"link_angle{leg + 1}"] = (lo, hi)
                m = min(m, lo - lo_req, hi_req - hi)
            out["margin"]["link_angle"] = m
            out["g"]["link_angle"] = -m / (math.pi / 2)
        if spec.length_constraint:  # bipod struts
            qmax = max(mech.q1_max, mech.q2_max)
            out["margin"]["lengths"] = self.max_length - qmax
            out["g"]["lengths"] = (qmax - self.max_length) / self.max_length

        # speed and force (Liu eq. 10, 13) in the user's units
        u_m = UNITS[self.unit]
        need_sv = any(n in names for n in ("speed", "force")) or {"speed", "force", "torque"} & set(self.objectives)
        if need_sv:
            def extremes(sv):  # -s_max and s_min, both minimised (one SVD for the two)
                return np.stack([_bad(-sv[0], -np.inf), _bad(sv[1], 0.0)])

            sample_sv = extremes(_ix.singular_values(J_s))
            if self.task.is_region:
                neg_smax_min, smin_min = self._region_mins(ctx, lambda x, y: extremes(svals(x, y)), refine,
                                                           sample_sv)
                smax_max = -neg_smax_min
            else:
                smax_max = -float(sample_sv[0].min())
                smin_min = float(sample_sv[1].min())
            # J in rad/[unit] (revolute) or 1 (prismatic); torque N m -> N [unit] for revolute
            t_factor = 1.0 / u_m if spec.angular else 1.0
            if req.actuator_speed is not None:
                sp = req.actuator_speed / smax_max if smax_max > 0 and math.isfinite(smax_max) else 0.0
                out["values"]["speed"] = sp
            if req.actuator_torque is not None:
                out["values"]["force"] = req.actuator_torque * t_factor * smin_min
            if req.payload is not None:
                tq = req.payload / smin_min / t_factor if smin_min > 0 else 1e3 * req.payload * D / t_factor
                out["values"]["torque"] = min(tq, 1e3 * req.payload * D / t_factor)
            if "speed" in names:
                out["margin"]["speed"] = out["values"]["speed"] - req.min_speed
                out["g"]["speed"] = (req.min_speed - out["values"]["speed"]) / req.min_speed
            if "force" in names:
                out["margin"]["force"] = out["values"]["force"] - req.min_force
                out["g"]["force"] = (req.min_force - out["values"]["force"]) / req.min_force

        # size and footprint
        out["values"]["size"] = float(spec.size(mech, derived))
        if "footprint" in self.objectives:
            fp = 0.0
            mx, my = tm(allx, ally)
            for jx, jy in spec.joints(mech, mx, my):
                jx, jy = np.asarray(jx), np.asarray(jy)
                ox = jx - (mx - allx)  # back to the task frame
                r = np.hypot(ox, jy)
                fp = max(fp, float(np.nanmax(r)) if np.any(np.isfinite(r)) else 0.0)
            out["values"]["footprint"] = max(fp, float(np.hypot(allx, ally).max()))
        out["derived"] = derived
        out["mechanism"] = mech
        out["names"] = names
        return out

    def _invalid(self, v, names, validity):
        """A design whose variables describe no mechanism: finite objectives, every
        constraint violated, the length one by how much."""
        lengths = {n: v[n] for n in self.spec.lengths}
        size = 2.0 * sum(lengths.values())
        out = {"g": {n: 1.0 for n in names}, "margin": {n: math.nan for n in names},
               "values": {"size": size, "footprint": size, "lci_min": 0.0, "lci_mean": 0.0,
                          "type2_min": -1.0, "speed": 0.0, "force": 0.0,
                          "torque": 1e3 * (self.req.payload or 1.0) * self.task.diameter},
               "derived": {}, "mechanism": None, "names": names}
        out["g"]["reach"] = 1.0 + validity
        return out

    # --- pymoo rows -------------------------------------------------------------------
    def objective_values(self, res) -> list[float]:
        key = {"size": "size", "footprint": "footprint", "min-lci": "lci_min", "mean-lci": "lci_mean",
               "speed": "speed", "force": "force", "torque": "torque"}
        return [float(res["values"][key[o]]) for o in self.objectives]

    def units(self):
        t = "N m" if self.spec.angular else "N"
        return {o: OBJECTIVES[o][1].format(L=self.unit, T=t) for o in self.objectives}

    def row(self, v, res) -> dict:
        """One front.csv row: variables (mode as a string), placement, objectives,
        margins (``margin_<requirement>``, natural units), derived values."""
        r = {n: v[n] for n in self.spec.lengths}
        if "D" in v:
            r["D"] = v["D"]
        r["mode"] = v["mode"]
        r["task_x"], r["task_y"] = v["task_x"], v["task_y"]
        for o, val in zip(self.objectives, self.objective_values(res)):
            r[o] = val
        for n in res["names"]:
            r[f"margin_{n}"] = res["margin"][n]
        d = res["derived"]
        if "joint_ranges" in d:
            for i, (lo, hi) in enumerate(d["joint_ranges"], 1):
                r[f"theta{i}_min_deg"], r[f"theta{i}_max_deg"] = math.degrees(lo), math.degrees(hi)
        if "strokes" in d:
            for i, (lo, hi) in enumerate(d["strokes"], 1):
                r[f"q{i}_min"], r[f"q{i}_max"] = lo, hi
            r["stroke"] = d["stroke"]
        for leg in (1, 2):
            if f"link_angle{leg}" in d:
                lo, hi = d[f"link_angle{leg}"]
                r[f"link{leg}_angle_min_deg"], r[f"link{leg}_angle_max_deg"] = math.degrees(lo), math.degrees(hi)
        r["size"] = res["values"]["size"]
        r["lci_min"] = res["values"]["lci_min"]
        return r

    def settings(self) -> dict:
        req = {k: v for k, v in asdict(self.req).items() if v is not None}
        return {"mechanism": self.spec.name, "task": self.task.to_dict(), "requirements": req,
                "objectives": list(self.objectives), "mode": "any" if self.mode_any else self.mode,
                "place": self.place, "min_length": self.min_length, "max_length": self.max_length,
                "shape": list(self.shape) if self.shape else None, "unit": self.unit}


# ------------------------------------------------------------------ certification
def feasible(g) -> bool:
    """Every requirement holds: each of the values ``g`` (an evaluation's ``"g"`` values,
    a row of G) is ``<= 0``; NaN fails."""
    return bool(all(v <= 0 for v in g))


def certify(evaluator: DesignEvaluator, v: dict, sampling: Sampling | None = None) -> dict:
    """Re-check one design with the fine sampling (:meth:`Sampling.fine`: 2048 boundary
    points, a 61 x 61 interior grid, zoom refinement); returns the evaluation with
    ``feasible`` (every ``g <= 0``) and ``tolerance`` (what the margins rest on)."""
    s = sampling or Sampling.fine()
    res = evaluator.evaluate(v, s)
    res["feasible"] = feasible(res["g"].values())
    task = evaluator.task
    if task.is_region:
        _, gap = task.boundary_params(s.n_boundary)
        res["tolerance"] = {
            "boundary_gap": gap,
            "interior_step": max(np.ptp(task.bbox[:2]), np.ptp(task.bbox[2:])) / (s.n_interior - 1),
            "reach": "certified: clearance >= sampled minimum - boundary_gap/2 (1-Lipschitz), no base joint in the task",
            "minima": "boundary and interior critical points located on the samples, refined to "
                      "boundary_gap/2048 (boundary) and interior_step/64 (interior)",
        }
    else:
        res["tolerance"] = {"points": "exact at the task's points"}
    return res


# ------------------------------------------------------------------ choosing
def knee_index(F: np.ndarray) -> int:
    """Knee of a front (minimisation form ``F``, rows = designs): with two objectives
    the design farthest from the line through the two extremes (normalised), with
    one the best, otherwise the design nearest the normalised ideal point."""
    F = np.asarray(F, float)
    if len(F) == 1 or F.shape[1] == 1:
        return int(np.argmin(F[:, 0]))
    lo, hi = F.min(0), F.max(0)
    Z = (F - lo) / np.where(hi > lo, hi - lo, 1.0)
    if F.shape[1] == 2:
        a, b = Z[np.argmin(Z[:, 0])], Z[np.argmin(Z[:, 1])]
        d = b - a
        n = np.hypot(*d)
        if n == 0:
            return int(np.argmin(Z.sum(1)))
        dist = np.abs(d[0] * (Z[:, 1] - a[1]) - d[1] * (Z[:, 0] - a[0])) / n
        return int(np.argmax(dist - _v.ROUNDING * Z.sum(1)))  # ties: the better sum
    return int(np.argmin(np.sqrt((Z ** 2).sum(1))))


def _parse_weights(weights, objectives):
    if isinstance(weights, str):
        d = {}
        for part in weights.split(","):
            if not part.strip():
                continue
            k, sep, val = part.partition("=")
            if not sep:
                raise ValueError(f"--pick must be name=weight,... (e.g. size=1,min-lci=2), got {weights!r}")
            d[k.strip()] = val
        weights = d
    out = {}
    for k, val in dict(weights).items():
        _v.choice("pick objective", k, objectives)
        w = _v.finite_number(f"weight of {k}", val)
        if w < 0:
            raise ValueError(f"weight of {k} must be >= 0, got {w!r}")
        out[k] = w
    if not out or not any(out.values()):
        raise ValueError("--pick needs at least one positive weight")
    return out
