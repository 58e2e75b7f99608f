"""The bodies of a mechanism as capsules: what :meth:`DesignSpec.links
<mechopt.core.design_spec.DesignSpec.links>` returns and :mod:`mechopt.analysis.collisions`
measures.

A body is a segment ``(x0, y0) -> (x1, y1)`` [L, task frame] swept by a disc of
diameter :attr:`Body.width`: a *capsule* (the set of points within ``width / 2`` of
the segment; robsynth-structdimsynth models links the same way). A motor housing is
a capsule of zero length: a disc of the housing's diameter about its base joint. A
slider's carriage is a capsule along its guide, centred on the slider joint, whose
axis is ``carriage_length`` long; a guide is a capsule along the guide line over the
slider's stroke and half a carriage beyond each end (where the carriage runs).

Each body names

* ``joints``: the joints it carries (a link: its two ends; a carriage: its slider
  joint; a guide: the slider joint that runs on it; a housing: its base joint). Two
  bodies that carry a common joint are *adjacent*: they touch by construction, and
  what keeps them apart is the angle between them at that joint (a joint-angle
  limit), not their distance.
* ``ends``: the names of the points its segment's two ends move with (a link's
  joints; a carriage's ends move with its slider joint; a fixed body's with
  ``"ground"``), so that the speed of each end per unit platform speed is that of a
  named joint (:meth:`DesignSpec.joint_speeds
  <mechopt.core.design_spec.DesignSpec.joint_speeds>`, the Lipschitz constants of
  :mod:`mechopt.analysis.collisions`).
* ``kind``: ``"housing"``, ``"guide"``, ``"carriage"``, ``"proximal"`` (a link that
  does not carry the tool: a crank), ``"distal"`` (a link that carries the tool
  point or the platform) or ``"platform"``. ``ground`` is True for the fixed bodies
  (housings, guides): two fixed bodies never move, so their clearance is the base
  width's (:func:`mechopt.analysis.collisions.base_margin`), not a pose's.

:class:`Shapes` states the sizes, in the task's unit [L]; its defaults (:meth:`Shapes.default`)
are stated in millimetres and converted to the task's unit.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mechopt.core import validation as _v

__all__ = ["Body", "Shapes", "KINDS", "GROUND", "TOOL_KINDS", "MM_DEFAULTS", "capsule_outline"]

#: the kinds of body
KINDS = ("housing", "guide", "carriage", "proximal", "distal", "platform")
#: the name of the fixed frame in :attr:`Body.ends`
GROUND = "ground"
#: the kinds that carry the tool (they enter the task by construction: a keep-out zone
#: made of the task itself does not apply to them)
TOOL_KINDS = ("distal", "platform")
#: the default sizes [mm] (:meth:`Shapes.default`): a 20 mm wide link (a 20 x 20 mm
#: aluminium profile or a printed arm), a 60 mm motor housing (the diagonal of a NEMA 17
#: stepper's 42 mm square flange, rounded up), a 60 mm long, 40 mm wide linear-guide
#: carriage on a 20 mm wide rail
MM_DEFAULTS = dict(link_width=20.0, housing_diameter=60.0, carriage_length=60.0,
                   carriage_width=40.0, guide_width=20.0)

_UNIT_MM = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": 25.4}


@dataclass(frozen=True)
class Shapes:
    """The sizes of the bodies [L, the task's unit].

    Parameters
    ----------
    link_width : float
        Diameter of every link's capsule [L] (> 0), unless ``widths`` names the link.
    housing_diameter : float
        Diameter of a motor housing (a disc about each base joint) [L] (>= 0; 0: no housing).
    carriage_length : float
        Length of a carriage's axis along its guide [L] (>= 0).
    carriage_width : float
        Diameter of a carriage's capsule [L] (> 0).
    guide_width : float
        Diameter of a guide's capsule [L] (> 0).
    widths : dict
        ``{body name: diameter [L]}``: per-body widths that replace the defaults above.
    """

    link_width: float = MM_DEFAULTS["link_width"]
    housing_diameter: float = MM_DEFAULTS["housing_diameter"]
    carriage_length: float = MM_DEFAULTS["carriage_length"]
    carriage_width: float = MM_DEFAULTS["carriage_width"]
    guide_width: float = MM_DEFAULTS["guide_width"]
    widths: dict = field(default_factory=dict)

    def __post_init__(self):
        _v.positive_length("link_width", self.link_width)
        _v.nonnegative_length("housing_diameter", self.housing_diameter)
        _v.nonnegative_length("carriage_length", self.carriage_length)
        _v.positive_length("carriage_width", self.carriage_width)
        _v.positive_length("guide_width", self.guide_width)
        for name, w in dict(self.widths).items():
            _v.nonnegative_length(f"width of {name}", w)

    @classmethod
    def default(cls, unit: str = "mm", **changes) -> "Shapes":
        """The sizes of :data:`MM_DEFAULTS` in ``unit`` (``"mm"``, ``"cm"``, ``"m"``,
        ``"in"``), with ``changes`` [unit] applied.

        Parameters
        ----------
        unit : str
            ``"mm"``, ``"cm"``, ``"m"`` or ``"in"``.
        **changes : 
            Sizes to change [unit].

        Returns
        -------
        Shapes
            The sizes.
        """
        f = 1.0 / _UNIT_MM[_v.choice("unit", unit, tuple(_UNIT_MM))]
        return cls(**{**{k: v * f for k, v in MM_DEFAULTS.items()}, **changes})

    def width(self, name: str, kind: str) -> float:
        """The diameter [L] of the body ``name`` of ``kind``.

        Parameters
        ----------
        name : str
            The body's name.
        kind : str
            Its kind.

        Returns
        -------
        float
            The diameter [L].
        """
        if name in self.widths:
            return float(self.widths[name])
        return {"housing": self.housing_diameter, "guide": self.guide_width,
                "carriage": self.carriage_width}.get(kind, self.link_width)


@dataclass(frozen=True, eq=False)
class Body:
    """One capsule of a mechanism at a set of poses (module docstring).

    ``x0, y0, x1, y1`` are arrays [L, task frame] of the shape of the poses (a fixed
    body's are broadcast to it); ``width`` is the capsule's diameter [L].

    Parameters
    ----------
    name : str
        The body's name.
    kind : str
        One of :data:`KINDS`.
    joints : tuple of str
        The joints it carries (adjacency).
    ends : tuple of str
        The names of its two end points.
    x0, y0, x1, y1 : ndarray
        End points [L, task frame], the poses' shape.
    width : float
        The capsule's diameter [L].
    """

    name: str
    kind: str
    joints: tuple
    ends: tuple
    x0: np.ndarray
    y0: np.ndarray
    x1: np.ndarray
    y1: np.ndarray
    width: float

    @property
    def ground(self) -> bool:
        """True for a fixed body (both ends move with the ground)."""
        return self.ends == (GROUND, GROUND)

    @classmethod
    def make(cls, name, kind, joints, ends, start, end, shapes: Shapes, shape=None):
        """A body of ``kind`` from its end points ``start = (x0, y0)``, ``end = (x1, y1)``
        (arrays or numbers, broadcast to ``shape``), its width from ``shapes``.

        Parameters
        ----------
        name : str
            The body's name.
        kind : str
            Its kind.
        joints : tuple of str
            The joints it carries.
        ends : tuple of str
            The names of its end points.
        start, end : tuple
            ``(x, y)`` end points [L], arrays or numbers.
        shapes : Shapes
            The sizes.
        shape : tuple, optional
            The poses' shape to broadcast to.

        Returns
        -------
        Body
            The body.

        Raises
        ------
        ValueError
            For a kind not in :data:`KINDS`.
        """
        if kind not in KINDS:
            raise ValueError(f"body kind must be one of {', '.join(map(repr, KINDS))}, got {kind!r}")
        pts = [np.asarray(v, dtype=float) for v in (*start, *end)]
        shape = np.broadcast_shapes(*(p.shape for p in pts), *(() if shape is None else (shape,)))
        x0, y0, x1, y1 = (p if p.shape == shape else np.broadcast_to(p, shape) for p in pts)
        return cls(name, kind, tuple(joints), tuple(ends), x0, y0, x1, y1, shapes.width(name, kind))


def capsule_outline(x0, y0, x1, y1, width, n: int = 16):
    """The outline of the capsule of the segment ``(x0, y0) -> (x1, y1)`` [L] and diameter
    ``width`` [L], for drawing: two half circles of ``n + 1`` points each about the ends,
    joined by the two straight sides (a circle of ``2 n`` points for a zero-length
    segment), closed. The points lie on the capsule's boundary (the polygon is
    inscribed in it).

    Parameters
    ----------
    x0, y0, x1, y1 : float
        The segment's ends [L].
    width : float
        The diameter [L], >= 0.
    n : int
        Points per half circle less one, >= 2.

    Returns
    -------
    tuple of numpy.ndarray
        ``(x, y)`` [L], the first point repeated at the end.

    Raises
    ------
    ValueError
        One line, when ``width`` is negative, not finite or too large, or ``n`` is below 2.
    """
    r = 0.5 * _v.nonnegative_length("width", width)
    if int(n) < 2:
        raise ValueError(f"n must be at least 2, got {n!r}")
    a = math.atan2(y1 - y0, x1 - x0) if (x1, y1) != (x0, y0) else 0.0
    t = np.linspace(0.0, math.pi, int(n) + 1)
    # the far end's half circle from the side at a - 90 deg to a + 90 deg, then the near end's
    tx = np.r_[x1 + r * np.cos(a - 0.5 * math.pi + t), x0 + r * np.cos(a + 0.5 * math.pi + t)]
    ty = np.r_[y1 + r * np.sin(a - 0.5 * math.pi + t), y0 + r * np.sin(a + 0.5 * math.pi + t)]
    return np.r_[tx, tx[:1]], np.r_[ty, ty[:1]]
