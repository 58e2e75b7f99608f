"""Rigid bodies of a planar mechanism for its dynamics: declarations, the mass law, frame kinematics.

(The bodies as capsules for collisions are :mod:`mechopt.core.bodies`.)

A mechanism declares its moving (and fixed) bodies in its own module with two methods:

* ``bodies()`` -> tuple of :class:`BodySpec`: name, kind (:data:`BODY_KINDS`), the
  length [L] the mass law needs, the joints the body connects;
* ``body_frames(x, y, xd, yd, xdd, ydd)`` -> ``(q, qd, qdd, frames)``: the actuator
  coordinates with their exact first and second time derivatives, and for each body
  its frame as ``(O, Od, Odd, r, rd, rdd)`` (arrays of shape ``(..., 2)``): the origin
  ``O`` (the body's first joint) and a vector ``r`` along the body (its x axis is
  ``r / |r|``), with their velocities and accelerations. Every derivative is a closed
  form of the mechanism's geometry (the loop closures differentiated twice), none is
  a finite difference.

From a frame, :func:`point_kinematics` gives the position, velocity and acceleration
of any point fixed in the body and the body's angular velocity and acceleration::

    omega = (r x r_dot) / |r|^2,
    alpha = (r x r_ddot) / |r|^2 - 2 (r . r_dot)(r x r_dot) / |r|^4,

(``e1 = r/|r|`` turns at ``omega``; the second term is zero for a body of constant
length), ``c = O + cx e1 + cy e2`` with ``e2`` ``e1`` turned by +90 deg,
``c_dot = O_dot + omega (cx e2 - cy e1)`` and
``c_ddot = O_ddot + alpha (cx e2 - cy e1) - omega^2 (cx e1 + cy e2)``.

The mass law (:class:`MassLaw`) turns each declaration into a :class:`RigidBody` (mass
[kg], centre of mass in the body frame [m], moment of inertia about the centre of
mass [kg m^2]); :func:`mechopt.analysis.dynamics.mass_model` applies it, with the
user's values per body on top.

Default law (stated; every number can be changed, :class:`MassLaw`): links are square
aluminium tubes 20 x 20 x 2 mm (area ``A = 0.02^2 - 0.016^2 = 1.44e-4 m^2``, density
2700 kg/m^3: 0.389 kg/m), centre of mass at mid-length, central inertia of a uniform
tube ``m (L^2 / 12 + I_s / A)`` with ``I_s = (0.02^4 - 0.016^4) / 12 m^4`` the
section's second moment about its in-plane axis (the bending axis of the planar
motion); motors 0.5 kg point masses on their base joints (fixed to the frame: they
are listed, they do not move); payload 0.2 kg at the platform point; slider carriages
0.3 kg point masses; actuator rotors 0 kg m^2 (a rotor inertia ``I_r`` with gear ratio
``N`` adds the reflected inertia ``I_r N^2`` on its actuator coordinate).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mechopt.core import validation as _v

__all__ = ["BODY_KINDS", "MATERIALS", "BodySpec", "RigidBody", "MassLaw", "point_kinematics",
           "fixed_frame", "translating_frame", "segment_frame", "cross", "stack2"]

#: kinds of bodies: a link of constant length (a tube of the law), a strut's cylinder and
#: rod (tubes, the bipod), a slider carriage, a motor stator (on the frame), the payload
#: at the platform point, a counterweight (Wu's gantry), a platform (Wu's gantry)
BODY_KINDS = ("link", "cylinder", "rod", "carriage", "motor", "payload", "counterweight", "platform")

#: densities [kg/m^3] of the materials the law knows
MATERIALS = {"aluminium": 2700.0, "steel": 7850.0, "stainless": 8000.0, "titanium": 4430.0,
             "cfrp": 1600.0, "pla": 1240.0}


@dataclass(frozen=True)
class BodySpec:
    """A body as the mechanism declares it: ``name``, ``kind`` (:data:`BODY_KINDS`),
    ``length`` [L] (the tube length for the law; 0 for point masses), ``joints`` (the
    names of the joints it connects, first the frame's origin) and ``com`` (the centre
    of mass along the body from its first joint, as a fraction of ``length``; for a rod,
    measured back from the platform joint).

    Parameters
    ----------
    name : str
        The body's name.
    kind : str
        One of :data:`BODY_KINDS`.
    length : float
        Tube length [L] (0 for point masses).
    joints : tuple of str
        The joints it connects, first the frame's origin.
    com : float
        Centre of mass along the body, a fraction of ``length``.
    leg : int
        The leg it belongs to (0: none).
    """

    name: str
    kind: str
    length: float = 0.0
    joints: tuple = ()
    com: float = 0.5
    leg: int = 0


@dataclass(frozen=True)
class RigidBody:
    """A body with its masses: ``mass`` [kg], ``com`` ``(cx, cy)`` [m] in the body frame
    (origin at the first joint, x along the body), ``inertia`` [kg m^2] about the centre
    of mass (axis normal to the plane), ``length`` [m], ``joints``, ``kind``.

    Parameters
    ----------
    name : str
        The body's name.
    kind : str
        Its kind.
    mass : float
        [kg].
    com : tuple of float
        ``(cx, cy)`` [m] in the body frame.
    inertia : float
        About the centre of mass [kg m^2].
    length : float
        [m].
    joints : tuple of str
        The joints it connects.
    """

    name: str
    kind: str
    mass: float
    com: tuple
    inertia: float
    length: float = 0.0
    joints: tuple = ()

    def __post_init__(self):
        for key in ("mass", "inertia"):
            v = _v.finite_number(f"{key} of body {self.name}", getattr(self, key))
            if v < 0:
                raise ValueError(f"{key} of body {self.name} must be >= 0 "
                                 f"[{'kg' if key == 'mass' else 'kg m^2'}], got {v!r}")
        cx, cy = _v.finite_numbers(f"com of body {self.name}", self.com, 2, "(cx, cy) [m]")
        object.__setattr__(self, "com", (cx, cy))

    def as_dict(self) -> dict:
        """The body for ``bodies.json``: SI units.

        Returns
        -------
        dict
            The body's fields (SI units).
        """
        return {"name": self.name, "kind": self.kind, "mass_kg": self.mass,
                "com_m": list(self.com), "com_along": (self.com[0] / self.length
                                                       if self.length > 0 else 0.0),
                "inertia_com_kg_m2": self.inertia, "length_m": self.length,
                "joints": list(self.joints)}


def _positive(name, v, unit, zero=False):
    v = _v.finite_number(name, v)
    if v < 0 or (v == 0 and not zero):
        raise ValueError(f"{name} must be {'>= 0' if zero else '> 0'} [{unit}], got {v!r}")
    return v


@dataclass(frozen=True)
class MassLaw:
    """How a declared body gets its masses (module docstring for the defaults).

    ``material`` (a key of :data:`MATERIALS`) sets ``density`` [kg/m^3] unless it is
    given; ``outer`` and ``wall`` [m] the square tube's side and wall (``wall = outer/2``:
    a solid bar); ``motor``, ``payload``, ``carriage`` [kg] the point masses;
    ``rotor_inertia`` [kg m^2] and ``gear_ratio`` (motor turns per actuator unit: -
    for cranks, rad/m for sliders) the actuators' reflected inertia.

    Parameters
    ----------
    material : str
        A key of :data:`MATERIALS`.
    density : float, optional
        [kg/m^3] (default: the material's).
    outer : float
        The square tube's side [m].
    wall : float
        Its wall [m].
    motor : float
        Motor mass [kg].
    payload : float
        Payload mass [kg].
    carriage : float
        Carriage mass [kg].
    rotor_inertia : float
        [kg m^2].
    gear_ratio : float
        Motor turns per actuator unit.
    extra : dict
        Additional data carried with the law (not read by :meth:`body`; not a key
        :meth:`from_dict` accepts).
    """

    material: str = "aluminium"
    density: float | None = None
    outer: float = 0.020
    wall: float = 0.002
    motor: float = 0.5
    payload: float = 0.2
    carriage: float = 0.3
    rotor_inertia: float = 0.0
    gear_ratio: float = 1.0
    extra: dict = field(default_factory=dict)

    def __post_init__(self):
        if self.material not in MATERIALS:
            raise ValueError(f"material must be one of {sorted(MATERIALS)}, got {self.material!r}")
        if self.density is None:
            object.__setattr__(self, "density", MATERIALS[self.material])
        _positive("density", self.density, "kg/m^3")
        _positive("outer", self.outer, "m")
        _positive("wall", self.wall, "m")
        if self.wall > self.outer / 2:
            raise ValueError(f"wall must be at most outer/2 = {self.outer / 2!r} m, got {self.wall!r}")
        for k in ("motor", "payload", "carriage", "rotor_inertia"):
            _positive(k, getattr(self, k), "kg m^2" if k == "rotor_inertia" else "kg", zero=True)
        _positive("gear_ratio", self.gear_ratio, "-")

    @classmethod
    def from_dict(cls, d: dict) -> "MassLaw":
        """The law from a JSON object with keys of the fields (unknown keys refused).

        Parameters
        ----------
        d : dict
            The law's fields.

        Returns
        -------
        MassLaw
            The law.

        Raises
        ------
        ValueError
            One line naming an unknown key.
        """
        names = {f for f in cls.__dataclass_fields__ if f != "extra"}
        bad = sorted(set(d) - names)
        if bad:
            raise ValueError(f"unknown mass-law key {bad[0]!r}; known: {sorted(names)}")
        return cls(**d)

    @property
    def section(self):
        """``(A, I_s)``: the tube's area [m^2] and second moment about its in-plane axis [m^4]."""
        b, h = self.outer, self.outer - 2.0 * self.wall
        return b * b - h * h, (b ** 4 - h ** 4) / 12.0

    def body(self, spec: BodySpec, length_unit: float = 1.0) -> RigidBody:
        """The :class:`RigidBody` of a declaration (lengths [L] times ``length_unit`` [m/L]).

        Parameters
        ----------
        spec : BodySpec
            The declaration.
        length_unit : float
            Metres per length unit [m/L].

        Returns
        -------
        RigidBody
            The body.
        """
        L = spec.length * length_unit
        if spec.kind in ("link", "cylinder", "rod"):
            A, Is = self.section
            m = self.density * A * L
            s = spec.com * L
            return RigidBody(spec.name, spec.kind, m, (-s if spec.kind == "rod" else s, 0.0),
                        m * (L * L / 12.0 + Is / A), L, spec.joints)
        m = {"motor": self.motor, "payload": self.payload, "carriage": self.carriage}.get(spec.kind, 0.0)
        return RigidBody(spec.name, spec.kind, m, (0.0, 0.0), 0.0, L, spec.joints)


def cross(a, b):
    """z component of ``a x b`` for arrays of shape ``(..., 2)``.

    Parameters
    ----------
    a, b : ndarray
        Shape ``(..., 2)``.

    Returns
    -------
    ndarray
        The z component.
    """
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def _perp(a):
    return np.stack([-a[..., 1], a[..., 0]], -1)


def point_kinematics(frame, com):
    """``(c, c_dot, c_ddot, omega, alpha)`` of the point ``com = (cx, cy)`` [m] fixed in the
    body of ``frame = (O, Od, Odd, r, rd, rdd)`` (module docstring for the formulas).

    Parameters
    ----------
    frame : tuple of ndarray
        ``(O, Od, Odd, r, rd, rdd)``.
    com : tuple of float
        ``(cx, cy)`` [m] in the body frame.

    Returns
    -------
    c, c_dot, c_ddot : ndarray
        Position [m], velocity [m/s], acceleration [m/s^2], shape ``(..., 2)``.
    omega, alpha : ndarray
        Angular velocity [rad/s] and acceleration [rad/s^2].
    """
    O, Od, Odd, r, rd, rdd = frame
    r2 = np.sum(r * r, axis=-1)
    w = cross(r, rd) / r2
    a = cross(r, rdd) / r2 - 2.0 * np.sum(r * rd, axis=-1) * cross(r, rd) / (r2 * r2)
    e1 = r / np.sqrt(r2)[..., None]
    e2 = _perp(e1)
    cx, cy = com
    arm = cx * e1 + cy * e2
    t = _perp(arm)  # cx e2 - cy e1
    c = O + arm
    cd = Od + w[..., None] * t
    cdd = Odd + a[..., None] * t - (w * w)[..., None] * arm
    return c, cd, cdd, w, a


def fixed_frame(point, shape):
    """Frame of a body fixed to the base at ``point`` (x axis along +x).

    Parameters
    ----------
    point : tuple of float
        The origin [m].
    shape : tuple
        The poses' shape.

    Returns
    -------
    tuple of ndarray
        ``(O, Od, Odd, r, rd, rdd)``.
    """
    O = np.broadcast_to(np.asarray(point, float), shape + (2,))
    z = np.zeros(shape + (2,))
    ex = np.broadcast_to(np.array([1.0, 0.0]), shape + (2,))
    return O, z, z, ex, z, z


def translating_frame(O, Od, Odd):
    """Frame of a body that translates with its origin (x axis along +x).

    Parameters
    ----------
    O, Od, Odd : ndarray
        Origin position, velocity, acceleration, shape ``(..., 2)``.

    Returns
    -------
    tuple of ndarray
        ``(O, Od, Odd, r, rd, rdd)``.
    """
    z = np.zeros(O.shape)
    return O, Od, Odd, np.broadcast_to(np.array([1.0, 0.0]), O.shape), z, z


def segment_frame(start, end):
    """Frame of the body from the point ``start = (X, Xd, Xdd)`` to ``end`` (each of shape
    ``(..., 2)``): origin at the start, x axis towards the end.

    Parameters
    ----------
    start : tuple of ndarray
        ``(X, Xd, Xdd)`` of the start point.
    end : tuple of ndarray
        The same of the end point.

    Returns
    -------
    tuple of ndarray
        ``(O, Od, Odd, r, rd, rdd)``.
    """
    (X, Xd, Xdd), (Y, Yd, Ydd) = start, end
    return X, Xd, Xdd, Y - X, Yd - Xd, Ydd - Xdd


def stack2(x, y):
    """``(..., 2)`` array of two coordinates.

    Parameters
    ----------
    x, y : array_like
        The coordinates.

    Returns
    -------
    ndarray
        Shape ``(..., 2)``.
    """
    return np.stack(np.broadcast_arrays(x, y), -1)

