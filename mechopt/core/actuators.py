"""Speed and force a 2-DOF mechanism guarantees in every direction under actuator limits.

Convention (Liu 2006 eq. 1): ``q_dot = J p_dot`` and, by virtual work, the platform
force balanced by actuator efforts ``tau`` is ``F = J^T tau``. ``J`` has shape
``(..., 2, 2)``; every function here broadcasts over its leading axes.

Two readings of the actuator limits (``norm``):

``"box"`` (real motors, each limited on its own)
    ``|q_dot_i| <= w_i`` and ``|tau_i| <= t_i``.

    *Speed.* Moving at speed ``v`` in the unit direction ``u`` needs
    ``q_dot = v J u``; the largest admissible ``v`` is ``min_i w_i / |(J u)_i|``. The
    speed guaranteed in every direction is its minimum over ``u``::

        v_box = min_u min_i w_i / |row_i(J) . u| = 1 / max_i max_u |row_i(J) . u| / w_i
              = min_i w_i / ||row_i(J)||_2,

    since ``max_{|u|=1} |r . u| = ||r||_2`` (Cauchy-Schwarz, attained at
    ``u = r / ||r||``). Exact: the worst direction is that of the row of the largest
    ``||row_i|| / w_i``.

    *Force.* The forces the motors can exert form the zonotope
    ``Z = J^T [-t_1, t_1] x [-t_2, t_2]``: a parallelogram centred at the origin with
    half-edges ``h_i = t_i c_i``, ``c_i = J^T e_i = row_i(J)``. The force guaranteed in
    every direction is the largest ``f`` with ``f u in Z`` for every unit ``u``: the
    radius of the largest disk about the origin inside ``Z``, its inradius
    ``min_{|n|=1} h_Z(n)`` with the support function ``h_Z(n) = max_{tau in box} n . J^T
    tau``. A linear function over a box takes its maximum at a vertex
    ``tau = (+/-t_1, +/-t_2)``, so ``h_Z(n) = t_1 |c_1 . n| + t_2 |c_2 . n|``. On each arc
    of the unit circle where both signs are fixed this is ``a . n`` for a fixed ``a``,
    a cosine, which is concave where positive, so its minimum lies at an end of the
    arc, where some ``c_k . n = 0``: at the normals of the edges (``n`` perpendicular
    to ``c_1`` or to ``c_2``). There ``h_Z = t_2 |c_1 x c_2| / ||c_1||`` or
    ``t_1 |c_1 x c_2| / ||c_2||``, and ``|c_1 x c_2| = |det J|``::

        f_box = t_1 t_2 |det J| / max(t_1 ||row_1(J)||, t_2 ||row_2(J)||),

    the distance from the centre of the parallelogram to its nearer pair of edges.

``2`` (Liu 2006 eq. 10 and 13: one Euclidean budget)
    ``||W^-1 q_dot||_2 <= 1`` and ``||T^-1 tau||_2 <= 1`` with ``W = diag(w)``,
    ``T = diag(t)``: ``v_2 = 1 / s_max(W^-1 J)`` and ``f_2 = s_min(T J)`` (for equal
    limits ``w / s_max(J)`` and ``t s_min(J)``, Liu's ``|V|min`` and ``|tau|min`` times
    the budget). The box contains the Euclidean ball of the same radii, so
    ``v_box >= v_2`` and ``f_box >= f_2``.

Units: ``w`` in the actuator rate unit (rad/s for cranks, [L]/s for sliders), ``J`` in
actuator unit per [L]; the speed is then in [L]/s. ``t`` in N m (cranks) or N
(sliders); the force in N when ``J`` is per metre. Singular ``J`` (``det J = 0``)
gives a force of 0; unreachable poses (NaN in ``J``) give NaN.

References
----------
Liu, Wang, Pritschow (2006), Mech. Mach. Theory 41:119-144, eq. (1), (10), (13).
Bouchard, Gosselin, Moore (2010), J. Mech. Robot. 2:011005 (wrench capabilities of
parallel mechanisms under box limits, zonotopes).
"""
from __future__ import annotations

import json
import math
from typing import NamedTuple

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v

__all__ = ["ACTUATOR_NORMS", "MOTOR_KEYS", "Motor", "read_motors", "actuator_norm", "guaranteed_speed",
           "guaranteed_force"]

#: readings of the actuator limits: per actuator (``"box"``) or one Euclidean budget (``2``)
ACTUATOR_NORMS = ("box", 2)


def _limits(name, value, unit):
    """The two positive limits of ``value`` (a number or a pair), as a ``(2,)`` array."""
    arr = np.asarray(value, dtype=float) if np.ndim(value) else np.full(2, value, dtype=float)
    if arr.shape != (2,) or not np.all(np.isfinite(arr)) or not np.all(arr > 0):
        raise ValueError(f"{name} must be a positive finite number or two of them [{unit}], "
                         f"got {_v.show(value)}")
    return arr


def actuator_norm(norm):
    """The reading ``norm`` normalised: ``"box"`` (also ``"inf"``) or ``2`` (also ``"2"``);
    anything else is a one-line ValueError.

    Parameters
    ----------
    norm : str or int
        ``"box"``, ``"inf"``, ``2`` or ``"2"``.

    Returns
    -------
    str or int
        ``"box"`` or ``2`` (one of :data:`ACTUATOR_NORMS`).

    Raises
    ------
    ValueError
        One line, for any other value.
    """
    if norm in ("box", "inf"):
        return "box"
    if norm in (2, "2"):
        return 2
    raise ValueError(f"norm must be one of {ACTUATOR_NORMS}, got {norm!r}")


def _matrix(J):
    J = np.asarray(J, dtype=float)
    if J.shape[-2:] != (2, 2):
        raise ValueError(f"J must have shape (..., 2, 2), got {J.shape}")
    return J


def guaranteed_speed(J, w, norm="box"):
    """Platform speed reachable in every direction under actuator rate limits.

    Parameters
    ----------
    J : array_like, shape (..., 2, 2)
        Jacobian with ``q_dot = J p_dot`` [actuator unit / L].
    w : float or (float, float)
        Rate limits ``|q_dot_i| <= w_i`` [rad/s or L/s], > 0.
    norm : {"box", 2}
        ``"box"``: each actuator on its own, ``min_i w_i / ||row_i(J)||``; ``2``: Liu
        2006 eq. (10), ``1 / s_max(diag(w)^-1 J)`` (module docstring for the proof).

    Returns
    -------
    ndarray, shape (...)
        The speed [L/s]; NaN where ``J`` has NaN.
    """
    J = _matrix(J)
    w = _limits("w", w, "actuator unit/s")
    if actuator_norm(norm) == 2:
        return 1.0 / _ix.singular_values(J / w[:, None])[0]
    rows = np.hypot(J[..., 0], J[..., 1])  # (..., 2): ||row_i||
    with np.errstate(divide="ignore"):
        return np.min(w / rows, axis=-1) if rows.size else rows[..., 0]


def guaranteed_force(J, t, norm="box"):
    """Platform force available in every direction under actuator effort limits.

    Parameters
    ----------
    J : array_like, shape (..., 2, 2)
        Jacobian with ``q_dot = J p_dot`` (so ``F = J^T tau``) [actuator unit / L].
    t : float or (float, float)
        Effort limits ``|tau_i| <= t_i`` [N m or N], > 0.
    norm : {"box", 2}
        ``"box"``: the inradius of the parallelogram ``J^T [-t, t]^2``,
        ``t_1 t_2 |det J| / max(t_1 ||row_1(J)||, t_2 ||row_2(J)||)``; ``2``: Liu 2006
        eq. (13), ``s_min(diag(t) J)`` (module docstring for the proof).

    Returns
    -------
    ndarray, shape (...)
        The force [N when ``J`` is per metre]; 0 at a type-II singularity, NaN where
        ``J`` has NaN.
    """
    J = _matrix(J)
    t = _limits("t", t, "N m or N")
    if actuator_norm(norm) == 2:
        return _ix.singular_values(J * t[:, None])[1]
    det = np.abs(J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0])
    e1 = t[0] * np.hypot(J[..., 0, 0], J[..., 0, 1])
    e2 = t[1] * np.hypot(J[..., 1, 0], J[..., 1, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        return t[0] * t[1] * det / np.maximum(e1, e2)


# --------------------------------------------------------------------- datasheets
#: the keys of a motor's datasheet (:class:`Motor`), with their SI units at the motor
MOTOR_KEYS = {"rated_torque": "N m", "peak_torque": "N m", "max_speed": "rad/s", "gear_ratio": "-",
              "rotor_inertia": "kg m^2"}
#: the largest actuator spec file read [bytes]
SPEC_LIMIT = 64 * 1024

_SI = {"rated_torque": {"Nm": 1.0, "N.m": 1.0, "N*m": 1.0, "Nmm": 1e-3, "mNm": 1e-3, "kNm": 1e3,
                        "N": 1.0, "kN": 1e3, "mN": 1e-3},
       "max_speed": {"rad/s": 1.0, "rpm": 2.0 * math.pi / 60.0, "deg/s": math.pi / 180.0, "m/s": 1.0,
                     "mm/s": 1e-3},
       "gear_ratio": {}, "rotor_inertia": {"kgm^2": 1.0, "kgm2": 1.0, "kg": 1.0, "gcm^2": 1e-7, "kgcm^2": 1e-4}}
_SI["peak_torque"] = _SI["rated_torque"]


class _MotorFields(NamedTuple):
    rated_torque: float
    peak_torque: float
    max_speed: float
    gear_ratio: float = 1.0
    rotor_inertia: float = 0.0


class Motor(_MotorFields):
    """One actuator as its datasheet states it, and what its gearbox makes of it.

    Values at the motor, SI: ``rated_torque`` and ``peak_torque`` [N m] (the continuous
    and the short-time torque), ``max_speed`` [rad/s], ``gear_ratio`` ``N`` [-] (motor
    turns per output turn; for a slider driven by a screw of lead ``p`` [m],
    ``N = 2 pi / p`` [rad/m]), ``rotor_inertia`` [kg m^2]. A linear motor: N, m/s, kg and
    ``gear_ratio`` 1. At the output (:attr:`torque`, :attr:`peak`, :attr:`speed`,
    :attr:`reflected_inertia`) a lossless gear multiplies torques by ``N``, divides
    speeds by ``N`` and reflects the rotor's inertia as ``I_r N^2`` (its kinetic energy
    ``1/2 I_r (N q_dot)^2``). A named tuple (JSON writes it as the list of the five
    values in this order, and :func:`read_motors` reads that list back).
    """

    __slots__ = ()

    def __new__(cls, rated_torque, peak_torque, max_speed, gear_ratio=1.0, rotor_inertia=0.0):
        values = dict(rated_torque=rated_torque, peak_torque=peak_torque, max_speed=max_speed,
                      gear_ratio=gear_ratio, rotor_inertia=rotor_inertia)
        for k, v in values.items():
            ok = (isinstance(v, (int, float, np.floating, np.integer)) and not isinstance(v, bool)
                  and math.isfinite(v) and (v >= 0 if k == "rotor_inertia" else v > 0))
            if not ok:
                raise ValueError(f"actuator {k} must be a {'non-negative' if k == 'rotor_inertia' else 'positive'} "
                                 f"finite number [{MOTOR_KEYS[k]}], got {_v.show(v)}")
        if peak_torque < rated_torque:
            raise ValueError(f"actuator peak_torque {peak_torque:g} is below its rated_torque {rated_torque:g} [N m]")
        return super().__new__(cls, *(float(v) for v in values.values()))

    @property
    def torque(self) -> float:
        """Rated (continuous) torque at the output, ``rated_torque x N`` [N m or N]."""
        return self.rated_torque * self.gear_ratio

    @property
    def peak(self) -> float:
        """Peak torque at the output, ``peak_torque x N`` [N m or N]."""
        return self.peak_torque * self.gear_ratio

    @property
    def speed(self) -> float:
        """Largest output rate, ``max_speed / N`` [rad/s or m/s]."""
        return self.max_speed / self.gear_ratio

    @property
    def reflected_inertia(self) -> float:
        """The rotor's inertia seen at the output, ``I_r N^2`` [kg m^2 or kg]."""
        return self.rotor_inertia * self.gear_ratio ** 2


def _si(key, value, where):
    """A datasheet value: a number (SI) or a text with a unit of :data:`_SI`."""
    from mechopt.core import units as _u

    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"{where}: {key} must be a number or a number with a unit, got {_v.show(value)}")
    if isinstance(value, str):
        q = _u.parse(value, f"{where}: {key}")
        unit = q.unit.replace(" ", "")
        if unit and unit not in _SI[key]:
            raise ValueError(f"{where}: unknown unit {q.unit!r} for {key}; use one of "
                             f"{', '.join(_SI[key]) or 'none (a ratio)'}")
        return q.value * (_SI[key][unit] if unit else 1.0)
    return float(value)


def _motor(d, where) -> Motor:
    if isinstance(d, (list, tuple)) and 3 <= len(d) <= 5:  # the values in MOTOR_KEYS order (design.json)
        d = dict(zip(MOTOR_KEYS, d))
    if not isinstance(d, dict):
        raise ValueError(f"{where} must be a table of {', '.join(MOTOR_KEYS)}, got {_v.show(d)}")
    unknown = sorted(set(d) - set(MOTOR_KEYS))
    if unknown:
        raise ValueError(f"{where}: unknown key {unknown[0]!r}; known: {', '.join(MOTOR_KEYS)}")
    missing = [k for k in ("rated_torque", "peak_torque", "max_speed") if k not in d]
    if missing:
        raise ValueError(f"{where}: {missing[0]} is missing (needed: rated_torque, peak_torque, max_speed)")
    return Motor(**{k: _si(k, v, where) for k, v in d.items()})


def _inline(text) -> list:
    """``key=value,...`` per motor, motors separated by ``;``."""
    out = []
    for part in text.split(";"):
        d = {}
        for item in part.split(","):
            key, eq, value = item.partition("=")
            if not eq:
                raise ValueError(f"actuator spec: {item.strip()!r} is not key=value (keys {', '.join(MOTOR_KEYS)})")
            d[key.strip()] = value.strip()
        out.append(d)
    return out


def read_motors(value) -> tuple:
    """The two actuators of an ``--actuator`` spec, ``(Motor, Motor)``.

    Parameters
    ----------
    value : str, path, dict, list or Motor
        An inline spec ``rated_torque=0.32,peak_torque=0.95,max_speed=3000rpm,
        gear_ratio=10,rotor_inertia=4.5e-5`` (both actuators; two separated by ``;``), a
        file ``*.json`` or ``*.toml`` of at most 64 KiB (read by
        :func:`mechopt.core.reading.read_bytes`: a regular file, no link) holding such a
        table, or ``{"motor": table}``, or ``{"motor": [table, table]}`` (one per
        actuator); the same as Python objects. Values are numbers in the SI units of
        :data:`MOTOR_KEYS` or texts with a unit (``0.32Nm``, ``3000rpm``, ``45gcm^2``).

    Returns
    -------
    tuple of Motor
        Two motors (one spec given for both is repeated).

    Raises
    ------
    ValueError
        One line naming the problem (unreadable file, unknown key or unit, missing,
        non-positive or non-finite value, peak below rated, not one or two motors).
    """
    from mechopt.core import reading

    if isinstance(value, Motor):
        items = [value]
    elif isinstance(value, (tuple, list)) and value and all(isinstance(m, Motor) for m in value):
        items = list(value)
    else:
        data, where = value, "actuator spec"
        text = str(value).strip() if isinstance(value, str) or hasattr(value, "__fspath__") else None
        if text is not None and text.lower().endswith((".json", ".toml")):
            where = f"actuator spec {text!r}"
            try:
                raw = reading.read_bytes(text, SPEC_LIMIT, where).decode("utf-8")
                if text.lower().endswith(".json"):
                    data = json.loads(raw)
                else:
                    import tomllib

                    data = tomllib.loads(raw)
            except FileNotFoundError:
                raise ValueError(f"{where}: no such file") from None
            except ImportError:
                raise ValueError(f"{where}: TOML needs Python >= 3.11 (tomllib); give JSON") from None
            except (UnicodeDecodeError, ValueError) as exc:
                msg = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
                raise ValueError(msg if msg.startswith(where) else f"{where} is not valid: {msg}") from None
        elif text is not None:
            data = _inline(text)
        if isinstance(data, dict) and set(data) == {"motor"}:
            data = data["motor"]
        one = isinstance(data, (list, tuple)) and all(isinstance(v, (int, float)) for v in data)
        items = list(data) if isinstance(data, (list, tuple)) and not one else [data]
        items = [_motor(d, where) for d in items]
    if len(items) not in (1, 2):
        raise ValueError(f"an actuator spec gives one motor (both actuators) or two, got {len(items)}")
    return tuple(items) * (2 // len(items))
