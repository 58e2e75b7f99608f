"""The kinematic tree of a planar closed-loop mechanism, as exporters write it.

A mechanism offers itself to ``mechopt export`` (:mod:`mechopt.export`: URDF, MJCF,
DXF, SVG, the path CSV and animation) by declaring, in its own module,

* ``kinematic_tree() -> KinematicTree``: its bodies and joints as a tree, with the
  loop cut at the platform joint (this module's classes), and
* ``tree_configuration(x, y) -> dict``: the value of every joint of that tree [rad or
  L] with the platform at the points ``(x, y)`` of its own frame (vectorised; NaN out
  of reach), from its own inverse kinematics and elbow positions,

so a new mechanism is exported without an edit in the export package.

Conventions (the same for every mechanism; the writers rely on them):

* Lengths in the mechanism's length unit [L], angles in rad. The mechanism's plane
  is the x-y plane; every revolute axis is z, every prismatic axis lies in the plane.
* The ground body is ``"base"`` (the mechanism's own frame). Every other body has one
  parent joint, and its frame is that joint's frame: origin on the joint, at
  ``origin`` in the parent's frame; a revolute joint turns it by the joint value
  ``q`` [rad] about z, a prismatic joint shifts it by ``q`` [L] along ``axis`` (a
  unit vector of the parent's frame). At ``q = 0`` the body's axes are the parent's.
  A link's pins lie on its x axis: the link from its joint at ``(0, 0)`` to its far
  pin at ``(length, 0)``.
* Joint names: the actuated joints carry the mechanism's actuator names
  (``joint_names``: ``theta1``, ``theta2`` for cranks, ``q1``, ``q2`` for sliders and
  struts), leg 1 first; passive joints are named by their role and leg
  (``elbow1``, ``pivot2``, ``base1``, ...).
* The loop is cut at the platform joint. The last body of each leg carries a
  closure frame at the platform point: ``closedloop1_A`` on leg 1, ``closedloop1_B``
  on leg 2 (the naming of Gepetto's example-parallel-robots: loop 1, sides A and B).
  The loop is closed by a point constraint between them (their origins coincide; the
  rotation about z stays free: the platform pin); ``closedloop1_A`` is the platform
  point ``P`` the mechanism reports.

:meth:`KinematicTree.forward` is the planar forward kinematics of such a tree
(NumPy, vectorised), which the drawings use; the exported models are checked against
Pinocchio and MuJoCo (``tests/test_export.py``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

__all__ = ["TreeJoint", "ClosureFrame", "KinematicTree", "BASE", "CLOSURE_NAMES", "JOINT_KINDS"]

#: the ground body's name
BASE = "base"
#: the closure frames of legs 1 and 2 (Gepetto's example-parallel-robots naming)
CLOSURE_NAMES = ("closedloop1_A", "closedloop1_B")
JOINT_KINDS = ("revolute", "prismatic")


@dataclass(frozen=True)
class TreeJoint:
    """One joint of a :class:`KinematicTree` (module docstring: frames and names).

    Parameters
    ----------
    name : str
        Joint name (actuated: the mechanism's actuator name).
    kind : {"revolute", "prismatic"}
        Revolute about z, or prismatic along ``axis``.
    parent, child : str
        Body names; ``parent`` is ``"base"`` or the child of an earlier joint.
    origin : tuple of float
        Joint position ``(x, y)`` in the parent's frame [L].
    axis : tuple of float
        Prismatic direction ``(ux, uy)`` in the parent's frame (unit); ignored for
        revolute joints.
    actuated : bool
        True for a motor (crank, slider, strut).
    limits : tuple of float or None
        ``(lower, upper)`` [rad or L], or None (unlimited).
    """

    name: str
    kind: str
    parent: str
    child: str
    origin: tuple = (0.0, 0.0)
    axis: tuple = (0.0, 0.0)
    actuated: bool = False
    limits: tuple | None = None


@dataclass(frozen=True)
class ClosureFrame:
    """A closure frame: the platform point ``point`` [L] in the frame of ``body``.

    Parameters
    ----------
    name : str
        The closure's name.
    body : str
        The body it is fixed in.
    point : tuple of float
        The platform point in that body's frame [L].
    """

    name: str
    body: str
    point: tuple


@dataclass(frozen=True)
class KinematicTree:
    """Bodies and joints of a mechanism cut open at its platform joint (module docstring).

    ``joints`` are in tree order (a body's parent joint before the joints it carries);
    ``closure`` holds the two :class:`ClosureFrame` (leg 1, leg 2); ``name`` is the
    mechanism's ``cli_name``. The constructor checks the structure (ValueError, one line).

    Parameters
    ----------
    name : str
        The mechanism's name.
    joints : tuple of TreeJoint
        The joints in tree order.
    closure : tuple of ClosureFrame
        The two closure frames.
    """

    name: str
    joints: tuple
    closure: tuple

    def __post_init__(self):
        seen = {BASE}
        names = set()
        for j in self.joints:
            if j.kind not in JOINT_KINDS:
                raise ValueError(f"joint {j.name!r}: kind must be one of {JOINT_KINDS}, got {j.kind!r}")
            if j.name in names or j.child in seen:
                raise ValueError(f"joint {j.name!r}: joint and body names must be unique")
            if j.parent not in seen:
                raise ValueError(f"joint {j.name!r}: parent {j.parent!r} is not an earlier body")
            if not all(math.isfinite(v) for v in (*j.origin, *j.axis)):
                raise ValueError(f"joint {j.name!r}: origin and axis must be finite")
            if j.kind == "prismatic" and abs(math.hypot(*j.axis) - 1.0) > 1e-12:
                raise ValueError(f"joint {j.name!r}: a prismatic axis must be a unit vector")
            if j.limits is not None and not (j.limits[0] < j.limits[1]):
                raise ValueError(f"joint {j.name!r}: limits must be (lower, upper) with lower < upper")
            names.add(j.name)
            seen.add(j.child)
        if len(self.closure) != 2 or tuple(c.name for c in self.closure) != CLOSURE_NAMES:
            raise ValueError(f"the closure frames must be {CLOSURE_NAMES}")
        for c in self.closure:
            if c.body not in seen or c.body == BASE:
                raise ValueError(f"closure frame {c.name!r}: {c.body!r} is not a moving body")

    # --- what the writers read ----------------------------------------------------
    @property
    def bodies(self) -> tuple:
        """The moving bodies, in tree order (``"base"`` excluded)."""
        return tuple(j.child for j in self.joints)

    @property
    def actuated(self) -> tuple:
        """Names of the actuated joints, in tree order (leg 1's first)."""
        return tuple(j.name for j in self.joints if j.actuated)

    def joint(self, name) -> TreeJoint:
        """The joint named ``name``.

        Parameters
        ----------
        name : str
            A joint's name.

        Returns
        -------
        TreeJoint
            The joint.

        Raises
        ------
        ValueError
            One line, when the tree has no such joint.
        """
        for j in self.joints:
            if j.name == name:
                return j
        raise ValueError(f"{self.name} has no joint {name!r}")

    def pins(self) -> dict:
        """``{body: [(name, (x, y)), ...]}``: the revolute pins of every body (``"base"``
        included) in its own frame [L]: the revolute joints it carries (at their
        origins), its own revolute parent joint (at ``(0, 0)``) and its closure frame
        (the platform pin). A body with two or more pins is a rigid link of fixed pin
        distances (what the DXF drawings show).

        Returns
        -------
        dict
            ``{body: [(name, (x, y)), ...]}`` [L].
        """
        out = {b: [] for b in (BASE, *self.bodies)}
        for j in self.joints:
            if j.kind == "revolute":
                out[j.parent].append((j.name, tuple(j.origin)))
                out[j.child].append((j.name, (0.0, 0.0)))
        for c in self.closure:
            out[c.body].append((c.name, tuple(c.point)))
        return out

    # --- changes of frame and unit ----------------------------------------------------
    def shifted(self, dx, dy) -> "KinematicTree":
        """The same tree with the base frame moved: the joints on ``"base"`` at
        ``origin + (dx, dy)`` [L] (e.g. the mechanism placed in the task frame).

        Parameters
        ----------
        dx, dy : float
            The shift [L].

        Returns
        -------
        KinematicTree
            A new tree.
        """
        js = tuple(replace(j, origin=(j.origin[0] + dx, j.origin[1] + dy)) if j.parent == BASE else j
                   for j in self.joints)
        return replace(self, joints=js)

    def scaled(self, factor) -> "KinematicTree":
        """Every length multiplied by ``factor`` (e.g. mm -> m); prismatic limits too.

        Parameters
        ----------
        factor : float
            The factor, > 0.

        Returns
        -------
        KinematicTree
            A new tree.
        """
        f = float(factor)
        js = []
        for j in self.joints:
            lim = j.limits
            if lim is not None and j.kind == "prismatic":
                lim = (lim[0] * f, lim[1] * f)
            js.append(replace(j, origin=(j.origin[0] * f, j.origin[1] * f), limits=lim))
        cl = tuple(replace(c, point=(c.point[0] * f, c.point[1] * f)) for c in self.closure)
        return replace(self, joints=tuple(js), closure=cl)

    def with_limits(self, limits: dict) -> "KinematicTree":
        """The tree with the joints named in ``limits`` (``{name: (lo, hi)}``) limited so.

        Parameters
        ----------
        limits : dict
            ``{joint: (lo, hi)}`` [rad or L].

        Returns
        -------
        KinematicTree
            A new tree.
        """
        for n in limits:
            self.joint(n)
        js = tuple(replace(j, limits=tuple(map(float, limits[j.name]))) if j.name in limits else j
                   for j in self.joints)
        return replace(self, joints=js)

    # --- planar forward kinematics ------------------------------------------------------
    def forward(self, q: dict) -> dict:
        """Poses of every body frame for joint values ``q`` (``{joint name: array}``,
        broadcastable): ``{body: (x, y, angle)}`` arrays [L, L, rad] in the base frame,
        and ``{closure name: (x, y, angle)}`` for the closure frames.

        Parameters
        ----------
        q : dict
            ``{joint name: array}`` [rad or L].

        Returns
        -------
        dict
            ``{body or closure name: (x, y, angle)}`` [L, L, rad].
        """
        z = np.zeros(np.broadcast(*[np.asarray(v, float) for v in q.values()]).shape)
        pose = {BASE: (z, z, z)}
        for j in self.joints:
            px, py, pa = pose[j.parent]
            c, s = np.cos(pa), np.sin(pa)
            ox, oy = j.origin
            v = np.asarray(q[j.name], float)
            if j.kind == "prismatic":
                ox, oy = ox + v * j.axis[0], oy + v * j.axis[1]
                a = pa
            else:
                a = pa + v
            pose[j.child] = (px + c * ox - s * oy, py + s * ox + c * oy, a + z)
        for cf in self.closure:
            px, py, pa = pose[cf.body]
            c, s = np.cos(pa), np.sin(pa)
            pose[cf.name] = (px + c * cf.point[0] - s * cf.point[1], py + s * cf.point[0] + c * cf.point[1], pa)
        return pose
