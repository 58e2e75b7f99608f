"""Global performance indices: means of local indices over a region.

Liu 2006 defines every global index as an area mean over a workspace W
(eq. 4, 11, 14, 19):

* GCI ``eta_J`` (mean LCI) and MCI (maximum LCI) over the maximal inscribed
  workspace (the MIC disk);
* GVI ``eta_Vmax/min``, GPI ``eta_Fmax/min`` and GSI ``eta_Dmax/min`` over the
  concentric disk of radius ``r_MIC/2`` (Liu 3.2.2: the extremes blow up near
  the singular loci);
* over the good-conditioning workspace (sec. 3.2.3): GCI and GSI.

The quadrature is named (``area`` or ``polar``, see :mod:`mechopt.quadrature`)
and is reported with every result.
"""
from __future__ import annotations

import numpy as np

from . import indices as _ix
from . import validation as _v
from .quadrature import QUADRATURES, disk_rule
from .workspace import MIC, Region, mic as _mic

__all__ = ["GLOBAL_INDEX_NAMES", "disk_mean", "global_indices", "region_indices", "max_lci"]

GLOBAL_INDEX_NAMES = (
    "gci", "mci", "gvi_max", "gvi_min", "gpi_max", "gpi_min", "gsi_max", "gsi_min",
)
# local index behind each global mean over the half-radius disk
_HALF_DISK = {
    "gvi_max": "v_max", "gvi_min": "v_min",
    "gpi_max": "tau_max", "gpi_min": "tau_min",
    "gsi_max": "d_max", "gsi_min": "d_min",
}


def disk_mean(mech, center_y, radius, quadrature="area", n_r=None, n_theta=None):
    """Means of every local index over the disk of ``radius`` centred at ``(0, center_y)``.

    Returns a dict keyed by :data:`mechopt.indices.LOCAL_INDEX_NAMES`.
    """
    kw = {k: v for k, v in (("n_r", n_r), ("n_theta", n_theta)) if v is not None}
    center_y = _v.coordinate("center_y", center_y)
    dx, dy, w = disk_rule(radius, quadrature, **kw)
    loc = mech.local_indices(dx, center_y + dy)
    return {k: float(np.sum(w * v)) for k, v in loc.items()}


def max_lci(mech, center_y, radius, n_r=64, n_theta=128, iters=40):
    """Maximum LCI over a disk (the MCI of Liu 2006 sec. 2.1).

    The best node of a polar grid seeds a compass search (step halved on failure)
    kept inside the disk.
    """
    center_y = _v.coordinate("center_y", center_y)
    iters = _v.integer("iters", iters, 0)
    n_r = _v.integer("n_r", n_r, 1)
    dx, dy, _ = disk_rule(radius, "polar", n_r=n_r, n_theta=n_theta)
    radius = float(radius)  # a finite number >= 0 (disk_rule)
    v = mech.lci(dx, center_y + dy)
    k = int(np.argmax(v))
    p = np.array([dx[k], dy[k]])
    best = float(v[k])
    step = radius / n_r
    dirs = np.array([[1, 0], [-1, 0], [0, 1], [0, -1], [1, 1], [1, -1], [-1, 1], [-1, -1]]) / 1.0
    for _ in range(iters):
        cand = p + step * dirs
        cand = cand[np.hypot(cand[:, 0], cand[:, 1]) <= radius]
        vals = mech.lci(cand[:, 0], center_y + cand[:, 1])
        j = int(np.argmax(vals))
        if vals[j] > best:
            best, p = float(vals[j]), cand[j]
        else:
            step *= 0.5
            if step == 0.0:  # converged to the last bit: more iterations change nothing
                break
    return best


def global_indices(mech, quadrature: str = "area", mic: MIC | None = None, **rule) -> dict:
    """Liu 2006 global indices of ``mech`` (eq. 4, 11, 14, 19) with the named quadrature.

    Returns a dict with ``r_mic``, ``mic_center_y`` and :data:`GLOBAL_INDEX_NAMES`.
    Lengths are those of ``mech`` [L]; GVI scales as L, GPI as 1/L, GSI as L^2.
    """
    _v.choice("quadrature", quadrature, QUADRATURES)
    m = _mic(mech) if mic is None else mic
    full = disk_mean(mech, m.center_y, m.radius, quadrature, **rule)
    half = disk_mean(mech, m.center_y, 0.5 * m.radius, quadrature, **rule)
    out = {"r_mic": m.radius, "mic_center_y": m.center_y, "gci": full["lci"],
           "mci": max_lci(mech, m.center_y, m.radius)}
    out.update({name: half[loc] for name, loc in _HALF_DISK.items()})
    return out


def region_indices(mech, region: Region) -> dict:
    """Area means over a raster region (e.g. the GCW): ``gci``, ``gsi_max``, ``gsi_min``;
    NaN for an empty region (no mean exists)."""
    if not region.mask.any():
        return {"gci": np.nan, "gsi_max": np.nan, "gsi_min": np.nan}
    x, y = region.points()
    loc = _ix.local_indices(mech.jacobian(x, y))
    return {"gci": float(np.mean(loc["lci"])),
            "gsi_max": float(np.mean(loc["d_max"])),
            "gsi_min": float(np.mean(loc["d_min"]))}
