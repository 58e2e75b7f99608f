"""Numerical building blocks shared by the analyses: one golden-section search.

:func:`golden_section_max` is the search of the MIC centre (:mod:`mechopt.analysis.workspace`,
both the rays method and the NumPy port of the atlas kernel), of the best LCI on a
disk's rim (:mod:`mechopt.analysis.performance`, many searches at once) and of the placement
that maximises a design's smallest margin (:mod:`mechopt.workflows.design`) and Le's
golden-section row (:mod:`mechopt.experiments.le2013`). The compiled twins
in :mod:`mechopt.mechanisms.five_bar.kernels` run the same steps in numba.
"""
from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

__all__ = ["INV_PHI", "GoldenSection", "golden_section_max"]

#: the inverse golden ratio ``(sqrt(5) - 1) / 2``: the interior points divide the bracket in it
INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0


class GoldenSection(NamedTuple):
    """The end of :func:`golden_section_max`: the bracket ``[a, b]``, its interior points
    ``x1 < x2`` with their values, the best point evaluated (``x_best``, ``f_best``) and
    the number of evaluations of ``f`` (per search: 2 plus one per step)."""

    a: Any
    b: Any
    x1: Any
    f1: Any
    x2: Any
    f2: Any
    x_best: Any
    f_best: Any
    evaluations: int


def _ternary(cond, u, v):
    return u if cond else v


def golden_section_max(f, a, b, *, tol=None, max_iter=None, stop=None, start=None,
                       right_within=None) -> GoldenSection:
    """Maximise ``f`` over ``[a, b]`` by golden-section search (``f`` unimodal there).

    The interior points are ``x1 = b - r (b - a)`` and ``x2 = a + r (b - a)``,
    ``r`` = :data:`INV_PHI`; each step keeps the side of the larger value (on a tie the
    left one, ``[a, x2]``), reuses the point kept and evaluates ``f`` once, at the new
    interior point. ``f`` is called with ``x1``, then ``x2``, then each new point.

    Vectorised: with arrays ``a``, ``b`` (one search per element, all advanced together)
    ``f`` receives an array of abscissae and returns their values; with scalars it
    receives and returns scalars.

    Parameters
    ----------
    f : callable
        The function to maximise; NaN values lose every comparison.
    a, b : float or array
        The bracket, ``a < b``.
    tol : float, optional
        Stop before a step once no bracket is wider than ``tol`` (``b - a <= tol``).
    max_iter : int, optional
        The most steps (every search makes them all when neither ``tol`` nor ``stop``
        ends it first).
    stop : callable, optional
        ``stop(a, b)``, asked before each step (after ``tol``): True ends the search.
    start : (x0, f0), optional
        A point already evaluated: it seeds the best point.
    right_within : float, optional
        Keep the left side only when ``f1 > f2 + right_within``: ties and values within
        ``right_within`` move right. A staircase needs it (Le 2013's a_MAX levels
        ``sqrt(2) r_MIC - k step`` carry the ~1e-11 noise of r_MIC, so equal levels
        compare unequal); default: the left side on a tie (``f1 >= f2``).

    Returns
    -------
    GoldenSection
        The final bracket and interior points, and the best point evaluated: the first,
        in the order of evaluation (``start`` first), of those of the largest value.

    Raises
    ------
    ValueError
        When none of ``tol``, ``max_iter`` and ``stop`` is given (the search would not end).
    """
    if tol is None and max_iter is None and stop is None:
        raise ValueError("golden_section_max needs tol, max_iter or stop to end, got none of them")
    pick = np.where if np.ndim(a) or np.ndim(b) else _ternary
    x1 = b - INV_PHI * (b - a)
    x2 = a + INV_PHI * (b - a)
    f1 = f(x1)
    best = (x1, f1) if start is None else start
    if start is not None:
        better = f1 > best[1]
        best = (pick(better, x1, best[0]), pick(better, f1, best[1]))
    f2 = f(x2)
    better = f2 > best[1]
    best = (pick(better, x2, best[0]), pick(better, f2, best[1]))
    step = 0
    while max_iter is None or step < max_iter:
        if tol is not None and not np.any(b - a > tol):
            break
        if stop is not None and stop(a, b):
            break
        left = f1 >= f2 if right_within is None else f1 > f2 + right_within
        a, b = pick(left, a, x1), pick(left, x2, b)
        x1, x2 = pick(left, b - INV_PHI * (b - a), x2), pick(left, x1, a + INV_PHI * (b - a))
        xn = pick(left, x1, x2)
        fn = f(xn)
        f1, f2 = pick(left, fn, f2), pick(left, f1, fn)
        better = fn > best[1]
        best = (pick(better, xn, best[0]), pick(better, fn, best[1]))
        step += 1
    return GoldenSection(a, b, x1, f1, x2, f2, best[0], best[1], 2 + step)
