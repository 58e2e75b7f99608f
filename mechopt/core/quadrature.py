"""Quadrature rules over disks and rasters, named in every output.

Two rules exist for means over a disk (the MIW of Liu 2006 and its concentric
disk of half radius):

``area``
    The true area mean ``int f dA / int dA``: Gauss-Legendre in the radius with
    the Jacobian ``r`` folded into the weights, and the periodic trapezoid rule
    in the angle. This is the default.
``polar``
    The plain mean of ``f`` over a uniform ``(r, theta)`` grid (mid-points in
    ``r``), i.e. ``(1/R) int int f dr dtheta / 2 pi``. It weights the centre
    more than the rim. Liu's tabulated global indices are reproduced by it (see
    ``tests/test_liu2006.py``).

Regions that are not disks (usable workspace, good-conditioning workspace) are
integrated on a :class:`Grid` of square cells (mid-point rule on a mask).
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from mechopt.core import validation as _v

__all__ = ["QUADRATURES", "gauss_legendre", "disk_rule", "Grid", "grid_over"]

QUADRATURES = ("area", "polar")

#: default resolutions; ``tests/test_quadrature.py`` shows each converged to 1e-3
DEFAULT_N_R = 48
DEFAULT_N_THETA = 96
#: most nodes of one rule or raster (a bad step or resolution would exhaust memory)
MAX_NODES = 10**7
#: the default raster of a mean over a mechanism's reachable set: this many cells across
#: the smaller side of its bounding box (:meth:`~mechopt.core.protocol.PlanarMechanism.raster_mean`,
#: the raster GTQI of the Bipod and of the two-slider mechanisms, the asymmetric five-bar's
#: ``raster-N`` summary). The mid-point rule on a mask errs to first order in the cell
#: size, i.e. by ``O(1/RASTER_CELLS)`` of the mean (the cells the boundary cuts)
RASTER_CELLS = 400


@lru_cache(maxsize=32)
def gauss_legendre(n: int):
    """The ``n``-point Gauss-Legendre rule on ``[-1, 1]``: read-only ``(nodes, weights)``.

    ``numpy.polynomial.legendre.leggauss(n)``, computed once per order: its eigenvalue
    problem costs about 1 ms for ``n = 48`` and the optimisation loops (Stan 2008's TQI
    and k_av integrals, Wu 2008's dynamics scans) ask for the same orders hundreds of
    times. Exact for polynomials of degree ``2 n - 1``.

    Parameters
    ----------
    n : int
        The number of nodes.

    Returns
    -------
    nodes, weights : ndarray
        Read-only arrays.
    """
    g, gw = np.polynomial.legendre.leggauss(n)
    g.flags.writeable = False
    gw.flags.writeable = False
    return g, gw


@lru_cache(maxsize=32)
def _unit_disk_rule(rule: str, n_r: int, n_theta: int):
    th = (np.arange(n_theta) + 0.5) * (2 * np.pi / n_theta)
    if rule == "area":
        g, gw = gauss_legendre(n_r)
        r = 0.5 * (g + 1.0)
        wr = 0.5 * gw * r  # int_0^1 f r dr
        wr = wr / wr.sum()
    else:
        r = (np.arange(n_r) + 0.5) / n_r
        wr = np.full(n_r, 1.0 / n_r)
    R, T = np.meshgrid(r, th, indexing="ij")
    w = np.repeat(wr[:, None], n_theta, axis=1) / n_theta
    out = (R * np.cos(T)).ravel(), (R * np.sin(T)).ravel(), w.ravel()
    for a in out:
        a.setflags(write=False)
    return out


def disk_rule(radius, rule: str = "area", n_r: int = DEFAULT_N_R, n_theta: int = DEFAULT_N_THETA):
    """Nodes ``(dx, dy)`` relative to the disk centre and weights ``w`` summing to 1.

    ``sum(w * f(cx + dx, cy + dy))`` is the mean of ``f`` over the disk of the
    given radius under the named rule (see the module docstring).

    Parameters
    ----------
    radius : float
        The disk's radius [L], >= 0.
    rule : str
        ``"area"`` or ``"polar"`` (module docstring).
    n_r, n_theta : int
        Nodes in radius and angle.

    Returns
    -------
    dx, dy : ndarray
        Nodes relative to the centre [L].
    w : ndarray
        Weights, summing to 1.

    Raises
    ------
    ValueError
        For an unknown rule, a negative radius or too many nodes.
    """
    _v.choice("quadrature", rule, QUADRATURES)
    radius = _v.nonnegative_length("radius", radius)
    n_r = _v.integer("n_r", n_r, 1, MAX_NODES)
    n_theta = _v.integer("n_theta", n_theta, 1, MAX_NODES // n_r)
    dx, dy, w = _unit_disk_rule(rule, n_r, n_theta)
    return radius * dx, radius * dy, w


@dataclass(frozen=True)
class Grid:
    """A raster of square cells of side ``step`` whose centres are ``x`` x ``y``.

    Parameters
    ----------
    x : ndarray
        Cell centres along x [L].
    y : ndarray
        Cell centres along y [L].
    step : float
        The cells' side [L].
    """

    x: np.ndarray
    y: np.ndarray
    step: float

    @property
    def cell_area(self) -> float:
        return self.step * self.step

    @property
    def shape(self):
        return (self.y.size, self.x.size)

    def points(self):
        """``(X, Y)`` arrays of shape ``(ny, nx)``: row index is y.

        Returns
        -------
        X, Y : ndarray
            Cell centres [L], shape ``(ny, nx)``.
        """
        return np.meshgrid(self.x, self.y)

    def area(self, mask) -> float:
        """Area of the cells where ``mask`` is True (mid-point rule).

        Parameters
        ----------
        mask : ndarray of bool
            Cells, the grid's shape.

        Returns
        -------
        float
            The area [L^2].
        """
        return float(np.count_nonzero(mask)) * self.cell_area

    def mean(self, values, mask) -> float:
        """Area mean of ``values`` over the cells where ``mask`` is True.

        Parameters
        ----------
        values : ndarray
            A field on the grid.
        mask : ndarray of bool
            Cells, the grid's shape.

        Returns
        -------
        float
            The mean.

        Raises
        ------
        ValueError
            For an empty mask.
        """
        if not np.any(mask):
            raise ValueError("cannot average over an empty region")
        return float(np.mean(np.asarray(values)[mask]))


def grid_over(box, step) -> Grid:
    """Cell-centred grid covering ``box = (xmin, xmax, ymin, ymax)`` with cells of ``step``
    (at most :data:`MAX_NODES` cells; ``step`` may be of any positive magnitude, as the
    lengths of a design scale it).

    Parameters
    ----------
    box : tuple of float
        ``(xmin, xmax, ymin, ymax)`` [L].
    step : float
        The cells' side [L], > 0.

    Returns
    -------
    Grid
        The grid.

    Raises
    ------
    ValueError
        For an invalid box or step, or more than :data:`MAX_NODES` cells.
    """
    step = _v.positive_size("step", step)
    xmin, xmax, ymin, ymax = _v.finite_numbers("box", box, 4, "(xmin, xmax, ymin, ymax)")
    if not (xmin <= xmax and ymin <= ymax):
        raise ValueError(f"box must be (xmin, xmax, ymin, ymax) with xmin <= xmax, ymin <= ymax, "
                         f"got {_v.show(box)}")
    fx, fy = float(np.ceil((xmax - xmin) / step)), float(np.ceil((ymax - ymin) / step))
    if not max(fx, 1.0) * max(fy, 1.0) <= MAX_NODES:
        raise ValueError(f"step {step!r} gives a raster of more than {MAX_NODES:.0e} cells over "
                         f"{_v.show(box)}; use a larger step")
    nx = max(1, int(fx))
    ny = max(1, int(fy))
    x = xmin + (np.arange(nx) + 0.5) * step
    y = ymin + (np.arange(ny) + 0.5) * step
    return Grid(x, y, step)
