"""All indices of many symmetric five-bar designs at once (Liu 2006 atlases and problems).

:func:`evaluate_designs` is the batch path of :mod:`mechopt.mechanisms.five_bar.kernels`
(compiled with numba when it imports, NumPy otherwise): the MIC of every design
(closed-form serial clearance and an explicit type-II locus, Liu 2006 sec. 3) and the
disk means over it (GCI, MCI, GVI, GPI, GSI; Liu eq. 4, 11, 14, 19), one row of
:data:`RESULT_COLUMNS` per design. The atlas (:mod:`mechopt.run.atlas`) and the Liu
problems (:mod:`mechopt.problems.liu2006`) call it; one design through the protocol is
:func:`mechopt.analysis.evaluate.evaluate`.
"""
from __future__ import annotations

import numpy as np

from mechopt.core import validation as _v
from mechopt.mechanisms.five_bar import kernels as _k

__all__ = ["RESULT_COLUMNS", "evaluate_designs"]

#: what :func:`evaluate_designs` returns, in order
RESULT_COLUMNS = ("r_mic", "mic_center_y") + _k.DISK_STAT_NAMES
#: a MIC radius below this (relative to the length scale 1) counts as none
_MIN_RADIUS = _v.RESOLUTION


def evaluate_designs(r1, r2, r3, quadrature: str = "area", mode: str = "+-", compiled=None):
    """``(n, 10)`` array of :data:`RESULT_COLUMNS` for arrays of designs.

    The fast path of :mod:`mechopt.mechanisms.five_bar.kernels`; degenerate designs (MIC radius 0)
    get ``r_mic = 0`` and NaN elsewhere. Lengths in any unit (results scale as in
    :func:`mechopt.analysis.performance.global_indices`); r1, r2 in [LENGTH_MIN, LENGTH_MAX] and
    r3 in [0, LENGTH_MAX] of :mod:`mechopt.core.validation`.

    Parameters
    ----------
    r1, r2, r3 : array_like
        Crank, distal link and half base [L] of each design.
    quadrature : str
        ``"area"`` or ``"polar"``.
    mode : str
        Working mode.
    compiled : bool, optional
        Use the numba kernels (None: when installed).

    Returns
    -------
    ndarray
        Shape ``(n, 10)``, columns :data:`RESULT_COLUMNS` (lengths [L], indices as in
        :func:`mechopt.analysis.performance.global_indices`).

    Raises
    ------
    ValueError
        One line, for non-numeric or inadmissible lengths, or arrays that do not broadcast.
    """
    arrays = []
    for name, v, lo in (("r1", r1, _v.LENGTH_MIN), ("r2", r2, _v.LENGTH_MIN), ("r3", r3, 0.0)):
        try:
            a = np.asarray(v)
        except (TypeError, ValueError):  # e.g. ragged lists
            a = None
        if a is None or a.dtype.kind not in "biuf":
            raise ValueError(f"{name} must be a number or an array of numbers, got {_v.show(v)}")
        a = a.astype(float)
        if not np.all((a >= lo) & (a <= _v.LENGTH_MAX)):  # NaN fails too
            raise ValueError(f"{name} must hold lengths in [{lo:g}, {_v.LENGTH_MAX:g}], got {_v.show(v)}")
        arrays.append(a)
    try:
        r1, r2, r3 = (a.ravel() for a in np.broadcast_arrays(*arrays))
    except ValueError:
        raise ValueError(f"r1, r2 and r3 must broadcast to one shape, got "
                         f"{', '.join(str(a.shape) for a in arrays)}") from None
    R, yc = _k.mic_batch(r1, r2, r3, mode=mode, compiled=compiled)
    scale = (r1 + r2 + r3) / 3.0
    ok = R > _MIN_RADIUS * scale
    R = np.where(ok, R, 0.0)
    stats = _k.disk_stats_batch(r1, r2, r3, yc, R, mode=mode, quadrature=quadrature,
                                compiled=compiled)
    out = np.column_stack([R, np.where(ok, yc, np.nan), stats])
    out[~ok, 1:] = np.nan
    return out
