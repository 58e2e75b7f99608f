"""Placeholder mass properties of the exported bodies, in ONE function.

Until the mass model of the dynamics work (bodies with a stated cross-section and
density) lands, every moving body of an exported URDF or MJCF is a **uniform solid
cylinder of mass 1 kg** along its x axis, from its joint at ``(0, 0)`` to its farthest
pin at ``(length, 0)``, of diameter :func:`link_width`. A body whose pins all sit on
its joint (a carriage on a guide, a strut's halves) has ``length = 0``: a disk of that
diameter. These numbers are unit defaults, not a design's masses: they make the
models simulate, and the kinematic checks do not depend on them. Swap
:func:`body_inertia` for the mass model when it exists.
"""
from __future__ import annotations

import math

__all__ = ["body_inertia", "link_width", "MASS_KG", "WIDTH_RATIO"]

#: mass of every moving body [kg] (placeholder)
MASS_KG = 1.0
#: link width (the DXF capsule and the cylinder's diameter) as a fraction of the
#: mechanism's longest pin distance
WIDTH_RATIO = 0.1


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


def body_inertia(length: float, width: float):
    """``(mass, com, (Ixx, Iyy, Izz))`` of the placeholder body (module docstring): a solid
    cylinder of mass :data:`MASS_KG` [kg], length ``length`` [m] along the body's x axis
    from its origin, diameter ``width`` [m]; ``com = (length / 2, 0, 0)`` [m], principal
    moments about the centre of mass [kg m^2]: ``Ixx = m r^2 / 2``,
    ``Iyy = Izz = m (3 r^2 + length^2) / 12`` with ``r = width / 2``.

    Parameters
    ----------
    length : float
        The body's length [m].
    width : float
        Its diameter [m].

    Returns
    -------
    mass : float
        [kg].
    com : tuple of float
        [m].
    inertia : tuple of float
        ``(Ixx, Iyy, Izz)`` [kg m^2].
    """
    m = MASS_KG
    r = 0.5 * float(width)
    L = float(length)
    ixx = 0.5 * m * r * r
    iyy = m * (3.0 * r * r + L * L) / 12.0
    return m, (0.5 * L, 0.0, 0.0), (ixx, iyy, iyy)
