"""Task geometry for ``mechopt design``: the region, path or point set a mechanism must
cover, and its command-line syntax.

* :class:`Task` - the region to cover (:meth:`Task.rect`, :meth:`Task.circle`,
  :meth:`Task.polygon`, :meth:`Task.points`), in the user's length unit, in the
  base frame (base midpoint at the origin, y away from the base); its boundary at
  arc-length parameters (:meth:`Task.boundary_at`, :meth:`Task.boundary_params`), an
  interior grid (:meth:`Task.grid`), membership and signed distance.
* :func:`parse_task` - ``rect:W,H@X,Y``, ``circle:R@X,Y``, ``polygon:...``,
  ``points:FILE.csv``.

How a task is sampled for an evaluation is :mod:`mechopt.analysis.sampling`; what
must hold over it is :mod:`mechopt.requirements`; the evaluation of a design is
:mod:`mechopt.analysis.design_eval`.
"""
from __future__ import annotations

import math
import re
from dataclasses import dataclass, replace
from functools import cached_property
from pathlib import Path

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.jit import Twin
from mechopt.core.zoom import arc_params, contains_points, polygon_grid, polygon_points

__all__ = ["Task", "parse_task", "read_points", "UNITS", "PLACEMENTS"]

#: length units a task may be given in, and their value in metres
UNITS = {"mm": 1e-3, "cm": 1e-2, "m": 1.0, "in": 0.0254}
#: how the task may be placed relative to the base: as given, moved along y, moved in x and y
PLACEMENTS = ("fixed", "free-y", "free")


# --------------------------------------------------------------------------- task
def _polygon_simple(v):
    """True when the closed polygon ``v`` (n, 2) has no two non-adjacent edges that
    meet and no two adjacent edges that fold back on each other. One pass per edge,
    vectorised over the edges after it: ``n`` numpy steps of length ``n`` (2000 vertices
    in well under a second; :data:`~mechopt.core.validation.POLYGON_VERTICES_MAX` bounds ``n``)."""
    n = len(v)
    a, b = v, np.roll(v, -1, axis=0)
    # adjacent edges i and i + 1 share b[i]: a fold is a collinear turn back (dot > 0)
    d1, d2 = a - b, np.roll(b, -1, axis=0) - b
    cross = d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]
    fold = (np.abs(cross) <= _v.ROUNDING * np.hypot(*d1.T) * np.hypot(*d2.T)) & ((d1 * d2).sum(1) > 0)
    if fold.any():
        return False

    def orient(p, q, r):
        return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                       - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))

    def on(p, q, r):  # r on the segment pq, given collinear
        return ((np.minimum(p[..., 0], q[..., 0]) <= r[..., 0]) & (r[..., 0] <= np.maximum(p[..., 0], q[..., 0]))
                & (np.minimum(p[..., 1], q[..., 1]) <= r[..., 1]) & (r[..., 1] <= np.maximum(p[..., 1], q[..., 1])))

    for i in range(n - 2):
        j = np.arange(i + 2, n - 1 if i == 0 else n)  # the edges after i that do not touch it
        if not j.size:
            continue
        p1, p2, p3, p4 = a[i], b[i], a[j], b[j]
        o1, o2 = orient(p1, p2, p3), orient(p1, p2, p4)
        o3, o4 = orient(p3, p4, p1[None, :]), orient(p3, p4, p2[None, :])
        meet = ((o1 != o2) & (o3 != o4)) | ((o1 == 0) & on(p1, p2, p3)) | ((o2 == 0) & on(p1, p2, p4)) \
            | ((o3 == 0) & on(p3, p4, p1[None, :])) | ((o4 == 0) & on(p3, p4, p2[None, :]))
        if meet.any():
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

    Parameters
    ----------
    kind : str
        ``rect``, ``circle``, ``polygon``, ``points`` or ``path``.
    vertices : ndarray, optional
        Vertices [unit] of a rectangle or polygon, counter-clockwise, shape (n, 2).
    center : tuple of float, optional
        A circle's centre [unit].
    radius : float, optional
        A circle's radius [unit].
    pts : ndarray, optional
        The points of a point set or path [unit], shape (n, 2).
    unit : str
        Length unit: mm, cm, m or in (default mm).
    label : str
        A description for messages and plots.
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
        """Axis-aligned ``width x height`` rectangle centred at ``center`` [unit].

        Parameters
        ----------
        width : float
            Width along x [unit], > 0.
        height : float
            Height along y [unit], > 0.
        center : tuple of float
            Centre (x, y) [unit].
        unit : str
            Length unit: mm, cm, m or in (default mm).

        Returns
        -------
        Task
            The rectangle.

        Raises
        ------
        ValueError
            One line naming the invalid input.
        """
        w = _v.positive_length("task width", width)
        h = _v.positive_length("task height", height)
        cx, cy = (_v.coordinate("task center", c) for c in _v.finite_numbers("task center", center, 2, "a point (x, y)"))
        v = np.array([[cx - w / 2, cy - h / 2], [cx + w / 2, cy - h / 2], [cx + w / 2, cy + h / 2],
                      [cx - w / 2, cy + h / 2]])
        return cls("rect", vertices=v, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"rect {w:g} x {h:g} {unit} at ({cx:g}, {cy:g})")

    @classmethod
    def circle(cls, radius, center=(0.0, 0.0), unit="mm"):
        """Disk of ``radius`` about ``center`` [unit].

        Parameters
        ----------
        radius : float
            Radius [unit], > 0.
        center : tuple of float
            Centre (x, y) [unit].
        unit : str
            Length unit: mm, cm, m or in (default mm).

        Returns
        -------
        Task
            The disk.

        Raises
        ------
        ValueError
            One line naming the invalid input.
        """
        r = _v.positive_length("task radius", radius)
        cx, cy = (_v.coordinate("task center", c) for c in _v.finite_numbers("task center", center, 2, "a point (x, y)"))
        return cls("circle", center=(cx, cy), radius=r, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"circle r {r:g} {unit} at ({cx:g}, {cy:g})")

    @classmethod
    def polygon(cls, vertices, unit="mm"):
        """Simple polygon (no self-intersection, positive area), vertices in order.

        Parameters
        ----------
        vertices : array_like
            Shape (n, 2) [unit], n >= 3, in boundary order (either orientation; a repeated
            first vertex closes it).
        unit : str
            Length unit: mm, cm, m or in (default mm).

        Returns
        -------
        Task
            The polygon, counter-clockwise.

        Raises
        ------
        ValueError
            For fewer than 3 distinct vertices, too many, zero area or crossing edges.
        """
        v = _as_xy("polygon vertices", vertices, 3)
        if len(v) > 3 and np.allclose(v[0], v[-1]):
            v = v[:-1]  # closed explicitly
        keep = np.r_[True, np.any(np.diff(v, axis=0) != 0, axis=1)]
        v = v[keep]
        if len(v) < 3:
            raise ValueError("polygon needs at least 3 distinct vertices")
        if len(v) > _v.POLYGON_VERTICES_MAX:
            raise ValueError(f"polygon has {len(v)} vertices, more than {_v.POLYGON_VERTICES_MAX}; simplify it")
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
        """A finite set of poses (a point cloud, or way-points checked at the points
        only: :meth:`path` for the polyline through them).

        Parameters
        ----------
        array : array_like
            Shape (n, 2) [unit].
        unit : str
            Length unit: mm, cm, m or in (default mm).

        Returns
        -------
        Task
            The point set.

        Raises
        ------
        ValueError
            One line naming the invalid input.
        """
        p = _as_xy("task points", array, 1)
        return cls("points", pts=p, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"{len(p)} points [{unit}]")

    @classmethod
    def path(cls, array, unit="mm"):
        """The polyline through ``array``'s points, in order (a trajectory): every point of
        every segment is covered, not only the way-points. Repeated consecutive points
        are dropped; at least two distinct points.

        Parameters
        ----------
        array : array_like
            Shape (n, 2) [unit], in order.
        unit : str
            Length unit: mm, cm, m or in (default mm).

        Returns
        -------
        Task
            The path.

        Raises
        ------
        ValueError
            For fewer than 2 distinct points or invalid values.
        """
        p = _as_xy("task path", array, 2)
        p = p[np.r_[True, np.any(np.diff(p, axis=0) != 0, axis=1)]]
        if len(p) < 2:
            raise ValueError("task path needs at least 2 distinct points")
        return cls("path", pts=p, unit=_v.choice("unit", unit, tuple(UNITS)),
                   label=f"path of {len(p)} points [{unit}]")

    # --- geometry --------------------------------------------------------------------
    @property
    def is_region(self) -> bool:
        return self.kind not in ("points", "path")

    @property
    def is_path(self) -> bool:
        """An open polyline (:meth:`path`): sampled along its length like a boundary."""
        return self.kind == "path"

    @cached_property
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
        if not self.is_region:
            return 0.0
        v = self.vertices
        return 0.5 * abs(float(np.sum(v[:, 0] * np.roll(v[:, 1], -1) - np.roll(v[:, 0], -1) * v[:, 1])))

    @property
    def perimeter(self) -> float:
        if self.kind == "circle":
            return 2 * math.pi * self.radius
        if self.kind == "points":
            return 0.0
        if self.is_path:  # its length
            return float(np.hypot(*np.diff(self.pts, axis=0).T).sum())
        return float(np.hypot(*(np.roll(self.vertices, -1, 0) - self.vertices).T).sum())

    def moved_to(self, x, y) -> "Task":
        """The same task translated so that its :attr:`reference` is ``(x, y)``.

        Parameters
        ----------
        x : float
            New reference abscissa [unit].
        y : float
            New reference ordinate [unit].

        Returns
        -------
        Task
            The translated task (this one when it is already there).
        """
        rx, ry = self.reference
        d = np.array([x - rx, y - ry], float)
        if not np.any(d):
            return self
        if self.kind == "circle":
            return replace(self, center=(self.center[0] + d[0], self.center[1] + d[1]))
        if not self.is_region:
            return replace(self, pts=self.pts + d)
        return replace(self, vertices=self.vertices + d)

    def outline(self):
        """Closed outline ``(x, y)`` for plots (the points themselves for a point task,
        the polyline for a path).

        Returns
        -------
        x, y : ndarray
            The outline's coordinates [unit].
        """
        if self.kind == "circle":
            t = np.linspace(0, 2 * np.pi, 361)
            return self.center[0] + self.radius * np.cos(t), self.center[1] + self.radius * np.sin(t)
        if not self.is_region:
            return self.pts[:, 0], self.pts[:, 1]
        v = np.vstack([self.vertices, self.vertices[:1]])
        return v[:, 0], v[:, 1]

    @cached_property
    def edges(self):
        """The polygon's edges, computed once (the design evaluation and the compiled
        zoom of :mod:`mechopt.core.zoom` ask for them at every boundary sample): ``(vx, vy, wy, ex, ey, L2, L, cum)`` with ``(vx, vy)``
        the vertices, ``wy`` the next vertex's y, ``(ex, ey) = w - v``, ``L2 = |e|^2``,
        ``L = |e|`` and ``cum`` the arc-length fractions of the vertices (``cum[-1] = 1``).
        A path's edges join its consecutive points (no closing edge)."""
        v = self.pts[:-1] if self.is_path else self.vertices
        w = self.pts[1:] if self.is_path else np.concatenate((v[1:], v[:1]))  # np.roll(v, -1, 0)
        e = w - v
        ex, ey = e[:, 0].copy(), e[:, 1].copy()
        L = np.hypot(ex, ey)
        return (v[:, 0].copy(), v[:, 1].copy(), w[:, 1].copy(), ex, ey, ex * ex + ey * ey, L,
                np.concatenate(([0.0], np.cumsum(L))) / L.sum())

    @property
    def inside_tolerance(self) -> float:
        """Distance within which a point outside counts as on the boundary
        (:meth:`contains`): rounding relative to the diameter [unit]."""
        return _v.ROUNDING * self.diameter

    def boundary_at(self, t):
        """Point at arc-length fraction ``t`` (mod 1) of the boundary, counter-clockwise;
        of a path, from its first point (``t`` clipped to [0, 1]: it has two ends).

        Parameters
        ----------
        t : array_like
            Arc-length fractions.

        Returns
        -------
        x, y : ndarray
            The boundary points [unit].
        """
        t = np.asarray(t, float)
        if self.kind == "circle":  # a region: no ends
            a = 2 * np.pi * np.mod(t, 1.0)
            return self.center[0] + self.radius * np.cos(a), self.center[1] + self.radius * np.sin(a)
        vx, vy, _, ex, ey, _, L, cum = self.edges
        if Twin.compiled():
            tf = t.reshape(-1)
            bx, by = np.empty(tf.size), np.empty(tf.size)
            _BOUNDARY_TWIN(tf, self.is_path, vx, vy, ex, ey, L, cum, bx, by)
            return bx.reshape(t.shape), by.reshape(t.shape)
        t = np.clip(t, 0.0, 1.0) if self.is_path else np.mod(t, 1.0)
        k = np.clip(np.searchsorted(cum, t, side="right") - 1, 0, len(vx) - 1)
        s = (t - cum[k]) / np.where(L[k] > 0, (cum[k + 1] - cum[k]), 1.0)
        return vx[k] + s * ex[k], vy[k] + s * ey[k]

    def boundary_params(self, n):
        """Arc-length fractions of about ``n`` boundary samples, every vertex included;
        returns ``(t, gap)`` with ``gap`` the largest distance between neighbours [unit].

        Parameters
        ----------
        n : int
            Requested number of samples (at least 8 are used).

        Returns
        -------
        t : ndarray
            The arc-length fractions.
        gap : float
            The largest distance between neighbouring samples [unit].
        """
        n = max(int(n), 8)
        if self.kind == "circle":
            t = np.arange(n) / n
            return t, 2 * self.radius * math.sin(math.pi / n)
        L, cum = self.edges[6], self.edges[7]
        total = L.sum()
        if Twin.compiled():
            return _PARAMS_TWIN(n, self.is_path, L, cum, total)
        # m_i samples on edge i at fractions cum_i + (cum_{i+1} - cum_i) k / m_i, k < m_i
        m = np.maximum(1, np.ceil(n * L / total).astype(int))
        k = np.arange(m.sum()) - np.repeat(np.cumsum(m) - m, m)
        t = np.repeat(cum[:-1], m) + np.repeat(np.diff(cum), m) * k / np.repeat(m, m)
        if self.is_path:  # its last point too (a polygon's is its first)
            t = np.r_[t, 1.0]
        return t, max(0.0, float((L / m).max()))

    def contains(self, x, y):
        """Points inside or on the boundary (to rounding).

        Parameters
        ----------
        x : array_like
            Abscissae [unit].
        y : array_like
            Ordinates [unit]; broadcast with ``x``.

        Returns
        -------
        ndarray of bool
            Inside or on the boundary; False everywhere for a point set or path.
        """
        x, y = np.asarray(x, float), np.asarray(y, float)
        if self.kind == "circle":
            return np.hypot(x - self.center[0], y - self.center[1]) <= self.radius * (1 + _v.ROUNDING)
        if not self.is_region:
            return np.zeros(np.broadcast(x, y).shape, bool)
        # signed_distance >= -tol: inside by the even-odd rule, or within tol of the
        # boundary; only the points outside need their distance (the same verdict as
        # computing signed_distance everywhere, for a fraction of the work)
        x, y = np.broadcast_arrays(x, y)
        if Twin.compiled():
            vx, vy, wy, ex, ey, L2, _, _ = self.edges
            out = np.empty(x.shape, dtype=np.bool_)
            _CONTAINS_TWIN(x.reshape(-1), y.reshape(-1), vx, vy, wy, ex, ey, L2, self.inside_tolerance,
                           out.reshape(-1))
            return out
        out = self._inside(x, y)
        rest = ~out
        if rest.any():
            out[rest] = self._distance(x[rest], y[rest]) <= self.inside_tolerance
        return out

    def signed_distance(self, x, y):
        """Distance to the boundary, positive inside, negative outside [unit].

        Parameters
        ----------
        x : array_like
            Abscissae [unit].
        y : array_like
            Ordinates [unit]; broadcast with ``x``.

        Returns
        -------
        ndarray
            The signed distance [unit].

        Raises
        ------
        ValueError
            For a point set or path (no inside).
        """
        x, y = np.broadcast_arrays(np.asarray(x, float), np.asarray(y, float))
        if self.kind == "circle":
            return self.radius - np.hypot(x - self.center[0], y - self.center[1])
        if not self.is_region:
            raise ValueError(f"a {self.kind} task has no inside")
        d = self._distance(x, y)
        return np.where(self._inside(x, y), d, -d)

    def _distance(self, x, y):
        """Distance of the points ``(x, y)`` to the polygon's boundary [unit]."""
        vx, vy, _, ex, ey, L2, _, _ = self.edges
        dx, dy = x[..., None] - vx, y[..., None] - vy
        s = np.clip((dx * ex + dy * ey) / L2, 0, 1)
        return np.hypot(dx - s * ex, dy - s * ey).min(-1)

    def _inside(self, x, y):
        """The points ``(x, y)`` inside the polygon by the even-odd rule (it is simple)."""
        vx, vy, wy, ex, ey, _, _, _ = self.edges
        px, py = x[..., None], y[..., None]
        with np.errstate(divide="ignore", invalid="ignore"):
            cross = ((vy > py) != (wy > py)) & (px < ex * (py - vy) / ey + vx)
        return np.count_nonzero(cross, axis=-1) % 2 == 1

    def grid(self, n):
        """``n x n`` grid over the bounding box (edges included), kept inside: ``(x, y, step)``.

        Parameters
        ----------
        n : int
            Nodes per side of the bounding box.

        Returns
        -------
        x, y : ndarray
            The nodes inside the task [unit] (a point set's or path's points).
        step : float
            The grid step [unit] (0 for points).
        """
        if not self.is_region:
            return self.pts[:, 0].copy(), self.pts[:, 1].copy(), 0.0
        x0, x1, y0, y1 = self.bbox
        step = max(x1 - x0, y1 - y0) / (n - 1)
        if Twin.compiled() and self.kind != "circle":  # a polygon: in one compiled call
            vx, vy, wy, ex, ey, L2, _, _ = self.edges
            gx, gy = _GRID_TWIN(x0, x1, y0, y1, int(n), vx, vy, wy, ex, ey, L2, self.inside_tolerance)
            return gx, gy, step
        gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
        keep = self.contains(gx, gy)
        return gx[keep], gy[keep], step

    @classmethod
    def from_dict(cls, d: dict) -> "Task":
        """The task of :meth:`to_dict` (run.json's ``design.task``), checked by its
        constructors (a rectangle keeps its vertices as written).

        Parameters
        ----------
        d : dict
            What :meth:`to_dict` wrote.

        Returns
        -------
        Task
            The task.

        Raises
        ------
        ValueError
            One line, for a missing key, an unknown kind or invalid values.
        """
        kind, unit = d.get("kind"), d.get("unit", "mm")
        try:
            if kind == "rect":
                v = _as_xy("task vertices", d["vertices"], 4)
                return cls("rect", vertices=v, unit=_v.choice("unit", unit, tuple(UNITS)), label=str(d.get("label", "")))
            if kind == "circle":
                return cls.circle(d["radius"], tuple(d["center"]), unit)
            if kind == "polygon":
                return cls.polygon(d["vertices"], unit)
            if kind in ("points", "path"):
                return getattr(cls, kind)(d["points"], unit)
        except (KeyError, TypeError) as exc:
            raise ValueError(f"the task ({kind}) lacks {exc}") from None
        raise ValueError(f"the task's kind must be rect, circle, polygon, points or path, got {kind!r}")

    def to_dict(self) -> dict:
        """The task as plain data (run.json's ``design.task``).

        Returns
        -------
        dict
            ``kind``, ``unit``, ``label`` and ``vertices``, ``center`` and ``radius``, or
            ``points`` [unit].
        """
        d = {"kind": self.kind, "unit": self.unit, "label": self.label}
        if self.kind == "circle":
            d.update(center=list(self.center), radius=self.radius)
        elif not self.is_region:
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


_HEADER_FIELD = re.compile(r"[A-Za-z_][A-Za-z0-9_ \[\]()/.-]*")


def read_points(path, what) -> list:
    """The ``[x, y]`` rows of a points file, strictly: a regular file of at most
    :data:`~mechopt.core.validation.POINTS_FILE_BYTES` (FIFOs, devices and giants are
    refused before reading), UTF-8 with or without a BOM; blank lines and ``#`` comments
    skipped; an optional header of two names (``x,y``); the delimiter ``,``, ``;`` or a
    tab, the one the first data line uses; with ``;`` a decimal comma is read as a point
    (``-20,5;120`` is (-20.5, 120)); every data line exactly two finite numbers, else
    the error names the line.

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        What the points are, for messages (``--task points``).

    Returns
    -------
    list
        ``[[x, y], ...]`` as floats, in the file's unit.

    Raises
    ------
    ValueError
        One line naming the file and the offending line, for an unreadable or malformed
        file.
    """
    from mechopt.core import reading

    try:
        raw = reading.read_bytes(path, _v.POINTS_FILE_BYTES, f"{what} {str(path)!r}")
    except OSError as exc:
        raise ValueError(f"{what} cannot read {str(path)!r} ({exc.strerror or exc})") from None
    try:
        text = raw.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise ValueError(f"{what} {str(path)!r} is not UTF-8 text") from None
    lines = [(k + 1, ln.strip()) for k, ln in enumerate(text.splitlines())]
    lines = [(k, ln) for k, ln in lines if ln and not ln.startswith("#")]
    if not lines:
        raise ValueError(f"{what} {str(path)!r} holds no x,y rows")
    first = lines[0][1]
    delim = ";" if ";" in first else "\t" if "\t" in first else ","
    fields = [f.strip() for f in first.split(delim)]
    if len(fields) == 2 and all(_HEADER_FIELD.fullmatch(f) for f in fields):
        lines = lines[1:]  # a header: two names
    rows = []
    for k, ln in lines:
        parts = [f.strip() for f in ln.split(delim)]
        if delim == ";":
            parts = [f.replace(",", ".") for f in parts]  # a decimal comma
        try:
            if len(parts) != 2:
                raise ValueError
            x, y = float(parts[0]), float(parts[1])
        except ValueError:
            sep = {"\t": "a tab", ";": "';'"}.get(delim, "','")
            raise ValueError(f"{what} line {k} of {str(path)!r} is not two numbers separated by {sep}: "
                             f"{ln[:60]!r}") from None
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"{what} line {k} of {str(path)!r} holds a number that is not finite: {ln[:60]!r}")
        rows.append([x, y])
        if len(rows) > _v.POINTS_MAX:
            raise ValueError(f"{what} {str(path)!r} holds more than {_v.POINTS_MAX} points")
    if not rows:
        raise ValueError(f"{what} {str(path)!r} holds no x,y rows")
    return rows


def parse_task(text: str, unit: str = "mm") -> Task:
    """A task from the CLI syntax: ``rect:W,H@X,Y``, ``circle:R@X,Y``,
    ``polygon:x1,y1;x2,y2;...``, ``points:FILE.csv`` (two columns x, y; a header line is
    skipped: the points alone) or ``path:FILE.csv`` (the same file: the polyline through
    the points, in order). ``@X,Y`` (the centre) defaults to the origin.

    Parameters
    ----------
    text : str
        The ``--task`` value.
    unit : str
        Length unit: mm, cm, m or in (default mm).

    Returns
    -------
    Task
        The task.

    Raises
    ------
    ValueError
        One line, for a malformed text or invalid values.
    """
    if not isinstance(text, str) or ":" not in text:
        raise ValueError(f"--task must be rect:W,H@X,Y, circle:R@X,Y, polygon:x1,y1;x2,y2;..., "
                         f"points:FILE.csv or path:FILE.csv, got {_v.show(text)}")
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
    if kind in ("points", "path"):
        rows = read_points(Path(body.strip()), f"--task {kind}:")
        return Task.points(rows, unit) if kind == "points" else Task.path(rows, unit)
    raise ValueError(f"--task kind must be rect, circle, polygon, points or path, got {kind!r}")


# --- compiled twins of the polygon's hot paths (mechopt.core.jit.Twin: the same
# operations point by point, so the same values bit for bit) -----------------------------
def _boundary_loop(t, is_path, vx, vy, ex, ey, L, cum, bx, by):
    """:meth:`Task.boundary_at` of a polygon or path at each ``t`` into ``bx, by``
    (:func:`mechopt.core.zoom.polygon_points`)."""
    polygon_points(t, is_path, vx, vy, ex, ey, L, cum, bx, by)


def _contains_loop(x, y, vx, vy, wy, ex, ey, L2, tol, out):
    """:meth:`Task.contains` of a polygon at each point into ``out``
    (:func:`mechopt.core.zoom.contains_points`: the even-odd rule of :meth:`Task._inside`,
    else the distance of :meth:`Task._distance` within ``tol``; a grid's rows share
    their crossings)."""
    contains_points(x, y, vx, vy, wy, ex, ey, L2, tol, out)


def _params_loop(n, is_path, L, cum, total):
    """:meth:`Task.boundary_params` of a polygon or path (:func:`mechopt.core.zoom.arc_params`)."""
    return arc_params(n, is_path, L, cum, total)


def _grid_loop(x0, x1, y0, y1, n, vx, vy, wy, ex, ey, L2, tol):
    """:meth:`Task.grid` of a polygon (:func:`mechopt.core.zoom.polygon_grid`)."""
    return polygon_grid(x0, x1, y0, y1, n, vx, vy, wy, ex, ey, L2, tol)


_BOUNDARY_TWIN = Twin(_boundary_loop)
_PARAMS_TWIN = Twin(_params_loop)
_GRID_TWIN = Twin(_grid_loop)
_CONTAINS_TWIN = Twin(_contains_loop)
