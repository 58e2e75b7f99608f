"""Performance atlases of the symmetric five-bar over Liu's whole design space.

Liu, Wang, Pritschow (2006), Mech. Mach. Theory 41:119-144,
doi:10.1016/j.mechmachtheory.2005.05.003, Fig. 2-8: the global indices GCI,
MCI, GVI, GPI, GSI (eq. 4, 11, 14, 19) and the MIC radius of every design of the
non-dimensional space ``r1 + r2 + r3 = 3``, ``0 < r1, r2``, ``0 <= r3 <= 1.5``.

Plane of the atlases
--------------------
Liu draws the space in coordinates ``(s, t)`` given by eq. (33) of his Ref. [19],
which our copy does not contain. We use the isometric (distance- and
angle-preserving) affine map of the plane ``r1 + r2 + r3 = 3`` onto the page::

    s = (r1 - r2) / sqrt(2)        t = sqrt(3/2) r3

(the orthonormal in-plane basis ``(1, -1, 0)/sqrt(2)``, ``(-1, -1, 2)/sqrt(6)``,
shifted so that ``t = 0`` on ``r3 = 0``). The design space is the trapezoid
between ``t = 0`` (``r3 = 0``) and ``t = sqrt(3/2) 1.5`` (``r3 = 1.5``), bounded left
by ``r1 = 0`` and right by ``r2 = 0``; ``r1 = r2`` is the vertical axis, and
``r1 + r3 = r2`` (i.e. ``r2 = 1.5``) and ``r2 + r3 = r1`` (``r1 = 1.5``) are straight
lines through the origin. Because the map is isometric, the picture has the
proportions of the design triangle itself.

Computation
-----------
Designs on a lattice of step ``step`` are split into chunks mapped through
:func:`mechopt.run.parallel.parallel_map` (joblib processes or a Dask cluster).
Inside a chunk, :func:`mechopt.mechanisms.five_bar.kernels.mic_batch` finds every MIC (closed-form
serial clearance plus an explicitly generated type-II locus) and
:func:`mechopt.mechanisms.five_bar.kernels.disk_stats_batch` every disk mean and the MCI; both loop
over designs and quadrature nodes in compiled code (numba) or in NumPy arrays,
never in Python. A design whose MIC radius is 0 (no singularity-free disk on
the y axis: every design with ``r3 = 1.5``, where ``r1 + r2 = r3``) gets NaN
indices.

With worker processes, :func:`run_atlas` starts them first (their start-up overlaps
its own), has one of them triangulate the plane beside the chunks, and draws the
figures there too, side by side, while it writes the CSV: each figure is the one
:func:`draw_atlas` gives, byte for byte.
"""
from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

from mechopt.mechanisms.five_bar import kernels as _k
from mechopt.mechanisms.five_bar.batch import RESULT_COLUMNS, evaluate_designs
from mechopt.mechanisms.five_bar.model import MODES
from mechopt.core import validation as _v

__all__ = [
    "INDEX_GROUPS",
    "DEFAULT_INDICES",
    "R3_MAX",
    "check_step",
    "parse_indices",
    "index_columns",
    "plane_coordinates",
    "design_grid",
    "compute_atlas",
    "draw_atlas",
    "run_atlas",
]

#: index names of the command line -> columns of atlas.csv
INDEX_GROUPS = {
    "gci": ("gci",),
    "mci": ("mci",),
    "gvi": ("gvi_max", "gvi_min"),
    "gpi": ("gpi_max", "gpi_min"),
    "gsi": ("gsi_max", "gsi_min"),
    "r_mic": ("r_mic",),
}
DEFAULT_INDICES = ("gci", "mci", "gvi", "gpi", "gsi", "r_mic")
#: Liu's design space: r1 + r2 + r3 = SUM, 0 <= r3 <= R3_MAX
SUM = 3.0
R3_MAX = 1.5
STEP_MAX = 0.5
STEP_MIN = 0.001

_TITLES = {
    "r_mic": "MIC radius $r_{MIC}$",
    "mic_center_y": "MIC centre $y_c$",
    "gci": "GCI $\\eta_J$ (mean LCI over the MIC)",
    "mci": "MCI (maximum LCI over the MIC)",
    "gvi_max": "GVI $\\eta_{V\\max}$ (over $r_{MIC}/2$)",
    "gvi_min": "GVI $\\eta_{V\\min}$ (over $r_{MIC}/2$)",
    "gpi_max": "GPI $\\eta_{F\\max}$ (over $r_{MIC}/2$)",
    "gpi_min": "GPI $\\eta_{F\\min}$ (over $r_{MIC}/2$)",
    "gsi_max": "GSI $\\eta_{D\\max}$ (over $r_{MIC}/2$)",
    "gsi_min": "GSI $\\eta_{D\\min}$ (over $r_{MIC}/2$)",
}


# --- inputs -----------------------------------------------------------------
def check_step(step) -> float:
    """The lattice step of the atlas: a finite number in [0.001, 0.5].

    Parameters
    ----------
    step : float
        The step (non-dimensional, Liu 2006's lengths sum to 3).

    Returns
    -------
    float
        The step.

    Raises
    ------
    ValueError
        One line, outside [0.001, 0.5] or not finite.
    """
    out = _v.step("step", step, STEP_MAX)
    if out < STEP_MIN:  # 3.4 million designs; finer lattices exhaust memory or never end
        raise ValueError(f"step must lie in [{STEP_MIN}, {STEP_MAX}], got {_v.show(step)}")
    return out


def parse_indices(indices) -> tuple:
    """``"gci,mci"`` or a sequence of names -> tuple of :data:`INDEX_GROUPS` keys.

    Parameters
    ----------
    indices : str or sequence of str
        Index group names.

    Returns
    -------
    tuple of str
        Keys of :data:`INDEX_GROUPS`.

    Raises
    ------
    ValueError
        One line naming an unknown group.
    """
    if isinstance(indices, str):
        items = [s.strip() for s in indices.split(",")]
    else:
        try:
            items = [str(s).strip() for s in indices]
        except TypeError:
            raise ValueError(f"index must be a comma-separated list of {', '.join(INDEX_GROUPS)}, "
                             f"got {_v.show(indices)}") from None
    if not items or any(s == "" for s in items):
        raise ValueError(f"index must be a comma-separated list of {', '.join(INDEX_GROUPS)}, "
                         f"got {indices!r}")
    out = []
    for s in items:
        _v.choice("index", s, INDEX_GROUPS)
        if s not in out:
            out.append(s)
    return tuple(out)


def index_columns(indices) -> tuple:
    """Columns of atlas.csv for the index groups (always ``r_mic`` and ``mic_center_y``).

    Parameters
    ----------
    indices : str or sequence of str
        Index group names.

    Returns
    -------
    tuple of str
        The columns.
    """
    cols = ["r_mic", "mic_center_y"]
    for g in parse_indices(indices):
        cols += [c for c in INDEX_GROUPS[g] if c not in cols]
    return tuple(cols)


# --- the design space -------------------------------------------------------
def plane_coordinates(r1, r2, r3):
    """``(s, t) = ((r1 - r2)/sqrt(2), sqrt(3/2) r3)``: the isometric map of the
    plane ``r1 + r2 + r3 = 3`` used to draw the atlases (module docstring).

    Parameters
    ----------
    r1, r2, r3 : array_like
        Non-dimensional link lengths (``r1 + r2 + r3 = 3``).

    Returns
    -------
    s, t : ndarray
        Plane coordinates (non-dimensional).
    """
    r1, r2, r3 = (np.asarray(v, dtype=float) for v in (r1, r2, r3))
    return (r1 - r2) / math.sqrt(2.0), math.sqrt(1.5) * r3


def design_grid(step):
    """Every design of the space on the lattice of ``step``: DataFrame ``r1, r2, r3, s, t``.

    ``r3 = k step`` (``0 <= r3 <= 1.5``) and ``r1 = j step`` with ``r1, r2 > 0``. When
    ``3/step`` is an integer the lattice is exact (``r2`` is a multiple of
    ``step`` too): 33 824 designs for ``step = 0.01``.

    Parameters
    ----------
    step : float
        The lattice step (non-dimensional).

    Returns
    -------
    DataFrame
        Columns ``r1, r2, r3, s, t``.
    """
    import pandas as pd

    r1, r2, r3 = _lattice(step)
    s, t = plane_coordinates(r1, r2, r3)
    return pd.DataFrame({"r1": r1, "r2": r2, "r3": r3, "s": s, "t": t})


def _lattice(step):
    """``(r1, r2, r3)`` arrays of :func:`design_grid` (NumPy only)."""
    step = check_step(step)
    n_sum = round(SUM / step)
    exact = abs(n_sum * step - SUM) <= _v.RESOLUTION * SUM
    k_max = int(math.floor(R3_MAX / step + _v.RESOLUTION))
    r1s, r3s = [], []
    for k in range(k_max + 1):
        if exact:
            j = np.arange(1, n_sum - k)  # r2 = (n_sum - k - j) step >= step
        else:
            j = np.arange(1, int(math.ceil((SUM - k * step) / step - _v.RESOLUTION)))
        r1s.append(j * step)
        r3s.append(np.full(j.size, k * step))
    r1 = np.round(np.concatenate(r1s), 12)
    r3 = np.round(np.concatenate(r3s), 12)
    r2 = np.round(SUM - r1 - r3, 12)
    keep = r2 > 0
    return r1[keep], r2[keep], r3[keep]


# --- evaluation -------------------------------------------------------------
def _atlas_chunk(task):
    """One work unit of :func:`compute_atlas` (module level, so it pickles)."""
    r1, r2, r3, quadrature, mode = task
    return evaluate_designs(r1, r2, r3, quadrature=quadrature, mode=mode)


def _prepare_worker(_):
    """Sent to each worker when the pool starts (:func:`mechopt.run.parallel.start_workers`):
    unpickling it imports this module there (NumPy, numba, the kernels' module) before
    the first work unit arrives; the compiled kernels load with the warm-up or the
    first chunk."""
    return None


def _warm_up(quadrature, mode):
    """Compile (or load from numba's cache) the kernels once in this process,
    so that worker processes started afterwards load them from the cache."""
    if _k.HAVE_NUMBA:
        evaluate_designs([1.0], [1.5], [0.5], quadrature=quadrature, mode=mode)


def _warm_up_task(task):
    """Work unit: :func:`_warm_up` in one worker, alone, before the chunks are sent: with
    a cold numba cache the kernels compile there once and the other workers then load
    them from the cache it wrote; with a warm one that worker has them loaded for its
    first chunk (and this process, which evaluates nothing, loads nothing)."""
    _warm_up(*task)


#: designs per work unit: fixed (not tied to the worker count) so that the chunks
#: of a killed run are the chunks of its resumption
DEFAULT_CHUNK_SIZE = 512


class _ChunkStore:
    """Finished chunks of an atlas saved in a folder, so that a killed run resumes by
    skipping them; nothing in it is trusted blindly.

    ``settings.json`` holds the run's settings (step, quadrature, mode, chunk size,
    design count, kernel path, mechopt version): a folder of other settings is
    refused. Each chunk is an ``.npz`` with its values and a header: the settings,
    the chunk index, a digest of the chunk's designs, the shape and a SHA-256 of the
    values. On reuse every field is checked; a chunk that fails (edited, truncated,
    empty, swapped, another shape or dtype, another kernel path) is recomputed with
    one line saying why (``warn``). Files are fsynced before the rename (mechopt.run.io).
    """

    def __init__(self, folder, settings: dict, warn=None):
        import os
        import stat

        from mechopt.run import io as _io

        self.folder, self.settings = folder, settings
        self.warn = warn if warn is not None else (lambda msg: None)
        try:  # its own folder, never a link planted to write elsewhere
            folder.mkdir()
        except FileExistsError:
            if not stat.S_ISDIR(os.lstat(folder).st_mode):
                raise ValueError(f"{str(folder)!r} is not a folder of atlas chunks (a link or a file); "
                                 f"remove it") from None
        meta = folder / "settings.json"
        if os.path.lexists(meta):
            try:
                old = _io.read_json(meta)
            except (OSError, ValueError):
                old = None
            if old != settings:
                raise ValueError(f"{str(folder)!r} holds chunks of an atlas with other settings "
                                 f"({_settings_diff(old, settings)}); use another --out or delete "
                                 "that folder")
        else:
            _io.write_json(settings, meta)

    def path(self, i):
        return self.folder / f"chunk_{i:06d}.npz"

    @staticmethod
    def _digest(values) -> str:
        import hashlib

        return hashlib.sha256(np.ascontiguousarray(values, dtype="<f8").tobytes()).hexdigest()

    def _header(self, i, designs, values) -> dict:
        return {"settings": self.settings, "chunk": int(i), "designs": self._digest(designs),
                "shape": list(values.shape), "sha256": self._digest(values)}

    def load(self, i, designs, n_cols):
        """The saved values of chunk ``i`` (the designs ``designs``, an ``(n, 3)`` array),
        or None when there is none or it fails a check (then it is recomputed)."""
        import io
        import json

        from mechopt.run import io as _io

        path = self.path(i)
        if not path.exists():
            return None
        try:
            data = _io.read_bytes(path, 1 << 30, path.name)  # a regular file, not a FIFO or a giant
            with np.load(io.BytesIO(data), allow_pickle=False) as z:
                values = z["values"]
                header = json.loads(str(z["header"][()]))
        except Exception as exc:  # noqa: BLE001 - any corruption: zip, json, keys, dtype
            self.warn(f"atlas chunk {path.name} unreadable ({type(exc).__name__}); recomputed")
            return None
        want = self._header(i, designs, np.empty((len(designs), n_cols)))
        checks = (
            (values.dtype == np.float64, f"dtype {values.dtype}"),
            (list(values.shape) == want["shape"], f"shape {tuple(values.shape)}"),
            (header.get("settings") == self.settings, "other settings or kernel path"),
            (header.get("chunk") == i and header.get("designs") == want["designs"],
             "it belongs to other designs"),
            (values.dtype == np.float64 and header.get("sha256") == self._digest(values),
             "its values do not match their checksum"),
        )
        for ok, why in checks:
            if not ok:
                self.warn(f"atlas chunk {path.name}: {why}; recomputed")
                return None
        return values

    def save(self, i, designs, values):
        import json

        from mechopt.run import io as _io

        header = json.dumps(self._header(i, designs, values), sort_keys=True)
        with _io.atomic_path(self.path(i)) as tmp, open(tmp, "wb") as fh:
            np.savez(fh, values=np.asarray(values, dtype=np.float64), header=np.array(header))


def _settings_diff(old, new) -> str:
    if not isinstance(old, dict):
        return "unreadable settings.json"
    keys = sorted(set(old) | set(new))
    return ", ".join(f"{k}: {old.get(k)!r} there, {new.get(k)!r} here" for k in keys
                     if old.get(k) != new.get(k))


def compute_atlas(step=0.01, indices=DEFAULT_INDICES, quadrature: str = "area", mode: str = "+-",
                  n_jobs: int = 2, client=None, chunk_size: int | None = None, progress=None,
                  chunk_dir=None, warn=None):
    """The atlas table: one row per design of :func:`design_grid`, columns
    ``r1, r2, r3, s, t`` and :func:`index_columns`.

    Parameters
    ----------
    step : float
        Lattice step in (0, 0.5].
    indices : str or sequence
        Index groups of :data:`INDEX_GROUPS` (``gvi`` gives ``gvi_max, gvi_min``, ...).
    quadrature : {"area", "polar"}
        Rule of the disk means (:mod:`mechopt.core.quadrature`).
    mode : {"+-", "-+", "++", "--"}
        Working mode (Liu's atlases are ``"+-"``).
    n_jobs : int
        joblib worker processes (ignored with ``client``).
    client : dask.distributed.Client, optional
        Map the chunks on a Dask cluster instead.
    chunk_size : int, optional
        Designs per work unit (default :data:`DEFAULT_CHUNK_SIZE`).
    progress : callable, optional
        ``progress(done, total)`` after each chunk.
    chunk_dir : path, optional
        Save each finished chunk there and skip the chunks already saved (resume);
        each saved chunk is checked before reuse (:class:`_ChunkStore`).
    warn : callable, optional
        ``warn(message)`` for each saved chunk that failed its checks and is recomputed.

    Returns
    -------
    DataFrame
        One row per design: ``r1, r2, r3, s, t`` and the columns of :func:`index_columns`
        (NaN where a design has no MIC).

    Raises
    ------
    ValueError
        One line, for invalid inputs.
    """
    import pandas as pd

    from mechopt.run.parallel import chunks, map_async, parallel_map
    from mechopt.core.quadrature import QUADRATURES

    cols = index_columns(indices)
    _v.choice("quadrature", quadrature, QUADRATURES)
    _v.choice("mode", mode, MODES)
    grid = design_grid(step)
    n = len(grid)
    if client is not None:
        from mechopt.run.parallel import cluster_threads

        workers = cluster_threads(client)
    else:
        workers = int(_v.finite_number("n_jobs", n_jobs))
        if workers < 1 or workers != n_jobs:
            raise ValueError(f"n_jobs must be a positive integer, got {n_jobs!r}")
    chunk_size = DEFAULT_CHUNK_SIZE if chunk_size is None else _v.integer("chunk_size", chunk_size, 1)
    n_chunks = max(1, math.ceil(n / int(chunk_size)))
    warm = None
    if client is None and workers > 1 and n_chunks > 1:
        # the kernels compile (or load from numba's cache) once, in one worker, while this
        # process prepares the chunks; the other workers then load them from the cache
        warm = map_async(_warm_up_task, [(quadrature, mode)], n_jobs=workers)
    idx = np.arange(n)
    parts = chunks(idx, n_chunks)
    r1, r2, r3 = (grid[c].to_numpy() for c in ("r1", "r2", "r3"))
    tasks = [(r1[p], r2[p], r3[p], quadrature, mode) for p in parts]
    done = [None] * len(tasks)
    store = None
    if chunk_dir is not None:
        from pathlib import Path

        from mechopt import __version__
        from mechopt.run.parallel import kernel_path

        store = _ChunkStore(Path(chunk_dir), {"step": float(step), "quadrature": quadrature,
                                              "mode": mode, "chunk_size": int(chunk_size),
                                              "n_designs": int(n), "kernel": kernel_path(),
                                              "mechopt": __version__}, warn=warn)
        done = [store.load(i, np.column_stack(t[:3]), len(RESULT_COLUMNS))
                for i, t in enumerate(tasks)]
    todo = [i for i, d in enumerate(done) if d is None]
    if client is None and todo:
        if warm is not None:
            warm.result(0)
        else:
            _warm_up(quadrature, mode)

    def _save(k, values):
        if store is not None:
            i = todo[k]
            store.save(i, np.column_stack(tasks[i][:3]), values)

    def _progress(k, total):
        if progress is not None:
            progress(len(tasks) - len(todo) + k, len(tasks))

    res = parallel_map(_atlas_chunk, [tasks[i] for i in todo], n_jobs=workers, client=client,
                       on_result=_progress, on_item=_save)
    for i, values in zip(todo, res):
        done[i] = values
    values = np.vstack(done) if done else np.empty((0, len(RESULT_COLUMNS)))
    table = pd.DataFrame(values, columns=list(RESULT_COLUMNS))
    out = pd.concat([grid.reset_index(drop=True), table[list(cols)]], axis=1)
    return out


# --- drawing ----------------------------------------------------------------
def _boundary_lines():
    """``(label, style, (s, t))`` of the sub-region boundaries drawn on every atlas."""
    r3 = np.linspace(0.0, R3_MAX, 61)
    lines = [
        ("$r_1 = r_2$", dict(color="k", ls="--", lw=0.9), ((SUM - r3) / 2, (SUM - r3) / 2, r3)),
        ("$r_1 + r_3 = r_2$", dict(color="k", ls="-.", lw=0.9), (R3_MAX - r3, np.full_like(r3, 1.5), r3)),
        ("$r_2 + r_3 = r_1$", dict(color="k", ls=":", lw=1.1), (np.full_like(r3, 1.5), R3_MAX - r3, r3)),
    ]
    rr = r3[r3 <= 1.0]  # r1 = r3 (the cranks can meet iff r1 >= r3); r2 = 3 - 2 r3 > 0
    lines.append(("$r_1 = r_3$", dict(color="0.35", ls=(0, (1, 3)), lw=0.9), (rr, SUM - 2 * rr, rr)))
    return [(lab, st, plane_coordinates(*r)) for lab, st, r in lines]


def _outline():
    """The trapezoid of the design space in (s, t)."""
    r3 = np.array([0.0, 0.0, R3_MAX, R3_MAX, 0.0])
    r1 = np.array([0.0, SUM, SUM - R3_MAX, 0.0, 0.0])
    return plane_coordinates(r1, SUM - r1 - r3, r3)


def _levels(v):
    """Contour levels: round numbers over the range, or over the 0.5-99.5 %
    quantiles (colour bar extended) when a few corner designs stretch it."""
    from matplotlib.ticker import MaxNLocator

    finite = v[np.isfinite(v)]
    if finite.size == 0:
        return None, "neither"
    lo, hi = float(finite.min()), float(finite.max())
    qlo, qhi = (float(q) for q in np.quantile(finite, [0.005, 0.995]))
    extend = "neither"
    if hi - lo > 0 and (qhi - qlo) < 0.5 * (hi - lo):  # heavy tail (near-degenerate corners)
        lo, hi, extend = qlo, qhi, "both"
    if not hi > lo:
        hi = lo + max(abs(lo), 1.0) * _v.RESOLUTION
    levels = MaxNLocator(nbins=20).tick_values(lo, hi)
    if extend == "neither":
        levels = levels[(levels >= lo - _v.ROUNDING * abs(hi)) | (np.arange(levels.size) == 0)]
        if levels[-1] < hi:
            levels = np.append(levels, hi)
        if levels[0] > lo:
            levels = np.insert(levels, 0, lo)
    return levels, extend


#: Delaunay triangulations of recent design planes: digest of (s, t) -> (triangles,
#: neighbours). Every figure of an atlas (one per index, each region of Liu 2006) is
#: drawn on the same points; qhull takes about a second for the 33 824 designs of
#: step 0.01
_TRIANGULATIONS: dict = {}


def _plane_key(s, t) -> str:
    import hashlib

    s = np.ascontiguousarray(s, dtype=float)
    t = np.ascontiguousarray(t, dtype=float)
    return hashlib.sha256(s.tobytes() + b"|" + t.tobytes()).hexdigest()


def _remember_triangulation(s, t, triangles, neighbors):
    """Store qhull's ``(triangles, neighbors)`` of the points ``(s, t)`` (computed in
    another process) for :func:`_triangulation`."""
    if len(_TRIANGULATIONS) >= 4:
        _TRIANGULATIONS.clear()
    _TRIANGULATIONS[_plane_key(s, t)] = (np.array(triangles, copy=True),
                                         None if neighbors is None else np.array(neighbors, copy=True))


def _triangulation(s, t):
    """``matplotlib.tri.Triangulation(s, t)``: a new object each call (a figure may mask
    it), its triangles and neighbours computed by qhull once per point set (the
    same arrays qhull returns, so the drawing is the same byte for byte)."""
    import matplotlib.tri as mtri

    s = np.ascontiguousarray(s, dtype=float)
    t = np.ascontiguousarray(t, dtype=float)
    hit = _TRIANGULATIONS.get(_plane_key(s, t))
    if hit is None:
        tri = mtri.Triangulation(s, t)
        _remember_triangulation(s, t, tri.triangles, tri._neighbors)
        return tri
    triangles, neighbors = hit
    tri = mtri.Triangulation(s, t, triangles.copy())
    tri.is_delaunay = True
    tri._neighbors = None if neighbors is None else neighbors.copy()
    return tri


def _delaunay(task):
    """Work unit: qhull's ``(triangles, neighbors)`` of the points ``task = (s, t)``
    (computed in a worker while the others evaluate designs; see :func:`_triangulation`)."""
    s, t = task
    tri = _triangulation(s, t)
    return tri.triangles, tri._neighbors


def draw_atlas(table, column: str, region=None, where: str | None = None, quadrature=None):
    """Filled-contour atlas of ``table[column]`` in the (s, t) plane: a
    :class:`matplotlib.figure.Figure` with the sub-region boundary lines, a
    colour bar and, when ``region`` (boolean per row) is given, its outline.

    Parameters
    ----------
    table : DataFrame
        An atlas (atlas.csv).
    column : str
        The column to draw.
    region : array_like of bool, optional
        Rows inside a region to outline.
    where : str, optional
        The region's condition, for the title.
    quadrature : str, optional
        For the title.

    Returns
    -------
    Figure
        The figure (not saved).
    """
    return _draw_plane(table["s"].to_numpy(float), table["t"].to_numpy(float),
                       table[column].to_numpy(float), column, region, where, quadrature)


def _draw_plane(s, t, v, column, region=None, where=None, quadrature=None):
    """:func:`draw_atlas` of the values ``v`` at the points ``(s, t)`` (float arrays)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(8.0, 5.4))
    ax = fig.add_subplot()
    tri = _triangulation(s, t)
    bad = ~np.isfinite(v)
    if bad.any():
        tri.set_mask(bad[tri.triangles].any(axis=1))
    levels, extend = _levels(v)
    if levels is not None:
        vv = np.where(bad, np.nanmean(v) if (~bad).any() else 0.0, v)
        cs = ax.tricontourf(tri, vv, levels=levels, cmap="viridis", extend=extend)
        ax.tricontour(tri, vv, levels=levels[::2], colors="w", linewidths=0.35, alpha=0.6)
        cb = fig.colorbar(cs, ax=ax, pad=0.1, shrink=0.85)
        cb.set_label(column)
    if bad.any():
        ax.plot(s[bad], t[bad], ".", color="0.6", ms=1.5, label="no MIC (NaN)")
    os_, ot = _outline()
    ax.plot(os_, ot, color="k", lw=1.2)
    for lab, st, (ls_, lt) in _boundary_lines():
        ax.plot(ls_, lt, label=lab, **st)
    if region is not None:
        region = np.asarray(region, dtype=bool)
        if region.any() and not region.all():
            full = _triangulation(s, t)
            ax.tricontour(full, region.astype(float), levels=[0.5], colors="r", linewidths=1.8)
        ax.plot([], [], color="r", lw=1.8, label=f"where {where}" if where else "region")
    ax.set_aspect("equal")
    ax.set_xlabel("$s = (r_1 - r_2)/\\sqrt{2}$ [-]")
    ax.set_ylabel("$t = \\sqrt{3/2}\\, r_3$ [-]")
    sec = ax.secondary_yaxis("right", functions=(lambda tt: tt / math.sqrt(1.5),
                                                 lambda r: r * math.sqrt(1.5)))
    sec.set_ylabel("$r_3$ [-]")
    ax.text(-SUM / math.sqrt(2), -0.12, "$r_1 \\to 0$", ha="left", va="top", fontsize=8)
    ax.text(SUM / math.sqrt(2), -0.12, "$r_2 \\to 0$", ha="right", va="top", fontsize=8)
    q = f", {quadrature} means" if quadrature else ""
    ax.set_title(f"{_TITLES.get(column, column)}{q}", fontsize=10)
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.3), fontsize=7, ncol=3, frameon=False)
    ax.set_ylim(-0.3, math.sqrt(1.5) * R3_MAX + 0.15)
    return fig


def _figure_columns(cols, groups) -> list:
    """The columns of ``cols`` that get a figure (not ``mic_center_y``; ``r_mic`` only
    when asked for)."""
    return [c for c in cols if c != "mic_center_y" and (c != "r_mic" or "r_mic" in groups)]


def _draw_figure(task) -> str:
    """Work unit: draw one atlas (:func:`_draw_plane`) and save it as ``task["path"]``
    (:func:`mechopt.run.io.save_figure`); the figures of an atlas are independent, so
    the workers draw them side by side. ``task["triangulation"]`` (qhull's triangles and
    neighbours of the points, or None) spares each worker its own qhull run."""
    from mechopt.run import io as _io

    s, t = task["s"], task["t"]
    if task.get("triangulation") is not None and _plane_key(s, t) not in _TRIANGULATIONS:
        _remember_triangulation(s, t, *task["triangulation"])
    fig = _draw_plane(s, t, task["values"], task["column"], task["region"], task["where"],
                      task["quadrature"])
    _io.save_figure(fig, task["path"])
    return Path(task["path"]).name


# --- the command ------------------------------------------------------------
#: sub-folder of --out holding the finished chunks of a running atlas
CHUNK_DIR = ".atlas_chunks"


def run_atlas(out, step=0.01, indices=DEFAULT_INDICES, quadrature: str = "area", mode: str = "+-",
              n_jobs: int = 2, dask: str | None = None, where: str | None = None,
              figures: bool = True, chunk_size: int | None = None, dask_timeout: float = 10.0,
              verbose: bool = True, overwrite: bool = False) -> dict:
    """Compute, write and draw an atlas into the folder ``out``.

    Writes ``atlas.csv``, ``atlas.json`` (settings, counts, timings),
    ``atlas_<column>.png`` per index column and, with ``where``, ``region.csv``,
    as one set (:func:`mechopt.run.io.output_set`: ``manifest.json`` says last that the
    set is complete). Every input is checked before any work starts. A folder
    holding an atlas of other settings (or another kernel path) is refused unless
    ``overwrite``; the same command again resumes from the finished chunks.
    Returns the contents of ``atlas.json``.

    Parameters
    ----------
    out : str or Path
        Output folder.
    step : float
        Lattice step (non-dimensional).
    indices : str or sequence
        Index groups.
    quadrature : str
        ``"area"`` or ``"polar"``.
    mode : str
        Working mode.
    n_jobs : int
        Worker processes.
    dask : str, optional
        A Dask scheduler address.
    where : str, optional
        A region's condition (``"r_mic > 0.8 and gci > 0.6"``).
    figures : bool
        Draw the figures.
    chunk_size : int, optional
        Designs per work unit.
    dask_timeout : float
        Dask connection and stall time-out [s].
    verbose : bool
        Log the progress.
    overwrite : bool
        Replace an atlas of other settings.

    Returns
    -------
    dict
        atlas.json's content.

    Raises
    ------
    ValueError
        One line, for invalid inputs or a folder holding an atlas of other settings.
    """
    from mechopt.run import io as _io
    from mechopt.core.conditions import parse_condition
    from mechopt.core.quadrature import QUADRATURES

    t0 = time.perf_counter()
    step = check_step(step)
    groups = parse_indices(indices)
    cols = index_columns(groups)
    _v.choice("quadrature", quadrature, QUADRATURES)
    _v.choice("mode", mode, MODES)
    if dask is None:
        nj = _v.finite_number("n_jobs", n_jobs)
        if nj < 1 or nj != int(nj):
            raise ValueError(f"n_jobs must be a positive integer, got {n_jobs!r}")
        n_jobs = int(nj)
    if chunk_size is not None:
        chunk_size = _v.integer("chunk_size", chunk_size, 1)
    if dask is not None:
        if not _v.finite_number("dask_timeout", dask_timeout) > 0:
            raise ValueError(f"dask_timeout must be a positive number of seconds, got {_v.show(dask_timeout)}")
    cond = None
    if where is not None:
        cond = parse_condition(where, names=("r1", "r2", "r3", "s", "t") + cols)
    out = _io.prepare_out_dir(out)
    key = {"mechanism": "five-bar", "step": step, "indices": list(groups), "quadrature": quadrature,
           "mode": mode, "where": where, "figures": bool(figures), "kernel": "numba" if _k.HAVE_NUMBA else "numpy"}
    with _io.run_in(out, "atlas", key, ATLAS_OUTPUTS, overwrite) as run:
        return _run_atlas(out, run, step, groups, cols, quadrature, mode, n_jobs, dask, dask_timeout, where,
                          cond, figures, chunk_size, verbose, t0)


def _run_atlas(out, run, step, groups, cols, quadrature, mode, n_jobs, dask, dask_timeout, where, cond,
               figures, chunk_size, verbose, t0):
    """The computation and the files of :func:`run_atlas` (its inputs checked)."""
    from mechopt.run import io as _io
    from mechopt.run.parallel import connect, map_async, start_workers, stop_workers
    from mechopt.run.progress import Progress

    client = connect(dask, timeout=dask_timeout) if dask is not None else None
    # worker processes of this machine: the chunks go there when there are several (else
    # everything runs here, as parallel_map would), and then the figures too
    grid_n = len(_lattice(step)[0])
    size = DEFAULT_CHUNK_SIZE if chunk_size is None else chunk_size
    local = n_jobs if client is None and n_jobs > 1 and grid_n > size else 1
    tri = None
    try:
        if local > 1:  # their start-up overlaps the work of this process up to the first chunk
            start_workers(local, prepare=_prepare_worker)
        if figures and local > 1:  # the plane's triangulation, in a worker beside the chunks
            grid = design_grid(step)
            tri = map_async(_delaunay, [(grid["s"].to_numpy(float), grid["t"].to_numpy(float))],
                            n_jobs=local)
        bar = Progress(1, "atlas") if verbose else None

        def _tick(done, total):
            if bar is not None:
                bar.total = max(total, 1)
                bar.update(done, f"{grid_n} designs")

        t1 = time.perf_counter()
        def _warn(msg):
            if verbose:
                print(msg, file=sys.stderr, flush=True)

        table = compute_atlas(step, groups, quadrature, mode, n_jobs=n_jobs, client=client,
                              chunk_size=chunk_size, progress=_tick, chunk_dir=out / CHUNK_DIR,
                              warn=_warn)
        t_compute = time.perf_counter() - t1
        if bar is not None:
            bar.close()
        if tri is not None:
            try:
                tri = tri.result(0)
            except Exception:  # noqa: BLE001 - each figure then triangulates (and fails) itself
                tri = None
    except BaseException:  # e.g. chunks of other settings: no worker outlives the run
        if local > 1:
            stop_workers()
        raise
    finally:
        if client is not None:
            from mechopt.run.parallel import close_client

            close_client(client)
    with _io.output_set(out, run) as stage:
        _write_atlas(stage, table, groups, cols, cond, where, quadrature, figures, t0, t_compute, step,
                     mode, dask, n_jobs, local=local, triangulation=tri)
    import shutil

    shutil.rmtree(out / CHUNK_DIR, ignore_errors=True)  # the atlas is complete
    manifest = json.loads((out / "atlas.json").read_text())
    if verbose:
        msg = (f"atlas: {len(table)} designs ({manifest['n_degenerate']} without MIC) in {t_compute:.1f} s "
               f"[{manifest['backend']}, {'numba' if _k.HAVE_NUMBA else 'numpy'}], "
               f"{quadrature} means, mode {mode}")
        print(msg)
        if manifest["n_region"] is not None:
            print(f"region '{where}': {manifest['n_region']} designs -> {out / 'region.csv'}")
        print(f"wrote {', '.join(manifest['files'])} in {out}")
    return manifest


#: the names an atlas writes (such files that no run manifest accounts for are refused)
ATLAS_OUTPUTS = ("atlas.csv", "region.csv", "atlas.json", "atlas_*.png")


def _write_atlas(stage, table, groups, cols, cond, where, quadrature, figures, t0, t_compute, step, mode,
                 dask, n_jobs, local=1, triangulation=None):
    """The atlas's files, written into the staging folder of its output set.

    With ``local`` > 1 worker processes the figures are drawn there, side by side, while
    this process writes the tables (``seconds.figures`` is then the time from the first
    figure sent to the last one saved); otherwise the tables first, then each figure."""
    from mechopt.run import io as _io
    from mechopt.run.parallel import map_async

    region = cond.evaluate(table) if cond is not None else None
    files = ["atlas.csv"] + (["region.csv"] if region is not None else [])
    pending = None
    if figures:
        names = _figure_columns(cols, groups)
        s, t = table["s"].to_numpy(float), table["t"].to_numpy(float)
        mask = None if region is None else np.asarray(region, dtype=bool)
        tasks = [{"s": s, "t": t, "values": table[c].to_numpy(float), "column": c, "region": mask,
                  "where": where, "quadrature": quadrature,
                  "path": os.path.abspath(stage / f"atlas_{c}.png"),  # workers keep their own cwd
                  "triangulation": triangulation} for c in names]
        files += [f"atlas_{c}.png" for c in names]
        if local > 1:
            t2 = time.perf_counter()
            pending = map_async(_draw_figure, tasks, n_jobs=local)
    try:
        _io.write_csv(table, stage / "atlas.csv")
        if region is not None:
            _io.write_csv(table[region], stage / "region.csv")
        if figures:
            if pending is None:
                t2 = time.perf_counter()
                pending = map_async(_draw_figure, tasks, n_jobs=1)  # here, one after another
            pending.results()
    except BaseException:  # no worker draws into the staging folder once it is removed
        if pending is not None:
            pending.cancel()
        raise
    t_draw = time.perf_counter() - t2 if figures else 0.0
    n_bad = int((table["r_mic"] <= 0).sum())
    manifest = {
        "mechanism": "five-bar",
        "step": step,
        "indices": list(groups),
        "columns": list(table.columns),
        "quadrature": quadrature,
        "mode": mode,
        "n_designs": int(len(table)),
        "n_degenerate": n_bad,
        "plane": "s = (r1 - r2)/sqrt(2), t = sqrt(3/2) r3 (isometric map of r1 + r2 + r3 = 3)",
        "backend": f"dask {dask}" if dask else f"joblib n_jobs={n_jobs}",
        "compiled": bool(_k.HAVE_NUMBA),
        "kernel": "numba" if _k.HAVE_NUMBA else "numpy",
        "where": where,
        "n_region": None if region is None else int(region.sum()),
        "seconds": {"compute": round(t_compute, 3), "figures": round(t_draw, 3),
                    "total": round(time.perf_counter() - t0, 3)},
        "files": files + ["atlas.json"],
    }
    _io.write_json(manifest, stage / "atlas.json")
