"""An accuracy budget: the worst-case platform position error of a mechanism under an
error model (actuator resolution and backlash, joint clearance, link-length and
base-placement tolerances), as a proven upper bound at each pose, and its Monte
Carlo check with the exact forward kinematics of the perturbed mechanism.

The model
---------
:class:`ErrorModel` gives, with explicit units, per actuator the encoder resolution
(counts per revolution for cranks, the length of one count for sliders and struts)
and the backlash (arcmin, or um), per passive joint the radial clearance (um), and
the tolerances of every link length and of every base-joint (guide) coordinate (+/-
um). Each scalar quantity deviates by at most its half width ``t_k`` (a resolution of
``n`` counts per revolution by ``pi / n`` rad, a backlash ``b`` by ``b / 2``, the two
added for one actuator); each clearance is a vector ``delta_j`` in the disk of radius
``c_j`` (the pin anywhere in its bore). The mechanism's own module declares what is
perturbable and how (its :class:`~mechopt.core.error_spec.ErrorSpec`): leg ``i`` holds
the platform point ``P`` on a circle of centre ``C_i`` and radius ``R_i``, functions of
the actuator coordinates and of the deviations; a clearance moves the centres of the
legs it joins.

The bound at a pose (:func:`pose_error`)
----------------------------------------
With ``d_i = P - C_i`` (``|d_i| = R_i``), ``n_i = d_i / R_i`` and the perturbed pose
``P + e``, the closure ``|d_i + e - dC_i| = R_i + dR_i`` is, exactly::

    n_i . e = b_i + r_i,   b_i = n_i . dC_i + dR_i,
    r_i = (dR_i^2 - |e - dC_i|^2) / (2 R_i),

so ``e = N^-1 (b + r)`` with ``N`` the matrix of rows ``n_i`` (singular at a type-II
singularity). First order: ``e1 = N^-1 b_lin``, ``b_lin`` from the analytic derivatives
of the centres and radii (:meth:`~mechopt.core.error_spec.ErrorSpec.circle_jacobian`):
``e1 = sum_k G_k xi_k + sum_j A_j delta_j``, columns ``G_k = N^-1 (n_i . dC_i/dxi_k +
dR_i/dxi_k)_i`` and 2 x 2 blocks ``A_j = N^-1 [n_i^T if leg i holds joint j]``.

* Worst case of the linear map over the box (and the clearance disks): the set of
  ``e1`` is a zonotope plus ellipses, convex, with support function
  ``h(u) = sum_k t_k |G_k . u| + sum_j c_j |A_j^T u|``. Per direction (x or y) the
  worst error is ``h(e_x)``, ``h(e_y)``: the sum of the columns' contributions. The
  farthest point of a convex set from the origin is ``max_u h(u)``; for a box alone
  (a zonotope) it is one of its vertices, the image of a vertex of the box (a convex
  function's maximum over a polytope). Evaluated on ``M`` directions ``u_m`` at equal
  angles: any ``e1`` of norm ``rho`` in direction ``psi`` has a direction ``u_m``
  within ``pi / M`` of ``psi``, so ``max_m h(u_m) >= rho cos(pi / M)``, and
  ``W1 = max_m h(u_m) / cos(pi / M)`` is an upper bound, tight to that factor
  (``M = 64``: 1.0012).
* The remainder. ``e - e1 = N^-1 ((b - b_lin) + r)``: the centres' non-linear part is
  bounded per leg by ``k_i`` (:meth:`~mechopt.core.error_spec.ErrorSpec.centre_curvature`:
  a crank's rotation) and the radii are affine, so ``|b - b_lin| <= |(k_1, k_2)|``.
  With ``m`` a bound on every ``|dC_i|`` and ``|dR_i|`` over the box (sums of the
  columns' contributions, the clearances and ``k_i``), ``|r_i| <= (|e| + m)^2 / (2 R_i)``
  (``|dR^2 - w^2| <= max(dR^2, w^2)``), so ``|r| <= kappa (|e| + m)^2`` with
  ``kappa = sqrt(1/R_1^2 + 1/R_2^2) / 2``. With ``nu = |N^-1|_2`` (closed form) the map
  ``T(e) = N^-1 (b + r(e))``, whose fixed points are the solutions, satisfies
  ``|T(e)| <= W1 + nu |k| + nu kappa (|e| + m)^2``. With ``s = |e| + m`` and
  ``c0 = m + W1 + nu |k|``, ``T`` maps the ball ``|e| <= E = s_- - m`` into itself,
  ``s_- = 2 c0 / (1 + sqrt(1 - 4 nu kappa c0))`` the smaller root of
  ``nu kappa s^2 - s + c0 = 0`` (at the root, ``W1 + nu |k| + nu kappa s_-^2 = E``), so a
  solution lies in it (Brouwer). It is the pose of the nominal assembly mode, continued
  along the deviations ``t xi`` (``t`` from 0 to 1; the same bound holds for each ``t``)
  without meeting a type-II configuration, whenever no point of the ball comes within
  the centres' shift of the line ``C_1 C_2``: ``h > E + (1 + 2 Lambda) m_C`` with ``h``
  the distance of ``P`` from that line, ``m_C`` the largest centre shift and
  ``Lambda = (R_1 + E + m_C) / (|C_2 - C_1| - 2 m_C)`` (a point of the moved line is
  ``C_1' + lambda (C_2' - C_1')``, at most ``(1 + 2 |lambda|) m_C`` from the matching
  point of the nominal line); the two circles then meet transversally all along, and
  the continued solution cannot leave the ball (the quadratic's gap ``(s_-, s_+)``).

The result, ``bound = E = W1 + remainder``, is an upper bound of the position
error of the perturbed mechanism for every deviation within the stated tolerances,
in rounding-free arithmetic (its floating-point evaluation has relative errors of
order 1e-15, negligible beside the ``1/cos(pi/M)`` margin); it is ``inf`` where the
quadratic has no root or the guard fails (at or next to a type-II singularity, or
tolerances too large for the geometry). The assumptions: rigid links, the stated
clearances as the only play, the tool point on the pin of the platform joint
carried by leg 2 (clearances in the legs' circle centres,
:mod:`mechopt.core.error_spec`).

Over given points (:func:`max_error`) the bound is the maximum of the pose bounds, e.g.
at the task samples of ``mechopt design`` (:func:`task_points`: 192 boundary points and
a 13 x 13 grid). Over a task (:func:`task_max_error`, the ``--max-error`` requirement)
the maximum is located on the samples and refined by the zoom searches of
:mod:`mechopt.analysis.sampling`, like the minima of the other requirements: each
point's number is proven, the maximum over the region is located (to the searches'
stated tolerance), not proven between the points.

Monte Carlo (:func:`monte_carlo`): deviations drawn in the box (uniformly, or at its
vertices with the clearances on their circles, where the maximum of a near-linear
map lies, plus the vertex the linear map predicts as the worst), each perturbed
mechanism solved exactly (:func:`perturbed_fk`: the circles of the mechanism's
module intersected on the nominal pose's side of ``C_1 C_2``), not linearised.

References
----------
Chen, Wang, Lin (2013), Mech. Mach. Theory 64: the error of a 5R under input
uncertainty and joint clearance (the clearance as a vector in a disk, as here).
Merlet (2006), Parallel Robots, 2nd ed., Springer, ch. 5 (accuracy analysis).
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, fields
from functools import lru_cache
from pathlib import Path

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.protocol import as_points

__all__ = ["ErrorModel", "load_error_model", "pose_error", "max_error", "perturbed_fk", "monte_carlo",
           "task_points", "parse_length_um", "parse_error_model", "DIRECTIONS", "UM_PER_UNIT", "PER_MOTOR",
           "POSE_KEYS", "errors_at", "parse_poses", "task_max_error"]

#: directions of the support function (the linear worst case is within 1/cos(pi/M) of exact)
DIRECTIONS = 64
#: micrometres per task length unit
UM_PER_UNIT = {"mm": 1e3, "cm": 1e4, "m": 1e6, "in": 25400.0}
#: the fields of :class:`ErrorModel` that take one value per motor
PER_MOTOR = ("encoder_counts", "backlash_arcmin", "resolution_um", "backlash_um")


@dataclass(frozen=True)
class ErrorModel:
    """The error budget of a mechanism, units in the names (module docstring).

    The four actuator fields (:data:`PER_MOTOR`) take one number for both motors or a
    pair ``(motor 1, motor 2)``, each motor its own encoder or backlash (motor ``i``
    drives the ``i``-th actuator coordinate of the mechanism, ``q1`` or ``theta1`` first;
    in a ``key=value`` text the pair is written ``16384/4096``).

    Parameters
    ----------
    encoder_counts : float or (float, float)
        Counts per revolution of each crank's encoder (0: exact); the angle is known
        to +/- half a count, ``pi / counts`` [rad].
    backlash_arcmin : float or (float, float)
        Lost motion of each crank's drive [arcmin] (the full width: +/- half of it).
    resolution_um : float or (float, float)
        One count of each slider's or strut's scale [um] (+/- half of it).
    backlash_um : float or (float, float)
        Lost motion of each slider's or strut's drive [um] (+/- half of it).
    clearance_um : float
        Radial clearance of each passive joint [um]: the pin's centre anywhere within
        this distance of the bore's.
    link_tol_um : float
        Tolerance on each link length, +/- [um].
    base_tol_um : float
        Tolerance on each coordinate of each base joint (guide), +/- [um].
    """

    encoder_counts: float = 0.0
    backlash_arcmin: float = 0.0
    resolution_um: float = 0.0
    backlash_um: float = 0.0
    clearance_um: float = 0.0
    link_tol_um: float = 0.0
    base_tol_um: float = 0.0

    def __post_init__(self):
        for f in fields(self):
            raw = getattr(self, f.name)
            if f.name in PER_MOTOR and isinstance(raw, str) and "/" in raw:
                raw = raw.split("/")
            if f.name in PER_MOTOR and isinstance(raw, (list, tuple, np.ndarray)):
                if len(raw) != 2:
                    raise ValueError(f"{f.name} takes one number or one per motor (2), got {_v.show(raw)}")
                val = tuple(_v.finite_number(f"{f.name} of motor {i + 1}", r) for i, r in enumerate(raw))
            else:
                val = _v.finite_number(f.name, raw)
            if min(np.atleast_1d(val)) < 0:
                raise ValueError(f"{f.name} must be >= 0, got {_v.show(getattr(self, f.name))}")
            object.__setattr__(self, f.name, val)

    def motor(self, name: str, i: int) -> float:
        """The value of the actuator field ``name`` (:data:`PER_MOTOR`) for motor ``i`` (0 or 1).

        Parameters
        ----------
        name : str
            One of :data:`PER_MOTOR`.
        i : int
            The motor, 0 or 1.

        Returns
        -------
        float
            The field's value for that motor (its single value when it holds one for both).
        """
        v = getattr(self, name)
        return v[i] if isinstance(v, tuple) else v

    @classmethod
    def from_dict(cls, d) -> "ErrorModel":
        """The model of ``{field: value}`` (unknown keys refused).

        Parameters
        ----------
        d : dict
            ``{field: value}``.

        Returns
        -------
        ErrorModel
            The model.

        Raises
        ------
        ValueError
            One line, for an unknown key or an invalid value.
        """
        if not isinstance(d, dict):
            raise ValueError(f"an error model is a table of numbers, got {_v.show(d)}")
        known = {f.name for f in fields(cls)}
        bad = sorted(set(d) - known)
        if bad:
            raise ValueError(f"unknown error model key(s) {', '.join(bad)}; known: {', '.join(sorted(known))}")
        return cls(**d)

    def half_widths(self, spec, angular: bool, unit: str) -> np.ndarray:
        """Half width of each scalar of ``spec`` (rad for crank angles, else [unit]).

        Parameters
        ----------
        spec : mechopt.core.error_spec.ErrorSpec
            The mechanism's error model.
        angular : bool
            Whether the actuators are cranks.
        unit : str
            The length unit of the mechanism.

        Returns
        -------
        ndarray
            One half width per scalar [rad or unit].
        """
        to_l = 1.0 / _um_per(unit)
        act = []
        for i in (0, 1):
            if angular:
                counts = self.motor("encoder_counts", i)
                act.append((math.pi / counts if counts > 0 else 0.0)
                           + 0.5 * math.radians(self.motor("backlash_arcmin", i) / 60.0))
            else:
                act.append(0.5 * (self.motor("resolution_um", i) + self.motor("backlash_um", i)) * to_l)
        out, motor = [], 0
        for _, kind in spec.scalars:
            if kind == "actuator":
                out.append(act[min(motor, 1)])
                motor += 1
            else:
                out.append({"link": self.link_tol_um, "base": self.base_tol_um}[kind] * to_l)
        return np.array(out)

    def clearances(self, spec, unit: str) -> np.ndarray:
        """Radial clearance [unit] of each passive joint of ``spec``.

        Parameters
        ----------
        spec : mechopt.core.error_spec.ErrorSpec
            The mechanism's error model.
        unit : str
            The length unit of the mechanism.

        Returns
        -------
        ndarray
            One clearance per passive joint [unit].
        """
        return np.full(len(spec.joints), self.clearance_um / _um_per(unit))


def parse_length_um(text) -> float:
    """A positive length with its unit (``"20um"``, ``"20 µm"``, ``"0.05mm"``, ``"1e-5 m"``;
    units ``um``/``µm`` and those of :data:`UM_PER_UNIT`) in micrometres, e.g. the
    value of a ``--max-error`` option. ValueError (one line) otherwise.

    Parameters
    ----------
    text : str
        A length with its unit.

    Returns
    -------
    float
        The length [um].

    Raises
    ------
    ValueError
        One line, for text that is not a positive length with a known unit.
    """
    import re

    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*([a-zA-Zµ]+)\s*", str(text))
    units = {"um": 1.0, "µm": 1.0, **UM_PER_UNIT}
    if not m or m.group(2) not in units:
        raise ValueError(f"a length needs a number and a unit ({', '.join(units)}), e.g. 20um, got {_v.show(text)}")
    try:
        value = float(m.group(1))
    except ValueError:
        raise ValueError(f"a length needs a number and a unit, e.g. 20um, got {_v.show(text)}") from None
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"a length must be positive and finite, got {_v.show(text)}")
    return value * units[m.group(2)]


def _um_per(unit) -> float:
    return UM_PER_UNIT[_v.choice("unit", unit, tuple(UM_PER_UNIT))]


def load_error_model(path) -> ErrorModel:
    """:class:`ErrorModel` from a JSON file (an object) or a TOML file (``.toml``: a
    table of the same keys); ValueError naming the file when it cannot be read.

    Parameters
    ----------
    path : str or Path
        A JSON or TOML file.

    Returns
    -------
    ErrorModel
        The model.

    Raises
    ------
    ValueError
        One line naming the file, when it cannot be read or holds an invalid model.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise ValueError(f"cannot read the error model {str(path)!r} ({exc.strerror})") from None
    try:
        if path.suffix.lower() == ".toml":
            try:
                import tomllib
            except ImportError:  # Python 3.10
                raise ValueError(f"reading {str(path)!r} needs Python >= 3.11 (tomllib); give the model as JSON") from None
            d = tomllib.loads(text)
        else:
            d = json.loads(text)
    except (ValueError, UnicodeDecodeError) as exc:
        if "tomllib" in str(exc):
            raise
        raise ValueError(f"unreadable error model {str(path)!r}: {' '.join(str(exc).split())}") from None
    return ErrorModel.from_dict(d)


def parse_error_model(text) -> ErrorModel:
    """An :class:`ErrorModel` from a command-line text: ``key=value`` pairs separated by
    commas (``encoder_counts=16384,clearance_um=5``; one value per motor as
    ``encoder_counts=16384/4096``) or the path of a JSON/TOML file
    (:func:`load_error_model`); an :class:`ErrorModel` or a dict passes through.

    Parameters
    ----------
    text : str
        ``key=value`` pairs or a file's path.

    Returns
    -------
    ErrorModel
        The model.

    Raises
    ------
    ValueError
        One line, for unknown keys, invalid values or an unreadable file.
    """
    if isinstance(text, ErrorModel):
        return text
    if isinstance(text, dict):
        return ErrorModel.from_dict(text)
    text = str(text)
    if "=" in text and not Path(text).exists():
        d = {}
        for part in (p.strip() for p in text.split(",") if p.strip()):
            key, eq, val = part.partition("=")
            if not eq:
                raise ValueError(f"an error model is key=value pairs separated by commas, got {text!r}")
            d[key.strip()] = val.strip()
        return ErrorModel.from_dict(d)
    return load_error_model(text)


def _spec(mech):
    cls = type(mech).error_spec
    if cls is None:
        raise ValueError(f"{type(mech).__name__} declares no error model (error_spec)")
    spec = cls()
    spec.check(mech)
    return spec


@lru_cache(maxsize=None)
def _directions(m=DIRECTIONS):
    """The first half of ``m`` directions at equal angles (the sets bounded here are
    symmetric about the origin, ``h(-u) = h(u)``: the other half adds nothing); read-only."""
    a = 2.0 * np.pi * np.arange((m + 1) // 2) / m
    out = np.stack([np.cos(a), np.sin(a)], -1)
    out.setflags(write=False)
    return out


def _linear_terms(mech, spec, x, y):
    """``(G, A, parts)``: the columns ``G`` (..., 2, K) of the scalars, the blocks ``A``
    (..., J, 2, 2) of the clearances and the pieces of the remainder bound."""
    x, y = as_points(x, y)
    q1, q2, ok = mech.ik(x, y)
    c1x, c1y, r1, c2x, c2y, r2 = spec.circles(mech, q1, q2, {})
    with np.errstate(divide="ignore", invalid="ignore"):
        n = np.stack([np.stack([(x - c1x) / r1, (y - c1y) / r1], -1),
                      np.stack([(x - c2x) / r2, (y - c2y) / r2], -1)], -2)  # (..., 2 legs, 2)
        det = n[..., 0, 0] * n[..., 1, 1] - n[..., 0, 1] * n[..., 1, 0]
        Ninv = np.stack([np.stack([n[..., 1, 1], -n[..., 0, 1]], -1),
                         np.stack([-n[..., 1, 0], n[..., 0, 0]], -1)], -2) / det[..., None, None]
    D = spec.circle_jacobian(mech, q1, q2)  # (..., 6, K)
    dC = np.stack([D[..., 0:2, :], D[..., 3:5, :]], -3)  # (..., 2 legs, 2, K)
    dR = np.stack([D[..., 2, :], D[..., 5, :]], -2)  # (..., 2 legs, K)
    K = np.einsum("...ic,...ick->...ik", n, dC) + dR  # (..., 2 legs, K)
    G = Ninv @ K
    blocks = []
    for _, legs in spec.joints:
        M = np.zeros_like(n)
        for i in legs:
            M[..., i, :] = n[..., i, :]
        blocks.append(Ninv @ M)
    A = np.stack(blocks, -3) if blocks else np.zeros(n.shape[:-2] + (0, 2, 2))
    parts = dict(q=(q1, q2), ok=ok, n=n, Ninv=Ninv, K=K, dC=dC, dR=dR, R=(r1, r2),
                 C=((c1x, c1y), (c2x, c2y)))
    return G, A, parts


def _support(G, A, t, c, U):
    """``h(u)`` at the directions ``U`` (M, 2): shape (..., M). One matrix product: the
    rows ``t_k G_k`` and the rows of ``c_j A_j^T`` times the directions; the first
    summed in absolute value, the second in pairs' norms (``|A_j^T u|``)."""
    shape, k = G.shape[:-2], G.shape[-1]
    live = [j for j, cj in enumerate(c) if cj > 0]
    rows = [np.swapaxes(G * t, -1, -2)]  # (..., K, 2)
    if live:
        B = np.swapaxes(A[..., live, :, :], -1, -2) * np.asarray(c)[live][:, None, None]  # c_j A_j^T
        rows.append(B.reshape(shape + (2 * len(live), 2)))
    V = np.concatenate(rows, -2)
    P = (V.reshape(-1, 2) @ U.T).reshape(V.shape[:-1] + (U.shape[0],))  # (..., R, M)
    h = np.abs(P[..., :k, :]).sum(-2)
    if live:
        Q = P[..., k:, :].reshape(shape + (len(live), 2, U.shape[0]))
        h = h + np.sqrt((Q * Q).sum(-2)).sum(-2)
    return h


def _norm2(M):
    """Spectral norm of 2 x 2 matrices (..., 2, 2), closed form: the largest singular
    value ``sqrt((F + sqrt(F^2 - 4 det^2)) / 2)``, ``F`` the squared Frobenius norm."""
    F = (M * M).sum((-2, -1))
    det = M[..., 0, 0] * M[..., 1, 1] - M[..., 0, 1] * M[..., 1, 0]
    return np.sqrt(0.5 * (F + np.sqrt(np.maximum(F * F - 4.0 * det * det, 0.0))))


def pose_error(mech, model: ErrorModel, x, y, unit: str = "mm", directions: int = DIRECTIONS) -> dict:
    """The proven worst-case position error at the poses ``(x, y)`` [unit, the
    mechanism's frame] under ``model`` (module docstring: the argument).

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with an :attr:`~mechopt.core.protocol.PlanarMechanism.error_spec`.
    model : ErrorModel
        The tolerances.
    x, y : array_like
        Poses [unit], broadcast together.
    unit : str
        The length unit of the mechanism and the poses (``mm``, ``cm``, ``m``, ``in``).
    directions : int
        Directions ``M`` of the support function (the linear worst case to 1/cos(pi/M)).

    Returns
    -------
    dict of arrays [unit], the poses' shape
        ``bound`` (the upper bound of ``|e|`` over the tolerance box; inf where it cannot
        be proven, NaN where unreachable), ``linear`` (``W1``, the first-order worst
        case, an upper bound of it), ``linear_low`` (``max_m h(u_m)``, attained by the
        first-order map), ``remainder`` (the second-order bound, ``bound - linear``),
        ``x``, ``y`` (the first-order worst error along each axis, exact), ``worst_dir``
        (the angle [rad] of the direction of ``linear_low``).
    """
    spec = _spec(mech)
    t = model.half_widths(spec, mech.angular_joints, unit)
    c = model.clearances(spec, unit)
    G, A, p = _linear_terms(mech, spec, x, y)
    M = _v.integer("directions", directions, 4)
    U = _directions(M)
    h = _support(G, A, t, c, U)
    low = h.max(-1)
    worst_dir = np.arctan2(U[:, 1], U[:, 0])[np.argmax(np.nan_to_num(h, nan=-1.0), -1)]
    W1 = low / math.cos(math.pi / M)
    # the axes are directions 0 and M/4 when 4 divides M (cos(pi/2) = 6e-17: exact to rounding)
    axes = h[..., [0, M // 4]] if M % 4 == 0 else _support(G, A, t, c, np.eye(2))
    # --- the remainder (module docstring) ---
    r1, r2 = p["R"]
    q1, q2 = p["q"]
    half = {name: t[i] for i, (name, _) in enumerate(spec.scalars)}
    k1, k2 = spec.centre_curvature(mech, q1, q2, half)
    kk = np.stack(np.broadcast_arrays(k1, k2, r1)[:2], -1)  # (..., 2 legs)
    clear_leg = np.array([sum(c[j] for j, (_, legs) in enumerate(spec.joints) if i in legs) for i in (0, 1)])
    mC = np.linalg.norm(p["dC"], axis=-2) @ t + clear_leg + kk
    mR = np.abs(p["dR"]) @ t
    m = np.maximum(mC, mR).max(-1)
    nu = _norm2(p["Ninv"])
    with np.errstate(divide="ignore", invalid="ignore"):
        kap = 0.5 * np.sqrt(1.0 / (r1 * r1) + 1.0 / (r2 * r2))
        c0 = m + W1 + nu * np.hypot(kk[..., 0], kk[..., 1])
        disc = 1.0 - 4.0 * nu * kap * c0
        s_minus = 2.0 * c0 / (1.0 + np.sqrt(np.where(disc >= 0, disc, np.nan)))
        E = s_minus - m
        rem = E - W1
        # the guard: the ball stays away from the line C1 C2 (no type-II configuration)
        (c1x, c1y), (c2x, c2y) = p["C"]
        x_, y_ = as_points(x, y)
        lx, ly = c2x - c1x, c2y - c1y
        span = np.hypot(lx, ly)
        h_line = np.abs(lx * (y_ - c1y) - ly * (x_ - c1x)) / span
        mc = mC.max(-1)
        lam = (r1 + E + mc) / (span - 2.0 * mc)
        safe = (disc >= 0) & (span > 2.0 * mc) & (h_line > E + (1.0 + 2.0 * lam) * mc)
    bound = np.where(safe, E, np.inf)
    ok = p["ok"]
    nan = lambda v: np.where(ok, v, np.nan)  # noqa: E731
    return dict(bound=nan(bound), linear=nan(W1), linear_low=nan(low), remainder=nan(np.where(safe, rem, np.inf)),
                x=nan(axes[..., 0]), y=nan(axes[..., 1]),
                worst_dir=nan(worst_dir))


def max_error(mech, model: ErrorModel, x, y, unit: str = "mm") -> float:
    """The largest :func:`pose_error` bound [unit] over the points ``(x, y)`` (the
    mechanism's frame); inf when one is unreachable or unproven. Each pose's bound is
    proven; the maximum over a region is as good as the points sample it.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism [unit].
    model : ErrorModel
        The tolerances.
    x, y : array_like
        Poses [unit], the mechanism's frame.
    unit : str
        The length unit of the mechanism.

    Returns
    -------
    float
        The largest bound [unit] (inf when one pose is unreachable or unproven).
    """
    b = pose_error(mech, model, x, y, unit)["bound"]
    return float(np.max(np.where(np.isnan(b), np.inf, b))) if b.size else 0.0


#: the keys of :func:`errors_at` (``mechopt evaluate --error-model``; docs/outputs.md)
POSE_KEYS = ("error_at", "error_bound_um", "error_linear_um", "error_remainder_um", "error_x_um", "error_y_um")


def parse_poses(text) -> list:
    """Poses ``[[x, y], ...]`` from ``"x,y"`` texts (one or a list of them, e.g. the
    repeated ``--at`` of ``mechopt evaluate``) or pairs of numbers; ValueError (one
    line) otherwise.

    Parameters
    ----------
    text : str or sequence
        One ``"x,y"`` text, or a list of ``"x,y"`` texts or ``(x, y)`` pairs [unit].

    Returns
    -------
    list of [float, float]
        The poses ``[[x, y], ...]`` [unit].

    Raises
    ------
    ValueError
        One line, for an item that is not two numbers, a coordinate that is not finite
        or is beyond :data:`~mechopt.core.validation.POINT_MAX`, or no pose at all.
    """
    items = [text] if isinstance(text, str) else list(text)
    out = []
    for item in items:
        parts = item.split(",") if isinstance(item, str) else list(item)
        if len(parts) != 2:
            raise ValueError(f"a pose is two numbers x,y, got {_v.show(item)}")
        out.append([_v.position("pose x", parts[0]), _v.position("pose y", parts[1])])
    if not out:
        raise ValueError("give at least one pose x,y")
    return out


def errors_at(mech, model: ErrorModel, poses, unit: str = "mm") -> dict:
    """The proven worst-case position error of ``mech`` under ``model`` at each pose.

    Parameters
    ----------
    mech : PlanarMechanism
        A mechanism with an error model (:func:`pose_error`).
    model : ErrorModel
        The tolerances.
    poses : sequence of (x, y)
        Poses [unit] in the mechanism's frame (``"x,y"`` texts accepted, :func:`parse_poses`).
    unit : str
        The length unit of the mechanism's lengths and the poses.

    Returns
    -------
    dict
        The keys :data:`POSE_KEYS`, each a list with one entry per pose: ``error_at``
        the pose ``[x, y]`` [unit], ``error_bound_um`` the proven bound [um] (inf where
        not proven, NaN where unreachable), ``error_linear_um`` its first-order part and
        ``error_remainder_um`` its second-order remainder [um], ``error_x_um``,
        ``error_y_um`` the first-order worst error along each axis [um].
    """
    pts = np.array(parse_poses(poses), dtype=float)
    pe = pose_error(mech, model, pts[:, 0], pts[:, 1], unit)
    um = UM_PER_UNIT[unit]
    out = {"error_at": pts.tolist()}
    for key, part in (("error_bound_um", "bound"), ("error_linear_um", "linear"),
                      ("error_remainder_um", "remainder"), ("error_x_um", "x"), ("error_y_um", "y")):
        out[key] = [float(v) for v in pe[part] * um]
    return {k: out[k] for k in POSE_KEYS}


def task_max_error(mech, model: ErrorModel, s: dict, to_mech=None, unit: str = "mm", refine: bool = True,
                   vals=None) -> float:
    """The largest :func:`pose_error` bound [unit] over a task: located on its samples
    and refined by the zoom searches of :mod:`mechopt.analysis.sampling`
    (:func:`~mechopt.analysis.sampling.region_mins` on the negated bound: boundary and
    interior maxima placed to ``h_b/2048`` and ``h/64``).

    Each point's bound is proven; the maximum over the task is located, to the stated
    tolerance of the zoom searches (the samples resolve the peaks of the bound), not
    proven between the points. ``inf`` when a point is unreachable or unproven.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism (with an error model).
    model : ErrorModel
        The tolerances.
    s : dict
        The task's samples (:func:`mechopt.analysis.sampling.samples`), in the task frame.
    to_mech : callable, optional
        ``to_mech(x, y)``: task points in the mechanism's frame (default: the same frame).
    unit : str
        The length unit of the task and the mechanism.
    refine : bool
        False: the samples' maximum alone.
    vals : array, optional
        The negated bound at ``s["allx"], s["ally"]`` when already computed.

    Returns
    -------
    float
        The largest bound over the task [unit] (inf when a point is unreachable or unproven).
    """
    from mechopt.analysis.sampling import region_mins

    def f(x, y):
        b = pose_error(mech, model, *(to_mech(x, y) if to_mech else (x, y)), unit)["bound"]
        return -np.where(np.isnan(b), np.inf, b)[None]

    if vals is None:
        vals = f(s["allx"], s["ally"])[0]
    return -region_mins(s, f, refine, np.asarray(vals)[None])[0]


def task_points(task, n_boundary: int = 192, n_interior: int = 13):
    """``(x, y)`` [task unit, task frame]: the samples of one evaluation of ``mechopt
    design`` (:func:`mechopt.analysis.sampling.samples`: ``n_boundary`` points along the
    boundary at uniform arc length, every vertex included, and an ``n_interior`` x
    ``n_interior`` grid over the box, kept inside); a point task's points.

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The placed task.
    n_boundary : int
        Boundary points.
    n_interior : int
        Interior grid nodes per side.

    Returns
    -------
    x, y : ndarray
        The samples [task unit, task frame].
    """
    from mechopt.analysis.sampling import Sampling, samples

    s = samples(task, Sampling(n_boundary, n_interior))
    return s["allx"], s["ally"]


def perturbed_fk(mech, q1, q2, d, delta, side):
    """The exact pose ``(x, y)`` of the perturbed mechanism: the circles of its module
    (:meth:`~mechopt.core.error_spec.ErrorSpec.circles` at actuator values ``q1, q2``
    with the scalar deviations ``d``, ``{name: array}``), their centres moved by the
    clearance vectors ``delta`` (``{joint: (dx, dy)}``), intersected on the side
    ``side`` (+1: left of ``C_1 -> C_2``, -1: right). NaN where they do not meet.

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism [unit].
    q1, q2 : array_like
        Actuator values [rad or unit].
    d : dict
        ``{name: array}`` scalar deviations.
    delta : dict
        ``{joint: (dx, dy)}`` clearance vectors [unit].
    side : int
        +1 or -1.

    Returns
    -------
    x, y : ndarray
        The pose [unit].
    """
    spec = _spec(mech)
    c1x, c1y, r1, c2x, c2y, r2 = spec.circles(mech, q1, q2, d)
    for name, legs in spec.joints:
        if name in delta:
            dx, dy = delta[name]
            if 0 in legs:
                c1x, c1y = c1x + dx, c1y + dy
            if 1 in legs:
                c2x, c2y = c2x + dx, c2y + dy
    mx, my = c2x - c1x, c2y - c1y
    m2 = mx * mx + my * my
    with np.errstate(divide="ignore", invalid="ignore"):
        u = (r1 * r1 - r2 * r2 + m2) / (2.0 * m2)
        h2 = r1 * r1 / m2 - u * u
        h = np.sqrt(np.where(h2 >= 0, h2, np.nan)) * side
    return c1x + u * mx - h * my, c1y + u * my + h * mx


def _side(mech, spec, x, y, q1, q2):
    c1x, c1y, _, c2x, c2y, _ = spec.circles(mech, q1, q2, {})
    return np.where((c2x - c1x) * (y - c1y) - (c2y - c1y) * (x - c1x) >= 0, 1.0, -1.0)


def _errors(px, py, x, y):
    """``|P' - P|``, inf where the perturbed circles do not meet (no pose at all)."""
    e = np.hypot(px - x, py - y)
    return np.where(np.isnan(e), np.inf, e)


def monte_carlo(mech, model: ErrorModel, x, y, samples: int = 1000, unit: str = "mm", seed: int = 1,
                draw: str = "vertices", worst: bool = True, chunk: int = 250_000):
    """The largest exact position error [unit] of ``samples`` perturbed mechanisms at
    each pose ``(x, y)`` (the mechanism's frame): deviations drawn in the tolerance box
    (``draw="vertices"``: each scalar at +/- its half width and each clearance on its
    circle, with equal odds; ``"uniform"``: uniformly in the box and the disks), each
    pose solved by :func:`perturbed_fk`. With ``worst``, the first draw at each pose is
    the vertex the first-order map predicts as the worst (the scalars at the signs of
    ``G_k . u``, the clearances along ``A_j^T u``, ``u`` the worst direction). At most
    ``chunk`` draws x poses are solved at once (memory: about 30 arrays of that size).
    Returns an array [unit] of the poses' shape (NaN where unreachable, inf where a
    perturbed mechanism does not assemble).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism [unit].
    model : ErrorModel
        The tolerances.
    x, y : array_like
        Poses [unit], the mechanism's frame.
    samples : int
        Perturbed mechanisms per pose.
    unit : str
        The length unit of the mechanism.
    seed : int
        Random seed.
    draw : str
        ``"vertices"`` or ``"uniform"``.
    worst : bool
        Draw the predicted worst vertex first.
    chunk : int
        Draws x poses solved at once.

    Returns
    -------
    ndarray
        The largest error [unit] per pose.
    """
    spec = _spec(mech)
    draw = _v.choice("draw", draw, ("vertices", "uniform"))
    n = _v.integer("samples", samples, 1)
    x, y = as_points(x, y)
    shape = x.shape
    x, y = x.ravel(), y.ravel()
    q1, q2, ok = mech.ik(x, y)
    side = _side(mech, spec, x, y, q1, q2)
    t = model.half_widths(spec, mech.angular_joints, unit)
    c = model.clearances(spec, unit)
    rng = np.random.default_rng(seed)
    best = np.zeros(x.shape)
    if worst:
        G, A, _ = _linear_terms(mech, spec, x, y)
        a = pose_error(mech, model, x, y, unit)["worst_dir"]
        u = np.stack([np.cos(a), np.sin(a)], -1)
        sgn = np.sign(np.einsum("pck,pc->pk", G, u))
        d = {name: (sgn[:, k] * t[k])[None] for k, (name, _) in enumerate(spec.scalars)}
        delta = {}
        for j, (name, _) in enumerate(spec.joints):
            v = np.einsum("pca,pc->pa", A[:, j], u)
            with np.errstate(divide="ignore", invalid="ignore"):
                v = v / np.linalg.norm(v, axis=-1, keepdims=True) * c[j]
            v = np.nan_to_num(v)
            delta[name] = (v[None, :, 0], v[None, :, 1])
        px, py = perturbed_fk(mech, q1[None], q2[None], d, delta, side[None])
        best = np.maximum(best, _errors(px, py, x, y)[0])
    per = max(1, chunk // max(1, x.size))
    done = 0
    while done < n:
        k = min(per, n - done)
        done += k
        if draw == "vertices":
            d = {name: rng.choice((-1.0, 1.0), (k, x.size)) * t[i] for i, (name, _) in enumerate(spec.scalars)}
            rad = [np.full((k, x.size), cj) for cj in c]
        else:
            d = {name: rng.uniform(-1.0, 1.0, (k, x.size)) * t[i] for i, (name, _) in enumerate(spec.scalars)}
            rad = [np.sqrt(rng.uniform(0.0, 1.0, (k, x.size))) * cj for cj in c]
        delta = {}
        for j, (name, _) in enumerate(spec.joints):
            ang = rng.uniform(0.0, 2 * np.pi, (k, x.size))
            delta[name] = (rad[j] * np.cos(ang), rad[j] * np.sin(ang))
        px, py = perturbed_fk(mech, q1[None], q2[None], d, delta, side[None])
        best = np.maximum(best, _errors(px, py, x, y).max(0))
    return np.where(ok, best, np.nan).reshape(shape)
