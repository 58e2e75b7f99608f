"""``mechopt explore``: one self-contained, interactive HTML page of a run folder.

:func:`build_page` reads a folder and writes one HTML page that works offline: the
plotting library (Plotly, from the ``plotly`` Python package) and the data are embedded
in the page, gzip-compressed and base64-encoded, and inflated by the browser's own
``DecompressionStream``; nothing is fetched from the network. Three kinds of folder:

design run (``mechopt design``: ``front.csv``, ``run.json``, ``design.json``)
    The Pareto front with any two of its columns on the axes (the objectives first;
    two drop-down lists), a parallel-coordinates view of the objectives and lengths,
    and the mechanism of the selected design (the chosen one first; a click on the
    front selects another) drawn over its placed task with its reachable boundary,
    its type-II locus and, when ``--min-lci`` was asked, its good-conditioning
    workspace, with every variable, objective and margin of its front.csv row. A
    slider moves the platform along the task: the boundary of a region at uniform
    arc length (:data:`N_POSES` positions), a path task end to end at uniform arc
    length (:data:`N_POSES` positions), or the points of a point task (at most
    :data:`MAX_POINTS`, evenly taken). The drawings are computed here, when the page
    is built: the joint positions of every front design at every slider position
    from the design spec's ``sketch`` (the mechanism's own inverse kinematics), the
    outlines from the mechanism's ``serial_clearance``, ``type2_function`` and LCI
    on a :data:`GRID` x :data:`GRID` raster (contour lines). With a collision option
    (:func:`mechopt.requirements.collisions.drawn`) the bodies at every slider position
    as capsules (their axes and widths; the page draws the outlines), the keep-out zone
    and the worst poses (where front.csv's clearance and keep-out margin lie).
optimisation run (``mechopt optimize`` / ``sweep``: ``front.csv``, ``history.csv``)
    The front (two drop-down lists), the hypervolume per generation (else the best
    value of each objective per generation) and the weighting sweep when
    ``sweep.csv`` is there; a click shows the design's row.
atlas (``mechopt atlas``: ``atlas.csv``, ``atlas.json``)
    Liu's design triangle in the plane ``(s, t)`` coloured by any index (a drop-down
    list; the colour scale spans the 0.5-99.5 % quantiles when a few corner designs
    stretch the range, as the atlas figures do), each ``where`` condition
    (:func:`mechopt.core.conditions.parse_condition`, the grammar of ``mechopt atlas
    --where``) drawn as a region: its designs marked and its outline; a click on a
    design shows its indices and its workspace (the reachable set of the five-bar
    with ``r1, r2, r3``, the two annuli about the base joints ``(+-r3, 0)``) with its
    maximal inscribed circle.

Sizes: the full plotly.min.js (about 4.7 MB) is embedded gzip-compressed (about
1.4 MB); numbers of the drawings and of the atlas are rounded to :data:`DIGITS`
significant digits (the front rows are kept as front.csv has them), and the atlas
page of a step-0.01 atlas (33 824 designs) stays below 5 MB.
"""
from __future__ import annotations

import base64
import functools
import gzip
import json
import math
from html import escape
from pathlib import Path

import numpy as np
import pandas as pd

from mechopt import __version__
from mechopt.run import io as _io

__all__ = ["build_page", "write_page", "page_kind", "page_data", "serve", "N_POSES", "MAX_POINTS",
           "GRID", "DIGITS"]

#: slider positions along the boundary of a region task (uniform arc length)
N_POSES = 72
#: most slider positions of a point task (its points, evenly taken)
MAX_POINTS = 200
#: raster of the workspace outlines of each design (per side)
GRID = 121
#: significant digits of the embedded drawings and atlas values
DIGITS = 6


# --------------------------------------------------------------------------- reading
def page_kind(folder) -> str:
    """``"atlas"``, ``"design"`` or ``"optimize"``: what the run folder ``folder`` holds.

    Parameters
    ----------
    folder : str or Path
        A run folder.

    Returns
    -------
    str
        The kind.

    Raises
    ------
    ValueError
        One line, when it is no folder or holds none of them.
    """
    d = Path(folder)
    if not d.is_dir():
        raise ValueError(f"DIR must be a run folder (design, optimize, sweep or atlas), got "
                         f"{'the file ' if d.exists() else 'the missing '}{str(d)!r}")
    if (d / "atlas.csv").is_file():
        return "atlas"
    if (d / "front.csv").is_file():
        info = _read_json(d / "run.json")
        return "design" if isinstance(info.get("design"), dict) else "optimize"
    raise ValueError(f"{str(d)!r} holds no front.csv or atlas.csv: give the --out folder of "
                     f"`mechopt design`, `optimize`, `sweep` or `atlas`")


def _read_json(path: Path) -> dict:
    try:
        obj = _io.read_json(path)  # a regular file, bounded, one-line errors
    except FileNotFoundError:
        return {}
    except OSError as exc:
        raise ValueError(f"cannot read {path}: {exc.strerror or exc}") from None
    return obj if isinstance(obj, dict) else {}


def _read_csv(path: Path) -> pd.DataFrame:
    try:
        return pd.read_csv(path, dtype={"mode": str})
    except (OSError, ValueError) as exc:
        raise ValueError(f"cannot read {path}: {' '.join(str(exc).split())}") from None


# --------------------------------------------------------------------------- numbers
def _round(a, digits=DIGITS):
    """``a`` rounded to ``digits`` significant digits (NaN and inf kept)."""
    a = np.asarray(a, float)
    with np.errstate(divide="ignore", invalid="ignore"):
        mag = np.floor(np.log10(np.abs(a)))
        scale = np.where(np.isfinite(mag), 10.0 ** (digits - 1 - mag), 1.0)
        out = np.round(a * scale) / scale
    return np.where(np.isfinite(mag), out, a)


def _list(a, digits=DIGITS):
    """A JSON-ready list of ``a`` rounded (NaN and inf as None)."""
    r = _round(a, digits)
    return [None if not math.isfinite(v) else float(v) for v in r.ravel().tolist()]


def _columns(df: pd.DataFrame) -> dict:
    """``{column: values}`` of a table: numbers as floats (NaN as None), text as text."""
    out = {}
    for c in df.columns:
        s = df[c]
        if pd.api.types.is_numeric_dtype(s) and not pd.api.types.is_bool_dtype(s):
            out[str(c)] = [None if not math.isfinite(v) else float(v) for v in s.to_numpy(float).tolist()]
        else:
            out[str(c)] = [None if (isinstance(v, float) and math.isnan(v)) else
                           (bool(v) if isinstance(v, (bool, np.bool_)) else str(v)) for v in s.tolist()]
    return out


def _polylines(lines) -> dict:
    """Plotly ``{"x": [...], "y": [...]}`` of polylines, separated by None."""
    xs, ys = [], []
    for ln in lines:
        ln = np.asarray(ln, float)
        if len(ln) < 2:
            continue
        xs += _list(ln[:, 0]) + [None]
        ys += _list(ln[:, 1]) + [None]
    return {"x": xs, "y": ys}


def _contour(gx, gy, z, level) -> dict:
    """The contour lines of ``z`` (NaN masked) at ``level`` on the grid ``(gx, gy)``."""
    import contourpy

    z = np.ma.masked_invalid(np.asarray(z, float))
    if z.count() == 0:
        return {"x": [], "y": []}
    return _polylines(contourpy.contour_generator(gx, gy, z).lines(level))


# --------------------------------------------------------------------------- design runs
def _task_from(d: dict):
    """The :class:`~mechopt.analysis.task.Task` of a run.json ``design.task`` record."""
    from mechopt.analysis.task import Task

    kind, unit = d.get("kind"), d.get("unit", "mm")
    if kind == "circle":
        return Task.circle(d["radius"], tuple(d["center"]), unit)
    if kind == "points":
        return Task.points(d["points"], unit)
    if kind == "path":
        return Task.path(d["points"], unit)
    if kind in ("rect", "polygon"):
        t = Task.polygon(d["vertices"], unit)
        return Task(kind, vertices=t.vertices, unit=t.unit, label=d.get("label", t.label))
    raise ValueError(f"run.json: unknown task kind {kind!r}")


def _mechanism(spec, row: dict):
    """The mechanism of one front.csv row (strokes from its ``q*_min/max`` columns)."""
    v = {n: float(row[n]) for n in spec.lengths}
    mode = str(row["mode"])
    if spec.derived_strokes:
        strokes = [(float(row[f"q{i}_min"]), float(row[f"q{i}_max"])) for i in (1, 2)]
        return spec.build(v, mode, strokes=strokes), strokes
    return spec.build(v, mode), []


def _path_positions(task):
    """``(x, y, t)``: the slider positions of a task (at its reference placement) and
    their arc-length fractions (a point task: its points and their index fractions)."""
    if task.is_region:
        t = np.arange(N_POSES) / N_POSES
        x, y = task.boundary_at(t)
        return np.asarray(x, float), np.asarray(y, float), t
    p = task.pts
    if task.kind == "path":  # the polyline, end to end at uniform arc length
        s = np.r_[0.0, np.cumsum(np.hypot(*np.diff(p, axis=0).T))]
        t = np.linspace(0.0, 1.0, N_POSES)
        return np.interp(t * s[-1], s, p[:, 0]), np.interp(t * s[-1], s, p[:, 1]), t
    idx = np.unique(np.linspace(0, len(p) - 1, min(len(p), MAX_POINTS)).round().astype(int))
    return p[idx, 0].astype(float), p[idx, 1].astype(float), idx / max(len(p) - 1, 1)


def _pose(spec, mech, px, py):
    """The legs with the platform at ``(px, py)`` (task frame): ``{"chains", "bases"}``
    rounded, or None where a joint is undefined (out of reach)."""
    mx, my = spec.to_mech(mech, np.float64(px), np.float64(py))
    with np.errstate(invalid="ignore"):
        chains, bases = spec.sketch(mech, float(px), float(py), mx, my)
    pts = np.array([p for c in chains for p in c] + list(bases), float)
    if not np.all(np.isfinite(pts)):
        return None
    return {"chains": [[_list(p) for p in c] for c in chains], "bases": [_list(b) for b in bases]}


def _view_box(spec, mech, task):
    """``(x0, x1, y0, y1)`` [L, task frame]: the task, the base and the reachable set's
    bounding box, 5 % of the larger side about them."""
    x0, x1, y0, y1 = task.bbox
    bb = mech.bounding_box()
    off = spec.to_mech(mech, 0.0, 0.0)[0]
    X0, X1 = min(bb[0] - off, x0), max(bb[1] - off, x1)
    Y0, Y1 = min(bb[2], y0, 0.0), max(bb[3], y1)
    pad = 0.05 * max(X1 - X0, Y1 - Y0)
    return X0 - pad, X1 + pad, Y0 - pad, Y1 + pad


def _segments(bodies, k=0) -> list:
    """``[[x0, y0, x1, y1], ...]`` of the capsule axes of ``bodies`` at their pose ``k``,
    rounded; None for a body out of reach."""
    out = []
    for b in bodies:
        e = np.array([b.x0[k], b.y0[k], b.x1[k], b.y1[k]], float)
        out.append(_list(e) if np.isfinite(e).all() else None)
    return out


def _bodies(ev, spec, mech, row, placed, xs, ys) -> dict:
    """The capsules of one front design (:mod:`mechopt.requirements.collisions`): names,
    kinds, widths, the axes of every body at every slider position ``(xs, ys)``
    (``segments[k][j]``: body ``j`` at position ``k``), the keep-out zone's outline
    (placed with the task) and the worst poses (the reported minima's poses, from the
    evaluation with the certification's sampling: the values of front.csv)."""
    from mechopt.analysis.sampling import Sampling
    from mechopt.requirements import collisions as _rc

    v = {**{n: float(row[n]) for n in spec.lengths}, "mode": str(row["mode"]),
         "task_x": float(row["task_x"]), "task_y": float(row["task_y"])}
    ctx = ev.context(v, Sampling.fine())
    col = _rc.collisions(ctx)
    ref = col.bodies(np.zeros(1), np.zeros(1))
    at = col.bodies(np.asarray(xs, float), np.asarray(ys, float))
    segments = [_segments(at, k) for k in range(len(xs))]
    out = {"names": [b.name for b in ref], "kinds": [b.kind for b in ref],
           "widths": _list([b.width for b in ref]), "segments": segments, "worst": []}
    zone = _rc.zone_of(ctx)
    if zone is not None:
        zx, zy = zone.outline(_view_box(spec, mech, placed))
        out["zone"] = {"label": zone.label, "x": _list(zx), "y": _list(zy)}
    for what in ("clearance", "keep_out"):
        w = _rc.worst_pose(ctx, what)
        if w is not None:
            which = list(w["which"]) if isinstance(w["which"], tuple) else [w["which"]]
            out["worst"].append({"what": what, "value": w["value"], "x": w["x"], "y": w["y"], "which": which,
                                 "segments": _segments(col.bodies(np.array([w["x"]]), np.array([w["y"]])))})
    return out


def _evaluator(settings, task, spec):
    """A :class:`~mechopt.analysis.design_eval.DesignEvaluator` of a design run's task
    with its collision requirements only (run.json's ``design``): what :func:`_bodies`
    evaluates."""
    from mechopt.analysis.design_eval import DesignEvaluator
    from mechopt.requirements import Requirements
    from mechopt.requirements import collisions as _rc

    req = settings.get("requirements") or {}
    kept = {k: req[k] for k in (*_rc.DRAWN_BY, "singularity_margin") if req.get(k) is not None}
    return DesignEvaluator(spec.name, task, Requirements(**kept), ("size",), mode=settings.get("mode"),
                           place=settings.get("place", "fixed"), max_length=settings.get("max_length"),
                           min_length=settings.get("min_length"), shape=settings.get("shape"))


def _outlines(spec, mech, task, gamma, n=GRID) -> dict:
    """Reachable boundary, type-II locus and (``gamma`` given) the good-conditioning
    workspace ``{LCI >= gamma}`` of the singularity-free piece holding the task, as
    contour lines over a raster covering the task, the base and the reachable set."""
    from mechopt.core import indices as _ix

    X0, X1, Y0, Y1 = _view_box(spec, mech, task)
    gx, gy = np.meshgrid(np.linspace(X0, X1, n), np.linspace(Y0, Y1, n))
    mx, my = spec.to_mech(mech, gx, gy)
    with np.errstate(invalid="ignore", divide="ignore"):
        f = np.asarray(mech.type2_function(mx, my), float)
        clr = np.asarray(mech.serial_clearance(mx, my), float)
        out = {"reach": _contour(gx, gy, clr, 0.0), "type2": _contour(gx, gy, f, 0.0)}
        if gamma is not None:
            rx, ry = task.reference if task.is_region else (task.pts[:, 0].mean(), task.pts[:, 1].mean())
            s0 = np.sign(mech.type2_function(*spec.to_mech(mech, np.float64(rx), np.float64(ry)))) or 1.0
            lci = np.asarray(_ix.lci(mech.jacobian(mx, my)), float)
            good = (np.sign(f) == s0) & (lci >= gamma)
            out["gcw"] = _contour(gx, gy, good.astype(float), 0.5)
    return out


def _design_data(d: Path) -> dict:
    from mechopt.analysis.design_eval import get_spec

    info = _read_json(d / "run.json")
    settings = info["design"]
    front = _read_csv(d / "front.csv")
    chosen = _read_json(d / "design.json")
    spec = get_spec(settings["mechanism"])
    task = _task_from(settings["task"])
    unit = settings.get("unit") or task.unit
    objectives = list(settings.get("objectives") or [])
    missing = [c for c in (*spec.lengths, "mode", "task_x", "task_y", *objectives) if c not in front.columns]
    if missing:
        raise ValueError(f"{d / 'front.csv'} is not a design front: it has no column {', '.join(missing)}")
    req = settings.get("requirements") or {}
    gamma = req.get("min_lci")
    px, py, tpath = _path_positions(task)
    rx, ry = task.reference
    from mechopt.requirements import collisions as _rc

    ev = _evaluator(settings, task, spec) if _rc.drawn(req, objectives) else None
    designs = []
    for _, r in front.iterrows():
        row = r.to_dict()
        mech, strokes = _mechanism(spec, row)
        dx, dy = float(row["task_x"]) - rx, float(row["task_y"]) - ry
        placed = task.moved_to(float(row["task_x"]), float(row["task_y"]))
        ox, oy = placed.outline()
        poses = [_pose(spec, mech, x + dx, y + dy) for x, y in zip(px, py)]
        designs.append({
            "task": {"x": _list(ox), "y": _list(oy)},
            "path": {"x": _list(px + dx), "y": _list(py + dy)},
            "poses": poses,
            "actuators": [[_list(a), _list(b)] for a, b in spec.actuator_paths(mech, strokes)],
            "outlines": _outlines(spec, mech, placed, gamma),
        })
        if ev is not None:  # a collision option: the capsules, the keep-out zone, the worst poses
            designs[-1]["bodies"] = _bodies(ev, spec, mech, row, placed, px + dx, py + dy)
    from mechopt.requirements import objectives as _objectives

    declared = _objectives()

    lengths = [c for c in (*spec.lengths, "D") if c in front.columns]
    margins = [c for c in front.columns if c.startswith("margin_")]
    return {
        "kind": "design", "unit": unit, "mechanism": spec.name,
        "title": f"{spec.name} sized for {task.label}" + (
            "" if settings.get("place", "fixed") == "fixed" else
            f" as given; placed per design ({settings['place']}: task_x, task_y)"),
        "task_kind": task.kind, "region": bool(task.is_region or task.kind == "path"),
        "path_t": _list(tpath), "n_task_points": int(len(task.pts)) if task.kind == "points" else 0,
        "columns": list(map(str, front.columns)), "front": _columns(front),
        "objectives": objectives,
        "senses": {o: ("max" if declared[o].sense < 0 else "min") for o in objectives if o in declared},
        "objective_units": (chosen.get("objective_units") or {}),
        "lengths": lengths, "margins": margins,
        "requirements": _io.plain_json(req), "gamma": gamma,
        "chosen": int(chosen.get("index", 0)) if chosen else 0,
        "designs": designs,
        "settings": _io.plain_json({k: v for k, v in settings.items() if k != "task"}),
    }


# --------------------------------------------------------------------------- optimisation runs
def _optimize_data(d: Path) -> dict:
    info = _read_json(d / "run.json")
    front = _read_csv(d / "front.csv")
    history = _read_csv(d / "history.csv") if (d / "history.csv").is_file() else pd.DataFrame()
    objectives = [c[len("best_"):] for c in history.columns if c.startswith("best_")]
    objectives = [o for o in objectives if o in front.columns] or \
        [c for c in front.columns if pd.api.types.is_numeric_dtype(front[c])][:2]
    sweep = _read_csv(d / "sweep.csv") if (d / "sweep.csv").is_file() else None
    problem = info.get("problem") or d.name
    return {
        "kind": "optimize", "title": f"optimisation run of {problem}", "problem": problem,
        "columns": list(map(str, front.columns)), "front": _columns(front), "objectives": objectives,
        "history": _columns(history) if len(history) else None,
        "sweep": _columns(sweep) if sweep is not None else None,
        "algorithm": _io.plain_json(info.get("algorithm")), "seed": info.get("seed"),
    }


# --------------------------------------------------------------------------- atlases
def _region_outline(s, t, mask) -> dict:
    """The outline of the designs ``mask`` in the plane (the 0.5 contour of the mask
    over the Delaunay triangulation of the lattice, as the atlas figures draw it)."""
    if not mask.any() or mask.all():
        return {"x": [], "y": []}
    import matplotlib.tri as mtri
    from matplotlib.figure import Figure

    ax = Figure().add_subplot()
    cs = ax.tricontour(mtri.Triangulation(s, t), mask.astype(float), levels=[0.5])
    lines = []
    for path in cs.get_paths():
        lines += path.to_polygons(closed_only=False)
    return _polylines(lines)


def _atlas_data(d: Path, where=()) -> dict:
    from mechopt.core.conditions import parse_condition

    table = _read_csv(d / "atlas.csv")
    info = _read_json(d / "atlas.json")
    missing = [c for c in ("r1", "r2", "r3", "s", "t") if c not in table.columns]
    if missing:
        raise ValueError(f"{d / 'atlas.csv'} is not an atlas: it has no column {', '.join(missing)}")
    names = tuple(map(str, table.columns))
    s, t = table["s"].to_numpy(float), table["t"].to_numpy(float)
    regions = []
    for w in where or ():
        cond = parse_condition(w, names=names, param="--where")
        mask = np.asarray(cond.evaluate(table), bool)
        regions.append({"where": w, "count": int(mask.sum()), "index": np.flatnonzero(mask).tolist(),
                        "outline": _region_outline(s, t, mask)})
    indices = [c for c in table.columns if c not in ("r1", "r2", "r3", "s", "t")]
    cols = {c: _list(table[c].to_numpy(float)) for c in table.columns}
    return {"kind": "atlas", "title": f"atlas of the {info.get('mechanism', 'five-bar')} design space",
            "n": int(len(table)), "indices": indices, "columns": list(names), "table": cols,
            "regions": regions, "quadrature": info.get("quadrature"), "mode": info.get("mode"),
            "step": info.get("step"), "atlas_where": info.get("where")}


# --------------------------------------------------------------------------- the page
def page_data(folder, where=()) -> dict:
    """The data the page of ``folder`` embeds (a JSON-ready dict; see the module docstring).

    Parameters
    ----------
    folder : path
        A run folder of ``mechopt design``, ``optimize``, ``sweep`` or ``atlas``.
    where : sequence of str
        Conditions drawn as regions on an atlas page (``mechopt atlas --where`` syntax).

    Returns
    -------
    dict
        ``kind`` (:func:`page_kind`), ``title`` and the kind's tables and drawings.

    Raises
    ------
    ValueError
        One line, for a folder that holds no run, unreadable run files or ``where`` on a
        run that is not an atlas.
    """
    d = Path(folder)
    kind = page_kind(d)
    if isinstance(where, str):
        where = (where,)
    if where and kind != "atlas":
        raise ValueError(f"--where applies to an atlas folder; {str(d)!r} holds a {kind} run")
    if kind == "atlas":
        data = _atlas_data(d, where)
    elif kind == "design":
        data = _design_data(d)
    else:
        data = _optimize_data(d)
    data["folder"] = d.name or str(d)
    data["version"] = __version__
    return data


def _plotly_js() -> str:
    try:
        from plotly.offline import get_plotlyjs
    except ImportError:
        raise ValueError("mechopt explore needs the plotly package: pip install 'mechopt[explore]'") from None
    return get_plotlyjs()


def _packed(text: str) -> str:
    """``text`` gzip-compressed (level 6, no time stamp: the page is reproducible) and
    base64-encoded."""
    return base64.b64encode(gzip.compress(text.encode("utf-8"), 6, mtime=0)).decode("ascii")


@functools.lru_cache(maxsize=1)
def _packed_library() -> str:
    """The plotting library, packed once per process (about 1 s)."""
    return _packed(_plotly_js())


def build_page(folder, where=()) -> str:
    """The HTML text of the explorer page of ``folder`` (module docstring).

    Parameters
    ----------
    folder : path
        A run folder (:func:`page_kind`).
    where : sequence of str
        Atlas regions (:func:`page_data`).

    Returns
    -------
    str
        One self-contained HTML page (pure ASCII).
    """
    data = page_data(folder, where)
    payload = _packed(json.dumps(data, separators=(",", ":"), allow_nan=False))
    lib = _packed_library()
    title = f"mechopt explore: {data['title']}"
    html = _TEMPLATE.format(title=escape(title), css=_CSS, heading=escape(data["title"]),
                            sub=escape(f"mechopt {__version__} - folder {data['folder']}"),
                            body=_BODY[data["kind"]], lib=lib, payload=payload, js=_JS)
    return html.encode("ascii", "xmlcharrefreplace").decode("ascii")


def write_page(folder, out=None, where=()) -> Path:
    """Write :func:`build_page` of ``folder`` to ``out`` (default ``folder/explore.html``)
    atomically; returns its path.

    Parameters
    ----------
    folder : path
        A run folder (:func:`page_kind`).
    out : path, optional
        The HTML file to write.
    where : sequence of str
        Atlas regions (:func:`page_data`).

    Returns
    -------
    pathlib.Path
        The page written.

    Raises
    ------
    ValueError
        One line, for a folder that holds no run, unreadable run files, ``where`` on a
        run that is not an atlas, or ``out`` naming a folder.
    """
    out = Path(folder) / "explore.html" if out is None else Path(out)
    if not str(out).strip() or out.is_dir():
        raise ValueError(f"--out must name an HTML file, got the folder {str(out)!r}")
    html = build_page(folder, where)
    return _io.write_text(out, html)


def serve(path, port: int = 0, open_browser: bool = True, ready=None):
    """Serve the page ``path`` on ``http://127.0.0.1:PORT/`` (``port`` 0: a free one) until
    interrupted, opening it in the default browser.

    Parameters
    ----------
    path : path
        The HTML file.
    port : int
        The port; 0 picks a free one.
    open_browser : bool
        Open the page with :mod:`webbrowser`.
    ready : callable, optional
        Called with the server (its ``server_address``) once it listens; the caller may
        ``shutdown()`` it from another thread.
    """
    import functools
    import http.server
    import threading

    page = Path(path).read_bytes()

    class Handler(http.server.BaseHTTPRequestHandler):
        def do_GET(self):  # noqa: N802 - the http.server interface
            if self.path.split("?")[0] not in ("/", "/" + Path(path).name):
                self.send_error(404)
                return
            self.send_response(200)
            self.send_header("Content-Type", "text/html; charset=utf-8")
            self.send_header("Content-Length", str(len(page)))
            self.end_headers()
            self.wfile.write(page)

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", int(port)), Handler)
    url = f"http://127.0.0.1:{server.server_address[1]}/"
    print(f"serving {url} (Ctrl-C to stop)", flush=True)
    if open_browser:
        import webbrowser

        threading.Thread(target=functools.partial(webbrowser.open, url), daemon=True).start()
    if ready is not None:
        ready(server)
    try:
        server.serve_forever()
    finally:
        server.server_close()


_CSS = """
* { box-sizing: border-box; }
body { font: 14px/1.4 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif;
       color: #1d2228; margin: 0; background: #fff; }
header { background: #22303f; color: #fff; padding: 12px 20px; }
header h1 { margin: 0 0 2px; font-size: 20px; }
header p { margin: 0; color: #d6dde6; font-size: 13px; }
main { padding: 12px 20px 40px; }
.cols { display: grid; grid-template-columns: minmax(420px, 1fr) minmax(420px, 1fr); gap: 16px; }
.panel { border: 1px solid #d0d4da; border-radius: 4px; padding: 8px; min-width: 0; }
.panel h2 { font-size: 15px; margin: 0 0 6px; }
.controls { margin: 0 0 6px; }
.controls label { margin-right: 12px; }
.plot { width: 100%; height: 420px; }
.plot.small { height: 300px; }
table.kv { border-collapse: collapse; font-size: 13px; margin: 6px 0; }
table.kv th, table.kv td { padding: 2px 8px; border-bottom: 1px solid #e3e6ea; text-align: left; }
table.kv td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.neg { color: #8c1d18; font-weight: 600; }
input[type=range] { width: 100%; }
.note { color: #5a6573; font-size: 12px; }
#status { color: #8c1d18; }
.tables { display: flex; flex-wrap: wrap; gap: 0 24px; }
@media (max-width: 900px) { .cols { grid-template-columns: 1fr; } }
"""

_BODY = {
    "design": """
<div class="cols">
<section class="panel"><h2>Pareto front</h2>
<div class="controls"><label>x <select id="front-x"></select></label>
<label>y <select id="front-y"></select></label>
<span class="note">click a design to draw it</span></div>
<div id="front" class="plot"></div>
<h2>Parallel coordinates</h2><div id="parcoords" class="plot small"></div></section>
<section class="panel"><h2 id="mech-title">Mechanism</h2>
<div id="mech" class="plot"></div>
<label for="pose">platform along the task: <span id="pose-label"></span></label>
<input type="range" id="pose" min="0" max="0" value="0" step="1">
<div class="tables"><div><h2>Variables and objectives</h2><table class="kv" id="design-vars"></table></div>
<div><h2>Margins</h2><table class="kv" id="design-margins"></table></div></div>
<p class="note" id="legend-note"></p></section>
</div>""",
    "optimize": """
<div class="cols">
<section class="panel"><h2>Pareto front</h2>
<div class="controls"><label>x <select id="front-x"></select></label>
<label>y <select id="front-y"></select></label>
<span class="note">click a design to list it</span></div>
<div id="front" class="plot"></div>
<h2>Selected design</h2><table class="kv" id="design-vars"></table></section>
<section class="panel"><h2 id="history-title">History</h2><div id="history" class="plot small"></div>
<h2 id="sweep-title">Weighting sweep</h2><div id="sweep" class="plot small"></div></section>
</div>""",
    "atlas": """
<div class="cols">
<section class="panel"><h2>Design triangle r1 + r2 + r3 = 3</h2>
<div class="controls"><label>colour <select id="atlas-index"></select></label>
<span class="note">click a design to show it</span></div>
<div id="atlas" class="plot" style="height:520px"></div>
<div id="regions"></div></section>
<section class="panel"><h2 id="atlas-design-title">Design</h2>
<div id="workspace" class="plot"></div>
<table class="kv" id="atlas-design"></table></section>
</div>""",
}

_TEMPLATE = """<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<link rel="icon" href="data:,">
<style>{css}</style>
</head>
<body>
<header><h1>{heading}</h1><p>{sub}</p></header>
<main><p id="status">Loading (the page inflates its embedded plotting library and data) ...</p>
{body}
</main>
<script type="application/octet-stream" id="plotly-gz">{lib}</script>
<script type="application/octet-stream" id="payload-gz">{payload}</script>
<script>{js}</script>
</body>
</html>
"""

_JS = r"""
(function () {
  "use strict";
  function bytes(id) {
    var b = atob(document.getElementById(id).textContent.trim());
    var out = new Uint8Array(b.length);
    for (var i = 0; i < b.length; i++) { out[i] = b.charCodeAt(i); }
    return out;
  }
  function inflate(id) {
    var stream = new Blob([bytes(id)]).stream().pipeThrough(new DecompressionStream("gzip"));
    return new Response(stream).text();
  }
  function fmt(v) {
    if (v === null || v === undefined) { return ""; }
    if (typeof v === "number") { return Number(v.toPrecision(6)).toString(); }
    return String(v);
  }
  function el(id) { return document.getElementById(id); }
  function kvTable(table, rows) {
    table.innerHTML = "";
    rows.forEach(function (r) {
      var tr = document.createElement("tr");
      var th = document.createElement("th"); th.textContent = r[0]; tr.appendChild(th);
      var td = document.createElement("td"); td.textContent = fmt(r[1]);
      td.setAttribute("data-name", r[0]);
      if (typeof r[1] === "number") { td.className = "num" + (r[2] ? " neg" : ""); td.setAttribute("data-value", String(r[1])); }
      tr.appendChild(td); table.appendChild(tr);
    });
  }
  function numericColumns(D) {
    return D.columns.filter(function (c) {
      return D.front[c].some(function (v) { return typeof v === "number"; });
    });
  }
  var CONFIG = {displaylogo: false, responsive: true};

  // ---------------------------------------------------------------- fronts
  function frontPlot(D, onSelect) {
    var cols = numericColumns(D);
    var first = D.objectives.filter(function (o) { return cols.indexOf(o) >= 0; });
    var order = first.concat(cols.filter(function (c) { return first.indexOf(c) < 0; }));
    var sx = el("front-x"), sy = el("front-y");
    order.forEach(function (c) {
      [sx, sy].forEach(function (s) { var o = document.createElement("option"); o.value = c; o.textContent = c; s.appendChild(o); });
    });
    sx.value = order[0]; sy.value = order.length > 1 ? order[1] : order[0];
    var n = D.front[D.columns[0]].length;
    var state = {selected: D.chosen || 0};
    function label(c) {
      var u = D.objective_units && D.objective_units[c] ? " [" + D.objective_units[c] + "]" : "";
      var s = D.senses && D.senses[c] ? " (" + D.senses[c] + ")" : "";
      return c + u + s;
    }
    function draw() {
      var x = D.front[sx.value], y = D.front[sy.value];
      var idx = []; for (var i = 0; i < n; i++) { idx.push(i); }
      var one = n === 1;
      var traces = [{x: x, y: y, customdata: idx, mode: one ? "markers+text" : "markers", type: "scatter",
                     name: "front", marker: {size: one ? 14 : 9, color: "#1f77b4"},
                     text: one ? [fmt(x[0]) + ", " + fmt(y[0])] : undefined, textposition: "top center",
                     hovertemplate: "design %{customdata}<br>" + sx.value + " %{x}<br>" + sy.value + " %{y}<extra></extra>"}];
      if (D.chosen !== undefined) {
        traces.push({x: [x[D.chosen]], y: [y[D.chosen]], mode: "markers", type: "scatter", name: "chosen (design.json)",
                     marker: {symbol: "star", size: 16, color: "#ff7f0e", line: {width: 1, color: "#333"}}, hoverinfo: "skip"});
      }
      traces.push({x: [x[state.selected]], y: [y[state.selected]], mode: "markers", type: "scatter", name: "selected",
                   marker: {symbol: "circle-open", size: 20, color: "#d62728", line: {width: 2}}, hoverinfo: "skip"});
      var layout = {margin: {l: 70, r: 10, t: 10, b: 50}, showlegend: true, legend: {orientation: "h", y: -0.22},
                    xaxis: {title: {text: label(sx.value)}, exponentformat: "power", zeroline: false},
                    yaxis: {title: {text: label(sy.value)}, exponentformat: "power", zeroline: false},
                    hovermode: "closest"};
      return Plotly.react("front", traces, layout, CONFIG);
    }
    function select(i) { state.selected = i; draw(); onSelect(i); }
    sx.addEventListener("change", draw); sy.addEventListener("change", draw);
    return draw().then(function () {
      el("front").on("plotly_click", function (ev) {
        var p = ev.points.filter(function (q) { return q.curveNumber === 0; })[0];
        if (p) { select(p.customdata); }
      });
      return {select: select, state: state};
    });
  }

  function rowOf(D, i) { var r = {}; D.columns.forEach(function (c) { r[c] = D.front[c][i]; }); return r; }

  // ---------------------------------------------------------------- capsules
  // the outline of the capsule of segment s = [x0, y0, x1, y1] and diameter w (closed;
  // mechopt.core.bodies.capsule_outline): half circles about the far end, then the near end
  function capsule(s, w, n) {
    var r = w / 2, a = (s[0] === s[2] && s[1] === s[3]) ? 0 : Math.atan2(s[3] - s[1], s[2] - s[0]), x = [], y = [];
    [[s[2], s[3], a - Math.PI / 2], [s[0], s[1], a + Math.PI / 2]].forEach(function (e) {
      for (var k = 0; k <= n; k++) { var b = e[2] + Math.PI * k / n; x.push(e[0] + r * Math.cos(b)); y.push(e[1] + r * Math.sin(b)); }
    });
    x.push(x[0]); y.push(y[0]);
    return [x, y];
  }
  var BODY_GROUPS = {housing: ["motor housings", "#7f7f7f"], guide: ["guides", "#b0b0b0"], carriage: ["carriages", "#c49a6c"],
                     proximal: ["links (capsules)", "#4a7fb5"], distal: ["links (capsules)", "#4a7fb5"], platform: ["links (capsules)", "#4a7fb5"]};
  var WORST = {clearance: ["worst clearance", "#ff7f0e", "dash"], keep_out: ["closest to the keep-out zone", "#e377c2", "dot"]};
  // the keep-out zone, the bodies at slider position k (filled, by group) and the worst poses (outlines)
  function bodyTraces(B, k, unit) {
    var t = [];
    if (B.zone) {
      t.push({x: B.zone.x, y: B.zone.y, mode: "lines", fill: "toself", name: "keep-out zone: " + B.zone.label,
              line: {color: "#d62728", width: 1}, fillcolor: "rgba(214,39,40,0.08)",
              fillpattern: {shape: "/", fgcolor: "#d62728", size: 8, solidity: 0.15}, hoverinfo: "skip"});
    }
    var groups = {}, order = [];
    (B.segments[k] || []).forEach(function (s, j) {
      if (!s) { return; }
      var grp = BODY_GROUPS[B.kinds[j]], c = capsule(s, B.widths[j], 12);
      if (!groups[grp[0]]) { groups[grp[0]] = {x: [], y: [], colour: grp[1]}; order.push(grp[0]); }
      groups[grp[0]].x = groups[grp[0]].x.concat(c[0], [null]); groups[grp[0]].y = groups[grp[0]].y.concat(c[1], [null]);
    });
    order.forEach(function (name) {
      var G = groups[name];
      t.push({x: G.x, y: G.y, mode: "lines", fill: "toself", name: name, opacity: 0.45, fillcolor: G.colour,
              line: {color: G.colour, width: 1}, hoverinfo: "skip"});
    });
    B.worst.forEach(function (w) {
      var st = WORST[w.what], all = [[], []], pair = [[], []];
      w.segments.forEach(function (s, j) {
        if (!s) { return; }
        var c = capsule(s, B.widths[j], 12), to = w.which.indexOf(B.names[j]) >= 0 ? pair : all;
        to[0] = to[0].concat(c[0], [null]); to[1] = to[1].concat(c[1], [null]);
      });
      var name = st[0] + ": " + fmt(w.value) + " " + unit + " (" + w.which.join(" - ") + ")";
      t.push({x: all[0].concat(pair[0]), y: all[1].concat(pair[1]), mode: "lines", name: name, legendgroup: w.what,
              line: {color: st[1], width: 1, dash: st[2]}, hoverinfo: "skip"});
      t.push({x: pair[0].concat([w.x]), y: pair[1].concat([w.y]), mode: "lines+markers", name: name + " (pair, platform)",
              showlegend: false, legendgroup: w.what, line: {color: st[1], width: 2.5, dash: st[2]},
              marker: {symbol: "x", size: pair[0].map(function () { return 0; }).concat([9]), color: st[1]},
              hovertemplate: "platform (%{x}, %{y})<extra>" + st[0] + "</extra>"});
    });
    return t;
  }
  // ---------------------------------------------------------------- design page
  function designPage(D) {
    var slider = el("pose");
    var nPose = D.path_t.length;
    slider.max = String(nPose - 1);
    var cur = {i: D.chosen || 0, k: 0};
    var u = D.unit;
    function mechTraces() {
      var g = D.designs[cur.i], pose = g.poses[cur.k], t = [];
      t.push({x: g.path.x, y: g.path.y, mode: "markers", name: "slider positions", marker: {size: 3, color: "#aaa"}, hoverinfo: "skip"});
      t.push({x: g.task.x, y: g.task.y, mode: D.region ? "lines" : "markers", name: "task (placed)",
              line: {color: "#1f77b4", width: 2}, marker: {size: 4, color: "#1f77b4"}, hoverinfo: "skip"});
      if (g.outlines.gcw) {
        t.push({x: g.outlines.gcw.x, y: g.outlines.gcw.y, mode: "lines", name: "GCW: LCI >= " + D.gamma,
                line: {color: "#2ca02c", width: 1.2}, hoverinfo: "skip"});
      }
      t.push({x: g.outlines.reach.x, y: g.outlines.reach.y, mode: "lines", name: "reachable boundary",
              line: {color: "#666", width: 1, dash: "dash"}, hoverinfo: "skip"});
      t.push({x: g.outlines.type2.x, y: g.outlines.type2.y, mode: "lines", name: "type-II singularity",
              line: {color: "#d62728", width: 1}, hoverinfo: "skip"});
      var ax = [], ay = [];
      g.actuators.forEach(function (s) { ax.push(s[0][0], s[1][0], null); ay.push(s[0][1], s[1][1], null); });
      if (ax.length) {
        t.push({x: ax, y: ay, mode: "lines", name: "actuator travel", line: {color: "rgba(0,0,0,0.3)", width: 6}, hoverinfo: "skip"});
      }
      if (g.bodies) { bodyTraces(g.bodies, cur.k, u).forEach(function (tr) { t.push(tr); }); }
      var lx = [], ly = [], bx = [], by = [];
      if (pose) {
        pose.chains.forEach(function (c) { c.forEach(function (p) { lx.push(p[0]); ly.push(p[1]); }); lx.push(null); ly.push(null); });
        pose.bases.forEach(function (p) { bx.push(p[0]); by.push(p[1]); });
      }
      t.push({x: lx, y: ly, mode: "lines+markers", name: "legs", line: {color: "#111", width: 3}, marker: {size: 6, color: "#111"},
              hovertemplate: "(%{x}, %{y})<extra>joint</extra>"});
      t.push({x: bx, y: by, mode: "markers", name: "base joints", marker: {symbol: "square", size: 10, color: "#111"}, hoverinfo: "skip"});
      t.push({x: [g.path.x[cur.k]], y: [g.path.y[cur.k]], mode: "markers", name: "platform",
              marker: {size: 12, color: "#ff7f0e", line: {width: 1, color: "#111"}},
              hovertemplate: "platform (%{x}, %{y})<extra></extra>"});
      return t;
    }
    function drawMech() {
      var layout = {margin: {l: 60, r: 10, t: 10, b: 45}, showlegend: true, legend: {orientation: "h", y: -0.15, font: {size: 11}},
                    xaxis: {title: {text: "x [" + u + "]"}, zeroline: false, exponentformat: "power"},
                    yaxis: {title: {text: "y [" + u + "]"}, scaleanchor: "x", scaleratio: 1, zeroline: false, exponentformat: "power"},
                    uirevision: String(cur.i)};
      var pose = D.designs[cur.i].poses[cur.k];
      el("pose-label").textContent = (D.region ? (D.task_kind === "path" ? "path" : "boundary") + " at arc-length fraction " : "task point ") +
        (D.region ? fmt(D.path_t[cur.k]) : (cur.k + 1) + " of " + nPose) + " (position " + (cur.k + 1) + "/" + nPose + ")" +
        (pose ? "" : " - out of reach");
      var drawing = {i: cur.i, k: cur.k};
      return Plotly.react("mech", mechTraces(), layout, CONFIG).then(function () { cur.drawn = drawing; });
    }
    function showRow(i) {
      var r = rowOf(D, i);
      var vars = D.lengths.concat(["mode", "task_x", "task_y"]).concat(D.objectives);
      var rest = D.columns.filter(function (c) { return vars.indexOf(c) < 0 && D.margins.indexOf(c) < 0; });
      kvTable(el("design-vars"), [["design", i]].concat(vars.concat(rest).map(function (c) { return [c, r[c]]; })));
      kvTable(el("design-margins"), D.margins.map(function (c) { return [c, r[c], typeof r[c] === "number" && r[c] < 0]; }));
      el("mech-title").textContent = "Mechanism: design " + i + (i === D.chosen ? " (chosen, design.json)" : "");
    }
    function select(i) { cur.i = i; showRow(i); if (dims.length > 1) { drawParallel(); } return drawMech(); }
    function setPose(k) { cur.k = k; slider.value = String(k); return drawMech(); }
    // while the slider moves, one drawing per animation frame (the latest position)
    var pending = false;
    slider.addEventListener("input", function () {
      cur.k = Number(slider.value);
      if (pending) { return; }
      pending = true;
      requestAnimationFrame(function () { pending = false; drawMech(); });
    });
    el("legend-note").textContent = "Margins in the units of their requirement (front.csv); a negative one fails. " +
      "Drawings: " + D.designs.length + " designs x " + nPose + " platform positions, computed when the page was built " +
      "(the mechanism's inverse kinematics), outlines on a raster of the design's reach.";
    var dims = D.objectives.concat(D.lengths).filter(function (c) { return D.front[c] && typeof D.front[c][0] === "number"; });
    function drawParallel() {
      // parallel coordinates as SVG lines (no WebGL): each column scaled to [0, 1] by its range
      var n = D.designs.length, traces = [], ann = [];
      var lo = {}, hi = {};
      dims.forEach(function (c, j) {
        var v = D.front[c].filter(function (x) { return x !== null; });
        lo[c] = Math.min.apply(null, v); hi[c] = Math.max.apply(null, v);
        ann.push({x: j, y: 1.06, text: "<b>" + c + "</b>", showarrow: false, yanchor: "bottom"});
        ann.push({x: j, y: 1.0, text: fmt(hi[c]), showarrow: false, yanchor: "bottom", font: {size: 10}});
        ann.push({x: j, y: 0.0, text: fmt(lo[c]), showarrow: false, yanchor: "top", font: {size: 10}});
      });
      function scaled(i) { return dims.map(function (c) { var v = D.front[c][i]; return hi[c] > lo[c] ? (v - lo[c]) / (hi[c] - lo[c]) : 0.5; }); }
      var xs = dims.map(function (c, j) { return j; });
      for (var i = 0; i < n; i++) {
        var sel = i === cur.i, ch = i === D.chosen;
        traces.push({x: xs, y: scaled(i), mode: "lines+markers", customdata: xs.map(function () { return i; }), showlegend: false,
                     line: {color: sel ? "#d62728" : (ch ? "#ff7f0e" : "rgba(31,119,180,0.45)"), width: sel ? 3 : 1.5},
                     marker: {size: sel ? 7 : 4}, hovertemplate: "design " + i + "<extra></extra>"});
      }
      var order = traces.map(function (t, i) { return i; }).filter(function (i) { return i !== cur.i; }).concat([cur.i]);
      return Plotly.react("parcoords", order.map(function (i) { return traces[i]; }), {margin: {l: 30, r: 30, t: 40, b: 30},
        annotations: ann, hovermode: "closest",
        xaxis: {range: [-0.3, dims.length - 0.7], showticklabels: false, showgrid: true, zeroline: false, dtick: 1},
        yaxis: {range: [-0.08, 1.12], showticklabels: false, showgrid: false, zeroline: false}}, CONFIG);
    }
    var pc = dims.length > 1 ? drawParallel().then(function () {
      el("parcoords").on("plotly_click", function (ev) { if (ev.points.length) { fpSelect(ev.points[0].customdata); } });
    }) : Promise.resolve(el("parcoords").textContent = "one column: no parallel coordinates");
    var fpSelect = function () {};
    return pc.then(function () { window.mechoptTimings.parcoords = performance.now(); return frontPlot(D, select); }).then(function (fp) {
      window.mechoptTimings.front = performance.now();
      fpSelect = fp.select;
      showRow(cur.i);
      return drawMech().then(function () {
        window.mechoptExplorer = {data: D, select: function (i) { fp.select(i); }, setPose: setPose, current: cur};
      });
    });
  }

  // ---------------------------------------------------------------- optimisation page
  function optimizePage(D) {
    function show(i) { var r = rowOf(D, i); kvTable(el("design-vars"), [["design", i]].concat(D.columns.map(function (c) { return [c, r[c]]; }))); }
    var n = D.front[D.columns[0]] ? D.front[D.columns[0]].length : 0;
    var p = n ? frontPlot(D, show).then(function (fp) { show(0); return fp; }) : Promise.resolve(el("front").textContent = "no feasible design: empty front");
    return p.then(function (fp) {
      var H = D.history, traces = [], title = "History";
      if (H && H.hypervolume) {
        traces.push({x: H.generation, y: H.hypervolume, mode: "lines+markers", name: "hypervolume"});
        title = "Hypervolume per generation";
      } else if (H) {
        D.objectives.forEach(function (o) { if (H["best_" + o]) { traces.push({x: H.generation, y: H["best_" + o], mode: "lines+markers", name: "best " + o}); } });
        title = "Best objective per generation";
      }
      el("history-title").textContent = title;
      var hp = traces.length ? Plotly.newPlot("history", traces, {margin: {l: 60, r: 10, t: 10, b: 45},
        xaxis: {title: {text: "generation"}}, yaxis: {title: {text: traces.length === 1 ? traces[0].name : "value"}, exponentformat: "power"}}, CONFIG)
        : Promise.resolve(el("history").textContent = "no history.csv");
      return hp.then(function () {
        var S = D.sweep, a = D.objectives[0], b = D.objectives[1];
        if (!S || !S[a] || !S[b]) { el("sweep").textContent = "no sweep.csv in this folder"; return null; }
        var ok = S.feasible ? S.feasible.map(function (f) { return f === true || f === "True"; }) : S[a].map(function () { return true; });
        var xs = [], ys = [], ws = [];
        S[a].forEach(function (v, i) { if (ok[i]) { xs.push(v); ys.push(S[b][i]); ws.push("w = " + fmt(S.weight[i])); } });
        return Plotly.newPlot("sweep", [{x: D.front[a], y: D.front[b], mode: "markers", name: "front", marker: {color: "#aaa", size: 6}},
          {x: xs, y: ys, text: ws, mode: "markers+text", textposition: "top center", cliponaxis: false, name: "weighted-sum optima", marker: {color: "#d62728", symbol: "x", size: 9}}],
          {margin: {l: 60, r: 30, t: 20, b: 45}, legend: {orientation: "h", y: -0.25}, xaxis: {title: {text: a}, exponentformat: "power"}, yaxis: {title: {text: b}, exponentformat: "power"}}, CONFIG);
      }).then(function () { window.mechoptExplorer = {data: D, select: fp ? fp.select : null}; });
    });
  }

  // ---------------------------------------------------------------- atlas page
  function quantiles(v) {
    var f = v.filter(function (x) { return x !== null; }).sort(function (a, b) { return a - b; });
    if (!f.length) { return [0, 1]; }
    var lo = f[0], hi = f[f.length - 1];
    var qlo = f[Math.floor(0.005 * (f.length - 1))], qhi = f[Math.ceil(0.995 * (f.length - 1))];
    if (hi > lo && (qhi - qlo) < 0.5 * (hi - lo)) { return [qlo, qhi]; }
    return [lo, hi];
  }
  function atlasPage(D) {
    var T = D.table, sel = el("atlas-index"), n = D.n;
    D.indices.forEach(function (c) { var o = document.createElement("option"); o.value = c; o.textContent = c; sel.appendChild(o); });
    sel.value = D.indices.indexOf("gci") >= 0 ? "gci" : D.indices[0];
    var big = n > 4000;
    // a dense lattice is drawn with WebGL; every trace of the plot then is (a canvas covers the SVG layer)
    var kind = big ? "scattergl" : "scatter";
    var COLORS = ["#d62728", "#ff7f0e", "#e377c2", "#17becf", "#8c564b"];
    var idx = []; for (var i = 0; i < n; i++) { idx.push(i); }
    var cur = {i: null};
    function traces() {
      var c = sel.value, v = T[c], r = quantiles(v);
      var ok = [], nan = [];
      idx.forEach(function (i) { (v[i] === null ? nan : ok).push(i); });
      var t = [{type: kind, x: ok.map(function (i) { return T.s[i]; }), y: ok.map(function (i) { return T.t[i]; }),
                customdata: ok, mode: "markers", name: c,
                marker: {color: ok.map(function (i) { return v[i]; }), colorscale: "Viridis", cmin: r[0], cmax: r[1],
                         size: big ? 3 : 7, colorbar: {title: {text: c}}},
                hovertemplate: "r1 %{customdata}<extra></extra>"}];
      t[0].hovertemplate = c + " %{marker.color}<extra></extra>";
      t.push({type: kind, x: nan.map(function (i) { return T.s[i]; }), y: nan.map(function (i) { return T.t[i]; }),
              customdata: nan, mode: "markers", name: "no MIC (NaN)", marker: {color: "#bbb", size: big ? 2 : 5}});
      D.regions.forEach(function (R, k) {
        var col = COLORS[k % COLORS.length];
        t.push({type: kind, x: R.index.map(function (i) { return T.s[i]; }), y: R.index.map(function (i) { return T.t[i]; }),
                customdata: R.index, mode: "markers", name: "where " + R.where + " (" + R.count + ")",
                visible: big ? "legendonly" : true,  // dense lattices: the outline alone (a click on the legend shows the designs)
                marker: {symbol: "circle-open", size: big ? 4 : 9, color: col, opacity: 0.6}, hoverinfo: "skip"});
        t.push({type: kind, x: R.outline.x, y: R.outline.y, mode: "lines", name: "outline of region " + (k + 1),
                line: {color: col, width: 2.5}, hoverinfo: "skip", showlegend: false});
      });
      if (cur.i !== null) {
        t.push({type: kind, x: [T.s[cur.i]], y: [T.t[cur.i]], mode: "markers", name: "selected",
                marker: {symbol: "star", size: 16, color: "#ff7f0e", line: {width: 1, color: "#111"}}, hoverinfo: "skip"});
      }
      return t;
    }
    function draw() {
      return Plotly.react("atlas", traces(), {margin: {l: 60, r: 10, t: 10, b: 45}, hovermode: "closest",
        legend: {orientation: "h", y: -0.15}, xaxis: {title: {text: "s = (r1 - r2)/sqrt(2)"}, zeroline: false},
        yaxis: {title: {text: "t = sqrt(3/2) r3"}, scaleanchor: "x", scaleratio: 1, zeroline: false}}, CONFIG);
    }
    function circle(cx, cy, r) { var x = [], y = []; for (var k = 0; k <= 360; k++) { var a = k * Math.PI / 180; x.push(cx + r * Math.cos(a)); y.push(cy + r * Math.sin(a)); } return [x, y]; }
    function select(i) {
      cur.i = i;
      var rows = D.columns.map(function (c) { return [c, T[c][i]]; });
      kvTable(el("atlas-design"), [["design", i]].concat(rows));
      el("atlas-design-title").textContent = "Design " + i + ": r1 = " + fmt(T.r1[i]) + ", r2 = " + fmt(T.r2[i]) + ", r3 = " + fmt(T.r3[i]);
      // the reachable set: |P - A_j| in [|r1 - r2|, r1 + r2] about both base joints A_j = (+-r3, 0)
      var r1 = T.r1[i], r2 = T.r2[i], r3 = T.r3[i], lo = Math.abs(r1 - r2), hi = r1 + r2, wx = [], wy = [];
      [-r3, r3].forEach(function (a) {
        [lo, hi].forEach(function (rad) {
          var c = circle(a, 0, rad);
          for (var k = 0; k < c[0].length; k++) {
            var x = c[0][k], y = c[1][k], ok = true;
            [-r3, r3].forEach(function (b) { var d = Math.hypot(x - b, y); if (d < lo - 1e-9 || d > hi + 1e-9) { ok = false; } });
            wx.push(ok ? x : null); wy.push(ok ? y : null);
          }
          wx.push(null); wy.push(null);
        });
      });
      var t = [{x: wx, y: wy, mode: "lines", name: "reachable boundary", line: {color: "#666", dash: "dash"}}];
      if (T.r_mic && T.r_mic[i]) {
        var m = circle(0, T.mic_center_y[i], T.r_mic[i]);
        t.push({x: m[0], y: m[1], mode: "lines", fill: "toself", name: "MIC r = " + fmt(T.r_mic[i]), line: {color: "#2ca02c"}});
      }
      t.push({x: [-r3, r3], y: [0, 0], mode: "markers", name: "base joints", marker: {symbol: "square", size: 10, color: "#111"}});
      draw();
      return Plotly.react("workspace", t, {margin: {l: 50, r: 10, t: 10, b: 40}, legend: {orientation: "h", y: -0.15},
        xaxis: {title: {text: "x [-]"}, zeroline: false}, yaxis: {title: {text: "y [-]"}, scaleanchor: "x", scaleratio: 1, zeroline: false}}, CONFIG);
    }
    sel.addEventListener("change", draw);
    var reg = el("regions");
    reg.innerHTML = "";
    D.regions.forEach(function (R, k) {
      var p = document.createElement("p");
      p.className = "region"; p.setAttribute("data-count", String(R.count)); p.setAttribute("data-where", R.where);
      p.textContent = "region " + (k + 1) + ": where " + R.where + ": " + R.count + " of " + n + " designs";
      reg.appendChild(p);
    });
    var note = document.createElement("p"); note.className = "note";
    note.textContent = n + " designs (step " + fmt(D.step) + ", " + (D.quadrature || "?") + " means, mode " + (D.mode || "?") +
      "); the colour scale spans the 0.5-99.5 % quantiles when a few designs stretch the range.";
    reg.appendChild(note);
    return draw().then(function () {
      el("atlas").on("plotly_click", function (ev) {
        var p = ev.points.filter(function (q) { return q.customdata !== undefined; })[0];
        if (p) { select(p.customdata); }
      });
      // first shown: the design of the first region (else of the whole space) with the largest index
      var v = T[sel.value], pool = D.regions.length && D.regions[0].count ? D.regions[0].index : idx, best = pool[0];
      pool.forEach(function (i) { if (v[i] !== null && (v[best] === null || v[i] > v[best])) { best = i; } });
      return select(best);
    }).then(function () { window.mechoptExplorer = {data: D, select: select, current: cur}; });
  }

  function start(D) {
    var page = {design: designPage, optimize: optimizePage, atlas: atlasPage}[D.kind];
    return page(D);
  }
  if (typeof DecompressionStream === "undefined") {
    el("status").textContent = "This browser cannot inflate the embedded data (no DecompressionStream): use a current browser.";
    return;
  }
  var times = window.mechoptTimings = {start: performance.now()};
  inflate("plotly-gz").then(function (code) {
    times.inflated = performance.now();
    var s = document.createElement("script");
    s.textContent = code;
    document.head.appendChild(s);
    times.library = performance.now();
    return inflate("payload-gz");
  }).then(function (text) { var D = JSON.parse(text); times.data = performance.now(); return start(D); }).then(function () {
    times.drawn = performance.now();
    el("status").textContent = "";
    document.body.setAttribute("data-ready", "1");
  }, function (err) {
    el("status").textContent = "The page failed: " + err;
    throw err;
  });
}());
"""
