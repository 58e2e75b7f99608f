"""Mass properties of the exported bodies: the dynamics' mass model on the export's tree.

The exported URDF and MJCF carry, on each body of the kinematic tree
(:mod:`mechopt.core.kinematic_tree`), the masses of the mechanism's mass model
(:func:`mechopt.analysis.dynamics.mass_model`: 20 x 20 x 2 mm aluminium tubes, 0.3 kg
carriages, a 0.2 kg payload point at the platform; or a mechanism's own table, Wu 2008 Table 2)
that ride on it (:func:`body_masses`):

* which tree body a mass body rides on: the tree body of the same name, else the one
  in whose frame its centre of mass stays fixed over three poses (the payload at the
  platform point rides on leg 1's last body; a carriage on its prismatic joint's body). A body fixed to
  the frame (a motor on the base) is left out: it does no work. The attachment of
  every body is checked on the three poses (to 1e-9 of the mechanism's size); a body
  riding on none (counterweights that move against the actuated joints through
  a cable the tree does not hold) is left out and named in the result, so that
  ``export.json`` says which masses the simulators do not see;
* the centre of mass in the tree body's frame: its position from
  :func:`mechopt.analysis.dynamics.body_centres` carried into that frame (the frames
  from the joints' values, :func:`tree_frames`);
* bodies riding on one tree body combine: mass summed, centre of mass the mean
  weighted by mass, inertia about it ``Izz = sum(I_k + m_k |c_k - c|^2)`` (parallel
  axes). The mechanism is planar: only ``Izz`` (about the joint axes, z) acts; the
  other two principal moments are written ``Ixx = Iyy = Izz / 2`` (a lamina in the
  plane, the perpendicular-axis theorem), so the triangle inequality MuJoCo checks
  holds. Every moving tree body gets at least :data:`MIN_MASS` kg and
  :data:`MIN_INERTIA` kg m^2 (simulators refuse a massless moving body): a body with
  no mass of its own adds at most that much.

:func:`link_width` (the DXF capsule and the simulators' geom size) is geometry only.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core.kinematic_tree import BASE

__all__ = ["body_masses", "tree_frames", "link_width", "WIDTH_RATIO", "MIN_MASS", "MIN_INERTIA"]

#: link width (the DXF capsule and the simulators' geom diameter) as a fraction of the
#: mechanism's longest pin distance
WIDTH_RATIO = 0.1
#: the smallest mass [kg] and moment [kg m^2] written on a moving body
MIN_MASS = 1e-6
MIN_INERTIA = 1e-9


def link_width(tree) -> float:
    """Width of every link [L]: :data:`WIDTH_RATIO` times the longest distance between
    two pins of one body of ``tree`` (e.g. 18.4 mm for a mechanism whose longest link
    is 184 mm).

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.

    Returns
    -------
    float
        The width [L].
    """
    longest = 0.0
    for pins in tree.pins().values():
        for i, (_, a) in enumerate(pins):
            for _, b in pins[i + 1:]:
                longest = max(longest, math.hypot(a[0] - b[0], a[1] - b[1]))
    return WIDTH_RATIO * longest if longest > 0 else 1.0


def tree_frames(tree, config) -> dict:
    """``{body: (origin (..., 2), angle (...))}`` of every body of ``tree`` (the base
    at the origin, angle 0) for the joints' values ``config`` (rad, or the tree's length
    unit for prismatic joints): a joint's frame is its parent's moved by the joint's
    ``origin``, then turned by ``q`` about z (revolute) or moved by ``q axis``
    (prismatic), as URDF reads it.

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    config : dict
        ``{joint: value}`` of every joint of ``tree``: [rad] (revolute) or the tree's
        length unit (prismatic), arrays of one shape.

    Returns
    -------
    dict
        ``{body: (origin, angle)}``: the frame's origin, shape ``(..., 2)`` [the tree's
        length unit], and its angle, shape ``(...)`` [rad].

    Raises
    ------
    ValueError
        When some joints hang from no body the walk from the base reaches.
    """
    shape = np.shape(next(iter(config.values()))) if config else ()
    frames = {BASE: (np.zeros(shape + (2,)), np.zeros(shape))}
    pending = list(tree.joints)
    while pending:
        j = next((j for j in pending if j.parent in frames), None)
        if j is None:
            raise ValueError(f"tree {tree.name!r}: joints {[k.name for k in pending]} hang from no placed body")
        pending.remove(j)
        o, a = frames[j.parent]
        q = np.asarray(config[j.name], float)
        local = np.asarray(j.origin, float) + (q[..., None] * np.asarray(j.axis, float)
                                               if j.kind == "prismatic" else 0.0)
        c, s = np.cos(a), np.sin(a)
        origin = o + np.stack([c * local[..., 0] - s * local[..., 1], s * local[..., 0] + c * local[..., 1]], -1)
        frames[j.child] = (origin, a + q if j.kind == "revolute" else a + 0.0 * q)
    return frames


def _local(frame, point):
    """``point`` (..., 2) in the frame ``(origin, angle)``."""
    o, a = frame
    d = point - o
    c, s = np.cos(a), np.sin(a)
    return np.stack([c * d[..., 0] + s * d[..., 1], -s * d[..., 0] + c * d[..., 1]], -1)


def body_masses(mech, x, y, length_unit: float, model=None) -> tuple:
    """``({tree body: (mass [kg], com (x, y, 0) [m], (Ixx, Iyy, Izz) [kg m^2])}, omitted)``
    for every moving body of ``mech.kinematic_tree()``, and the names of the mass
    model's bodies that ride on no body of the tree (module docstring).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism (lengths [L]) with ``bodies()`` and ``kinematic_tree()``.
    x, y : array_like, shape (3,)
        Three reachable platform points in the mechanism's frame [L], not all on one
        line (the attachment test).
    length_unit : float
        Metres per [L].
    model : MassModel, optional
        Default :func:`mechopt.analysis.dynamics.mass_model` of ``mech``.

    Returns
    -------
    tuple
        ``(dict, tuple of str)``.

    Raises
    ------
    ValueError
        When the poses ``x, y`` leave a mass body's centre undefined (out of reach).
    """
    from mechopt.analysis import dynamics as dyn

    model = model or dyn.mass_model(mech, length_unit=length_unit)
    x, y = np.asarray(x, float), np.asarray(y, float)
    tree = mech.kinematic_tree()
    cfg = {j.name: np.asarray(v, float) * (length_unit if tree.joint(j.name).kind == "prismatic" else 1.0)
           for j in tree.joints for v in [mech.tree_configuration(x, y)[j.name]]}
    frames = tree_frames(tree.scaled(length_unit), cfg)
    centres = dyn.body_centres(mech, model, x, y, length_unit)
    size = max(1.0, max(float(np.max(np.abs(o))) for o, _ in frames.values())) * 1e-9
    parts, omitted = {b: [] for b in tree.bodies}, []
    for b in model.bodies:
        c = centres[b.name]
        if not np.all(np.isfinite(c)):
            raise ValueError(f"the poses given to place the masses are out of reach of {type(mech).__name__}")
        order = ([b.name] if b.name in parts else []) + [BASE] + [n for n in tree.bodies if n != b.name]
        home = next((n for n in order if np.ptp(_local(frames[n], c), axis=0).max() <= size), None)
        if home is None:
            omitted.append(b.name)
        elif home != BASE:
            parts[home].append((b.mass, _local(frames[home], c)[0], b.inertia))
    out = {}
    for name, ps in parts.items():
        m = sum(p[0] for p in ps)
        com = sum(p[0] * p[1] for p in ps) / m if m > 0 else np.zeros(2)
        izz = sum(p[2] + p[0] * float(np.sum((p[1] - com) ** 2)) for p in ps)
        izz = max(izz, MIN_INERTIA)
        out[name] = (max(m, MIN_MASS), (float(com[0]), float(com[1]), 0.0), (izz / 2, izz / 2, izz))
    return out, tuple(omitted)
