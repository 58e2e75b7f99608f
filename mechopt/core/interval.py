"""A small vectorised interval arithmetic on NumPy arrays, with outward rounding.

An :class:`Interval` holds two float arrays ``lo <= hi`` of one shape: the set of reals
``[lo, hi]`` elementwise. Every operation returns an interval that contains the exact
(real-number) result of the operation applied to every pair of reals of its operands:

* ``+ - * /``, :meth:`Interval.sqr`, :meth:`Interval.sqrt` are computed on the
  endpoints in IEEE 754 double precision, whose basic operations (``+ - * /`` and
  ``sqrt``) are correctly rounded to nearest: the exact value lies within half an ulp
  of the float. Each computed endpoint is then moved one ulp outward
  (``np.nextafter`` toward ``-inf`` for ``lo``, toward ``+inf`` for ``hi``), so the
  enclosure holds in floating point (a rounding of one ulp is more than the half ulp
  the rounding can lose; overflow gives an infinite endpoint, still an enclosure).
* ``abs``, ``min``, ``max`` and negation are exact in floating point: no rounding.
* division by an interval that contains 0 gives ``(-inf, inf)`` (unbounded); a NaN
  endpoint (``inf - inf``, ``0 * inf``) is replaced by the infinite endpoint on its
  side, so a result is always an interval, possibly unbounded.
* :meth:`Interval.sqrt` of an interval whose lower end is negative takes the root of
  its non-negative part and reports where that happened (:meth:`Interval.sqrt`
  returns the flags): the argument may be negative there, which the callers read as
  "the point may be out of reach".

Inclusion isotonicity: each operation is monotone in its operands' endpoints (rounding
to nearest and ``nextafter`` are monotone), so the result over a sub-box is contained in
the result over the box; :mod:`mechopt.analysis.bounds` relies on it (its bounds never
fall when a cell is split). The natural interval extension of an expression (each
operation replaced by its interval version) encloses the expression's range over a
box, overestimating it by the dependency between repeated variables, an error of
first order in the box's width (Moore, Kearfott, Cloud, *Introduction to Interval
Analysis*, SIAM 2009, ch. 5-6).
"""
from __future__ import annotations

import numpy as np

__all__ = ["Interval", "as_interval", "hypot", "minimum", "maximum"]

_NINF, _PINF = -np.inf, np.inf


def _make(lo, hi):
    """An :class:`Interval` of endpoint arrays known to be ordered (no check)."""
    out = object.__new__(Interval)
    out.lo, out.hi = lo, hi
    return out


def _down(v):
    """``v`` moved one ulp toward -inf (NaN -> -inf: unbounded)."""
    v = np.nextafter(v, _NINF)
    return np.where(np.isnan(v), _NINF, v)


def _up(v):
    """``v`` moved one ulp toward +inf (NaN -> +inf: unbounded)."""
    v = np.nextafter(v, _PINF)
    return np.where(np.isnan(v), _PINF, v)


class Interval:
    """Closed intervals ``[lo, hi]``, elementwise over arrays (module docstring).

    Parameters
    ----------
    lo : array_like
        Lower ends.
    hi : array_like, optional
        Upper ends (default ``lo``: degenerate intervals); broadcast with ``lo``.

    Raises
    ------
    ValueError
        Where ``lo > hi``.
    """

    __slots__ = ("lo", "hi")
    __array_priority__ = 1000  # ndarray op Interval -> Interval's reflected op

    def __init__(self, lo, hi=None):
        lo = np.asarray(lo, dtype=float)
        hi = lo if hi is None else np.asarray(hi, dtype=float)
        lo, hi = np.broadcast_arrays(lo, hi)
        if np.any(lo > hi):
            raise ValueError("an interval needs lo <= hi")
        self.lo, self.hi = lo, hi

    # --- helpers -------------------------------------------------------------------
    @property
    def shape(self):
        return self.lo.shape

    def __repr__(self):
        return f"Interval({self.lo!r}, {self.hi!r})"

    def __getitem__(self, key):
        return _make(self.lo[key], self.hi[key])

    def contains(self, v):
        """Elementwise ``lo <= v <= hi``.

        Parameters
        ----------
        v : array_like
            Values.

        Returns
        -------
        ndarray of bool
            Whether each value lies in its interval.
        """
        v = np.asarray(v, dtype=float)
        return (self.lo <= v) & (v <= self.hi)

    @property
    def width(self):
        """``hi - lo`` (rounded up)."""
        return _up(self.hi - self.lo)

    @property
    def mid(self):
        """The midpoints (a float inside each interval; not an enclosure)."""
        m = 0.5 * self.lo + 0.5 * self.hi
        return np.clip(np.where(np.isfinite(m), m, np.where(np.isfinite(self.lo), self.lo, self.hi)),
                       self.lo, self.hi)

    def nonneg(self):
        """The interval with its lower end raised to 0: only for an expression known to be
        non-negative in exact arithmetic (a sum of squares), whose outward rounding may
        have moved ``lo`` below 0.

        Returns
        -------
        Interval
            ``[max(lo, 0), max(hi, 0)]``.
        """
        return _make(np.maximum(self.lo, 0.0), np.maximum(self.hi, 0.0))

    # --- arithmetic ----------------------------------------------------------------
    def __neg__(self):
        return _make(-self.hi, -self.lo)

    def __add__(self, other):
        o = as_interval(other)
        return _make(_down(self.lo + o.lo), _up(self.hi + o.hi))

    __radd__ = __add__

    def __sub__(self, other):
        o = as_interval(other)
        return _make(_down(self.lo - o.hi), _up(self.hi - o.lo))

    def __rsub__(self, other):
        return as_interval(other) - self

    def __mul__(self, other):
        o = as_interval(other)
        with np.errstate(invalid="ignore", over="ignore"):
            p = np.stack(np.broadcast_arrays(self.lo * o.lo, self.lo * o.hi, self.hi * o.lo, self.hi * o.hi))
        bad = np.isnan(p).any(axis=0)  # 0 * inf: unbounded
        return _make(np.where(bad, _NINF, _down(p.min(axis=0))), np.where(bad, _PINF, _up(p.max(axis=0))))

    __rmul__ = __mul__

    def __truediv__(self, other):
        o = as_interval(other)
        zero = (o.lo <= 0.0) & (o.hi >= 0.0)
        with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
            p = np.stack(np.broadcast_arrays(self.lo / o.lo, self.lo / o.hi, self.hi / o.lo, self.hi / o.hi))
        bad = zero | np.isnan(p).any(axis=0)
        return _make(np.where(bad, _NINF, _down(p.min(axis=0))), np.where(bad, _PINF, _up(p.max(axis=0))))

    def __rtruediv__(self, other):
        return as_interval(other) / self

    def sqr(self):
        """``x^2`` (tighter than ``x * x``: one variable), lower end >= 0.

        Returns
        -------
        Interval
            The squares.
        """
        with np.errstate(over="ignore"):
            a, b = self.lo * self.lo, self.hi * self.hi
        straddle = (self.lo <= 0.0) & (self.hi >= 0.0)
        lo = np.where(straddle, 0.0, np.maximum(_down(np.minimum(a, b)), 0.0))
        return _make(lo, _up(np.maximum(a, b)))

    def sqrt(self):
        """``sqrt(x)`` of the non-negative part, and where ``lo < 0``.

        Returns
        -------
        root : Interval
            ``[sqrt(max(lo, 0)), sqrt(max(hi, 0))]``, outward rounded (lower end >= 0).
        negative : ndarray of bool
            Where the argument may be negative (``lo < 0``): the root encloses only its
            non-negative part there.
        """
        neg = self.lo < 0.0
        lo = np.maximum(_down(np.sqrt(np.maximum(self.lo, 0.0))), 0.0)
        return _make(lo, _up(np.sqrt(np.maximum(self.hi, 0.0)))), neg

    def __abs__(self):
        straddle = (self.lo <= 0.0) & (self.hi >= 0.0)
        alo, ahi = np.abs(self.lo), np.abs(self.hi)
        return _make(np.where(straddle, 0.0, np.minimum(alo, ahi)), np.maximum(alo, ahi))


def as_interval(v) -> Interval:
    """``v`` as an :class:`Interval` (a number or array: degenerate intervals).

    Parameters
    ----------
    v : Interval or array_like
        An interval, or exact values.

    Returns
    -------
    Interval
        ``v`` itself, or ``[v, v]``.
    """
    return v if isinstance(v, Interval) else Interval(v)


def hypot(a, b) -> Interval:
    """``sqrt(a^2 + b^2)`` (the sum of squares is non-negative: no flag).

    Parameters
    ----------
    a, b : Interval or array_like
        The legs.

    Returns
    -------
    Interval
        The enclosure of the norm.
    """
    return (as_interval(a).sqr() + as_interval(b).sqr()).nonneg().sqrt()[0]


def minimum(a, b) -> Interval:
    """Elementwise ``min(a, b)`` (exact: no rounding).

    Parameters
    ----------
    a, b : Interval or array_like
        The operands.

    Returns
    -------
    Interval
        ``[min(a.lo, b.lo), min(a.hi, b.hi)]``.
    """
    a, b = as_interval(a), as_interval(b)
    return _make(np.minimum(a.lo, b.lo), np.minimum(a.hi, b.hi))


def maximum(a, b) -> Interval:
    """Elementwise ``max(a, b)`` (exact: no rounding).

    Parameters
    ----------
    a, b : Interval or array_like
        The operands.

    Returns
    -------
    Interval
        ``[max(a.lo, b.lo), max(a.hi, b.hi)]``.
    """
    a, b = as_interval(a), as_interval(b)
    return _make(np.maximum(a.lo, b.lo), np.maximum(a.hi, b.hi))
