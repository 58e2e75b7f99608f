"""Proven lower bounds of the minima over a task of the local quantities the requirements
bound (LCI, the type-II function, the guaranteed speed and force), by interval
branch-and-bound.

The argument. Cover the task ``T`` by cells: a region's by squares of its bounding box
(kept when they may meet ``T``), a path's by pieces of its segments, a point set's by
its points. Over a cell ``C``, each mechanism's
:meth:`~mechopt.core.protocol.PlanarMechanism.closure_enclosure` gives intervals that
contain the exact closure matrices ``A``, ``diag B`` at every point of ``C`` (outward
rounding, :mod:`mechopt.core.interval`), or says that some point of ``C`` may be out of
reach. A :class:`Quantity` turns those intervals into a lower bound of the quantity over
``C``: the larger of the natural interval extension of its formula and its mean value
form ``q(c) + grad q(C) . (C - c)`` about the cell's centre ``c``, the gradient enclosed
by interval forward differentiation (:class:`mechopt.core.interval.Gradient`; an error
of second order in the cell's width, where the natural extension's is of first order);
or, for a cell that may be out of reach, the quantity's floor (its value at
unreachable and singular poses in the point evaluators: LCI, speed and force 0, the type-II function -1; the floor is
a lower bound of every value, so the bound stays sound). The minimum over the cells'
lower bounds is a lower bound of ``min_T q``.

Branch and bound: each round splits, all at once (vectorised), every cell whose lower
bound is below ``upper - tol`` (``upper``: the smallest value of ``q`` at a point of
``T`` found so far, at the cells' centres that lie in ``T`` and at boundary samples: an
upper bound of the minimum) into 4 (a square) or 2 (a piece of a path), or, while the
cells are few, two levels at once (16 or 4); it stops when
``upper - lower <= tol`` or when the budget of evaluated cells would be exceeded (a
round that does not fit splits the cells of lowest bound that fit, then the search
stops). A child's bound is at least its parent's (both bound it; interval evaluation
is inclusion isotone), so the bound never falls as cells split, and a smaller budget
runs a prefix of the same search: the bound does not rise when the budget shrinks.

Lock-step (:func:`lower_bounds`, :func:`lower_bounds_of_designs`): the searches of several
quantities, and of several designs (mechanisms and placements) over one task, advance
round by round together; each search picks and splits its own cells as alone, and the
enclosures over all the rounds' new cells are computed in one vectorised call (designs
that differ only in their lengths share it, each cell with its design's lengths), each
kind of quantity's bounds in one more. A cell's enclosures are elementwise functions of
its box and its design, so each search returns the bound it returns alone, bit for bit
(tests/test_bounds_lockstep.py; but for endpoints in ``[2^-1022, 2^-1020]``, whose
outward rounding depends on the batch's size, :mod:`mechopt.core.interval`: either
encloses), and the argument above holds for each; only the number of array operations
falls.

Ranges (:func:`range_quantity`): ``max_T q_i = -min_T (-q_i)``, so the same search
bounds an actuator coordinate's range from outside (the joints' and strokes' proofs).
Over a cell the mechanism's
:meth:`~mechopt.core.protocol.PlanarMechanism.actuator_enclosure` encloses ``q_i`` (the
natural extension) and the mean value form ``q_i(c) + grad q_i(C) . (C - c)`` uses the
gradient ``a_i / b_i`` (a row of ``J = B^-1 A``, from the closure enclosure over the
cell), valid where ``q_i`` is continuous and differentiable over the cell (the closure
certain: ``b_i`` does not vanish); with a tolerance box the value at the centre is
enclosed over all the box's lengths, so the form needs no derivative in them. A cell
that may be out of reach bounds nothing: its bound is ``-inf`` (the range quantities'
floor), so is the task's.

Tolerance boxes (``lengths``): the enclosures take the mechanism's lengths as intervals
too, so the bound covers the task and every mechanism of the box at once; the lengths
are variables of the mean value form but are not split, so the bound's excess over the
box's minimum does not vanish with the cells (it grows like the square of the
tolerance).

Assumptions, stated: the region's signed distance
(:meth:`~mechopt.analysis.task.Task.signed_distance`) is the exact distance to its boundary up to rounding, absorbed by a margin of
``1e-9 * diameter`` in the test ``sd(centre) >= -half diagonal`` that keeps a cell; the
design spec's ``to_mech`` is a translation (checked; every spec's is); a path is the
polyline through its float points, each piece enclosed by ``v + [t0, t1] e`` in
interval arithmetic; the quantity at a point is the exact real-number value of the
formula of the requirement at that point (the point evaluators compute it in floating
point: a dense check compares within a relative ``1e-9``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from mechopt.core import indices as _ix
from mechopt.core import interval as _iv
from mechopt.core.interval import Gradient, Interval, hypot
from mechopt.analysis.sampling import bad_to

__all__ = ["Quantity", "Bound", "lci_quantity", "type2_quantity", "speed_quantity", "force_quantity",
           "range_quantity", "range_quantities", "lower_bound", "lower_bounds", "lower_bounds_of_designs", "outer_range", "Ranges", "BUDGET", "RTOL", "METHOD"]

#: default budget of evaluated cells per quantity
BUDGET = 30000
#: default stopping gap, relative to ``max(|upper|, scale)`` of the quantity
RTOL = 2e-3
#: the name of the method in certificates
METHOD = "interval branch-and-bound"
#: cells are not split below this fraction of the task's diameter
_MIN_CELL = 1e-9
#: a round splits its cells two levels deep while that makes at most this many children
_TWO_LEVELS = 4096
#: the margin of the cell-keeping test, a fraction of the task's diameter
_KEEP_MARGIN = 1e-9


@dataclass(frozen=True)
class Quantity:
    """A local quantity ``q(P)`` whose minimum over a task is bounded.

    Parameters
    ----------
    name : str
        Its name (``lci``, ``type2``, ``speed``, ``force``).
    floor : float
        Its value at unreachable or singular poses (a lower bound of every value).
    scale : float
        The size of the stopping gap's reference (``tol = rtol * max(|upper|, scale)``).
    cap : float
        An upper bound of every value (LCI and the type-II function: 1).
    terms : callable
        ``terms(A, b)``: the quantity is the minimum of these expressions of the closure
        (:meth:`~mechopt.core.protocol.PlanarMechanism.closure_enclosure`), evaluated on
        :class:`~mechopt.core.interval.Interval` or
        :class:`~mechopt.core.interval.Gradient` arguments.
    point : callable
        ``point(mech, x, y)``: the quantity at points of the mechanism's frame, the
        floor where unreachable (the requirements' formula).
    actuator : int or None
        A range quantity (:func:`range_quantity`): ``sign * q_actuator`` (``terms``
        unused); None for a quantity of the closure.
    sign : float
        +1 or -1 (a range quantity).
    relative : bool
        The stopping gap is relative to ``max(|upper|, scale)`` (True) or to ``scale``
        alone (a coordinate whose offset says nothing of its precision).
    key : tuple or None
        Quantities of equal keys have the same cell bounds (the same ``terms``, or the
        same actuator and sign): :func:`lower_bounds_of_designs` evaluates them in one
        call; None: none other.
    """

    name: str
    floor: float
    scale: float
    cap: float
    terms: object = field(repr=False)
    point: object = field(repr=False)
    actuator: int | None = None
    sign: float = 1.0
    relative: bool = True
    key: tuple | None = None


@dataclass
class Bound:
    """The result of :func:`lower_bound`.

    Parameters
    ----------
    lower : float
        The proven lower bound of the minimum.
    upper : float
        The smallest value found at a task point (an upper bound of the minimum).
    cells : int
        Cells evaluated.
    leaves : int
        Cells of the final cover.
    smallest_cell, largest_cell : float
        Extremes of the final cells' sizes (the larger side of a square, the length of
        a piece of path) [L]; 0 for a point task.
    may_unreachable : bool
        Some cell of the final cover may be out of reach (its bound is the floor).
    converged : bool
        ``upper - lower <= tol`` was reached within the budget.
    tol : float
        The stopping gap.
    """

    lower: float
    upper: float
    cells: int
    leaves: int
    smallest_cell: float
    largest_cell: float
    may_unreachable: bool
    converged: bool
    tol: float

    @property
    def gap(self) -> float:
        """``upper - lower``."""
        return self.upper - self.lower


# ------------------------------------------------------------------ interval helpers
def _det(m):
    return m[0][0] * m[1][1] - m[0][1] * m[1][0]


def _two_smax_squared(m):
    """``2 s_max^2 = S + sqrt(P Q)`` (:func:`mechopt.core.indices.two_smax_squared`) of an
    interval 2x2 matrix, with ``P = (a - d)^2 + (b + c)^2``, ``Q = (a + d)^2 + (b - c)^2``,
    as ``sqrt(P) sqrt(Q)``, each a norm (:func:`~mechopt.core.interval.hypot`: Lipschitz,
    so the mean value form holds at isotropic poses, ``P = 0``)."""
    (a, b), (c, d) = m
    S = a.sqr() + b.sqr() + c.sqr() + d.sqr()
    return S + hypot(a - d, b + c) * hypot(a + d, b - c)


def _jacobian(A, b, w=(1.0, 1.0)):
    """Rows ``a_i / (b_i w_i)``: ``diag(w)^-1 J`` (each ``b_i w_i`` enclosed once)."""
    bw = [b[i] * w[i] for i in range(2)]
    return tuple((A[i][0] / bw[i], A[i][1] / bw[i]) for i in range(2))


# ------------------------------------------------------------------ the quantities
def lci_quantity() -> Quantity:
    """LCI ``= 2 |det J| / (2 s_max^2)`` (Liu 2006 eq. 3, :func:`mechopt.core.indices.lci`),
    ``J`` rows ``a_i / b_i``; floor 0, at most 1.

    Returns
    -------
    Quantity
        The quantity.
    """
    def terms(A, b):
        J = _jacobian(A, b)
        return [2.0 * abs(_det(J)) / _two_smax_squared(J)]

    def point(mech, x, y):
        return bad_to(_ix.lci(mech.jacobian(x, y)), 0.0)
    return Quantity("lci", 0.0, 1.0, 1.0, terms, point, key=("lci",))


def type2_quantity(sign: float) -> Quantity:
    """``sign * det A / (|a_1| |a_2|)`` (:meth:`mechopt.core.protocol.PlanarMechanism.type2_function`
    with the design's sign, :class:`mechopt.requirements.singular.Singular`); floor -1,
    at most 1.

    Parameters
    ----------
    sign : float
        ``s0``, +1 or -1.

    Returns
    -------
    Quantity
        The quantity.
    """
    s = 1.0 if sign >= 0 else -1.0

    def terms(A, b):
        return [(s * _det(A)) / (hypot(*A[0]) * hypot(*A[1]))]

    def point(mech, x, y):
        return bad_to(s * mech.type2_function(x, y), -1.0)
    return Quantity("type2", -1.0, 1.0, 1.0, terms, point, key=("type2", s))


def speed_quantity(w, norm="box") -> Quantity:
    """The guaranteed speed (:func:`mechopt.requirements.speed.speed`) at a pose [L/s]:
    ``min_i w_i / ||row_i(J)|| = min_i w_i |b_i| / |a_i|`` (``"box"``) or
    ``1 / s_max(diag(w)^-1 J)`` (``2``, Liu 2006 eq. 10); floor 0.

    Parameters
    ----------
    w : array_like
        The two rate limits [rad/s or L/s].
    norm : str or int
        ``"box"`` or ``2``.

    Returns
    -------
    Quantity
        The quantity.
    """
    w = np.broadcast_to(np.asarray(w, dtype=float), (2,)).copy()
    box = norm == "box"

    def terms(A, b):
        if box:
            return [w[i] * abs(b[i]) / hypot(*A[i]) for i in range(2)]
        return [1.0 / (_two_smax_squared(_jacobian(A, b, w)) * 0.5).nonneg().sqrt()[0]]

    def point(mech, x, y):
        J = mech.jacobian(x, y)
        with np.errstate(divide="ignore", invalid="ignore"):
            if box:
                r = [bad_to(w[i] / np.hypot(J[..., i, 0], J[..., i, 1]), 0.0) for i in range(2)]
                return np.minimum(*r)
            smax = _ix.singular_values(J / w[:, None])[0]
            return bad_to(1.0 / smax, 0.0)
    return Quantity("speed", 0.0, 0.0, math.inf, terms, point, key=("speed", tuple(map(float, w)), str(norm)))


def force_quantity(t, norm="box", factor=1.0) -> Quantity:
    """The guaranteed force (:func:`mechopt.requirements.force.force`) at a pose [N]:
    ``factor min(t_2 |det J| / ||row_1||, t_1 |det J| / ||row_2||)`` with ``|det J| /
    ||row_i|| = |det A| / (|b_j| |a_i|)`` (``"box"``), or ``factor s_min(diag(t) J)``
    (``2``, Liu 2006 eq. 13); floor 0.

    Parameters
    ----------
    t : array_like
        The two effort limits [N m or N].
    norm : str or int
        ``"box"`` or ``2``.
    factor : float
        N m -> N per rad/L (:func:`mechopt.requirements.force.effort_factor`).

    Returns
    -------
    Quantity
        The quantity.
    """
    t = np.broadcast_to(np.asarray(t, dtype=float), (2,)).copy()
    box, f = norm == "box", float(factor)

    def terms(A, b):
        D = abs(_det(A))
        if box:
            return [(f * t[1]) * D / (abs(b[1]) * hypot(*A[0])), (f * t[0]) * D / (abs(b[0]) * hypot(*A[1]))]
        M = _jacobian(A, b, 1.0 / t)
        return [f * abs(_det(M)) / (_two_smax_squared(M) * 0.5).nonneg().sqrt()[0]]

    def point(mech, x, y):
        J = mech.jacobian(x, y)
        with np.errstate(divide="ignore", invalid="ignore"):
            if box:
                det = np.abs(J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0])
                r1 = bad_to(det / np.hypot(J[..., 0, 0], J[..., 0, 1]), 0.0)
                r2 = bad_to(det / np.hypot(J[..., 1, 0], J[..., 1, 1]), 0.0)
                return np.minimum(t[1] * r1, t[0] * r2) * f
            return bad_to(_ix.singular_values(J * t[:, None])[1], 0.0) * f
    return Quantity("force", 0.0, 0.0, math.inf, terms, point,
                    key=("force", tuple(map(float, t)), str(norm), f))


def range_quantity(i: int, sign: float, scale: float) -> Quantity:
    """``sign * q_i``, the actuator coordinate ``i`` of :meth:`ik` (a crank angle [rad],
    a slider position or strut length [L]): its minimum bounds ``min q_i`` (``sign``
    +1) or ``-max q_i`` (-1) from below; floor ``-inf`` (out of reach: no bound), no cap;
    the stopping gap ``rtol * scale``.

    Parameters
    ----------
    i : int
        0 or 1.
    sign : float
        +1 or -1.
    scale : float
        The stopping gap's reference [rad or L], > 0.

    Returns
    -------
    Quantity
        The quantity.

    Raises
    ------
    ValueError
        For an actuator other than 0 or 1.
    """
    if i not in (0, 1):
        raise ValueError(f"the actuator must be 0 or 1, got {i!r}")
    s = 1.0 if sign >= 0 else -1.0

    def point(mech, x, y):
        return bad_to(s * mech.ik(x, y)[i], -math.inf)
    return Quantity(f"{'' if s > 0 else '-'}q{i + 1}", -math.inf, float(scale), math.inf, None, point,
                    actuator=i, sign=s, relative=False, key=("range", i, s))


def range_quantities(scale: float) -> list:
    """The four quantities of :func:`outer_range`: ``q1``, ``-q1``, ``q2``, ``-q2``
    (:func:`range_quantity`).

    Parameters
    ----------
    scale : float
        The stopping gap's reference [rad or L], > 0.

    Returns
    -------
    list of Quantity
        The quantities, in that order.
    """
    return [range_quantity(i, s, scale) for i in (0, 1) for s in (1.0, -1.0)]


# ------------------------------------------------------------------ cells
def _translation(to_mech):
    """``(dx, dy)`` of ``to_mech`` (a translation; ValueError otherwise)."""
    if to_mech is None:
        return 0.0, 0.0
    px = np.array([0.0, 1.0, -3.0])
    py = np.array([0.0, 2.0, 5.0])
    mx, my = (np.asarray(v, dtype=float) for v in to_mech(px, py))
    dx, dy = float(mx[0]), float(my[0])
    if not (np.allclose(mx - px, dx, rtol=0, atol=1e-12 * (1 + abs(dx)))
            and np.allclose(my - py, dy, rtol=0, atol=1e-12 * (1 + abs(dy)))):
        raise ValueError("the bounds need a design spec whose to_mech is a translation")
    return dx, dy


class _Cells:
    """The cover of a task: ``kind`` ``"box"`` (rows ``x0, x1, y0, y1``), ``"seg"`` (rows
    ``k, t0, t1``: a piece of segment ``k`` of a path) or ``"pt"`` (rows ``x, y``)."""

    def __init__(self, task, n0=4):
        self.task = task
        D = task.diameter
        if task.is_region:
            self.kind = "box"
            x0, x1, y0, y1 = task.bbox
            side = max(x1 - x0, y1 - y0)
            nx, ny = (max(1, int(math.ceil(n0 * (s / side)))) for s in (x1 - x0, y1 - y0))
            ex, ey = np.linspace(x0, x1, nx + 1), np.linspace(y0, y1, ny + 1)
            X0, Y0 = np.meshgrid(ex[:-1], ey[:-1])
            X1, Y1 = np.meshgrid(ex[1:], ey[1:])
            rows = np.stack([X0.ravel(), X1.ravel(), Y0.ravel(), Y1.ravel()], 1)
            self.rows = rows[self._meets(rows)]
        elif task.is_path:
            self.kind = "seg"
            p = np.asarray(task.pts, dtype=float)
            self.v, self.e = p[:-1], p[1:] - p[:-1]
            k = np.arange(len(self.v), dtype=float)
            self.rows = np.stack([k, np.zeros_like(k), np.ones_like(k)], 1)
        else:
            self.kind = "pt"
            self.rows = np.asarray(task.pts, dtype=float).copy()
        self.min_size = _MIN_CELL * D

    def _meets(self, rows):
        """Cells that may meet the task: ``sd(centre) >= -half diagonal - margin``."""
        cx, cy = 0.5 * (rows[:, 0] + rows[:, 1]), 0.5 * (rows[:, 2] + rows[:, 3])
        half = 0.5 * np.hypot(rows[:, 1] - rows[:, 0], rows[:, 3] - rows[:, 2])
        sd = self.task.signed_distance(cx, cy)
        return sd >= -half - _KEEP_MARGIN * self.task.diameter

    def boxes(self, rows, dx, dy):
        """``(X, Y)`` intervals of the cells in the mechanism's frame."""
        if self.kind == "box":
            X, Y = Interval(rows[:, 0], rows[:, 1]), Interval(rows[:, 2], rows[:, 3])
        elif self.kind == "seg":
            k = rows[:, 0].astype(int)
            T = Interval(rows[:, 1], rows[:, 2])
            X = T * self.e[k, 0] + self.v[k, 0]
            Y = T * self.e[k, 1] + self.v[k, 1]
        else:
            X, Y = Interval(rows[:, 0]), Interval(rows[:, 1])
        if dx or dy:
            X, Y = X + dx, Y + dy
        return X, Y

    def sizes(self, rows):
        """Each cell's size [L] (the larger side, the piece's length, 0)."""
        if self.kind == "box":
            return np.maximum(rows[:, 1] - rows[:, 0], rows[:, 3] - rows[:, 2])
        if self.kind == "seg":
            k = rows[:, 0].astype(int)
            return (rows[:, 2] - rows[:, 1]) * np.hypot(self.e[k, 0], self.e[k, 1])
        return np.zeros(len(rows))

    def centres(self, rows):
        """Task points of the cells (task frame): centres in the task, a path's piece's
        midpoint; and which of them lie in the task."""
        if self.kind == "box":
            cx, cy = 0.5 * (rows[:, 0] + rows[:, 1]), 0.5 * (rows[:, 2] + rows[:, 3])
            return cx, cy, self.task.contains(cx, cy)
        if self.kind == "seg":
            k = rows[:, 0].astype(int)
            t = 0.5 * (rows[:, 1] + rows[:, 2])
            return self.v[k, 0] + t * self.e[k, 0], self.v[k, 1] + t * self.e[k, 1], np.ones(len(rows), bool)
        return rows[:, 0], rows[:, 1], np.ones(len(rows), bool)

    def children(self, levels: int) -> int:
        """How many children one split of ``levels`` levels gives (a square: ``4^levels``,
        a piece of path: ``2^levels``, a point: 0)."""
        return {"box": 4, "seg": 2, "pt": 0}[self.kind] ** levels if self.kind != "pt" else 0

    def split(self, rows, levels: int = 1):
        """The children of ``rows`` after ``levels`` halvings of each side, kept where they
        may meet the task; and the index of each child's parent."""
        return self.split_each([rows], [levels])[0]

    def split_each(self, rows_list, levels_list):
        """:meth:`split` of each ``rows`` of ``rows_list`` by its ``levels``, each level's
        halving and keeping computed once over the distinct rows of all (a row's children
        and whether they may meet the task are functions of the row alone: the same arrays
        as one :meth:`split` per ``rows``).

        Parameters
        ----------
        rows_list : list of ndarray
            The cells of each search.
        levels_list : list of int
            Per search, the levels of its split.

        Returns
        -------
        list of tuple
            Per search ``(children, parent)``, as :meth:`split`'s.
        """
        out = [(np.asarray(r, dtype=float), np.arange(len(r))) for r in rows_list]
        for level in range(max(levels_list, default=0)):
            active = [i for i, n in enumerate(levels_list) if n > level]
            for i, (kids, parent) in zip(active, self._halve_each([out[i][0] for i in active])):
                out[i] = (kids, out[i][1][parent])
        return out

    def _halve_each(self, rows_list):
        """One halving of each ``rows`` (:meth:`split_each`): per ``rows`` the children,
        quadrant by quadrant (a piece of path: half by half) in the order of ``rows``, kept
        where they may meet the task, and each child's parent."""
        rows = np.ascontiguousarray(np.concatenate(rows_list))
        key = rows.view(np.dtype((np.void, rows.dtype.itemsize * rows.shape[1])))[:, 0]
        _, first, where = np.unique(key, return_index=True, return_inverse=True)
        where = where.ravel()
        if self.kind == "box":
            x0, x1, y0, y1 = rows[first].T
            xm, ym = 0.5 * (x0 + x1), 0.5 * (y0 + y1)
            parts = [np.stack(c, 1) for c in ((x0, xm, y0, ym), (xm, x1, y0, ym), (x0, xm, ym, y1), (xm, x1, ym, y1))]
            m = len(first)
            keep = self._meets(np.concatenate(parts))
            keeps = [keep[q * m:(q + 1) * m] for q in range(4)]
        else:
            k, t0, t1 = rows[first].T
            tm = 0.5 * (t0 + t1)
            parts = [np.stack([k, t0, tm], 1), np.stack([k, tm, t1], 1)]
            keeps = [None, None]
        out, at = [], 0
        for r in rows_list:
            idx = where[at:at + len(r)]
            at += len(r)
            kids, parent = [], []
            for part, keep in zip(parts, keeps):
                if keep is None:
                    kids.append(part[idx])
                    parent.append(np.arange(len(idx)))
                else:
                    kept = keep[idx]
                    kids.append(part[idx[kept]])
                    parent.append(np.flatnonzero(kept))
            out.append((np.concatenate(kids), np.concatenate(parent)))
        return out


def _take(v, idx):
    """``v`` (an :class:`~mechopt.core.interval.Interval`, a
    :class:`~mechopt.core.interval.Gradient`, an array or a tuple of them) at the cells
    ``idx`` (exact: indexing; a scalar, the same for every cell, stays)."""
    if isinstance(v, tuple):
        return tuple(_take(w, idx) for w in v)
    if isinstance(v, Gradient):
        return Gradient(_take(v.v, idx), _take(v.g, idx))
    if isinstance(v, Interval):
        lo, hi = v.lo, v.hi
        if np.shape(lo) != np.shape(hi):
            lo, hi = np.broadcast_arrays(lo, hi)
        return _pair(lo[idx], hi[idx]) if np.ndim(lo) else v
    return v[idx] if np.ndim(v) else v


def _subset(v, idx):
    """:func:`_take` of ``v`` at ``idx``, or ``v`` itself for ``idx`` None (every cell)."""
    return v if idx is None else _take(v, idx)


def _value(v):
    """The value of a :class:`~mechopt.core.interval.Gradient` (an interval: itself)."""
    return v.v if isinstance(v, Gradient) else v


def _pair(lo, hi):
    """An :class:`~mechopt.core.interval.Interval` of ordered endpoints (no check)."""
    out = object.__new__(Interval)
    out.lo, out.hi = lo, hi
    return out


class _Enclosures:
    """The enclosures over cells ``rows`` that the quantities read, each computed once for
    all the searches that share a round (:func:`lower_bounds`): for quantities of the
    closure, the closure enclosure with interval derivatives over each cell (and the
    lengths' box) and at its centre; for range quantities, the actuator enclosure over each
    cell and at its centre, and the closure enclosure over the cell. Each cell's
    enclosures are elementwise functions of its own box, so a cell gets the same
    intervals whichever cells share its batch; each part (closure, ranges) is computed
    over the cells its quantities read (``closure``, ``ranges``: masks of the batch's
    cells, True for every cell, False for none), in the size class of the whole batch
    (:meth:`_part`)."""

    def __init__(self, mech, cells, rows, dx, dy, lengths, shift, closure, ranges, fixed=None):
        if np.ndim(dx) or np.ndim(dy):  # per cell (cells of several designs): moved where nonzero,
            X, Y = cells.boxes(rows, 0.0, 0.0)  # as :meth:`_Cells.boxes` moves a design's cells
            moved = (dx != 0) | (dy != 0)
            if np.any(moved):
                Xm, Ym = X + dx, Y + dy
                X, Y = (_pair(np.where(moved, m.lo, b.lo), np.where(moved, m.hi, b.hi)) for m, b in ((Xm, X), (Ym, Y)))
        else:
            X, Y = cells.boxes(rows, dx, dy)
        if shift:  # outward-rounded sums: every point of the cell moved by up to +-shift
            X, Y = X + Interval(-shift, shift), Y + Interval(-shift, shift)
        self.n = n = len(rows)
        # the lengths of the cells' designs (constants, each cell its own design's)
        fixed = {k: Interval(v) for k, v in (fixed or {}).items()}
        plain_of_grad = closure is not False and ranges is not False and not lengths
        if plain_of_grad:  # the range quantities' closure: the values of the derivatives' (below)
            closure = True if closure is True or ranges is True else closure | ranges
        self._cpos, C = self._part(closure)
        self._rpos, R = self._part(ranges)
        with np.errstate(all="ignore"):
            if closure is not False:
                Xc, Yc, fc = _subset(X, C), _subset(Y, C), {k: _subset(v, C) for k, v in fixed.items()}
                names = list(lengths or {})
                boxes = [Xc, Yc] + [Interval(*lengths[k]) for k in names]
                self.centres = [Xc.mid, Yc.mid] + [float(b.mid) for b in boxes[2:]]
                self.boxes = boxes
                v = Gradient.variables(*boxes)
                kw = {"lengths": {**fc, **dict(zip(names, v[2:]))}} if names or fc else {}
                self.grad = mech.closure_enclosure(v[0], v[1], **kw)
                at = {"lengths": {**fc, **{k: Interval(c) for k, c in zip(names, self.centres[2:])}}} \
                    if names or fc else {}
                self.at_centre = mech.closure_enclosure(Interval(self.centres[0]), Interval(self.centres[1]), **at)
            if ranges is not False:
                Xr, Yr, fr = _subset(X, R), _subset(Y, R), {k: _subset(v, R) for k, v in fixed.items()}
                L = {**fr, **({k: Interval(*lh) for k, lh in lengths.items()} if lengths else {})}
                kw = {"lengths": L} if L else {}
                cx, cy = Xr.mid, Yr.mid
                self.rX, self.rY, self.cx, self.cy = Xr, Yr, cx, cy
                self.act = mech.actuator_enclosure(Xr, Yr, **kw)
                self.act_centre = mech.actuator_enclosure(Interval(cx), Interval(cy), **kw)
                if plain_of_grad:  # the values of the closure with derivatives: the same
                    # interval operations on the same boxes (Gradient's values are Interval's)
                    A, b, certain = _take(self.grad, self._at(self._cpos, np.arange(n) if R is None else R))
                    self.plain = (tuple(tuple(_value(e) for e in row) for row in A), tuple(_value(e) for e in b),
                                  certain)
                else:
                    self.plain = mech.closure_enclosure(Xr, Yr, **kw)

    def _part(self, which):
        """``(positions, cells)`` of a part of the enclosures (closure or ranges): over
        every cell (``which`` True; positions and cells None), none (False), or the cells
        of the mask ``which`` (the cells its searches read). A part over fewer than
        :data:`~mechopt.core.interval._FEW` cells of a batch of more is over every cell:
        outward rounding depends on the size class of the arrays
        (:mod:`mechopt.core.interval`), so a part's intervals are those of the whole batch
        only where both are of one class."""
        if which is True or which is False:
            return None, None
        cells = np.flatnonzero(which)
        if len(cells) == self.n or (len(cells) < _iv._FEW <= self.n):
            return None, None
        pos = np.full(self.n, -1)
        pos[cells] = np.arange(len(cells))
        return pos, cells

    @staticmethod
    def _at(pos, idx):
        """The positions in a part of the batch's cells ``idx``."""
        return idx if pos is None else pos[idx]

    def bound(self, q, idx):
        """Lower bounds of ``q`` over the cells ``idx`` (of the batch) and where they may be
        out of reach."""
        if not len(idx):  # a search without cells this round (its part may not be computed)
            return np.empty(0), np.zeros(0, bool)
        rng = q.actuator is not None
        idx = self._at(self._rpos if rng else self._cpos, idx)
        m = len(self.rX.lo) if rng else len(self.boxes[0].lo)
        if len(idx) == m and np.array_equal(idx, np.arange(m)):
            idx = slice(None)  # every cell of the part in order: views, no copies
        with np.errstate(all="ignore"):
            if rng:
                return self._range(q, idx)
            return self._closure(q, idx)

    def _closure(self, q, idx):
        """Per term the larger of the natural interval bound and the mean value form's
        about the cell's centre and the lengths' midpoints (both enclose the term's range),
        the smallest over the terms, within ``[floor, cap]``; the floor where the cell may
        be out of reach."""
        A, b, certain = _take(self.grad, idx)
        Ac, bc, _ = _take(self.at_centre, idx)
        box = list(zip(_take(tuple(self.boxes), idx), _take(tuple(self.centres), idx)))
        lb = np.full(len(self.boxes[0].lo[idx]), np.inf)
        for term, at_c in zip(q.terms(A, b), q.terms(Ac, bc)):
            low = np.maximum(term.lo, term.mean_value_lower(at_c, box))
            lb = np.minimum(lb, np.where(np.isnan(low), -np.inf, low))
        lb = np.minimum(np.maximum(lb, q.floor), q.cap)
        lb = np.where(certain, lb, q.floor)
        return lb, ~np.broadcast_to(certain, lb.shape)

    def _range(self, q, idx):
        """The larger of the natural enclosure of ``sign * q_i`` and the mean value form
        ``q(c) + g . (C - c)`` with ``g = sign a_i / b_i`` over the box (where the closure
        is certain: ``q_i`` is differentiable there) and ``q(c)`` enclosed at the centre
        over the lengths' box; ``-inf`` where the box may be out of reach."""
        i, s = q.actuator, q.sign
        (qs, certain), (qc, _) = _take(self.act, idx), _take(self.act_centre, idx)
        A, b, smooth = _take(self.plain, idx)
        X, Y, cx, cy = _take((self.rX, self.rY, self.cx, self.cy), idx)
        val, at_c = (qs[i], qc[i]) if s > 0 else (-qs[i], -qc[i])
        mv = at_c + (s * A[i][0] / b[i]) * (X - cx) + (s * A[i][1] / b[i]) * (Y - cy)
        low = np.where(np.broadcast_to(smooth, val.lo.shape), np.maximum(val.lo, mv.lo), val.lo)
        certain = np.broadcast_to(certain, low.shape)
        low = np.where(certain & ~np.isnan(low), low, -math.inf)
        return low, ~certain


def _upper(mech, q, cells, rows, dx, dy):
    """The smallest value of ``q`` at the cells' task points (inf when none)."""
    cx, cy, inside = cells.centres(rows)
    if not np.any(inside):
        return math.inf
    with np.errstate(all="ignore"):
        v = q.point(mech, cx[inside] + dx, cy[inside] + dy)
    return float(np.min(v))


def _tol(q, ub, rtol):
    """The stopping gap: ``rtol * max(|upper|, scale)`` (``scale`` alone for a quantity
    not ``relative``)."""
    return rtol * max(abs(ub) if q.relative and math.isfinite(ub) else 0.0, q.scale, 1e-300)


def lower_bound(mech, task, q: Quantity, to_mech=None, budget: int = BUDGET, rtol: float = RTOL,
                upper: float = math.inf, lengths: dict | None = None, shift: float = 0.0) -> Bound:
    """A proven lower bound of ``min_T q`` by interval branch-and-bound (module docstring).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism (with :meth:`~mechopt.core.protocol.PlanarMechanism.closure_enclosure`).
    task : mechopt.analysis.task.Task
        The task, as placed (task frame).
    q : Quantity
        The quantity.
    to_mech : callable, optional
        Task frame -> mechanism frame (a design spec's ``to_mech`` bound to ``mech``; a
        translation); default the identity.
    budget : int
        The most cells evaluated, >= 1.
    rtol : float
        The stopping gap relative to ``max(|upper|, q.scale)``, > 0.
    upper : float
        A known value of ``q`` at a task point (e.g. a sampled minimum), if any.
    lengths : dict, optional
        ``{parameter: (lo, hi)}`` [L]: bound over every mechanism whose lengths lie in
        these ranges (a tolerance box about ``mech``'s, which must lie inside them), not
        split (:meth:`~mechopt.core.protocol.PlanarMechanism.closure_enclosure`).
    shift : float
        ``>= 0`` [L]: bound over every placement of the task moved by up to ``shift`` in
        x and y (each cell's box widened by it; a tolerance on the task's placement).
        ``upper`` and the values found stay those of the task as placed (one of them).

    Returns
    -------
    Bound
        The bound, the best value found, the cells and sizes.

    Raises
    ------
    ValueError
        For a mechanism without enclosure, a ``to_mech`` that is not a translation, a
        budget < 1 or a non-positive ``rtol``.
    """
    return lower_bounds(mech, task, [q], to_mech=to_mech, budget=budget, rtol=rtol, uppers=[upper],
                        lengths=lengths, shift=shift)[0]


class _Search:
    """The state of one quantity's branch and bound in :func:`lower_bounds`."""

    def __init__(self, q, upper, design):
        self.q, self.ub, self.design = q, float(upper), design
        self.converged, self.done, self.step = False, False, None


def lower_bounds(mech, task, qs, to_mech=None, budget: int = BUDGET, rtol: float = RTOL, uppers=None,
                 lengths: dict | None = None, shift: float = 0.0) -> list:
    """:func:`lower_bound` of several quantities over the same task, mechanism, lengths
    and shift, their searches run in lock-step (:func:`lower_bounds_of_designs`).

    Parameters
    ----------
    mech, task, to_mech, budget, rtol, lengths, shift
        As :func:`lower_bound`'s (``budget``: per quantity).
    qs : sequence of Quantity
        The quantities.
    uppers : sequence of float, optional
        Per quantity, :func:`lower_bound`'s ``upper`` (default none known).

    Returns
    -------
    list of Bound
        One per quantity, in order.

    Raises
    ------
    ValueError
        As :func:`lower_bound`.
    """
    return lower_bounds_of_designs(task, [(mech, to_mech, qs, uppers)], budget=budget, rtol=rtol, lengths=lengths,
                                   shift=shift)[0]


def _alike(m1, m2, names) -> bool:
    """``m1`` and ``m2`` of one class and equal in every attribute but the lengths ``names``
    (then ``m1``'s enclosures with ``m2``'s lengths passed as ``lengths`` are ``m2``'s)."""
    if type(m1) is not type(m2) or not hasattr(m1, "__dict__") or not hasattr(m2, "__dict__"):
        return False
    a = {k: v for k, v in vars(m1).items() if k not in names}
    b = {k: v for k, v in vars(m2).items() if k not in names}
    if a.keys() != b.keys():
        return False
    for k in a:
        try:
            if not (a[k] is b[k] or (type(a[k]) is type(b[k]) and isinstance(a[k], (int, float, str, bool, tuple))
                                     and bool(a[k] == b[k]))):
                return False
        except Exception:  # noqa: BLE001 - an attribute that does not compare: not alike
            return False
    return True


def lower_bounds_of_designs(task, designs, budget: int = BUDGET, rtol: float = RTOL, lengths: dict | None = None,
                            shift: float = 0.0, names=()) -> list:
    """:func:`lower_bound` of several quantities of several designs (mechanisms and
    placements) over the same task, every search run in lock-step: each round every search
    still running picks and splits its cells as it would alone, and the enclosures over
    all the new cells (the same cell of the same design once) are computed in one
    vectorised call per group of designs (:class:`_Enclosures`), which the quantities then
    read (:mod:`mechopt.analysis.bounds`, "Lock-step"). Designs whose mechanisms differ
    only in the lengths ``names`` (same class, every
    other attribute equal: the working mode, the strokes) share a group: the group's first
    mechanism's enclosures are called with each cell's design's lengths as ``lengths``
    (degenerate intervals, per cell), which the enclosures' contract makes the enclosures
    of that design's mechanism. A cell's enclosures are elementwise functions of its own
    box and lengths, and each search's picks read its own cells only: every search takes
    the same steps as alone, only the number of array operations falls (the lengths as
    degenerate intervals instead of floats: the same interval operations for the
    mechanisms of mechopt, whose enclosures turn a float length into a degenerate interval
    first).

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The task, as placed (task frame).
    designs : sequence of tuple
        Per design ``(mech, to_mech, qs, uppers)``: :func:`lower_bound`'s ``mech`` and
        ``to_mech``, its quantities and their ``upper`` values (None: none known).
    budget, rtol, lengths, shift
        As :func:`lower_bound`'s (``budget``: per quantity).
    names : sequence of str
        The length attributes in which the designs' mechanisms may differ and share a
        group (the design spec's lengths); with ``lengths`` (a tolerance box) no group
        forms.

    Returns
    -------
    list of list of Bound
        Per design, one per quantity, in order.

    Raises
    ------
    ValueError
        As :func:`lower_bound`.
    """
    budget = int(budget)
    if budget < 1:
        raise ValueError(f"budget must be >= 1, got {budget!r}")
    if not (rtol > 0 and math.isfinite(rtol)):
        raise ValueError(f"rtol must be a number > 0, got {rtol!r}")
    if not (shift >= 0 and math.isfinite(shift)):
        raise ValueError(f"shift must be a length >= 0, got {shift!r}")
    searches, mechs, moves, groups = [], [], [], []
    for d, (mech, to_mech, qs, uppers) in enumerate(designs):
        qs = list(qs)
        uppers = [math.inf] * len(qs) if uppers is None else [float(u) for u in uppers]
        if len(uppers) != len(qs):
            raise ValueError(f"{len(qs)} quantities but {len(uppers)} upper values")
        if mech.closure_enclosure(Interval(np.zeros(1)), Interval(np.zeros(1))) is None:
            raise ValueError(f"{type(mech).__name__} has no closure enclosure")
        if any(q.actuator is not None for q in qs) and \
                mech.actuator_enclosure(Interval(np.zeros(1)), Interval(np.zeros(1))) is None:
            raise ValueError(f"{type(mech).__name__} has no actuator enclosure")
        mechs.append(mech)
        moves.append(_translation(to_mech))
        searches += [_Search(q, u, d) for q, u in zip(qs, uppers)]
        g = next((g for g in groups if not lengths and names and _alike(mechs[g[0]], mech, names)), None)
        if g is None:
            groups.append([d])
        else:
            g.append(d)
    group_of = {d: k for k, g in enumerate(groups) for d in g}
    cells = _Cells(task)
    if task.is_region:  # boundary samples: the minimum is often on the boundary
        tb, _ = task.boundary_params(256)
        bx, by = task.boundary_at(tb)

    def evaluate(todo, rows_of):
        """Per search of ``todo`` the bounds over its cells ``rows_of(s)``, its group's
        enclosures computed once over the distinct (design, cell) pairs."""
        out = {}
        for k, g in enumerate(groups):
            mine = [s for s in todo if group_of[s.design] == k]
            if not mine:
                continue
            rows = np.concatenate([rows_of(s) for s in mine])
            tag = np.concatenate([np.full(len(rows_of(s)), s.design, float) for s in mine])
            # the same cell of the same design once: rows equal bit for bit
            full = np.ascontiguousarray(np.column_stack([rows, tag]))
            key = full.view(np.dtype((np.void, full.dtype.itemsize * full.shape[1])))[:, 0]
            _, first, where = np.unique(key, return_index=True, return_inverse=True)
            where = where.ravel()
            design = tag[first].astype(int)
            if len(g) > 1:
                dx = np.array([moves[d][0] for d in range(len(designs))])[design]
                dy = np.array([moves[d][1] for d in range(len(designs))])[design]
                fixed = {n: np.array([float(getattr(mechs[d], n)) for d in range(len(designs))])[design]
                         for n in names}
            else:
                (dx, dy), fixed = moves[g[0]], None
            # the searches' cells in the batch; one evaluation per kind of quantity
            spans, at = {}, 0
            for s in mine:
                n = len(rows_of(s))
                spans[id(s)] = (at, at + n)
                at += n
            # the cells the closure's and the ranges' quantities read (each part over its own)
            parts = []
            for rng in (False, True):
                mask = np.zeros(len(first), bool)
                for s in mine:
                    if (s.q.actuator is not None) == rng:
                        mask[where[slice(*spans[id(s)])]] = True
                parts.append(mask if mask.any() else False)
            enc = _Enclosures(mechs[g[0]], cells, rows[first], dx, dy, lengths, shift, *parts, fixed)
            kinds = {}
            for s in mine:
                kinds.setdefault(s.q.key if s.q.key is not None else id(s.q), []).append(s)
            for same in kinds.values():
                lb, unk = enc.bound(same[0].q, np.concatenate([where[slice(*spans[id(s)])] for s in same]))
                at = 0
                for s in same:
                    n = spans[id(s)][1] - spans[id(s)][0]
                    out[id(s)] = lb[at:at + n], unk[at:at + n]
                    at += n
        return out

    for s in searches:
        s.rows = cells.rows
    first = evaluate(searches, lambda s: s.rows)
    for s in searches:
        mech, (dx, dy) = mechs[s.design], moves[s.design]
        s.lb, s.unk = first[id(s)]
        s.used = len(s.rows)
        s.ub = min(s.ub, _upper(mech, s.q, cells, s.rows, dx, dy))
        if task.is_region:
            with np.errstate(all="ignore"):
                s.ub = min(s.ub, float(np.min(s.q.point(mech, bx + dx, by + dy))))
    while True:
        for s in searches:
            s.step = None if s.done else _step(s, cells, budget, rtol)
        todo = [s for s in searches if s.step is not None]
        if not todo:
            break
        # every search's cells split at once (each gets the children of its own split)
        split = cells.split_each([s.rows[s.step[0]] for s in todo], [s.step[1] for s in todo])
        for s, (kids, parent) in zip(todo, split):
            s.step = (s.step[0], kids, parent, s.step[2])
        found = evaluate(todo, lambda s: s.step[1])
        for s in todo:
            pick, k, parent, truncated = s.step
            klb, kunk = found[id(s)]
            klb = np.maximum(klb, s.lb[pick][parent])  # both bound the child
            s.used += len(k)
            s.ub = min(s.ub, _upper(mechs[s.design], s.q, cells, k, *moves[s.design]))
            keep = np.ones(len(s.rows), bool)
            keep[pick] = False
            s.rows = np.concatenate([s.rows[keep], k])
            s.lb = np.concatenate([s.lb[keep], klb])
            s.unk = np.concatenate([s.unk[keep], kunk])
            s.done = truncated
    out = [[] for _ in designs]
    for s in searches:
        q, lb, rows = s.q, s.lb, s.rows
        low = float(lb.min()) if len(lb) else math.inf
        tol = _tol(q, s.ub, rtol)
        sizes = cells.sizes(rows)
        out[s.design].append(Bound(lower=low, upper=s.ub, cells=int(s.used), leaves=int(len(rows)),
                                   smallest_cell=float(sizes.min()) if len(sizes) else 0.0,
                                   largest_cell=float(sizes.max()) if len(sizes) else 0.0,
                                   may_unreachable=bool(np.any(s.unk & (lb <= q.floor))),
                                   converged=s.converged or s.ub - low <= tol, tol=float(tol)))
    return out


def _step(s, cells, budget, rtol):
    """One round of a search: None when it stops (converged, nothing to split, out of
    budget), else ``(pick, levels, truncated)``: the cells to split and how deep (the
    caller splits, :meth:`_Cells.split_each`)."""
    q, lb, rows = s.q, s.lb, s.rows
    tol = _tol(q, s.ub, rtol)
    low = float(lb.min()) if len(lb) else math.inf
    if s.ub - low <= tol:
        s.converged = s.done = True
        return None
    if cells.kind == "pt":
        s.done = True
        return None
    pick = np.flatnonzero((lb < s.ub - tol) & (cells.sizes(rows) > cells.min_size))
    if not pick.size:
        s.done = True
        return None
    # few cells: two levels at once (a round costs mostly its fixed overhead)
    levels = 2 if pick.size * cells.children(2) <= _TWO_LEVELS else 1
    room = (budget - s.used) // cells.children(levels)
    truncated = room < pick.size
    if truncated:
        if room <= 0:
            s.done = True
            return None
        pick = pick[np.argsort(lb[pick], kind="stable")[:room]]
    return pick, levels, truncated


@dataclass
class Ranges:
    """The result of :func:`outer_range`.

    Parameters
    ----------
    outer : list of tuple
        ``[(lo1, hi1), (lo2, hi2)]``: proven outer ranges of the actuator coordinates over
        the task (each contains the exact range) [rad or L]; infinite ends where a cell
        may be out of reach.
    inner : list of tuple
        The extremes of the values found at task points (inside the exact range).
    bounds : list of Bound
        The four searches: ``q1``, ``-q1``, ``q2``, ``-q2``.
    """

    outer: list
    inner: list
    bounds: list

    @classmethod
    def of(cls, bounds):
        """The ranges of the four searches of :func:`range_quantities`, in its order.

        Parameters
        ----------
        bounds : list of Bound
            ``q1``, ``-q1``, ``q2``, ``-q2``.

        Returns
        -------
        Ranges
            Their outer and inner ranges.
        """
        bounds = list(bounds)
        outer = [(bounds[k].lower, -bounds[k + 1].lower) for k in (0, 2)]
        inner = [(bounds[k].upper, -bounds[k + 1].upper) for k in (0, 2)]
        return cls(outer, inner, bounds)

    @property
    def cells(self) -> int:
        """Cells evaluated by the four searches."""
        return int(sum(b.cells for b in self.bounds))

    @property
    def converged(self) -> bool:
        """Every search converged."""
        return all(b.converged for b in self.bounds)

    @property
    def may_unreachable(self) -> bool:
        """Some cell of a final cover may be out of reach."""
        return any(b.may_unreachable for b in self.bounds)

    @property
    def gap(self) -> float:
        """The largest excess of an outer end over the inner one [rad or L]."""
        return float(max(max(ilo - olo, ohi - ihi) for (olo, ohi), (ilo, ihi) in zip(self.outer, self.inner)))


def outer_range(mech, task, scale: float, to_mech=None, budget: int = BUDGET, rtol: float = RTOL,
                lengths: dict | None = None, shift: float = 0.0) -> Ranges:
    """Proven outer ranges of both actuator coordinates over the task: ``min q_i`` and
    ``max q_i = -min(-q_i)`` bounded by :func:`lower_bound` with :func:`range_quantity`
    (four searches, each of ``budget`` cells at most).

    Parameters
    ----------
    mech : PlanarMechanism
        The mechanism (with :meth:`~mechopt.core.protocol.PlanarMechanism.actuator_enclosure`).
    task : mechopt.analysis.task.Task
        The task, as placed (task frame).
    scale : float
        The stopping gap's reference [rad or L] (each end within ``rtol * scale``).
    to_mech, budget, rtol, lengths, shift
        As :func:`lower_bound`'s.

    Returns
    -------
    Ranges
        The outer and inner ranges and the searches.

    Raises
    ------
    ValueError
        As :func:`lower_bound`, and for a mechanism without actuator enclosure.
    """
    return Ranges.of(lower_bounds(mech, task, range_quantities(scale), to_mech=to_mech, budget=budget, rtol=rtol,
                                  lengths=lengths, shift=shift))
