"""Links that do not collide, machines that stay out of a zone: capsule geometry over a task.

Every mechanism declares its bodies as capsules (:meth:`DesignSpec.links
<mechopt.core.design_spec.DesignSpec.links>`, :mod:`mechopt.core.bodies`): a segment and
a width ``w`` (its diameter). This module measures them, vectorised over poses:

segment distance
    :func:`segment_distance`: the exact distance between two segments (0 where they
    cross: the orientation test; otherwise the smallest of the four end-to-segment
    distances, which is the distance of two disjoint segments in the plane). Zero-length
    segments (discs) are points.
clearance
    of two capsules: ``distance(axes) - (w_a + w_b) / 2`` [L], negative when they
    overlap. :meth:`Collisions.clearance` is its minimum over every *checked* pair: two
    bodies that carry no common joint (adjacent bodies touch by construction) and are
    not both fixed (two fixed bodies never move: :meth:`Collisions.base_margin`).
joint angles
    of adjacent links, at their common joint: the angle between the two links' axes
    seen from the joint, in ``[0, pi]`` [rad] (:meth:`Collisions.joint_angles`): a
    joint-angle limit ``angle >= alpha`` keeps two links that share a joint apart.
keep-out zones
    :class:`Zone`: a polygon (the task itself, ``--keep-out task``, or
    ``polygon:x1,y1;...``), a disc (a circular task) or a half-plane (``above:Y``: the
    zone ``y >= Y``; ``below:Y``: ``y <= Y``). The margin of a capsule is ``min over its
    axis of phi - w/2`` with ``phi`` the signed distance to the zone (positive outside):
    exact for half-planes and discs, and for a polygon wherever the axis stays outside
    (its distance to the polygon's edges); an axis that enters a polygon gets minus the
    depth of its deepest end inside (0 when only its middle crosses), which makes the
    margin negative (the design infeasible) without claiming its exact depth.
    The task as a zone spares the bodies that carry the tool (``distal`` links and the
    platform reach the tool point by construction).
base width
    :meth:`Collisions.base_margin`: the clearance of the fixed bodies (the five-bar's two
    motor housings at ``-+r3``: ``2 r3 - d``), and :meth:`Collisions.base_distance`, the
    distance between their axes (``2 r3``).

Certification over a task (:func:`task_samples`, :meth:`Collisions.certified_minimum`)
------------------------------------------------------------------------------------
The samples are those of :mod:`mechopt.analysis.task` (``n_boundary`` points along the
boundary, every polygon vertex among them, largest gap ``h_b``; an ``n_interior`` x
``n_interior`` grid over the box, step ``h`` the larger cell side, kept inside). Every
point ``p`` of the task joins a sample by a path inside the task no longer than the
covering radius ``rho = delta + kappa h_b / 2`` (:func:`covering_radius`), ``delta`` the
half diagonal of a grid cell (``<= h / sqrt(2)``): if ``p`` lies at least ``delta``
inside, the disc of that radius about it lies in the task and holds the nearest grid
node (a corner of ``p``'s cell); otherwise a straight step to the nearest boundary point
(shorter than ``delta``, inside) and then along the boundary to the nearest
boundary sample (half a gap: ``h_b / 2`` along a polygon's straight edges, ``kappa =
(pi / n) / sin(pi / n)`` times it along a circle's arcs).

Along that path the clearance of a pair changes no faster than the sum of the two
bodies' speeds: the distance of two sets is 1-Lipschitz in each set's Hausdorff
displacement, and a segment whose ends move by ``e0, e1`` moves by at most
``max(|e0|, |e1|)`` in that distance (its points are convex combinations of its ends).
The speed of an end per unit platform speed is that of the joint it moves with
(:meth:`DesignSpec.joint_speeds <mechopt.core.design_spec.DesignSpec.joint_speeds>`,
from the Jacobian: a crank's elbow ``1 / |sin gamma|``, a slider ``1 / cos theta``, the
tool 1, the base 0), bounded over the disc of radius ``rho`` about each sample, which
holds the whole path. Hence, pair by pair and sample by sample,

    clearance(p) >= clearance(s) - (k_a(s) + k_b(s)) rho,

and the certified minimum is the smallest right-hand side over pairs and samples
(:func:`lipschitz_bound`; with one global constant ``L`` it is ``sampled min - L rho``).
A joint angle moves no faster than ``(k_E + k_J) / |E - J|`` for each of its two links
(``E`` the far end, ``J`` the joint; the direction of a vector of length ``r`` turns by at
most its displacement over ``r``), a keep-out margin no faster than the body's speed
(``phi`` is 1-Lipschitz). Assumptions: the task lies in the reachable set of one working
mode without a singularity (the ``reach`` and ``singular`` requirements), so the bodies
move continuously along the path; a bound is ``-inf`` where a joint speed is unbounded
within ``rho`` (a type-I singularity within reach of a sample). Rounding: the distances are
those of float64 arithmetic (relative error ~1e-15 of the lengths).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.bodies import GROUND, TOOL_KINDS, Shapes

__all__ = ["segment_distance", "point_segment_distance", "Zone", "parse_zone", "Collisions",
           "covering_radius", "covering_radius_of", "task_samples", "lipschitz_bound", "ZONE_KINDS"]

#: the kinds of keep-out zone
ZONE_KINDS = ("polygon", "disc", "above", "below")
#: bodies whose joint angles are measured (links, not housings, guides or carriages)
_LINK_KINDS = ("proximal", "distal", "platform")


# ----------------------------------------------------------------------- distances
def _point_segment_sq(px, py, x0, y0, x1, y1):
    """Squared distance from points to segments (:func:`point_segment_distance`)."""
    dx, dy = np.subtract(x1, x0), np.subtract(y1, y0)
    ux, uy = np.subtract(px, x0), np.subtract(py, y0)
    L2 = dx * dx + dy * dy
    # t = clamp(u.d / |d|^2, 0, 1), 0 for a zero-length segment (a point)
    t = np.minimum(np.maximum(ux * dx + uy * dy, 0.0), L2) / np.maximum(L2, np.finfo(float).tiny)
    ex, ey = ux - t * dx, uy - t * dy
    return ex * ex + ey * ey


def point_segment_distance(px, py, x0, y0, x1, y1):
    """Distance [L] from points ``(px, py)`` to the segments ``(x0, y0) -> (x1, y1)``
    (broadcast); a segment of zero length is its point.

    Parameters
    ----------
    px, py : array_like
        The points [L].
    x0, y0, x1, y1 : array_like
        The segments' ends [L] (coordinates up to 1e150: their squares are summed).

    Returns
    -------
    numpy.ndarray
        The distances [L] (the closest point at the clamped projection ``t in [0, 1]``).
    """
    return np.sqrt(_point_segment_sq(px, py, x0, y0, x1, y1))


def segment_distance(ax0, ay0, ax1, ay1, bx0, by0, bx1, by1):
    """Exact distance [L] between the segments ``a0 -> a1`` and ``b0 -> b1``, vectorised
    (every argument broadcast).

    Two segments that cross (each one's ends strictly on both sides of the other's
    line) are at distance 0; otherwise the distance of two segments in the plane is
    attained at an end of one of them, so it is the smallest of the four
    end-to-segment distances (:func:`point_segment_distance`; touching and collinear
    overlapping segments give 0 there).

    Parameters
    ----------
    ax0, ay0, ax1, ay1, bx0, by0, bx1, by1 : array_like
        The ends [L]; NaN propagates.

    Returns
    -------
    numpy.ndarray
        The distances [L], >= 0.
    """
    d2 = np.minimum(np.minimum(_point_segment_sq(ax0, ay0, bx0, by0, bx1, by1),
                               _point_segment_sq(ax1, ay1, bx0, by0, bx1, by1)),
                    np.minimum(_point_segment_sq(bx0, by0, ax0, ay0, ax1, ay1),
                               _point_segment_sq(bx1, by1, ax0, ay0, ax1, ay1)))

    def side(x0, y0, x1, y1, px, py):  # the sign of the orientation of (p0, p1, p)
        return np.sign((x1 - x0) * (py - y0) - (y1 - y0) * (px - x0))

    cross = ((side(ax0, ay0, ax1, ay1, bx0, by0) * side(ax0, ay0, ax1, ay1, bx1, by1) < 0)
             & (side(bx0, by0, bx1, by1, ax0, ay0) * side(bx0, by0, bx1, by1, ax1, ay1) < 0))
    return np.where(cross, 0.0, np.sqrt(d2))


def _capsule_clearance(a, b):
    """Clearance [L] of two bodies' capsules at every pose."""
    return segment_distance(a.x0, a.y0, a.x1, a.y1, b.x0, b.y0, b.x1, b.y1) - 0.5 * (a.width + b.width)


# ----------------------------------------------------------------------- zones
@dataclass(frozen=True, eq=False)
class Zone:
    """A keep-out zone (module docstring): ``kind`` one of :data:`ZONE_KINDS`.

    ``vertices`` (polygon, ``(n, 2)``, any orientation, simple), ``center`` and ``radius``
    (disc), ``level`` (``above``: the zone ``y >= level``; ``below``: ``y <= level``) [L];
    ``spares_tool``: the bodies carrying the tool (:data:`mechopt.core.bodies.TOOL_KINDS`)
    may enter it (the task as a zone); ``label``: how it was given.

    Parameters
    ----------
    kind : str
        One of :data:`ZONE_KINDS`.
    vertices : ndarray, optional
        A polygon's vertices [L], shape ``(n, 2)``.
    center : tuple of float, optional
        A disc's centre [L].
    radius : float, optional
        A disc's radius [L].
    level : float, optional
        The line of ``above``/``below`` [L].
    spares_tool : bool
        Whether the tool-carrying bodies may enter it.
    label : str
        For messages.
    """

    kind: str
    vertices: np.ndarray | None = None
    center: tuple | None = None
    radius: float | None = None
    level: float | None = None
    spares_tool: bool = False
    label: str = ""

    @classmethod
    def from_task(cls, task) -> "Zone":
        """The task region of :class:`mechopt.analysis.task.Task` as a zone that spares
        the tool-carrying bodies (a rectangle or polygon: its polygon; a circle: its disc).

        Parameters
        ----------
        task : mechopt.analysis.task.Task
            A task region.

        Returns
        -------
        Zone
            The zone.

        Raises
        ------
        ValueError
            For a point task or path (no region).
        """
        if task.kind == "circle":
            return cls("disc", center=tuple(task.center), radius=float(task.radius), spares_tool=True,
                       label="task")
        if task.kind == "points":
            raise ValueError("--keep-out task needs a task region (rect, circle or polygon), got a point task")
        return cls("polygon", vertices=np.asarray(task.vertices, float), spares_tool=True, label="task")

    def outline(self, box, n: int = 128):
        """The zone's outline for drawing, closed: a polygon's vertices, a disc's circle of
        ``n`` points, a half-plane's part of ``box = (x0, x1, y0, y1)`` [L] (the view; an
        empty outline when the zone misses it).

        Parameters
        ----------
        box : tuple of float
            The view ``(x0, x1, y0, y1)`` [L]; used for a half-plane only.
        n : int
            Points on a disc's circle (n + 1 with the first repeated).

        Returns
        -------
        tuple of numpy.ndarray
            ``(x, y)`` [L], the first point repeated at the end.
        """
        if self.kind == "polygon":
            v = np.asarray(self.vertices, float)
            return np.r_[v[:, 0], v[:1, 0]], np.r_[v[:, 1], v[:1, 1]]
        if self.kind == "disc":
            t = np.linspace(0.0, 2.0 * math.pi, int(n) + 1)
            return self.center[0] + self.radius * np.cos(t), self.center[1] + self.radius * np.sin(t)
        x0, x1, y0, y1 = (float(b) for b in box)
        lo, hi = (max(self.level, y0), y1) if self.kind == "above" else (y0, min(self.level, y1))
        if lo >= hi:
            return np.zeros(0), np.zeros(0)
        return np.array([x0, x1, x1, x0, x0]), np.array([lo, lo, hi, hi, lo])

    def margin(self, x0, y0, x1, y1):
        """``min over the segment of phi`` [L]: the signed distance of the segments
        ``(x0, y0) -> (x1, y1)`` to the zone, positive outside (module docstring).

        Parameters
        ----------
        x0, y0, x1, y1 : ndarray
            Segment ends [L].

        Returns
        -------
        ndarray
            The signed distance [L], positive outside.
        """
        if self.kind == "above":
            return self.level - np.maximum(y0, y1)
        if self.kind == "below":
            return np.minimum(y0, y1) - self.level
        if self.kind == "disc":
            cx, cy = self.center
            return point_segment_distance(cx, cy, x0, y0, x1, y1) - self.radius
        v = self.vertices
        x0, y0, x1, y1 = np.broadcast_arrays(*(np.asarray(c, float) for c in (x0, y0, x1, y1)))
        # the edges along a new first axis, broadcast against the segments
        shape = (len(v),) + (1,) * x0.ndim
        vx, vy = v[:, 0].reshape(shape), v[:, 1].reshape(shape)
        w = np.roll(v, -1, 0)
        wx, wy = w[:, 0].reshape(shape), w[:, 1].reshape(shape)
        d = segment_distance(x0, y0, x1, y1, vx, vy, wx, wy).min(axis=0)  # the axis to the boundary
        deepest, entered = 0.0, False
        for px, py in ((x0, y0), (x1, y1)):
            e = np.sqrt(_point_segment_sq(px, py, vx, vy, wx, wy).min(axis=0))  # this end to the boundary
            inside = _inside(v, px, py)
            deepest = np.maximum(deepest, np.where(inside, e, 0.0))
            entered = entered | inside
        return np.where(entered, -deepest, d)


def _inside(v, x, y):
    """Points strictly inside the simple polygon ``v`` (even-odd rule)."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    inside = np.zeros(np.broadcast(x, y).shape, bool)
    for (vx, vy), (wx, wy) in zip(v, np.roll(v, -1, 0)):
        with np.errstate(divide="ignore", invalid="ignore"):
            inside ^= ((vy > y) != (wy > y)) & (x < (wx - vx) * (y - vy) / (wy - vy) + vx)
    return inside


def parse_zone(text: str, task=None) -> Zone:
    """A zone from the CLI syntax: ``task`` (the task region of ``task``, sparing the
    tool), ``polygon:x1,y1;x2,y2;x3,y3;...`` [L], ``above:Y`` (the zone ``y >= Y``) or
    ``below:Y`` (``y <= Y``).

    Parameters
    ----------
    text : str
        The zone.
    task : mechopt.analysis.task.Task, optional
        The task, for ``task``.

    Returns
    -------
    Zone

    Raises
    ------
    ValueError
        One line, for a malformed zone, or ``task`` without a task region.
    """
    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"--keep-out must be task, polygon:x1,y1;x2,y2;..., above:Y or below:Y, got {_v.show(text)}")
    kind, _, body = text.strip().partition(":")
    kind = kind.strip().lower()
    if kind == "task" and not body:
        if task is None:
            raise ValueError("--keep-out task needs a task")
        return Zone.from_task(task)
    if kind in ("above", "below"):
        try:
            level = float(body)
        except ValueError:
            raise ValueError(f"--keep-out {kind}:Y needs one number Y, got {body!r}") from None
        if not math.isfinite(level):
            raise ValueError(f"--keep-out {kind}:Y must be finite, got {body!r}")
        return Zone(kind, level=level, label=text.strip())
    if kind == "polygon":
        from mechopt.analysis.task import Task  # the polygon checks (simple, positive area)

        try:
            pts = [[float(c) for c in p.split(",")] for p in body.split(";") if p.strip()]
        except ValueError:
            raise ValueError(f"--keep-out polygon vertices must be numbers x,y;x,y;..., got {body!r}") from None
        if not pts or any(len(p) != 2 for p in pts):
            raise ValueError(f"--keep-out polygon vertices must be x,y pairs separated by ';', got {body!r}")
        try:
            poly = Task.polygon(pts)
        except ValueError as exc:
            raise ValueError(f"--keep-out {exc}") from None
        return Zone("polygon", vertices=poly.vertices, label=text.strip())
    raise ValueError(f"--keep-out must be task, polygon:x1,y1;x2,y2;..., above:Y or below:Y, got {text!r}")


# ----------------------------------------------------------------------- a mechanism's bodies
class Collisions:
    """The capsule checks of one mechanism (module docstring).

    Parameters
    ----------
    spec : mechopt.core.design_spec.DesignSpec
        The mechanism's design spec (its :meth:`links` and :meth:`joint_speeds`).
    mech : mechopt.core.protocol.PlanarMechanism
        The mechanism, built by ``spec``.
    shapes : mechopt.core.bodies.Shapes, optional
        The sizes [L]; default :meth:`Shapes.default() <mechopt.core.bodies.Shapes.default>` (mm).
    ignore : iterable of (str, str), optional
        Pairs of body names not to check (e.g. two links in different planes).

    Raises
    ------
    ValueError
        One line, when the spec names two bodies alike or ``ignore`` names no body.
    """

    def __init__(self, spec, mech, shapes: Shapes | None = None, ignore=()):
        self.spec, self.mech = spec, mech
        self.shapes = shapes or Shapes.default()
        # the bodies at one pose: their names, kinds, joints and the fixed ones (the
        # pose may be out of reach: only the fixed bodies' ends are read from it)
        self._ref = ref = spec.links(mech, np.zeros(1), np.zeros(1), self.shapes)
        self.names = tuple(b.name for b in ref)
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"{type(spec).__name__}.links names two bodies alike: {self.names}")
        index = {n: i for i, n in enumerate(self.names)}
        skip = set()
        for pair in ignore:
            a, b = pair
            for n in (a, b):
                if n not in index:
                    raise ValueError(f"ignore names no body of {spec.name}: {n!r} (bodies: {', '.join(self.names)})")
            skip |= {(a, b), (b, a)}
        self.pairs, self.adjacent, self.ground_pairs = [], [], []
        for i, a in enumerate(ref):
            for j in range(i + 1, len(ref)):
                b = ref[j]
                common = [J for J in a.joints if J in b.joints]
                if common:
                    J = common[0]
                    if (a.kind in _LINK_KINDS and b.kind in _LINK_KINDS and J in a.ends and J in b.ends):
                        self.adjacent.append((i, j, J))
                elif a.ground and b.ground:
                    self.ground_pairs.append((i, j))
                elif (a.name, b.name) not in skip:
                    self.pairs.append((i, j))
        self._pair_index = (np.array([i for i, _ in self.pairs], int), np.array([j for _, j in self.pairs], int))

    # --- the bodies ------------------------------------------------------------------
    def bodies(self, x, y):
        """The bodies at task points ``(x, y)`` (:meth:`DesignSpec.links`).

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].

        Returns
        -------
        list of mechopt.core.bodies.Body
            The capsules.
        """
        return self.spec.links(self.mech, x, y, self.shapes)

    def pair_names(self):
        """``[(name_a, name_b), ...]`` of the checked pairs, in the rows' order.

        Returns
        -------
        list of tuple
            ``(name_a, name_b)``.
        """
        return [(self.names[i], self.names[j]) for i, j in self.pairs]

    def angle_names(self):
        """``[(name_a, name_b, joint), ...]`` of the adjacent links, in the rows' order.

        Returns
        -------
        list of tuple
            ``(name_a, name_b, joint)``.
        """
        return [(self.names[i], self.names[j], J) for i, j, J in self.adjacent]

    # --- per pose -----------------------------------------------------------------
    def pair_clearances(self, x, y, bodies=None):
        """Capsule clearance [L] of every checked pair: shape ``(n_pairs, n_poses)``
        (NaN where the pose is out of reach).

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        bodies : list, optional
            The bodies at the poses (default: :meth:`bodies`).

        Returns
        -------
        ndarray
            [L].
        """
        b = bodies if bodies is not None else self.bodies(x, y)
        if not self.pairs:
            return np.full((0, *np.shape(b[0].x0)), np.inf)
        # every pair at once: the ends stacked by body, then taken by pair
        ends = np.stack([np.stack([k.x0, k.y0, k.x1, k.y1]) for k in b], axis=1)  # (4, bodies, ...)
        w = np.array([k.width for k in b])
        i, j = self._pair_index
        pa, pb = ends[:, i], ends[:, j]
        half = (0.5 * (w[i] + w[j])).reshape((-1,) + (1,) * (pa.ndim - 2))
        return segment_distance(*pa, *pb) - half

    def clearance(self, x, y):
        """The smallest capsule clearance [L] over the checked pairs at each pose
        (``inf`` with no pair; NaN where out of reach).

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].

        Returns
        -------
        ndarray
            [L] per pose.
        """
        c = self.pair_clearances(x, y)
        return np.min(c, axis=0) if len(c) else c.reshape(c.shape[1:])

    def joint_angles(self, x, y, bodies=None):
        """The angle [rad, in ``[0, pi]``] between adjacent links at their common joint:
        shape ``(n_adjacent, n_poses)``, rows as :meth:`angle_names`.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        bodies : list, optional
            The bodies at the poses (default: :meth:`bodies`).

        Returns
        -------
        ndarray
            [rad].
        """
        b = bodies if bodies is not None else self.bodies(x, y)
        rows = []
        for i, j, J in self.adjacent:
            (ux, uy), (vx, vy) = (self._away(b[k], J) for k in (i, j))
            rows.append(np.arctan2(np.abs(ux * vy - uy * vx), ux * vx + uy * vy))
        return np.stack(rows) if rows else np.zeros((0, *np.shape(b[0].x0)))

    @staticmethod
    def _away(body, J):
        """The vector from the joint ``J`` (one of ``body``'s ends) to its other end."""
        if body.ends[0] == J:
            return body.x1 - body.x0, body.y1 - body.y0
        return body.x0 - body.x1, body.y0 - body.y1

    def keep_out(self, x, y, zone: Zone, bodies=None):
        """The margin [L] of each body to ``zone`` (:meth:`Zone.margin` minus half its
        width): shape ``(n_bodies, n_poses)``, rows as :meth:`zone_bodies`.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        zone : Zone
            The keep-out zone.
        bodies : list, optional
            The bodies at the poses (default: :meth:`bodies`).

        Returns
        -------
        ndarray
            [L].
        """
        b = self._zone_bodies(bodies if bodies is not None else self.bodies(x, y), zone)
        ends = [np.stack([getattr(k, c) for k in b]) for c in ("x0", "y0", "x1", "y1")]  # (bodies, poses)
        half = 0.5 * np.array([k.width for k in b]).reshape((-1,) + (1,) * (ends[0].ndim - 1))
        return zone.margin(*ends) - half

    def _zone_bodies(self, bodies, zone):
        return [k for k in bodies if not (zone.spares_tool and k.kind in TOOL_KINDS)]

    def zone_bodies(self, zone):
        """Names of the bodies :meth:`keep_out` measures (all but the tool-carrying ones
        for a zone that spares them).

        Parameters
        ----------
        zone : Zone
            The keep-out zone.

        Returns
        -------
        list of str
            The names.
        """
        return [b.name for b in self._zone_bodies(self._ref, zone)]

    # --- the base -----------------------------------------------------------------
    def base_margin(self) -> float:
        """The smallest clearance [L] between two fixed bodies that carry no common
        joint (the five-bar's housings: ``2 r3 - d``; ``inf`` with fewer than two).

        Returns
        -------
        float
            [L].
        """
        b = self._ref
        vals = [float(_capsule_clearance(b[i], b[j])[0]) for i, j in self.ground_pairs]
        return min(vals, default=math.inf)

    def base_distance(self) -> float:
        """The smallest distance [L] between the axes of two fixed bodies (the five-bar's
        base distance ``2 r3``, the Biglide's guide distance ``2 l1``).

        Returns
        -------
        float
            [L].
        """
        b = self._ref
        vals = [float(_capsule_clearance(b[i], b[j])[0] + 0.5 * (b[i].width + b[j].width))
                for i, j in self.ground_pairs]
        return min(vals, default=math.inf)

    # --- speeds, Lipschitz constants --------------------------------------------------
    def _end_speeds(self, x, y, radius):
        sp = self.spec.joint_speeds(self.mech, x, y, radius)
        zero = np.zeros(np.broadcast(np.asarray(x), np.asarray(y)).shape)

        def speed(name):
            if name == GROUND:
                return zero
            if name not in sp:
                raise ValueError(f"{type(self.spec).__name__}.joint_speeds gives no speed of {name!r}")
            return np.asarray(sp[name], float)
        return speed

    def body_speeds(self, x, y, radius=0.0):
        """Upper bound of each body's displacement per unit platform displacement
        [L/L] within ``radius`` [L] of each pose: the larger of its ends' joint speeds,
        shape ``(n_bodies, n_poses)``.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        radius : float
            Radius [L] of the platform positions about each pose.

        Returns
        -------
        ndarray
            [L/L], shape ``(n_bodies, n_poses)``.
        """
        speed = self._end_speeds(x, y, radius)
        return np.stack([np.maximum(speed(k.ends[0]), speed(k.ends[1])) for k in self._ref])

    def clearance_lipschitz(self, x, y, radius=0.0):
        """``k_a + k_b`` of every checked pair (:meth:`body_speeds`): the clearance of
        the pair changes by at most this times the platform's displacement within
        ``radius`` of each pose, shape ``(n_pairs, n_poses)``.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        radius : float
            Radius [L] of the platform positions about each pose.

        Returns
        -------
        ndarray
            [L/L], shape ``(n_pairs, n_poses)``.
        """
        k = self.body_speeds(x, y, radius)
        n = k.shape[1:]
        return np.stack([k[i] + k[j] for i, j in self.pairs]) if self.pairs else np.zeros((0, *n))

    def angle_lipschitz(self, x, y, radius=0.0, bodies=None):
        """Bound of the rate [rad/L] of each joint angle within ``radius`` of each pose:
        ``sum over its two links of (k_E + k_J) / r_min`` (module docstring), ``r_min``
        the link's axis length less its largest change (``inf`` if it may vanish).

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        radius : float
            Radius [L] of the platform positions about each pose.
        bodies : list, optional
            The bodies at the poses (default: :meth:`bodies`).

        Returns
        -------
        ndarray
            [rad/L], shape ``(n_adjacent, n_poses)``.
        """
        speed = self._end_speeds(x, y, radius)
        b = bodies if bodies is not None else self.bodies(x, y)
        rows = []
        for i, j, J in self.adjacent:
            total = 0.0
            for k in (b[i], b[j]):
                kJ = speed(J)
                kE = speed(k.ends[1] if k.ends[0] == J else k.ends[0])
                r = np.hypot(k.x1 - k.x0, k.y1 - k.y0) - (kE + kJ) * radius
                with np.errstate(divide="ignore", invalid="ignore"):
                    total = total + np.where(r > 0, (kE + kJ) / np.where(r > 0, r, 1.0), np.inf)
            rows.append(total)
        return np.stack(rows) if rows else np.zeros((0, *np.shape(b[0].x0)))

    def keep_out_lipschitz(self, x, y, zone: Zone, radius=0.0):
        """Each measured body's speed bound (:meth:`body_speeds`, rows of :meth:`keep_out`):
        ``phi`` is 1-Lipschitz, so a body's margin changes no faster than the body moves.

        Parameters
        ----------
        x, y : array_like
            Task points [L, task frame].
        zone : Zone
            The keep-out zone.
        radius : float
            Radius [L] of the platform positions about each pose.

        Returns
        -------
        ndarray
            [L/L], rows of :meth:`keep_out`.
        """
        k = self.body_speeds(x, y, radius)
        keep = [not (zone.spares_tool and b.kind in TOOL_KINDS) for b in self._ref]
        return k[np.array(keep)]

    # --- over a task ------------------------------------------------------------------
    def certified_minimum(self, task, what="clearance", zone: Zone | None = None,
                          n_boundary: int = 192, n_interior: int = 13) -> dict:
        """The minimum over ``task`` of the clearance (``what="clearance"``), of the
        joint angles (``"angles"``) or of the margin to ``zone`` (``"keep_out"``), from
        the samples of :func:`task_samples` (module docstring).

        Returns
        -------
        dict
            ``sampled`` (the smallest sampled value), ``bound`` (certified: no point of the
            task has less, :func:`lipschitz_bound`), ``radius`` (the covering radius [L]),
            ``where`` (the sample ``(x, y)`` of the smallest value) and ``which`` (the pair,
            joint or body there).

        Parameters
        ----------
        task : mechopt.analysis.task.Task
            The placed task.
        what : str
            ``"clearance"``, ``"angles"`` or ``"keep_out"``.
        zone : Zone, optional
            The zone of ``"keep_out"``.
        n_boundary, n_interior : int
            Sample counts (:func:`task_samples`).

        Raises
        ------
        ValueError
            For an unknown ``what``, or ``"keep_out"`` without a zone.
        """
        x, y, radius = task_samples(task, n_boundary, n_interior)
        b = self.bodies(x, y)
        if what == "clearance":
            vals, L, names = self.pair_clearances(x, y, b), self.clearance_lipschitz(x, y, radius), self.pair_names()
        elif what == "angles":
            vals, L, names = self.joint_angles(x, y, b), self.angle_lipschitz(x, y, radius, b), self.angle_names()
        elif what == "keep_out":
            if zone is None:
                raise ValueError("what='keep_out' needs a zone")
            vals, L, names = (self.keep_out(x, y, zone, b), self.keep_out_lipschitz(x, y, zone, radius),
                              self.zone_bodies(zone))
        else:
            raise ValueError(f"what must be 'clearance', 'angles' or 'keep_out', got {what!r}")
        if vals.size == 0:
            return dict(sampled=math.inf, bound=math.inf, radius=radius, where=None, which=None)
        filled = np.where(np.isnan(vals), -np.inf, vals)
        r, c = np.unravel_index(int(np.argmin(filled)), filled.shape)
        return dict(sampled=float(filled[r, c]), bound=lipschitz_bound(vals, L, radius), radius=radius,
                    where=(float(x[c]), float(y[c])), which=names[r])


# ----------------------------------------------------------------------- samples, bounds
def covering_radius(task, n_boundary: int = 192, n_interior: int = 13) -> float:
    """Every point of ``task`` joins one of the samples of :func:`task_samples` by a path
    inside the task no longer than this [L] (module docstring): ``delta + kappa h_b / 2``,
    ``delta`` the half diagonal of a grid cell, ``h_b`` the largest boundary gap; 0 for a point task (its points are its samples).

    Parameters
    ----------
    task : mechopt.analysis.task.Task
    n_boundary, n_interior : int
        The sample counts (:class:`mechopt.analysis.task.Sampling`).

    Returns
    -------
    float

    Raises
    ------
    ValueError
        For fewer than 2 interior nodes per side, or invalid counts.
    """
    if not task.is_region:
        return 0.0
    if int(n_interior) < 2:
        raise ValueError(f"n_interior must be at least 2, got {n_interior!r}")
    tb, gap = task.boundary_params(n_boundary)
    x0, x1, y0, y1 = task.bbox
    return covering_radius_of(task, gap, tb.size, max(x1 - x0, y1 - y0) / (n_interior - 1))


def covering_radius_of(task, gap, n_boundary, step) -> float:
    """:func:`covering_radius` from the samples' figures: the largest boundary ``gap``
    [L], the number of boundary samples and the interior grid's ``step`` [L] (the larger
    cell side, :meth:`mechopt.analysis.task.Task.grid`); 0 for a point task.

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The task.
    gap : float
        The largest boundary gap [L].
    n_boundary : int
        Boundary samples.
    step : float
        The interior grid's step [L].

    Returns
    -------
    float
        [L].
    """
    if not task.is_region:
        return 0.0
    x0, x1, y0, y1 = task.bbox
    # the cell's half diagonal: sides (x1 - x0) / (n - 1) and (y1 - y0) / (n - 1), the larger = step
    half_diagonal = 0.5 * step * math.hypot(x1 - x0, y1 - y0) / max(x1 - x0, y1 - y0)
    kappa = 1.0
    if task.kind == "circle":  # the arc between two samples over its chord
        a = math.pi / n_boundary
        kappa = a / math.sin(a)
    return half_diagonal + kappa * 0.5 * gap


def task_samples(task, n_boundary: int = 192, n_interior: int = 13):
    """``(x, y, radius)``: the samples of one design evaluation of ``task`` (boundary
    points, then the interior grid kept inside, as :mod:`mechopt.analysis.task` takes
    them) and their :func:`covering_radius` [L].

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The placed task.
    n_boundary, n_interior : int
        Sample counts.

    Returns
    -------
    x, y : ndarray
        The samples [L].
    radius : float
        Their covering radius [L].
    """
    if not task.is_region:
        return task.pts[:, 0].copy(), task.pts[:, 1].copy(), 0.0
    tb, _ = task.boundary_params(n_boundary)
    bx, by = task.boundary_at(tb)
    ix, iy, _ = task.grid(n_interior)
    return np.concatenate([bx, ix]), np.concatenate([by, iy]), covering_radius(task, n_boundary, n_interior)


def lipschitz_bound(values, lipschitz, radius) -> float:
    """``min(values - lipschitz * radius)``: a lower bound of a function over a region
    from its values at samples, when every point of the region joins a sample by a path
    no longer than ``radius`` [L] along which the function changes no faster than
    ``lipschitz`` (per sample, or one constant). NaN values (a pose out of reach) and an
    unbounded rate with ``radius > 0`` give ``-inf``.

    Parameters
    ----------
    values : array_like
        The sampled values.
    lipschitz : array_like
        Rates [value / L], broadcast to ``values``.
    radius : float
        The covering radius [L], >= 0.

    Returns
    -------
    float
    """
    v = np.asarray(values, float)
    if v.size == 0:
        return math.inf
    if radius == 0:
        lo = v
    else:
        with np.errstate(invalid="ignore"):
            lo = v - np.asarray(lipschitz, float) * radius
    lo = np.where(np.isnan(lo), -np.inf, lo)
    return float(np.min(lo))
