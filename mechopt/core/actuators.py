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

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import validation as _v

__all__ = ["ACTUATOR_NORMS", "actuator_norm", "guaranteed_speed", "guaranteed_force"]

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
    anything else is a one-line ValueError."""
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
