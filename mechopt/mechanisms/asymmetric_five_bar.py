"""The general (asymmetric) five-bar 5R: each leg has its own crank and distal link.

Geometry: base joints ``A1 = (-r3, 0)``, ``A2 = (r3, 0)``; leg ``i`` has a crank
``A_i B_i`` of length ``a_i`` (actuated angle ``theta_i`` from the x axis) and a
distal link ``B_i P`` of length ``c_i``. With ``a1 = a2`` and ``c1 = c2`` it is the
symmetric :class:`~mechopt.FiveBar` (same working modes, same poses, same
Jacobian: the contract suite checks this). The elbow of leg ``i`` is the circle
intersection ``B_i = A_i + a_i R(s_i alpha_i) (P - A_i) / |P - A_i|`` with ``alpha_i``
from the law of cosines and ``s_i = +1`` for ``"+"`` (leg 1) and ``-1`` for leg 2's
``"+"`` read as in Le 2013 eq. (17)-(18) (``theta2 = pi - beta2 + s2 alpha2``).

The closure ``|P - B_i|^2 = c_i^2`` differentiates to ``a_i . p_dot = (B_i - A_i) x a_i
theta_dot_i`` with ``a_i = P - B_i``: ``J = B^-1 A`` as for every mechanism of the
protocol. The mechanism is not symmetric about the y axis, so the Liu 2006 disk
indices (MIC centred on the y axis) are not offered (``disk_indices = False``); its
own numbers (:meth:`AsymmetricFiveBar.summary`) are the reachable area and the area
means of the LCI and the TQI over it.

This module is the whole implementation: the contract suite (a case in
``tests/mechanism_cases.py``), ``mechopt evaluate asymmetric-five-bar`` and
:func:`mechopt.analysis.evaluate.evaluate` pick it up from :func:`mechopt.mechanisms.registry`.

References
----------
Le, Kang, Doan (2013), ICCAIS, doi:10.1109/ICCAIS.2013.6720521, eq. (9)-(19) (the
symmetric case).
"""
from __future__ import annotations

import numpy as np

from mechopt.core import validation as _v
from mechopt.core.protocol import Parameter, PlanarMechanism, as_points
from mechopt.mechanisms.five_bar.model import MODES

__all__ = ["AsymmetricFiveBar", "MODES", "ASSEMBLY_MODES"]

ASSEMBLY_MODES = ("up", "down")
_SIGN = {"+": 1.0, "-": -1.0}
#: raster cells across the smaller side of the bounding box for the area means
_CELLS = 400


class AsymmetricFiveBar(PlanarMechanism):
    """``AsymmetricFiveBar(a1, c1, a2, c2, r3, mode="+-")``: cranks ``a_i``, distal links
    ``c_i`` [L] (> 0), half base distance ``r3`` [L] (>= 0), working mode as for the
    symmetric five-bar."""

    cli_name = "asymmetric-five-bar"
    cli_help = "5R with unequal legs: reachable area, mean LCI and TQI (raster)"
    parameters = (
        Parameter("a1", "length", "L", "crank of leg 1 [L]"),
        Parameter("c1", "length", "L", "distal link of leg 1 [L]"),
        Parameter("a2", "length", "L", "crank of leg 2 [L]"),
        Parameter("c2", "length", "L", "distal link of leg 2 [L]"),
        Parameter("r3", "length0", "L", "half the base distance [L]"),
        Parameter("mode", "choice", "-", "working mode (elbow signs, leg 1 first)", "+-", MODES),
    )
    modes = MODES
    assembly_modes = ASSEMBLY_MODES
    joint_names = ("theta1", "theta2")
    angular_joints = True
    #: the keys of :meth:`summary`, in order
    summary_keys = ("workspace_area", "mean_lci", "mean_tqi", "quadrature")
    #: the area scales as ``D^2``, the means of indices not at all
    summary_powers = {"workspace_area": 2, "mean_lci": 0, "mean_tqi": 0}

    def __init__(self, a1, c1, a2, c2, r3, mode: str = "+-"):
        self.a1, self.c1 = _v.positive_length("a1", a1), _v.positive_length("c1", c1)
        self.a2, self.c2 = _v.positive_length("a2", a2), _v.positive_length("c2", c2)
        self.r3 = _v.nonnegative_length("r3", r3)
        self.mode = _v.choice("mode", mode, MODES)
        self._s = (_SIGN[mode[0]], _SIGN[mode[1]])

    def __repr__(self):
        return (f"AsymmetricFiveBar(a1={self.a1!r}, c1={self.c1!r}, a2={self.a2!r}, "
                f"c2={self.c2!r}, r3={self.r3!r}, mode={self.mode!r})")

    def _legs(self):
        """``(base x, crank, distal, elbow sign)`` of each leg."""
        return ((-self.r3, self.a1, self.c1, self._s[0]), (self.r3, self.a2, self.c2, self._s[1]))

    def with_mode(self, mode: str) -> "AsymmetricFiveBar":
        return AsymmetricFiveBar(self.a1, self.c1, self.a2, self.c2, self.r3, mode)

    def scaled(self, factor: float) -> "AsymmetricFiveBar":
        f = _v.positive_length("factor", factor)
        return AsymmetricFiveBar(self.a1 * f, self.c1 * f, self.a2 * f, self.c2 * f, self.r3 * f,
                                 self.mode)

    @property
    def length_scale(self) -> float:
        return (self.a1 + self.c1 + self.a2 + self.c2) / 4.0 + self.r3 / 2.0

    # --- geometry -------------------------------------------------------------
    def elbows(self, x, y):
        """``(b1x, b1y, b2x, b2y, reachable)`` of the working mode; NaN where unreachable."""
        x, y = as_points(x, y)
        out, ok = [], np.ones(x.shape, dtype=bool)
        for ax, a, c, s in self._legs():
            dx = x - ax
            dsq = dx * dx + y * y
            with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
                k = (a * a + dsq - c * c) / (2.0 * dsq)  # a cos(alpha) / d
                h2 = a * a / dsq - k * k  # (a sin(alpha) / d)^2
            leg_ok = (h2 >= -1e-12) & (dsq > 0)
            h = np.sqrt(np.clip(h2, 0.0, None)) * s
            with np.errstate(invalid="ignore", over="ignore"):
                out += [ax + k * dx - h * y, k * y + h * dx]
            ok &= leg_ok
        return (*(np.where(ok, v, np.nan) for v in out), ok)

    def closure(self, x, y):
        """``A p_dot = B theta_dot``: ``a_i = P - B_i``, ``B_ii = (B_i - A_i) x a_i``."""
        x, y = as_points(x, y)
        b1x, b1y, b2x, b2y, ok = self.elbows(x, y)
        a1x, a1y, a2x, a2y = x - b1x, y - b1y, x - b2x, y - b2y
        A = np.stack([np.stack([a1x, a1y], -1), np.stack([a2x, a2y], -1)], -2)
        k1 = (b1x + self.r3) * a1y - b1y * a1x
        k2 = (b2x - self.r3) * a2y - b2y * a2x
        return A, np.stack([k1, k2], -1), ok

    def _annulus_distances(self, x, y):
        """Per leg ``(d - |a - c|, (a + c) - d)`` with ``d = |P - A_i|``."""
        x, y = as_points(x, y)
        out = []
        for ax, a, c, _ in self._legs():
            d = np.hypot(x - ax, y)
            out += [d - abs(a - c), (a + c) - d]
        return out

    def reachable(self, x, y):
        d = self._annulus_distances(x, y)
        x, y = as_points(x, y)
        away = (np.hypot(x + self.r3, y) > 0) & (np.hypot(x - self.r3, y) > 0)
        return np.logical_and.reduce([v >= 0 for v in d]) & away

    def serial_clearance(self, x, y):
        """Signed distance to the nearest of the four circles bounding the legs' annuli."""
        return np.minimum.reduce(self._annulus_distances(x, y))

    def bounding_box(self):
        r1, r2 = self.a1 + self.c1, self.a2 + self.c2
        reach = min(r1, r2)
        return (max(-self.r3 - r1, self.r3 - r2), min(-self.r3 + r1, self.r3 + r2), -reach, reach)

    def ik(self, x, y):
        """Crank angles (rad) of the working mode, unwrapped as for :class:`~mechopt.FiveBar`."""
        x, y = as_points(x, y)
        b1x, b1y, b2x, b2y, ok = self.elbows(x, y)
        th1 = np.arctan2(b1y, b1x + self.r3)
        th2 = np.arctan2(b2y, b2x - self.r3)
        # continue the symmetric five-bar's branch: theta1 in (-pi, 2 pi), theta2 likewise
        th1 = np.where(th1 < -0.5 * np.pi, th1 + 2 * np.pi, th1)
        th2 = np.where(th2 < -0.5 * np.pi, th2 + 2 * np.pi, th2)
        return np.where(ok, th1, np.nan), np.where(ok, th2, np.nan), ok

    def fk(self, theta1, theta2, assembly: str = "up"):
        """Intersection of the distal circles about ``B_1``, ``B_2``; ``"up"``: ``P`` left of
        ``B1 -> B2``. Returns ``(x, y, valid)``."""
        _v.choice("assembly", assembly, ASSEMBLY_MODES)
        t1, t2 = as_points(theta1, theta2)
        b1x, b1y = -self.r3 + self.a1 * np.cos(t1), self.a1 * np.sin(t1)
        b2x, b2y = self.r3 + self.a2 * np.cos(t2), self.a2 * np.sin(t2)
        mx, my = b2x - b1x, b2y - b1y
        m2 = mx * mx + my * my
        with np.errstate(divide="ignore", invalid="ignore"):
            u = (self.c1 ** 2 - self.c2 ** 2 + m2) / (2.0 * m2)  # along B1 -> B2, in |m|
            h2 = self.c1 ** 2 / m2 - u * u
        valid = (h2 >= 0) & (m2 > 0)
        h = np.sqrt(np.clip(h2, 0.0, None)) * (1.0 if assembly == "up" else -1.0)
        with np.errstate(invalid="ignore"):
            x = b1x + u * mx - h * my
            y = b1y + u * my + h * mx
        return np.where(valid, x, np.nan), np.where(valid, y, np.nan), valid

    def assembly_of(self, x, y):
        b1x, b1y, b2x, b2y, _ = self.elbows(x, y)
        x, y = as_points(x, y)
        cross = (b2x - b1x) * (y - b1y) - (b2y - b1y) * (x - b1x)
        return np.where(cross >= 0, "up", "down")

    # --- global numbers -----------------------------------------------------------
    def summary(self) -> dict:
        """Reachable area [L^2] and the area means of the LCI and the TQI over it, by the
        mid-point rule on a raster of ``_CELLS`` cells across the bounding box's smaller
        side (first-order error in the cell size). An empty workspace is a result:
        area 0 and NaN means, also for legs that never meet (an empty bounding box,
        e.g. ``r3`` beyond both legs' reach)."""
        from mechopt.core.quadrature import grid_over

        empty = {"workspace_area": 0.0, "mean_lci": float("nan"), "mean_tqi": float("nan"),
                 "quadrature": f"raster-{_CELLS}"}
        box = self.bounding_box()
        if not (box[1] > box[0] and box[3] > box[2]):  # the legs' reaches do not overlap
            return empty
        step = min(box[1] - box[0], box[3] - box[2]) / _CELLS
        grid = grid_over(box, step)
        X, Y = grid.points()
        mask = self.reachable(X, Y)
        area = grid.area(mask)
        if not mask.any():
            return empty
        return {"workspace_area": area, "mean_lci": self.raster_mean(self.lci, step),
                "mean_tqi": self.raster_mean(self.tqi, step), "quadrature": f"raster-{_CELLS}"}
