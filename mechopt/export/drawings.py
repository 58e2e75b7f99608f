"""Drawings of an exported design: DXF per link, SVG at the task's centre, the
joint-space path (CSV) and its animation (GIF), all in the design's length unit [L].

* DXF (ezdxf, R2010, ``$INSUNITS`` the design's unit): one file per body with two or
  more pins (:meth:`~mechopt.core.kinematic_tree.KinematicTree.pins`: the rigid links,
  the base when it carries two revolute joints), in the body's own frame: a circle of
  diameter ``width / 3`` (layer ``HOLES``) centred on every pin, the capsule outline of
  width ``width`` (:func:`mechopt.export.inertia.link_width`) about the two farthest
  pins (layer ``OUTLINE``: two lines and two half circles) and a label (``TEXT``). The
  hole-centre distances are the link lengths. Bodies with one pin (a carriage on a
  guide, a strut's halves) are not drawn. The header's custom property ``MECHOPT_DESIGN_SHA256`` holds the digest.
* SVG (matplotlib): the task, the mechanism at the task's centre (each body as the
  polyline of its pins, each prismatic joint's stroke as a grey bar), the path and the
  boundary of the reachable set (the mechanism's ``serial_clearance = 0``, dashed).
* CSV: one row per path sample (:func:`mechopt.export.source.path_samples`): ``t`` (the
  arc-length fraction, [0, 1)), ``q1``, ``q2`` (the actuated joints in leg order: motor
  angles [rad] or linear positions [L], from the mechanism's inverse
  kinematics), ``x``, ``y`` (the platform point [L], task frame); a first line
  ``# mechopt design sha256 <digest>`` (read it with ``pandas.read_csv(path,
  comment="#")``).
* GIF (matplotlib's ``PillowWriter``): one frame per path sample ``0, k, 2k, ...`` with
  ``k = ceil(n / MAX_FRAMES)`` (:func:`frame_step`), so at most :data:`MAX_FRAMES`
  frames, 20 frames per second; the task, the reachable boundary, the traced path and
  the mechanism drawn; the GIF comment holds the digest.
"""
from __future__ import annotations

import math

import numpy as np

from mechopt.core.kinematic_tree import BASE

__all__ = ["link_dxf", "dxf_units", "pose_elements", "draw_svg", "path_frame", "write_gif", "frame_step",
           "MAX_FRAMES", "GIF_FPS", "DXF_UNITS"]

#: at most this many GIF frames (:func:`frame_step`)
MAX_FRAMES = 60
GIF_FPS = 20
#: the DXF ``$INSUNITS`` code of each length unit
DXF_UNITS = {"mm": 4, "cm": 5, "m": 6, "in": 1}


def frame_step(n: int) -> int:
    """``k = ceil(n / MAX_FRAMES)``: the GIF shows the samples ``0, k, 2k, ...``.

    Parameters
    ----------
    n : int
        Samples.

    Returns
    -------
    int
        ``k``.
    """
    return max(1, math.ceil(n / MAX_FRAMES))


def dxf_units(unit: str) -> int:
    """The DXF ``$INSUNITS`` code of a length unit.

    Parameters
    ----------
    unit : str
        ``"mm"``, ``"cm"``, ``"m"`` or ``"in"``.

    Returns
    -------
    int
        The code.
    """
    return DXF_UNITS[unit]


def link_dxf(tree, body: str, width: float, unit: str, digest: str):
    """The ezdxf document of one body (module docstring); lengths [L].

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    body : str
        The body's name.
    width : float
        The link's width [L].
    unit : str
        The length unit.
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.

    Returns
    -------
    ezdxf.document.Drawing
        The document.
    """
    import ezdxf

    pins = tree.pins()[body]
    doc = ezdxf.new("R2010", setup=False)
    doc.header["$INSUNITS"] = dxf_units(unit)
    doc.header.custom_vars.append("MECHOPT_DESIGN_SHA256", digest)
    doc.layers.add("HOLES")
    doc.layers.add("OUTLINE")
    msp = doc.modelspace()
    for _, (x, y) in pins:
        msp.add_circle((float(x), float(y)), radius=width / 6.0, dxfattribs={"layer": "HOLES"})
    # the two farthest pins carry the capsule
    best, a, b = -1.0, pins[0][1], pins[0][1]
    for i, (_, p) in enumerate(pins):
        for _, r in pins[i + 1:]:
            d = math.hypot(r[0] - p[0], r[1] - p[1])
            if d > best:
                best, a, b = d, p, r
    r = width / 2.0
    if best <= 0:
        msp.add_circle(a, radius=r, dxfattribs={"layer": "OUTLINE"})
    else:
        ux, uy = (b[0] - a[0]) / best, (b[1] - a[1]) / best
        nx, ny = -uy, ux
        pts = [(a[0] - nx * r, a[1] - ny * r, 0.0), (b[0] - nx * r, b[1] - ny * r, 1.0),
               (b[0] + nx * r, b[1] + ny * r, 0.0), (a[0] + nx * r, a[1] + ny * r, 1.0)]
        msp.add_lwpolyline(pts, format="xyb", close=True, dxfattribs={"layer": "OUTLINE"})
    msp.add_text(f"{tree.name} {body}: pins {best:.6g} {unit} apart, width {width:.4g} {unit}",
                 height=width / 4.0, dxfattribs={"layer": "OUTLINE"}).set_placement((a[0], a[1] - 1.5 * width))
    return doc


def pose_elements(tree, q: dict) -> list:
    """What a drawing shows at joint values ``q`` (arrays of one shape ``s``): a list of
    ``(kind, xs, ys)``, ``xs``/``ys`` of shape ``s + (points,)`` in the base frame [L]:
    ``"link"`` the polyline of a body's pins (bodies with two or more), ``"stroke"`` a
    prismatic joint's travel over its limits, ``"strut"`` the segment from a prismatic
    joint's parent body to its child (not drawn for a joint on the base: a guide), and
    ``"pin"`` every body's single pin.

    Parameters
    ----------
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    q : dict
        ``{joint: array}`` [rad or L].

    Returns
    -------
    list of tuple
        ``(kind, xs, ys)``.
    """
    pose = tree.forward(q)
    pins = tree.pins()
    out = []

    def world(body, px, py):
        x, y, a = pose[body]
        return x + np.cos(a) * px - np.sin(a) * py, y + np.sin(a) * px + np.cos(a) * py

    for body, ps in pins.items():
        if body == BASE and len(ps) < 2:
            continue
        pts = [world(body, *p) for _, p in ps]
        xs, ys = np.stack([p[0] for p in pts], -1), np.stack([p[1] for p in pts], -1)
        out.append(("link" if len(ps) >= 2 else "pin", xs, ys))
    for j in tree.joints:
        if j.kind != "prismatic":
            continue
        if j.limits is not None:
            ends = [world(j.parent, j.origin[0] + v * j.axis[0], j.origin[1] + v * j.axis[1]) for v in j.limits]
            out.append(("stroke", np.stack([e[0] for e in ends], -1), np.stack([e[1] for e in ends], -1)))
        if j.parent != BASE:
            a, b = world(j.parent, 0.0, 0.0), pose[j.child]
            out.append(("strut", np.stack([a[0], b[0]], -1), np.stack([a[1], b[1]], -1)))
    return out


_STYLE = {"link": dict(color="k", lw=2.5, marker="o", ms=5), "pin": dict(color="k", lw=0, marker="o", ms=5),
          "stroke": dict(color="0.6", lw=6, alpha=0.6, solid_capstyle="butt"), "strut": dict(color="k", lw=2.5)}


def _axes(src, tree, px, py, title):
    """A figure with the task, the path and room for the mechanism at every pose."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 5.5))
    ax = fig.add_subplot()
    task = src.task
    ox, oy = task.outline()
    if task.is_region:
        ax.fill(ox, oy, color="tab:blue", alpha=0.12, lw=0)
        ax.plot(ox, oy, color="tab:blue", lw=1.5, label="task")
    else:
        ax.plot(ox, oy, ".", color="tab:blue", ms=3, label="task")
    ax.set_aspect("equal")
    ax.set_xlabel(f"x [{src.unit}]")
    ax.set_ylabel(f"y [{src.unit}]")
    ax.set_title(title, fontsize=9)
    return fig, ax


def _limits(ax, elements, tx, ty):
    xs = np.concatenate([np.ravel(e[1]) for e in elements] + [np.ravel(tx)])
    ys = np.concatenate([np.ravel(e[2]) for e in elements] + [np.ravel(ty)])
    xs, ys = xs[np.isfinite(xs)], ys[np.isfinite(ys)]
    pad = 0.05 * max(np.ptp(xs), np.ptp(ys), 1e-12)
    ax.set_xlim(xs.min() - pad, xs.max() + pad)
    ax.set_ylim(ys.min() - pad, ys.max() + pad)


def _reach(ax, src, n=161):
    """The reachable set's boundary (``serial_clearance = 0``, the mechanism's own
    function, on an ``n x n`` grid over the axes), dashed grey."""
    from matplotlib.lines import Line2D

    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    mx, my = src.spec.to_mech(src.mech, gx, gy)
    clr = np.asarray(src.mech.serial_clearance(mx, my), float)
    if np.nanmin(clr) < 0 < np.nanmax(clr):
        ax.contour(gx, gy, clr, levels=[0.0], colors="0.4", linewidths=0.8, linestyles="--")
    return Line2D([], [], color="0.4", lw=0.8, ls="--", label="reachable boundary")


def draw_svg(src, tree, home_q: dict, path_xy, path, digest: str) -> None:
    """Write the SVG (module docstring) to ``path``: the mechanism at ``home_q``.

    Parameters
    ----------
    src : mechopt.export.source.DesignSource
        The loaded design.
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    home_q : dict
        Joint values at the task's centre.
    path_xy : tuple of ndarray
        The task's path ``(x, y)`` [L].
    path : str or Path
        The SVG file.
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.
    """
    px, py = path_xy
    fig, ax = _axes(src, tree, px, py, f"{tree.name}: {src.record['repr']}")
    ax.plot(px, py, "--", color="tab:orange", lw=1, label="path")
    els = pose_elements(tree, {k: np.asarray(v, float) for k, v in home_q.items()})
    for kind, xs, ys in els:
        ax.plot(np.ravel(xs), np.ravel(ys), **_STYLE[kind])
    _limits(ax, els, px, py)
    handles, _ = ax.get_legend_handles_labels()
    ax.legend(handles=[*handles, _reach(ax, src)], loc="lower right", fontsize=7)
    fig.savefig(path, format="svg", bbox_inches="tight",
                metadata={"Description": f"mechopt design sha256 {digest}"})


def path_frame(src, tree, q: dict, px, py):
    """``(figure, update, n_frames, step)`` of the animation along the path (samples
    ``q``/``px``/``py`` of length n): ``update(i)`` draws frame ``i`` (sample ``i * step``).

    Parameters
    ----------
    src : mechopt.export.source.DesignSource
        The loaded design.
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    q : dict
        Joint values along the path.
    px, py : ndarray
        The path [L].

    Returns
    -------
    figure : Figure
        The figure.
    update : callable
        ``update(i)`` draws frame ``i``.
    n_frames : int
        Frames.
    step : int
        Samples per frame.
    """
    n = len(px)
    step = frame_step(n)
    frames = list(range(0, n, step))
    fig, ax = _axes(src, tree, px, py, f"{tree.name} along the task's path ({len(frames)} frames, "
                                        f"every {step}. sample)")
    els = pose_elements(tree, q)
    _limits(ax, els, px, py)
    _reach(ax, src)
    lines = [ax.plot([], [], **_STYLE[kind])[0] for kind, _, _ in els]
    trace, = ax.plot([], [], color="tab:orange", lw=1)

    def update(i):
        k = frames[i]
        for line, (_, xs, ys) in zip(lines, els):
            line.set_data(xs[k], ys[k])
        trace.set_data(px[:k + 1], py[:k + 1])
        return [*lines, trace]

    return fig, update, len(frames), step


def write_gif(src, tree, q: dict, px, py, path, digest: str) -> int:
    """Write the GIF (module docstring) to ``path``; returns the number of frames.

    Parameters
    ----------
    src : mechopt.export.source.DesignSource
        The loaded design.
    tree : mechopt.core.kinematic_tree.KinematicTree
        The mechanism's tree.
    q : dict
        Joint values along the path.
    px, py : ndarray
        The path [L].
    path : str or Path
        The GIF file.
    digest : str
        The design's digest (:func:`mechopt.export.source.design_digest`), written into the
        file.

    Returns
    -------
    int
        The number of frames.
    """
    from matplotlib.animation import FuncAnimation, PillowWriter

    class _Writer(PillowWriter):  # PillowWriter, with the digest as the GIF comment
        def finish(self):
            self._frames[0].save(self.outfile, save_all=True, append_images=self._frames[1:],
                                 duration=int(1000 / self.fps), loop=0, comment=f"mechopt design sha256 {digest}")

    fig, update, n, _ = path_frame(src, tree, q, px, py)
    anim = FuncAnimation(fig, update, frames=n, blit=False)
    anim.save(str(path), writer=_Writer(fps=GIF_FPS), dpi=60)
    return n
