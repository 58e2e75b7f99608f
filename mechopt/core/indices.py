"""Local performance indices as pure functions of 2x2 Jacobian arrays.

Convention (Liu 2006, eq. 1): ``theta_dot = J p_dot``. With the singular values
``s_max >= s_min`` of ``J``:

==========================  =========================  ==============================
index                       value                      source
==========================  =========================  ==============================
LCI = 1/kappa_J             s_min / s_max              Liu eq. (3), Le eq. (20)
``|V|max``, ``|V|min``      1/s_min, 1/s_max           Liu eq. (10)
``|tau|max``, ``|tau|min``  s_max, s_min               Liu eq. (13)
``|D|max``, ``|D|min``      1/s_min^2, 1/s_max^2       Liu eq. (18), k_p = 1
TQI                         2 kappa/(kappa^2 + 1)      Stan 2008 eq. (9), Frobenius
manipulability              ``1/|det J|``              ``sqrt(det(J^-1 J^-T))``
==========================  =========================  ==============================

All functions broadcast over leading axes: ``J`` has shape ``(..., 2, 2)``. Where
``J`` contains NaN (unreachable pose) the result is NaN; callers decide how to
count such points (``lci`` treats them as 0, see :func:`lci`).
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core.jit import Twin, jitable

__all__ = [
    "lci_of_matrix",
    "box_rows_of_matrix",
    "two_smax_squared",
    "lci_of_entries",
    "singular_values",
    "lci",
    "velocity_extremes",
    "payload_extremes",
    "stiffness_extremes",
    "tqi",
    "manipulability",
    "LOCAL_INDEX_NAMES",
    "GLOBAL_INDEX_NAMES",
    "local_indices",
]

#: the global indices of Liu 2006, in the order of every table and array: GCI (eq. 4,
#: the mean LCI over the MIC), MCI (the largest LCI over the MIC), and the extremes of
#: GVI (eq. 11), GPI (eq. 14) and GSI (eq. 19), means over the disk of radius r_MIC / 2
GLOBAL_INDEX_NAMES = (
    "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min",
)

LOCAL_INDEX_NAMES = (
    "lci",
    "v_max",
    "v_min",
    "tau_max",
    "tau_min",
    "d_max",
    "d_min",
)


def _entries(J):
    J = np.asarray(J, dtype=float)
    if J.shape[-2:] != (2, 2):
        raise ValueError(f"J must have shape (..., 2, 2), got {J.shape}")
    return J[..., 0, 0], J[..., 0, 1], J[..., 1, 0], J[..., 1, 1]


@jitable
def two_smax_squared(a, b, c, d):
    """``2 s_max^2 = S + sqrt(S^2 - 4 det^2)`` of ``[[a, b], [c, d]]`` (``S`` the squared
    Frobenius norm), with the discriminant as ``sqrt(P Q)``,
    ``P = S - 2 det = (a - d)^2 + (b + c)^2`` and ``Q = S + 2 det = (a + d)^2 + (b - c)^2``:
    each factor is a sum of squares, so nothing cancels. (``P Q`` overflows only for
    entries beyond about 1e77, far from any Jacobian of admissible lengths; one root
    instead of two keeps the compiled LCI loop at 1.8e8 points/s, against 4e7.)

    Scalars or arrays; compiled kernels call it too (:func:`mechopt.core.jit.jitable`).

    Parameters
    ----------
    a, b, c, d : float or ndarray
        The entries of ``[[a, b], [c, d]]``.

    Returns
    -------
    float or ndarray
        ``2 s_max^2`` (the entries' unit squared).
    """
    S = a * a + b * b + c * c + d * d
    return S + np.sqrt(((a - d) ** 2 + (b + c) ** 2) * ((a + d) ** 2 + (b - c) ** 2))


@jitable
def lci_of_entries(a, b, c, d):
    """LCI ``s_min / s_max = |det| / s_max^2 = 2 |ad - bc| / (2 s_max^2)`` of
    ``[[a, b], [c, d]]`` (Liu 2006 eq. 3): the one LCI formula of the package.

    NaN for the zero matrix (0/0) and for NaN entries; every caller maps those to 0.
    The LCI is invariant under scaling the matrix and swapping its rows, so the
    five-bar kernels pass a scaled, row-swapped Jacobian (no division per entry).

    Parameters
    ----------
    a, b, c, d : float or ndarray
        The entries of ``[[a, b], [c, d]]``.

    Returns
    -------
    float or ndarray
        The LCI, in [0, 1] (NaN for the zero matrix).
    """
    return 2.0 * abs(a * d - b * c) / two_smax_squared(a, b, c, d)


def _scaled_entries(J):
    """``(a, b, c, d, e)``: the entries of each matrix times ``2^-e``, ``2^e`` the power of
    two next above the largest magnitude among them. Exact (a power of two), so the
    LCI is the unscaled one bit for bit and singular values scale back exactly
    (``ldexp``); it keeps :func:`two_smax_squared`'s ``P Q`` (entries of size about 1)
    from overflowing or underflowing for any finite matrix."""
    a, b, c, d = _entries(J)
    m = np.maximum(np.maximum(np.abs(a), np.abs(b)), np.maximum(np.abs(c), np.abs(d)))
    _, e = np.frexp(np.where(m > 0, m, 1.0))  # NaN and inf entries: e = 0, left as they are
    return np.ldexp(a, -e), np.ldexp(b, -e), np.ldexp(c, -e), np.ldexp(d, -e), e


def singular_values(J):
    """Closed-form singular values ``(s_max, s_min)`` of 2x2 matrices.

    ``s_max = sqrt(two_smax_squared / 2)`` (:func:`two_smax_squared`: no cancellation)
    on the scaled entries (:func:`_scaled_entries`), then ``s_min = |det| / s_max``.

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    s_max, s_min : ndarray
        The singular values, shape ``(...)`` (the unit of ``J``).
    """
    a, b, c, d, e = _scaled_entries(J)
    s_max = np.sqrt(0.5 * two_smax_squared(a, b, c, d))
    det = np.abs(a * d - b * c)
    with np.errstate(invalid="ignore", divide="ignore"):
        # 0/0 only for J = 0; NaN entries (unreachable poses) stay NaN
        s_min = np.where(s_max > 0, det / s_max, np.where(np.isnan(s_max), np.nan, 0.0))
    return np.ldexp(s_max, e), np.ldexp(s_min, e)


def lci(J):
    """Local conditioning index ``s_min/s_max`` in [0, 1] (:func:`lci_of_entries` on the
    scaled entries, :func:`_scaled_entries`); 0 where J is NaN or zero.

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    ndarray
        The LCI (dimensionless).
    """
    J = np.asarray(J, dtype=float)
    if Twin.compiled() and J.shape[-2:] == (2, 2):
        flat = np.ascontiguousarray(J).reshape(-1, 2, 2)
        out = np.empty(flat.shape[0])
        _LCI_TWIN(flat, out)
        return out.reshape(J.shape[:-2])
    with Twin.numpy_timer():
        # on arrays even for one matrix: NumPy's scalar arithmetic (a 2 x 2 J gives
        # scalar entries) differs from its array arithmetic in the last bit at times
        a, b, c, d, _ = _scaled_entries(J[None] if J.shape == (2, 2) else J)
        with np.errstate(invalid="ignore", divide="ignore"):
            out = lci_of_entries(a, b, c, d)
        return np.where(np.isfinite(out), out, 0.0).reshape(J.shape[:-2])


@jitable
def lci_of_matrix(a, b, c, d):
    """:func:`lci` of the one matrix ``[[a, b], [c, d]]`` (compiled kernels only):
    :func:`_scaled_entries` (NaN magnitudes scale by ``2^-1`` as there, an infinite one by
    ``2^0``), then :func:`lci_of_entries`, 0 where that is not finite.

    Parameters
    ----------
    a, b, c, d : float
        The entries of ``J`` (``q_dot = J p_dot``).

    Returns
    -------
    float
        The LCI (dimensionless, Liu 2006 eq. 3), 0 for a NaN or zero matrix.
    """
    m = np.maximum(np.maximum(abs(a), abs(b)), np.maximum(abs(c), abs(d)))
    if m > 0.0 and m < math.inf:
        e = math.frexp(m)[1]
    elif m > 0.0:
        e = 0
    else:  # 0 or NaN: np.frexp(1.0)
        e = 1
    if e >= -1023:
        # 2^-e is a double (normal, or subnormal down to 2^-1025), so a * 2^-e is the exact
        # product rounded once, as ldexp(a, -e) is: one ldexp instead of four
        f = math.ldexp(1.0, -e)
        v = lci_of_entries(a * f, b * f, c * f, d * f)
    else:
        v = lci_of_entries(math.ldexp(a, -e), math.ldexp(b, -e), math.ldexp(c, -e), math.ldexp(d, -e))
    return v if math.isfinite(v) else 0.0


@jitable
def box_rows_of_matrix(a, b, c, d):
    """``1/||row_1||, 1/||row_2||, |det J|/||row_1||, |det J|/||row_2||`` of the one
    matrix ``J = [[a, b], [c, d]]``, 0 where not finite (compiled kernels): the
    per-actuator (box) speed and force factors of :mod:`mechopt.core.actuators`.

    Parameters
    ----------
    a, b, c, d : float
        The entries of ``J`` (``q_dot = J p_dot``).

    Returns
    -------
    tuple of float
        The four factors.
    """
    n1, n2 = np.hypot(a, b), np.hypot(c, d)
    det = abs(a * d - b * c)
    v0, v1, v2, v3 = 1.0 / n1, 1.0 / n2, det / n1, det / n2
    return (v0 if np.isfinite(v0) else 0.0, v1 if np.isfinite(v1) else 0.0, v2 if np.isfinite(v2) else 0.0,
            v3 if np.isfinite(v3) else 0.0)


def _lci_loop(J, out):
    """:func:`lci` of each matrix of ``J`` (shape ``(n, 2, 2)``) into ``out``, compiled
    (:class:`mechopt.core.jit.Twin`, :func:`lci_of_matrix`)."""
    for i in range(J.shape[0]):
        out[i] = lci_of_matrix(J[i, 0, 0], J[i, 0, 1], J[i, 1, 0], J[i, 1, 1])


_LCI_TWIN = Twin(_lci_loop)


def velocity_extremes(J):
    """``(|V|max, |V|min) = (1/s_min, 1/s_max)`` for a unit input rate (Liu eq. 10).

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    v_max, v_min : ndarray
        ``1/s_min`` and ``1/s_max`` (inf where ``s_min = 0``).
    """
    s_max, s_min = singular_values(J)
    with np.errstate(divide="ignore"):
        return 1.0 / s_min, 1.0 / s_max


def payload_extremes(J):
    """``(|tau|max, |tau|min) = (s_max, s_min)`` for a unit actuator effort (Liu eq. 13).

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    s_max, s_min : ndarray
        The singular values of ``J``.
    """
    return singular_values(J)


def stiffness_extremes(J):
    """``(|D|max, |D|min) = (1/s_min^2, 1/s_max^2)``, K = J^T J, k_p = 1 (Liu eq. 16-18).

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    d_max, d_min : ndarray
        ``1/s_min^2`` and ``1/s_max^2``.
    """
    s_max, s_min = singular_values(J)
    with np.errstate(divide="ignore"):
        return 1.0 / s_min**2, 1.0 / s_max**2


def tqi(J):
    """Transmission quality index of Stan 2008 eq. (9) with Frobenius norms.

    For a 2x2 matrix ``||J||_F ||J^-1||_F = kappa + 1/kappa`` with ``kappa`` the
    2-norm condition number, so ``TQI = 2 / (kappa + 1/kappa) = 2 kappa / (kappa^2 + 1)``;
    written here as ``2 LCI / (1 + LCI^2)``, which is 0 at a singularity.

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    ndarray
        The TQI, in [0, 1] (dimensionless).
    """
    c = lci(J)
    return 2.0 * c / (1.0 + c * c)


def manipulability(J):
    """Yoshikawa manipulability of the forward map ``p_dot = J^-1 theta_dot``: ``1/|det J|``.

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    ndarray
        ``1/|det J|`` (inf at type-II singularities).
    """
    a, b, c, d = _entries(J)
    with np.errstate(divide="ignore"):
        return 1.0 / np.abs(a * d - b * c)


def local_indices(J) -> dict:
    """All local indices of :data:`LOCAL_INDEX_NAMES` at once (one closed-form SVD;
    the LCI by :func:`lci`).

    Parameters
    ----------
    J : array_like
        Jacobians, shape ``(..., 2, 2)`` (``q_dot = J p_dot``).

    Returns
    -------
    dict
        ``{name: ndarray}`` keyed by :data:`LOCAL_INDEX_NAMES`.
    """
    s_max, s_min = singular_values(J)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = {
            "lci": lci(J),
            "v_max": 1.0 / s_min,
            "v_min": 1.0 / s_max,
            "tau_max": s_max,
            "tau_min": s_min,
            "d_max": 1.0 / s_min**2,
            "d_min": 1.0 / s_max**2,
        }
    return out
