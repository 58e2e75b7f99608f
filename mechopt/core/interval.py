"""A small vectorised interval arithmetic on NumPy arrays, with outward rounding.

An :class:`Interval` holds two float arrays ``lo <= hi`` of one shape: the set of reals
``[lo, hi]`` elementwise. Every operation returns an interval that contains the exact
(real-number) result of the operation applied to every pair of reals of its operands:

* ``+ - * /``, :meth:`Interval.sqr`, :meth:`Interval.sqrt` are computed on the
  endpoints in IEEE 754 double precision, whose basic operations (``+ - * /`` and
  ``sqrt``) are correctly rounded to nearest: the exact value lies within half an ulp
  of the float. Each computed endpoint is then moved at least one ulp outward (toward
  ``-inf`` for ``lo``, toward ``+inf`` for ``hi``: ``np.nextafter`` for arrays of fewer
  than 256 elements; for more, ``v -+ (|v| u(1 + 2u) + 2^-1074)``, the same float except
  one ulp further out for ``|v|`` in ``[2^-1022, 2^-1020]``, :func:`_down` states the
  argument), so the enclosure holds in floating point (a rounding of one ulp is more
  than the half ulp the rounding can lose; overflow gives an infinite endpoint, still an
  enclosure).
* For arrays of at least 256 elements, once mechopt's compiled twins run
  (:class:`mechopt.core.jit.Twin`), ``+ - * /``, ``sqr`` and ``sqrt`` run as one compiled
  loop per operation that performs each element's operations of the NumPy path in its
  order and rounds by the same arithmetic (:func:`_round_down`): the same endpoints bit
  for bit, so the same argument (tests/test_interval_loops.py compares the two). The
  derivatives of :class:`Gradient` (``a v + w b``, ``(a - q b) / v``, ``-(q d) / v``,
  ``2 (v d)``) run as one loop per expression that performs, element by element, each of
  its operations as above, each rounded outward (no array between, the same endpoints
  as the operations one by one), where every operation's result has the expression's
  size (so the same rounding).
* ``abs``, ``min``, ``max`` and negation are exact in floating point: no rounding.
* division by an interval that contains 0 gives ``(-inf, inf)`` (unbounded); a NaN
  endpoint (``inf - inf``, ``0 * inf``) is replaced by the infinite endpoint on its
  side, so a result is always an interval, possibly unbounded.
* :meth:`Interval.sqrt` of an interval whose lower end is negative takes the root of
  its non-negative part and reports where that happened (:meth:`Interval.sqrt`
  returns the flags): the argument may be negative there, which the callers read as
  "the point may be out of reach".

Inclusion isotonicity: each operation is monotone in its operands' endpoints (rounding
to nearest and both outward roundings are monotone), so the result over a sub-box is
contained in the result over the box (computed in arrays of the same size class: the two
roundings differ in ``[2^-1022, 2^-1020]``); :mod:`mechopt.analysis.bounds` keeps the
larger of a cell's and its parent's bounds anyway (both bound the cell). The natural interval extension of an expression (each
operation replaced by its interval version) encloses the expression's range over a
box, overestimating it by the dependency between repeated variables, an error of
first order in the box's width (Moore, Kearfott, Cloud, *Introduction to Interval
Analysis*, SIAM 2009, ch. 5-6).
"""
from __future__ import annotations

import numpy as np

from mechopt.core.jit import Twin, jitable

__all__ = ["Interval", "Gradient", "as_interval", "hypot", "minimum", "maximum", "atan2", "acos", "PI",
           "LIBM_ULPS"]

_NINF, _PINF = -np.inf, np.inf


def _make(lo, hi):
    """An :class:`Interval` of endpoint arrays known to be ordered (no check)."""
    out = object.__new__(Interval)
    out.lo, out.hi = lo, hi
    return out


#: ``u (1 + 2u)``, ``u = 2^-53`` the unit roundoff of double precision (:func:`_down`)
_PHI = 2.0 ** -53 * (1.0 + 2.0 ** -52)
#: the smallest positive subnormal double, ``2^-1074``
_ETA = 2.0 ** -1074
#: the largest finite double
_MAX = float(np.finfo(float).max)
#: arrays of fewer elements are rounded by ``np.nextafter`` (:func:`_down`)
_FEW = 256


def _down(v):
    """``v`` moved at least one ulp toward -inf (NaN -> -inf: unbounded): ``v - (|v| phi +
    eta)`` in rounding to nearest, ``phi = u (1 + 2u)``, ``u = 2^-53``, ``eta = 2^-1074``
    (Rump, Zimmermann, Boldo, Melquiond, *Computing predecessor and successor in rounding
    to nearest*, BIT 49, 2009): ``np.nextafter(v, -inf)`` itself except for ``|v|`` in
    ``[2^-1022, 2^-1020]``, where it may be one ulp lower (tests/test_bounds_lockstep.py
    checks both), in a few cheap array operations where ``np.nextafter`` costs a libm call
    per element.

    The argument that the result is at most ``pred(v)`` (all an enclosure needs): for a
    finite ``v`` the gap from ``v`` down to ``pred(v)`` is at most ``2u |v|`` (``|v| >=
    2^-1022``) or ``eta`` (below); the computed ``e = fl(fl(phi |v|) + eta)`` is at least
    ``fl(phi |v|)`` (rounding is monotone), which is ``>= phi |v| / (1 + u) > u |v|`` where
    ``phi |v|`` is normal, and ``e = fl(phi |v|) + eta >= phi |v| + eta / 2`` exactly where
    it is subnormal; either way ``e`` exceeds half the gap (and ``e >= eta`` covers ``v = 0``
    and subnormal ``v``), so ``v - e`` lies strictly below the midpoint of ``pred(v)`` and
    ``v`` and rounds to ``pred(v)`` or lower. ``|v|`` is capped at the largest double first
    (no ``inf - inf``, no warning): ``+inf`` gives ``+inf``, capped to the largest double
    (``pred(inf)``, as ``np.nextafter``); ``-inf`` stays, overflow gives ``-inf``, NaN gives
    ``-inf`` (``np.fmax``).
    """
    if np.size(v) < _FEW:  # few: np.nextafter's fewer array operations cost less
        v = np.nextafter(v, _NINF)
        return np.fmax(v, _NINF, out=v) if type(v) is np.ndarray else np.asarray(np.fmax(v, _NINF))
    e = np.abs(v)
    np.minimum(e, _MAX, out=e)
    e *= _PHI
    e += _ETA
    np.subtract(v, e, out=e)
    np.minimum(e, _MAX, out=e)
    return np.fmax(e, _NINF, out=e)


def _up(v):
    """``v`` moved at least one ulp toward +inf (NaN -> +inf: unbounded): ``v + (|v| phi +
    eta)``, the mirror image of :func:`_down` (the same argument)."""
    if np.size(v) < _FEW:
        v = np.nextafter(v, _PINF)
        return np.fmin(v, _PINF, out=v) if type(v) is np.ndarray else np.asarray(np.fmin(v, _PINF))
    e = np.abs(v)
    np.minimum(e, _MAX, out=e)
    e *= _PHI
    e += _ETA
    np.add(v, e, out=e)
    np.maximum(e, -_MAX, out=e)
    return np.fmin(e, _PINF, out=e)


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
        if isinstance(other, Gradient):  # its reflected operation keeps the derivatives
            return NotImplemented
        return _binary(_ADD, self, as_interval(other))

    __radd__ = __add__

    def __sub__(self, other):
        if isinstance(other, Gradient):  # its reflected operation keeps the derivatives
            return NotImplemented
        return _binary(_SUB, self, as_interval(other))

    def __rsub__(self, other):
        return as_interval(other) - self

    def __mul__(self, other):
        if isinstance(other, Gradient):  # its reflected operation keeps the derivatives
            return NotImplemented
        return _binary(_MUL, self, as_interval(other))

    __rmul__ = __mul__

    def __truediv__(self, other):
        if isinstance(other, Gradient):  # its reflected operation keeps the derivatives
            return NotImplemented
        return _binary(_DIV, self, as_interval(other))

    def __rtruediv__(self, other):
        return as_interval(other) / self

    def sqr(self):
        """``x^2`` (tighter than ``x * x``: one variable), lower end >= 0.

        Returns
        -------
        Interval
            The squares.
        """
        return _unary(_SQR, self)

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
        return _unary(_SQRT, self), self.lo < 0.0

    def __abs__(self):
        straddle = (self.lo <= 0.0) & (self.hi >= 0.0)
        alo, ahi = np.abs(self.lo), np.abs(self.hi)
        return _make(np.where(straddle, 0.0, np.minimum(alo, ahi)), np.maximum(alo, ahi))


# ------------------------------------------------------------------ the NumPy paths
def _add(a, o):
    return _make(_down(a.lo + o.lo), _up(a.hi + o.hi))


def _sub(a, o):
    return _make(_down(a.lo - o.hi), _up(a.hi - o.lo))


def _mul(a, o):
    with np.errstate(invalid="ignore", over="ignore"):
        if o.lo is o.hi:  # a constant: two products
            p, q = a.lo * o.lo, a.hi * o.lo
            lo, hi = np.minimum(p, q), np.maximum(p, q)
        else:
            p, q, r, t = a.lo * o.lo, a.lo * o.hi, a.hi * o.lo, a.hi * o.hi
            lo = np.minimum(np.minimum(p, q), np.minimum(r, t))  # NaN (0 * inf) propagates
            hi = np.maximum(np.maximum(p, q), np.maximum(r, t))
    return _make(_down(lo), _up(hi))


def _div(a, o):
    zero = (o.lo <= 0.0) & (o.hi >= 0.0)
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        p, q, r, t = a.lo / o.lo, a.lo / o.hi, a.hi / o.lo, a.hi / o.hi
        lo = np.minimum(np.minimum(p, q), np.minimum(r, t))
        hi = np.maximum(np.maximum(p, q), np.maximum(r, t))
    return _make(np.where(zero, _NINF, _down(lo)), np.where(zero, _PINF, _up(hi)))


def _sqr(x):
    with np.errstate(over="ignore"):
        a, b = x.lo * x.lo, x.hi * x.hi
    straddle = (x.lo <= 0.0) & (x.hi >= 0.0)
    lo = np.where(straddle, 0.0, np.maximum(_down(np.minimum(a, b)), 0.0))
    return _make(lo, _up(np.maximum(a, b)))


def _sqrt(x):
    lo = np.maximum(_down(np.sqrt(np.maximum(x.lo, 0.0))), 0.0)
    return _make(lo, _up(np.sqrt(np.maximum(x.hi, 0.0))))

# ------------------------------------------------------------------ compiled loops
# For arrays of at least _FEW elements, once the compiled twins run
# (:meth:`mechopt.core.jit.Twin.compiled`), ``+ - * /``, :meth:`Interval.sqr` and
# :meth:`Interval.sqrt` run as one loop per operation: per element the same
# correctly-rounded operations as the NumPy path, in its order, then the same outward
# rounding (the arithmetic of :func:`_down`, which the NumPy path uses at this size), so
# the endpoints are the NumPy path's bit for bit (tests/test_interval_loops.py) without
# its temporary arrays. NaN, which NumPy's minimum and maximum propagate to ``_down`` and
# ``_up`` (-> -inf, +inf), is tested for explicitly; otherwise the smallest and largest
# of the products differ from NumPy's at most in the sign of a zero, which the rounding
# erases (``+-0`` rounds to ``-+2^-1074`` either way).

@jitable
def _round_down(v):
    """:func:`_down` of one float of an array of at least :data:`_FEW` elements."""
    if v != v:
        return _NINF
    a = abs(v)
    if a > _MAX:
        a = _MAX
    e = a * _PHI
    e = e + _ETA
    r = v - e
    return _MAX if r > _MAX else r


@jitable
def _round_up(v):
    """:func:`_up` of one float of an array of at least :data:`_FEW` elements."""
    if v != v:
        return _PINF
    a = abs(v)
    if a > _MAX:
        a = _MAX
    e = a * _PHI
    e = e + _ETA
    r = v + e
    return -_MAX if r < -_MAX else r


#: operation codes of :func:`_binary_loop`
_ADD, _SUB, _MUL, _DIV = 0, 1, 2, 3


@jitable
def _mul1(a0, a1, b0, b1):
    """:meth:`Interval.__mul__` of one element of an array of at least :data:`_FEW`:
    ``(lo, hi)``."""
    p, q, r, t = a0 * b0, a0 * b1, a1 * b0, a1 * b1
    if p != p or q != q or r != r or t != t:  # NaN: unbounded (NumPy's minimum propagates it)
        return _NINF, _PINF
    return _round_down(min(min(p, q), min(r, t))), _round_up(max(max(p, q), max(r, t)))


@jitable
def _div1(a0, a1, b0, b1):
    """:meth:`Interval.__truediv__` of one element (:func:`_mul1`)."""
    if b0 <= 0.0 and b1 >= 0.0:  # the divisor may vanish: unbounded
        return _NINF, _PINF
    p, q, r, t = a0 / b0, a0 / b1, a1 / b0, a1 / b1
    if p != p or q != q or r != r or t != t:
        return _NINF, _PINF
    return _round_down(min(min(p, q), min(r, t))), _round_up(max(max(p, q), max(r, t)))


def _binary_loop(op, alo, ahi, blo, bhi, lo, hi):
    """``[alo, ahi] op [blo, bhi]`` into ``lo``, ``hi`` (each operand of ``len(lo)``
    elements or of one, broadcast): :meth:`Interval.__add__`, ``__sub__``, ``__mul__``
    and ``__truediv__`` element by element (compiled, :class:`mechopt.core.jit.Twin`)."""
    k0 = 1 if alo.shape[0] > 1 else 0
    k1 = 1 if ahi.shape[0] > 1 else 0
    k2 = 1 if blo.shape[0] > 1 else 0
    k3 = 1 if bhi.shape[0] > 1 else 0
    n = lo.shape[0]
    if op == _ADD:
        for i in range(n):
            lo[i] = _round_down(alo[i * k0] + blo[i * k2])
            hi[i] = _round_up(ahi[i * k1] + bhi[i * k3])
    elif op == _SUB:
        for i in range(n):
            lo[i] = _round_down(alo[i * k0] - bhi[i * k3])
            hi[i] = _round_up(ahi[i * k1] - blo[i * k2])
    elif op == _MUL:
        for i in range(n):
            lo[i], hi[i] = _mul1(alo[i * k0], ahi[i * k1], blo[i * k2], bhi[i * k3])
    else:
        for i in range(n):
            lo[i], hi[i] = _div1(alo[i * k0], ahi[i * k1], blo[i * k2], bhi[i * k3])


@jitable
def _step(x):
    """1 for an operand of the result's elements, 0 for one element (broadcast)."""
    return 1 if x.shape[0] > 1 else 0


def _muladd_loop(alo, ahi, vlo, vhi, wlo, whi, blo, bhi, lo, hi):
    """``a * v + w * b`` (the product rule) element by element: each operation as
    :class:`Interval`'s, rounded as there, with no array between (compiled,
    :class:`mechopt.core.jit.Twin`)."""
    k = (_step(alo), _step(ahi), _step(vlo), _step(vhi), _step(wlo), _step(whi), _step(blo), _step(bhi))
    for i in range(lo.shape[0]):
        p0, p1 = _mul1(alo[i * k[0]], ahi[i * k[1]], vlo[i * k[2]], vhi[i * k[3]])
        q0, q1 = _mul1(wlo[i * k[4]], whi[i * k[5]], blo[i * k[6]], bhi[i * k[7]])
        lo[i] = _round_down(p0 + q0)
        hi[i] = _round_up(p1 + q1)


def _scale_loop(c, vlo, vhi, dlo, dhi, lo, hi):
    """``c * (v * d)`` (a number ``c``; :meth:`Gradient.sqr`) element by element
    (:func:`_muladd_loop`)."""
    k = (_step(vlo), _step(vhi), _step(dlo), _step(dhi))
    for i in range(lo.shape[0]):
        p0, p1 = _mul1(vlo[i * k[0]], vhi[i * k[1]], dlo[i * k[2]], dhi[i * k[3]])
        lo[i], hi[i] = _mul1(c, c, p0, p1)


def _quotient_loop(neg, alo, ahi, qlo, qhi, blo, bhi, vlo, vhi, lo, hi):
    """``(a - q * b) / v`` (the quotient rule), or ``-(q * b) / v`` where ``neg``
    (``a`` unused), element by element (:func:`_muladd_loop`)."""
    k = (_step(alo), _step(ahi), _step(qlo), _step(qhi), _step(blo), _step(bhi), _step(vlo), _step(vhi))
    for i in range(lo.shape[0]):
        p0, p1 = _mul1(qlo[i * k[2]], qhi[i * k[3]], blo[i * k[4]], bhi[i * k[5]])
        if neg:
            d0, d1 = -p1, -p0
        else:
            d0, d1 = _round_down(alo[i * k[0]] - p1), _round_up(ahi[i * k[1]] - p0)
        lo[i], hi[i] = _div1(d0, d1, vlo[i * k[6]], vhi[i * k[7]])


#: operation codes of :func:`_unary_loop`
_SQR, _SQRT = 0, 1


def _unary_loop(op, xlo, xhi, lo, hi):
    """:meth:`Interval.sqr` (``op`` :data:`_SQR`) or the root of :meth:`Interval.sqrt`
    (:data:`_SQRT`) element by element, into ``lo``, ``hi`` (compiled,
    :class:`mechopt.core.jit.Twin`)."""
    for i in range(lo.shape[0]):
        x0, x1 = xlo[i], xhi[i]
        if op == _SQR:
            a, b = x0 * x0, x1 * x1
            if a != a or b != b:  # NaN: unbounded above, 0 below (the NumPy path's max(-inf, 0))
                lo[i], hi[i] = 0.0, _PINF
                continue
            d = _round_down(min(a, b))
            lo[i] = 0.0 if (x0 <= 0.0 and x1 >= 0.0) or not d > 0.0 else d
            hi[i] = _round_up(max(a, b))
        else:  # max(x, 0) keeps NaN, as np.maximum
            d = _round_down(np.sqrt(0.0 if x0 < 0.0 else x0))
            lo[i] = d if d > 0.0 else 0.0
            hi[i] = _round_up(np.sqrt(0.0 if x1 < 0.0 else x1))


_BINARY_TWIN = Twin(_binary_loop)
_UNARY_TWIN = Twin(_unary_loop)
_MULADD_TWIN = Twin(_muladd_loop)
_SCALE_TWIN = Twin(_scale_loop)
_QUOTIENT_TWIN = Twin(_quotient_loop)
#: the NumPy paths of the operation codes
_BINARY_NUMPY = {_ADD: _add, _SUB: _sub, _MUL: _mul, _DIV: _div}
_UNARY_NUMPY = {_SQR: _sqr, _SQRT: _sqrt}


def _loop_operands(arrays):
    """``(shape, flat)``: the endpoint arrays as 1-d float arrays for the loops, each of
    the result's ``shape`` (C-ordered) or of one element; None where the NumPy path runs
    (fewer than :data:`_FEW` elements: ``np.nextafter``'s rounding; other dtypes;
    operands of other shapes); ``(shape, None)`` where it runs because the loops do not
    run yet."""
    shape = None
    for v in arrays:
        if np.size(v) >= _FEW:
            shape = np.shape(v)
            break
    if shape is None:
        return None
    if not Twin.compiled():
        return shape, None
    flat = []
    for v in arrays:
        if type(v) is not np.ndarray:
            v = np.asarray(v)
        if v.dtype != np.float64:
            return None
        if v.shape == shape:  # (a strided view, e.g. a column of cells, copied: one pass)
            flat.append(np.ascontiguousarray(v).reshape(-1))
        elif v.size == 1 and v.ndim <= len(shape):
            flat.append(v.reshape(1))
        else:
            return None
    return shape, flat


def _binary(op, a, b):
    """``a op b`` (intervals) by :func:`_binary_loop` or by the NumPy path (the same
    endpoints)."""
    got = _loop_operands((a.lo, a.hi, b.lo, b.hi))
    if got is None:
        return _BINARY_NUMPY[op](a, b)
    shape, flat = got
    if flat is None:  # many elements, the loops not yet running: the twins' NumPy time
        with Twin.numpy_timer():
            return _BINARY_NUMPY[op](a, b)
    n = max(f.size for f in flat)
    lo, hi = np.empty(n), np.empty(n)
    _BINARY_TWIN(op, *flat, lo, hi)
    return _make(lo.reshape(shape), hi.reshape(shape))


def _unary(op, x):
    """``op`` of the interval ``x`` (:data:`_SQR`, :data:`_SQRT`) by :func:`_unary_loop`
    or by the NumPy path (the same endpoints)."""
    got = _loop_operands((x.lo, x.hi))
    if got is None:
        return _UNARY_NUMPY[op](x)
    shape, flat = got
    if flat is None or flat[0].size != flat[1].size:
        with Twin.numpy_timer():
            return _UNARY_NUMPY[op](x)
    lo, hi = np.empty(flat[0].size), np.empty(flat[0].size)
    _UNARY_TWIN(op, *flat, lo, hi)
    return _make(lo.reshape(shape), hi.reshape(shape))


#: expressions of :func:`_fused` (the operands ``x0, x1, ...`` in order)
_F_MULADD = 0  # x0 * x1 + x2 * x3 (the product rule)
_F_SCALE = 1  # x0 * (x1 * x2), x0 a number
_F_SUBMULDIV = 2  # (x0 - x1 * x2) / x3 (the quotient rule)
_F_NEGMULDIV = 3  # -(x0 * x1) / x2
#: per expression, the operands of each product whose size is its result's (the first
#: operations'; for every expression the later results are at least as large)
_F_FIRST = {_F_MULADD: ((0, 1), (2, 3)), _F_SCALE: ((1, 2),), _F_SUBMULDIV: ((1, 2),), _F_NEGMULDIV: ((0, 1),)}


def _fused(op, *xs):
    """The expression ``op`` (:data:`_F_MULADD`, ...) of the intervals ``xs`` by its
    compiled loop (:func:`_muladd_loop`, :func:`_scale_loop`, :func:`_quotient_loop`), or None (compute it operation by operation): where the loops
    run, every operand's ends are of the result's shape or of one element, and each
    operation's result has the result's size (so its rounding is the loop's: at least
    :data:`_FEW` elements)."""
    ends = []
    for x in xs:
        ends += (x.lo, x.hi)
    got = _loop_operands(ends)
    if got is None or got[1] is None:
        return None
    shape, flat = got
    for pair in _F_FIRST[op]:
        if max(flat[i].size for j in pair for i in (2 * j, 2 * j + 1)) == 1:
            return None
    n = max(f.size for f in flat)
    lo, hi = np.empty(n), np.empty(n)
    if op == _F_MULADD:
        _MULADD_TWIN(*flat, lo, hi)
    elif op == _F_SCALE:
        c = flat[0][0]
        if flat[0].size != 1 or flat[1].size != 1 or flat[1][0] != c:
            return None
        _SCALE_TWIN(float(c), *flat[2:], lo, hi)
    elif op == _F_SUBMULDIV:
        _QUOTIENT_TWIN(False, *flat, lo, hi)
    else:
        _QUOTIENT_TWIN(True, *flat[:2], *flat, lo, hi)
    return _make(lo.reshape(shape), hi.reshape(shape))


def _product_rule(a, v, w, b):
    """``a * v + w * b`` (intervals), fused where it can be (:func:`_fused`)."""
    return _fused(_F_MULADD, a, v, w, b) or a * v + w * b


def as_interval(v) -> Interval:
    """``v`` as an :class:`Interval` (a number or array: degenerate intervals).

    Parameters
    ----------
    v : Interval, Gradient or array_like
        An interval (with derivatives), or exact values.

    Returns
    -------
    Interval or Gradient
        ``v`` itself, or ``[v, v]``.
    """
    if isinstance(v, (Interval, Gradient)):
        return v
    v = np.asarray(v, dtype=float)
    return _make(v, v)


def hypot(a, b):
    """``sqrt(a^2 + b^2)`` (the sum of squares is non-negative: no flag). Of
    :class:`Gradient` arguments, the derivative ``(a da + b db) / r`` with each of
    ``a / r``, ``b / r`` enclosed and intersected with ``[-1, 1]``: the norm is
    1-Lipschitz, so its derivatives stay bounded where ``r`` may vanish (where the
    square root's would not) and the mean value form keeps working near ``r = 0``.

    Parameters
    ----------
    a, b : Interval, Gradient or array_like
        The legs.

    Returns
    -------
    Interval or Gradient
        The enclosure of the norm.
    """
    a, b = as_interval(a), as_interval(b)
    if not (isinstance(a, Gradient) or isinstance(b, Gradient)):
        return (a.sqr() + b.sqr()).nonneg().sqrt()[0]
    (va, ga), (vb, gb) = _parts(a), _parts(b)
    r = (va.sqr() + vb.sqr()).nonneg().sqrt()[0]

    def unit(v):  # v / r within [-1, 1]
        u = v / r
        return _make(np.maximum(u.lo, -1.0), np.minimum(u.hi, 1.0))
    ua, ub = unit(va), unit(vb)
    n = len(ga if ga is not None else gb)
    zero = tuple(_make(np.zeros(1), np.zeros(1)) for _ in range(n))
    ga, gb = ga or zero, gb or zero
    out = object.__new__(Gradient)
    out.v, out.g = r, tuple(_product_rule(ua, da, ub, db) for da, db in zip(ga, gb))
    return out


#: ulps by which a libm result (``np.arctan2``, ``np.arccos``) is moved outward: the
#: assumption is that the platform's libm computes them within 1 ulp of the exact value
#: (glibc documents at most 1 ulp for ``atan2`` and ``acos`` on x86-64; the tests check
#: it against mpmath at random arguments); two ulps leave a margin of one.
LIBM_ULPS = 2


def _libm_widen(lo, hi):
    """``lo``, ``hi`` moved :data:`LIBM_ULPS` ulps outward."""
    for _ in range(LIBM_ULPS):
        lo, hi = _down(lo), _up(hi)
    return lo, hi


def atan2(y, x):
    """The range of ``atan2(y, x)`` (in ``(-pi, pi]``, the branch cut on the negative x
    axis, as ``np.arctan2``) over boxes ``x`` times ``y``, and where it is continuous.

    The argument: on a box that contains neither the origin nor a point of the cut
    (``x < 0, y = 0``), the angle is continuous, and monotone along every segment of the
    box (its derivative along ``p0 + t e`` is ``(p0 x e) / |p|^2``, of constant sign), so
    through any point a horizontal segment to the box's sides and then a side to its
    corners: the extremes are at the 4 corners (floats, the boxes' endpoints). Each
    corner's angle by ``np.arctan2`` is moved :data:`LIBM_ULPS` ulps outward (the libm
    assumption). Elsewhere (the box may meet the cut or the origin) the angle is only
    known to lie in ``[-pi, pi]`` (outward rounded) and is flagged discontinuous.

    Parameters
    ----------
    y, x : Interval or array_like
        Ordinates and abscissae of the boxes (the order of ``np.arctan2``).

    Returns
    -------
    angle : Interval
        The enclosure [rad].
    continuous : ndarray of bool
        Where the box meets neither the cut nor the origin (the angle is continuous on it).
    """
    y, x = as_interval(y), as_interval(x)
    with np.errstate(invalid="ignore"):
        c = [np.arctan2(yy, xx) for yy in (y.lo, y.hi) for xx in (x.lo, x.hi)]
    lo, hi = _libm_widen(np.minimum.reduce(c), np.maximum.reduce(c))
    cut = (x.lo <= 0.0) & (y.lo <= 0.0) & (y.hi >= 0.0)  # the origin or the negative x axis
    cont = ~cut & np.isfinite(x.lo) & np.isfinite(x.hi) & np.isfinite(y.lo) & np.isfinite(y.hi)
    return _make(np.where(cont, lo, -PI.hi),
                 np.where(cont, hi, PI.hi)), cont


def acos(u):
    """The range of ``arccos`` over intervals ``u`` clipped to ``[-1, 1]`` (as the point
    evaluators clip a cosine that rounding moved past 1): decreasing, so
    ``[acos(min(hi, 1)), acos(max(lo, -1))]``, each moved :data:`LIBM_ULPS` ulps outward
    (the libm assumption), within ``[0, PI.hi]``.

    Parameters
    ----------
    u : Interval or array_like
        The cosines.

    Returns
    -------
    Interval
        The enclosure [rad].
    """
    u = as_interval(u)
    with np.errstate(invalid="ignore"):
        lo = np.arccos(np.clip(u.hi, -1.0, 1.0))
        hi = np.arccos(np.clip(u.lo, -1.0, 1.0))
    lo, hi = _libm_widen(lo, hi)
    lo = np.where(np.isnan(lo), 0.0, lo)
    hi = np.where(np.isnan(hi), PI.hi, hi)
    return _make(np.maximum(lo, 0.0), np.minimum(hi, PI.hi))


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


#: the constant 2 (:meth:`Gradient.sqr`)
_TWO = _make(np.asarray(2.0), None)
_TWO.hi = _TWO.lo
#: an interval that contains the real number pi (``np.pi`` is below it by less than an ulp)
PI = _make(np.asarray(np.pi), np.nextafter(np.asarray(np.pi), _PINF))


def _parts(o):
    """``(value, gradient or None)`` of a :class:`Gradient` or a constant."""
    if isinstance(o, Gradient):
        return o.v, o.g
    return as_interval(o), None


class Gradient:
    """An interval value with interval partial derivatives: forward-mode automatic
    differentiation in interval arithmetic (each derivative by the chain rule, every
    operation outward rounded as :class:`Interval`'s). Over a box, ``v`` encloses the
    function's range and ``g[k]`` its ``k``-th partial derivative's range, so the mean
    value form ``f(C) in f(c) + sum_k g_k (C_k - c_k)`` (``c`` a point of the box ``C``)
    encloses the range with an overestimate of second order in the box's width
    (Moore, Kearfott, Cloud 2009, sec. 6.4). ``abs`` is Lipschitz, not differentiable at
    0: its derivative is enclosed by ``[-1, 1]`` times the argument's there (Clarke's
    generalised gradient; Lebourg's mean value theorem keeps the mean value form valid).
    Operations mirror :class:`Interval`'s (``lo``, ``hi``, ``sqr``, ``sqrt``, ``nonneg``,
    ``abs``), so one expression evaluates either way.

    Parameters
    ----------
    v : Interval
        The value.
    g : tuple of Interval
        The partial derivatives.
    """

    __slots__ = ("v", "g")
    __array_priority__ = 1001

    def __init__(self, v, g):
        self.v, self.g = as_interval(v), tuple(as_interval(d) for d in g)

    @classmethod
    def variables(cls, *boxes):
        """The independent variables ``boxes`` (intervals), each with a unit derivative.

        Parameters
        ----------
        *boxes : Interval
            The variables' ranges.

        Returns
        -------
        tuple of Gradient
            One per variable.
        """
        n = len(boxes)
        return tuple(cls(b, tuple(Interval(np.full(b.shape, float(i == k))) for k in range(n)))
                     for i, b in enumerate(boxes))

    @property
    def lo(self):
        return self.v.lo

    @property
    def hi(self):
        return self.v.hi

    @property
    def shape(self):
        return self.v.shape

    def _new(self, v, g):
        out = object.__new__(Gradient)
        out.v, out.g = v, g
        return out

    def __neg__(self):
        return self._new(-self.v, tuple(-d for d in self.g))

    def __add__(self, other):
        v, g = _parts(other)
        return self._new(self.v + v, self.g if g is None else tuple(a + b for a, b in zip(self.g, g)))

    __radd__ = __add__

    def __sub__(self, other):
        v, g = _parts(other)
        return self._new(self.v - v, self.g if g is None else tuple(a - b for a, b in zip(self.g, g)))

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        v, g = _parts(other)
        if g is None:
            return self._new(self.v * v, tuple(d * v for d in self.g))
        return self._new(self.v * v, tuple(_product_rule(a, v, self.v, b) for a, b in zip(self.g, g)))

    __rmul__ = __mul__

    def __truediv__(self, other):
        v, g = _parts(other)
        q = self.v / v
        if g is None:
            return self._new(q, tuple(d / v for d in self.g))
        return self._new(q, tuple(_fused(_F_SUBMULDIV, a, q, b, v) or (a - q * b) / v for a, b in zip(self.g, g)))

    def __rtruediv__(self, other):
        v, _ = _parts(other)
        q = v / self.v
        return self._new(q, tuple(_fused(_F_NEGMULDIV, q, d, self.v) or -(q * d) / self.v for d in self.g))

    def sqr(self):
        """``x^2``.

        Returns
        -------
        Gradient
            Value and derivatives ``2 x dx``.
        """
        return self._new(self.v.sqr(), tuple(_fused(_F_SCALE, _TWO, self.v, d) or 2.0 * (self.v * d) for d in self.g))

    def sqrt(self):
        """``sqrt(x)`` of the non-negative part, and where ``lo < 0`` (:meth:`Interval.sqrt`).

        Returns
        -------
        root : Gradient
            Value and derivatives ``dx / (2 sqrt(x))`` (unbounded where the root may vanish).
        negative : ndarray of bool
            Where the argument may be negative.
        """
        r, neg = self.v.sqrt()
        r2 = 2.0 * r
        return self._new(r, tuple(d / r2 for d in self.g)), neg

    def nonneg(self):
        """The value's lower end raised to 0 (:meth:`Interval.nonneg`), derivatives kept.

        Returns
        -------
        Gradient
            The same function, known non-negative.
        """
        return self._new(self.v.nonneg(), self.g)

    def __abs__(self):
        s = _make(np.where(self.v.lo >= 0.0, 1.0, -1.0), np.where(self.v.hi <= 0.0, -1.0, 1.0))
        return self._new(abs(self.v), tuple(d * s for d in self.g))

    def mean_value_lower(self, centre, box):
        """Lower ends of the mean value form ``f(c) + sum_k g_k (C_k - c_k)``.

        Parameters
        ----------
        centre : Interval or Gradient
            ``f`` enclosed at the point ``c`` (of each box).
        box : tuple
            Per variable ``(C_k, c_k)``: the box's interval and the point's coordinate.

        Returns
        -------
        ndarray
            The lower ends (-inf where a derivative is unbounded).
        """
        fc = centre.v if isinstance(centre, Gradient) else centre
        acc = fc
        for d, (C, c) in zip(self.g, box):
            acc = acc + d * (as_interval(C) - c)
        return acc.lo
