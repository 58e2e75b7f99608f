"""Inverse dynamics of every mechanism of the protocol, from one formulation.

Generalised coordinates: the platform point ``p = (x, y)``. Each mechanism declares its
bodies and their frames along a motion in its own module (``bodies()`` and
``body_frames()``, :mod:`mechopt.core.rigid_bodies`); the mass model
(:func:`mass_model`) gives each body its mass ``m``, centre of mass ``c`` and central
inertia ``I``. For a body, ``c_dot = Jc(p) p_dot`` and ``omega = Jw(p) p_dot``, so the
kinetic energy is ``T = 1/2 p_dot^T M(p) p_dot`` with

    M = sum_bodies m Jc^T Jc + I Jw^T Jw  (+ sum_i I_r N^2 J_i^T J_i, the rotors),

and ``V = -sum m g . c``. Lagrange's equations in ``p`` are, by d'Alembert's principle
(the virtual work of the inertia and gravity forces of each body),

    Q_p = sum_bodies m Jc^T (c_ddot - g) + I Jw^T alpha  (+ sum_i I_r N^2 q_ddot_i J_i^T),

which equals ``M p_ddot + (M_dot - 1/2 d/dp (p_dot^T M p_dot)) p_dot + dV/dp``. The
actuator efforts follow from the virtual work of the actuators, ``tau . q_dot =
Q_p . p_dot`` for every ``p_dot``, i.e. ``tau = J^-T Q_p`` with the mechanism's own
Jacobian ``J`` (``q_dot = J p_dot``, :meth:`~mechopt.core.protocol.PlanarMechanism.jacobian`).

Derivatives: ``c_ddot``, ``alpha`` come from the frames' exact accelerations (each
mechanism's loop closures differentiated twice in closed form); ``Jc`` and ``Jw`` are
the velocities of the bodies for ``p_dot = e_x`` and ``e_y`` (velocities are linear in
``p_dot``). No finite difference anywhere. ``tests/test_dynamics.py`` checks the
efforts against a sympy Lagrange derivation written from the geometry in the test and
the power balance ``sum tau_i q_dot_i = d(T + V)/dt``.

Units: SI. The mechanism and the motion are in [L]; ``length_unit`` [m/L] converts
(1e-3 for mm). Efforts in N m (cranks) or N (sliders, struts); ``q`` in rad or m.
"""
from __future__ import annotations

import json
from dataclasses import dataclass, replace

import numpy as np

from mechopt.core import rigid_bodies as _b
from mechopt.core import validation as _v

__all__ = ["STANDARD_GRAVITY", "MassModel", "mass_model", "load_mass_model", "inverse_dynamics",
           "energies", "parse_gravity", "motion_efforts", "MOTION_COLUMNS", "peak_torque", "rms_torque",
           "body_centres"]

#: the columns of :func:`motion_efforts`'s table (``_i`` for each actuator 1, 2)
MOTION_COLUMNS = ("t", "x", "y", "q_i", "qd_i", "qdd_i", "tau_i", "power_i")

#: standard gravity [m/s^2]
STANDARD_GRAVITY = 9.80665


@dataclass(frozen=True)
class MassModel:
    """The bodies of a mechanism with their masses (:class:`mechopt.core.rigid_bodies.RigidBody`, SI),
    the reflected rotor inertia of each actuator ``I_r N^2`` [kg m^2 or kg] and the
    gravity magnitude [m/s^2] the model was stated with; ``source`` says where the numbers
    come from (``"law"``, ``"wu2008-table2"``, plus ``"+user"`` for given bodies).

    Parameters
    ----------
    bodies : tuple of mechopt.core.rigid_bodies.RigidBody
        The bodies (SI).
    actuator_inertia : tuple of float
        Reflected rotor inertia per actuator [kg m^2 or kg].
    g : float
        Gravity magnitude [m/s^2].
    source : str
        Where the numbers come from.
    law : mechopt.core.rigid_bodies.MassLaw, optional
        The law used.
    """

    bodies: tuple
    actuator_inertia: tuple = (0.0, 0.0)
    g: float = STANDARD_GRAVITY
    source: str = "law"
    law: object = None

    @property
    def moving_mass(self) -> float:
        """Total mass of the bodies that move [kg] (motors on the frame excluded)."""
        return float(sum(b.mass for b in self.bodies if b.kind != "motor"))

    def as_dict(self) -> dict:
        """``bodies.json``: every body and the model's settings.

        Returns
        -------
        dict
            bodies.json's content (SI units).
        """
        law = self.law
        return {"source": self.source, "gravity_m_s2": self.g,
                "actuator_inertia": list(self.actuator_inertia),
                "moving_mass_kg": self.moving_mass,
                "law": None if law is None else {
                    "material": law.material, "density_kg_m3": law.density, "outer_m": law.outer,
                    "wall_m": law.wall, "motor_kg": law.motor, "payload_kg": law.payload,
                    "carriage_kg": law.carriage, "rotor_inertia_kg_m2": law.rotor_inertia,
                    "gear_ratio": law.gear_ratio},
                "bodies": [b.as_dict() for b in self.bodies]}


def _declared(mech):
    if not hasattr(mech, "bodies") or not hasattr(mech, "body_frames"):
        raise ValueError(f"{type(mech).__name__} declares no bodies (bodies(), body_frames())")
    return mech.bodies()


def mass_model(mech, law=None, bodies=None, length_unit: float = 1.0) -> MassModel:
    """The mass model of ``mech``: each declared body from the mass law, then the user's
    values per body.

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``bodies()`` (lengths in [L]).
    law : MassLaw or dict, optional
        The law (:class:`mechopt.core.rigid_bodies.MassLaw`; its defaults when None). A
        mechanism with ``default_masses`` (the gantry: Wu 2008 Table 2) uses those when
        neither ``law`` nor ``bodies`` is given.
    bodies : dict, optional
        ``{body name: {"mass": kg, "com": fraction along the body from its first joint,
        "inertia": kg m^2 about the centre of mass}}``, any of the three keys.
    length_unit : float
        Metres per [L], > 0.

    Returns
    -------
    MassModel

    Raises
    ------
    ValueError
        One line, for an unknown body or key, or invalid values.
    """
    unit = _v.positive_length("length_unit", length_unit)
    specs = _declared(mech)
    if isinstance(law, dict):
        law = _b.MassLaw.from_dict(law)
    if law is not None and not isinstance(law, _b.MassLaw):
        raise ValueError(f"law must be a MassLaw or a dict, got {type(law).__name__}")
    g = STANDARD_GRAVITY
    if law is None and hasattr(mech, "default_masses"):
        table = mech.default_masses(unit)
        g = table.pop("g", g)
        out = [_b.RigidBody(s.name, s.kind, m, (com, 0.0), I, s.length * unit, s.joints)
               for s in specs for m, com, I in [table[s.name]]]
        source, law_used = "wu2008-table2", None
    else:
        law_used = law or _b.MassLaw()
        out = [law_used.body(s, unit) for s in specs]
        source = "law"
    if bodies:
        if not isinstance(bodies, dict):
            raise ValueError(f"bodies must be a dict {{name: {{mass, com, inertia}}}}, got {type(bodies).__name__}")
        by_name = {b.name: i for i, b in enumerate(out)}
        for name, vals in bodies.items():
            if name not in by_name:
                raise ValueError(f"unknown body {name!r} of {type(mech).__name__}; known: {sorted(by_name)}")
            if not isinstance(vals, dict) or set(vals) - {"mass", "com", "inertia"}:
                raise ValueError(f"body {name!r} takes the keys mass [kg], com [fraction], inertia [kg m^2], got {vals!r}")
            b = out[by_name[name]]
            kw = {}
            if "mass" in vals:
                kw["mass"] = vals["mass"]
            if "inertia" in vals:
                kw["inertia"] = vals["inertia"]
            if "com" in vals:
                f = _v.finite_number(f"com of body {name}", vals["com"])
                kw["com"] = ((-f if b.kind == "rod" else f) * b.length, 0.0)
            out[by_name[name]] = replace(b, **kw)
        source += "+user"
    ai = (0.0, 0.0) if law_used is None else (law_used.rotor_inertia * law_used.gear_ratio ** 2,) * 2
    return MassModel(tuple(out), ai, g, source, law_used)


def load_mass_model(mech, path, length_unit: float = 1.0) -> MassModel:
    """:func:`mass_model` from a JSON file ``{"law": {...}, "bodies": {...}}`` (both
    optional; the keys of :class:`~mechopt.core.rigid_bodies.MassLaw` and of ``bodies``).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``bodies()`` and ``body_frames()`` (lengths [L]).
    path : str or Path
        The JSON file.
    length_unit : float
        Metres per length unit [m/L].

    Returns
    -------
    MassModel
        The model.

    Raises
    ------
    ValueError
        One line, for an unreadable file or invalid content.
    """
    try:
        with open(path, encoding="utf-8") as fh:
            d = json.load(fh)
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ValueError(f"mass model {str(path)!r} is not a readable JSON file: {e}") from None
    if not isinstance(d, dict) or set(d) - {"law", "bodies"}:
        raise ValueError(f"mass model {str(path)!r} must be a JSON object with the keys law, bodies")
    return mass_model(mech, d.get("law"), d.get("bodies"), length_unit)


def parse_gravity(value, g: float = STANDARD_GRAVITY):
    """``(gx, gy)`` [m/s^2] from ``"off"`` (a horizontal table: ``(0, 0)``), ``"down"``
    (``(0, -g)``), a pair, or a string ``"gx,gy"``.

    Parameters
    ----------
    value : str or tuple
        ``"off"``, ``"down"``, ``"gx,gy"`` or a pair [m/s^2].
    g : float
        The magnitude of ``"down"`` [m/s^2].

    Returns
    -------
    tuple of float
        ``(gx, gy)`` [m/s^2].

    Raises
    ------
    ValueError
        One line, for another value.
    """
    if value is None or (isinstance(value, str) and value.strip().lower() == "down"):
        return (0.0, -float(g))
    if isinstance(value, str):
        if value.strip().lower() == "off":
            return (0.0, 0.0)
        try:
            value = [float(v) for v in value.split(",")]
        except ValueError:
            raise ValueError(f"gravity must be 'off', 'down' or 'gx,gy' [m/s^2], got {value!r}") from None
    gx, gy = _v.finite_numbers("gravity", value, 2, "'off', 'down' or (gx, gy) [m/s^2]")
    return (gx, gy)


def _kinematics(mech, model, x, y, xd, yd, xdd, ydd):
    """Per body ``(c, c_dot, c_ddot, omega, alpha)`` and ``(q, qd, qdd)``."""
    q, qd, qdd, frames = mech.body_frames(x, y, xd, yd, xdd, ydd)
    kin = {b.name: _b.point_kinematics(frames[b.name], b.com) for b in model.bodies}
    return q, qd, qdd, kin


def body_centres(mech, model: MassModel, x, y, length_unit: float = 1.0) -> dict:
    """``{body name: (..., 2)}``: the centre of mass of every body of ``model`` [m] with
    the platform at ``(x, y)`` [L] (the exporters place the bodies' masses with it).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism, lengths in [L].
    model : MassModel
        From :func:`mass_model` with the same ``length_unit``.
    x, y : array_like
        Platform points [L].
    length_unit : float
        Metres per [L].

    Returns
    -------
    dict
        NaN where unreachable.
    """
    unit = _v.positive_length("length_unit", length_unit)
    m_si = mech.scaled(unit) if unit != 1.0 else mech
    x, y = (np.asarray(v, float) * unit for v in np.broadcast_arrays(x, y))
    zero = np.zeros(x.shape)
    kin = _kinematics(m_si, model, x, y, zero, zero, zero, zero)[3]
    return {name: k[0] for name, k in kin.items()}


def _motion_arrays(motion, unit):
    try:
        vals = [np.asarray(motion[k], float) * unit for k in ("x", "y", "xd", "yd", "xdd", "ydd")]
    except (KeyError, TypeError):
        raise ValueError("motion must hold the arrays x, y, xd, yd, xdd, ydd") from None
    return np.broadcast_arrays(*vals)


def inverse_dynamics(mech, motion, model: MassModel, gravity=None, length_unit: float = 1.0) -> dict:
    """Actuator efforts along a motion of the platform point (module docstring).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism, lengths in [L], with ``bodies()``/``body_frames()``.
    motion : dict
        Arrays ``x, y`` [L], ``xd, yd`` [L/s], ``xdd, ydd`` [L/s^2] (e.g. from
        :mod:`mechopt.core.motion`).
    model : MassModel
        From :func:`mass_model` with the same ``length_unit``.
    gravity : None, "off", "down" or (gx, gy)
        Gravity in the plane [m/s^2] (:func:`parse_gravity`); None: ``(0, -model.g)``.
    length_unit : float
        Metres per [L].

    Returns
    -------
    dict
        ``q, qd, qdd`` (shape ``(..., 2)``: rad, rad/s, rad/s^2 or m, m/s, m/s^2),
        ``tau`` (N m or N), ``power`` (``tau_i q_dot_i`` [W]), ``T``, ``V`` [J], ``Q``
        (the generalised force on ``p`` [N]); NaN where unreachable.
    """
    unit = _v.positive_length("length_unit", length_unit)
    grav = np.asarray(parse_gravity(gravity, model.g))
    m_si = mech.scaled(unit) if unit != 1.0 else mech
    x, y, xd, yd, xdd, ydd = _motion_arrays(motion, unit)
    q, qd, qdd, kin = _kinematics(m_si, model, x, y, xd, yd, xdd, ydd)
    one, zero = np.ones(x.shape), np.zeros(x.shape)
    virtual = [_kinematics(m_si, model, x, y, *e, zero, zero) for e in ((one, zero), (zero, one))]
    Q = np.zeros(x.shape + (2,))
    T = np.zeros(x.shape)
    V = np.zeros(x.shape)
    for b in model.bodies:
        if b.mass == 0.0 and b.inertia == 0.0:
            continue
        c, cd, cdd, w, a = kin[b.name]
        f = b.mass * (cdd - grav)
        for k, (_, _, _, kv) in enumerate(virtual):
            _, cdk, _, wk, _ = kv[b.name]
            Q[..., k] += np.sum(f * cdk, -1) + b.inertia * a * wk
        T += 0.5 * b.mass * np.sum(cd * cd, -1) + 0.5 * b.inertia * w * w
        V -= b.mass * (c @ grav)
    ai = np.asarray(model.actuator_inertia, float)
    if np.any(ai > 0):
        for k, (_, qdk, _, _) in enumerate(virtual):
            Q[..., k] += np.sum(ai * qdd * qdk, -1)
        T += 0.5 * np.sum(ai * qd * qd, -1)
    J = m_si.jacobian(x, y)
    with np.errstate(invalid="ignore", divide="ignore"):
        tau = np.linalg.solve(np.swapaxes(J, -1, -2), Q[..., None])[..., 0] if np.all(np.isfinite(J)) \
            else _solve_masked(J, Q)
    return {"q": q, "qd": qd, "qdd": qdd, "tau": tau, "power": tau * qd, "T": T, "V": V, "Q": Q}


def _solve_masked(J, Q):
    """``J^-T Q`` with NaN where ``J`` is not finite (unreachable poses)."""
    ok = np.all(np.isfinite(J), axis=(-1, -2))
    out = np.full(Q.shape, np.nan)
    out[ok] = np.linalg.solve(np.swapaxes(J[ok], -1, -2), Q[ok][..., None])[..., 0]
    return out


def energies(mech, motion, model: MassModel, gravity=None, length_unit: float = 1.0):
    """``(T, V)`` [J] along the motion (:func:`inverse_dynamics`'s).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``bodies()`` and ``body_frames()`` (lengths [L]).
    motion : dict
        A timed motion (:func:`mechopt.core.motion.timed_motion`) [L, s].
    model : MassModel
        The masses.
    gravity : tuple of float, optional
        ``(gx, gy)`` [m/s^2] (default: the model's, downwards).
    length_unit : float
        Metres per length unit [m/L].

    Returns
    -------
    T, V : ndarray
        Kinetic and potential energy [J] at each time.
    """
    out = inverse_dynamics(mech, motion, model, gravity, length_unit)
    return out["T"], out["V"]


def _check_reach(mech, motion, to_mech=None):
    x, y = np.asarray(motion["x"], float), np.asarray(motion["y"], float)
    mx, my = (x, y) if to_mech is None else to_mech(x, y)
    ok = mech.reachable(mx, my)
    if not np.all(ok):
        k = int(np.argmin(ok))
        t = motion.get("t")
        when = f" at t = {float(t[k]):.4g} s" if t is not None else ""
        raise ValueError(f"the motion leaves the reachable workspace{when}, at (x, y) = "
                         f"({float(x[k]):.6g}, {float(y[k]):.6g})")
    return mx, my


def motion_efforts(mech, motion, model: MassModel, gravity=None, length_unit: float = 1.0,
                   to_mech=None):
    """Per-actuator position, rate, acceleration, effort and power along a timed motion,
    and their extremes.

    Parameters
    ----------
    mech, model, gravity, length_unit
        As for :func:`inverse_dynamics`.
    motion : dict
        :func:`mechopt.core.motion.timed_motion`'s: ``t`` [s], ``x, y`` [L] and their
        derivatives, in the task frame when ``to_mech`` is given.
    to_mech : callable, optional
        ``(x, y) -> (x, y)``: task-frame points in the mechanism's frame (a translation,
        e.g. a design spec's ``to_mech``).

    Returns
    -------
    (table, summary)
        ``table``: ``{column: array}`` with the columns of :data:`MOTION_COLUMNS`
        (``q`` in rad or m, ``tau`` in N m or N, ``power`` in W); ``summary``: per
        actuator ``q_min, q_max, qd_peak, qdd_peak, tau_peak, tau_rms`` (root mean square
        over the cycle, trapezoidal rule in time) and ``power_peak``, as lists of two, and
        ``moving_mass`` [kg]. ValueError (one line) when a pose of the motion is out of
        reach.
    """
    mx, my = _check_reach(mech, motion, to_mech)
    m = dict(motion, x=mx, y=my)
    out = inverse_dynamics(mech, m, model, gravity, length_unit)
    t = np.asarray(motion["t"], float)
    table = {"t": t, "x": np.asarray(motion["x"], float), "y": np.asarray(motion["y"], float)}
    for key in ("q", "qd", "qdd", "tau", "power"):
        for i in (0, 1):
            table[f"{key}_{i + 1}"] = out[key][..., i]
    T = t[-1] - t[0]
    rms = np.sqrt(np.trapezoid(out["tau"] ** 2, t, axis=0) / T) if T > 0 else np.abs(out["tau"][0])
    summary = {"q_min": np.min(out["q"], 0).tolist(), "q_max": np.max(out["q"], 0).tolist(),
               "qd_peak": np.max(np.abs(out["qd"]), 0).tolist(),
               "qdd_peak": np.max(np.abs(out["qdd"]), 0).tolist(),
               "tau_peak": np.max(np.abs(out["tau"]), 0).tolist(), "tau_rms": rms.tolist(),
               "power_peak": np.max(np.abs(out["power"]), 0).tolist(),
               "moving_mass": model.moving_mass, "cycle_time": float(T)}
    return table, summary


def peak_torque(mech, motion, model: MassModel, gravity=None, length_unit: float = 1.0):
    """``(2,)`` array: the largest ``|tau_i|`` [N m or N] of each actuator along the motion
    (:func:`inverse_dynamics`; no reach check: NaN where a pose is out of reach).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``bodies()`` and ``body_frames()`` (lengths [L]).
    motion : dict
        A timed motion (:func:`mechopt.core.motion.timed_motion`) [L, s].
    model : MassModel
        The masses.
    gravity : tuple of float, optional
        ``(gx, gy)`` [m/s^2] (default: the model's, downwards).
    length_unit : float
        Metres per length unit [m/L].

    Returns
    -------
    ndarray
        Shape ``(2,)`` [N m or N].
    """
    tau = inverse_dynamics(mech, motion, model, gravity, length_unit)["tau"]
    return np.max(np.abs(tau), axis=0)


def rms_torque(mech, motion, model: MassModel, gravity=None, length_unit: float = 1.0):
    """``(2,)`` array: the root mean square of ``tau_i`` over the motion's time [N m or N]
    (trapezoidal rule on the samples ``motion["t"]``).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with ``bodies()`` and ``body_frames()`` (lengths [L]).
    motion : dict
        A timed motion (:func:`mechopt.core.motion.timed_motion`) [L, s].
    model : MassModel
        The masses.
    gravity : tuple of float, optional
        ``(gx, gy)`` [m/s^2] (default: the model's, downwards).
    length_unit : float
        Metres per length unit [m/L].

    Returns
    -------
    ndarray
        Shape ``(2,)`` [N m or N].
    """
    tau = inverse_dynamics(mech, motion, model, gravity, length_unit)["tau"]
    t = np.asarray(motion["t"], float)
    return np.sqrt(np.trapezoid(tau ** 2, t, axis=0) / (t[-1] - t[0]))
