"""``mechopt export``: a design of ``mechopt design`` as simulator models, CAD and a path.

:func:`export` reads a ``design.json`` and the ``run.json`` next to it
(:func:`mechopt.export.source.load`), takes the mechanism's kinematic tree, declared
in the mechanism's own module (``kinematic_tree()`` and ``tree_configuration(x, y)``,
:mod:`mechopt.core.kinematic_tree`: a new mechanism is exported without an edit
here), and writes the formats asked for into one folder:

========  ===========================================================================
format    files
========  ===========================================================================
urdf      ``robot.urdf`` (the open tree, closure frames ``closedloop1_A``/``_B``, SI
          units) and ``robot.yaml`` (the loop and the motors, example-parallel-robots
          format): :mod:`mechopt.export.simulators`
mjcf      ``robot.xml``: MuJoCo, the loop closed by ``<equality><connect>``, position
          servos on the motors, the design's joint ranges
dxf       ``link-<body>.dxf``: one per rigid link, hole centres at the link lengths
svg       ``mechanism.svg``: the mechanism at the task's centre, the task, the path
csv       ``path.csv``: ``t, q1, q2, x, y`` along the task's path
gif       ``path.gif``: the mechanism following the path
========  ===========================================================================

and ``export.json`` (the design's digest, the files and their sha256, the settings).
Naming: the actuated joints carry the mechanism's actuator names (``theta1``,
``theta2`` or ``q1``, ``q2``, leg 1 first), the closure frames are ``closedloop1_A``
(leg 1: the platform point) and ``closedloop1_B`` (leg 2). Every file carries the
design's digest (:func:`mechopt.export.source.design_digest`: sha256 of design.json's
canonical content) as a comment or property, so a file can be matched to its design.

The files are written as one set (:func:`mechopt.run.io.output_set`: a staging folder,
then renames, the manifest last); a bad input (a JSON of another tool, an unknown
format) is refused before anything is written.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np

__all__ = ["export", "parse_formats", "FORMATS", "EXPORT_OUTPUTS", "DEFAULT_SAMPLES"]

FORMATS = ("urdf", "mjcf", "dxf", "svg", "csv", "gif")
#: the names an export writes (glob patterns; the output folder's manifest accounts for them)
EXPORT_OUTPUTS = ("robot.urdf", "robot.yaml", "robot.xml", "link-*.dxf", "mechanism.svg", "path.csv", "path.gif",
                  "export.json")
#: path samples of a region task (its boundary) by default
DEFAULT_SAMPLES = 200


def parse_formats(text) -> tuple:
    """``"urdf,mjcf"`` -> ``("urdf", "mjcf")`` (None: every format); ValueError for an
    unknown or empty one.

    Parameters
    ----------
    text : str or None
        A comma list of formats.

    Returns
    -------
    tuple of str
        The formats.

    Raises
    ------
    ValueError
        For an unknown or empty format.
    """
    if text is None:
        return FORMATS
    names = tuple(dict.fromkeys(s.strip().lower() for s in str(text).split(",") if s.strip()))
    bad = [n for n in names if n not in FORMATS]
    if bad or not names:
        raise ValueError(f"--format must be a comma list of {', '.join(FORMATS)}, got {text!r}")
    return names


def export(design, to, formats=None, samples: int = DEFAULT_SAMPLES, overwrite: bool = False) -> dict:
    """Export the design at ``design`` (a design.json path) into the folder ``to``.

    Parameters
    ----------
    design : str or Path
        A ``design.json`` written by ``mechopt design`` (its ``run.json`` beside it).
    to : str or Path
        Output folder (created; a folder holding another run is refused unless
        ``overwrite``).
    formats : iterable of str or str, optional
        Any of :data:`FORMATS` (default all), or a comma list.
    samples : int
        Path samples of a region task (its boundary at uniform arc length); a point
        task uses its points.
    overwrite : bool
        Replace another run's files in ``to``.

    Returns
    -------
    dict
        The content of ``export.json``: ``design_sha256``, ``files`` (name -> sha256),
        ``frames``, ``samples``, ``wall_time_s`` and the conventions.

    Raises
    ------
    ValueError
        One line, for an unreadable design, an unknown format, or a folder holding another
        run.
    """
    from mechopt.core import validation as _v
    from mechopt.export import drawings, simulators
    from mechopt.export.inertia import body_masses, link_width
    from mechopt.export.source import load, path_samples
    from mechopt.run import io as _io

    t0 = time.perf_counter()
    fmts = parse_formats(formats if formats is None or isinstance(formats, str) else ",".join(formats))
    n = _v.integer("samples", samples, minimum=3, maximum=100_000)
    src = load(design)
    tree = src.tree()
    t, px, py = path_samples(src.task, n)
    q = src.configuration(px, py)
    bad = ~np.all([np.isfinite(v) for v in q.values()], axis=0)
    if bad.any():
        k = int(np.argmax(bad))
        raise ValueError(f"the design does not reach its task's path at ({px[k]:.6g}, {py[k]:.6g}) {src.unit}")
    hx, hy = src.home()
    home = {k: float(v[0]) for k, v in src.configuration(np.array([hx]), np.array([hy])).items()}
    width = link_width(tree)
    si = tree.scaled(src.metres)
    home_si = {j.name: home[j.name] * (src.metres if j.kind == "prismatic" else 1.0) for j in tree.joints}
    info = {"design_sha256": src.digest, "design": str(design), "mechanism": tree.name, "repr": src.record["repr"],
            "formats": list(fmts), "unit": src.unit, "simulator_unit": "m", "samples": int(len(t)),
            "actuated_joints": list(tree.actuated), "closure_frames": [c.name for c in tree.closure],
            "link_width": width, "home": {"x": hx, "y": hy},
            "inertia": "the mechanism's default mass model (mechopt.analysis.dynamics.mass_model) on the tree's "
                       "bodies (mechopt.export.inertia.body_masses)"}
    if "urdf" in fmts or "mjcf" in fmts:
        k = [len(t) // 3, (2 * len(t)) // 3]
        mx, my = src.spec.to_mech(src.mech, np.array([hx, px[k[0]], px[k[1]]]), np.array([hy, py[k[0]], py[k[1]]]))
        masses, omitted = body_masses(src.mech, mx, my, src.metres)
        info["masses"] = [{"body": b, "mass_kg": m, "com_m": list(c), "inertia_kg_m2": list(i)}
                          for b, (m, c, i) in masses.items()]
        info["masses_omitted"] = list(omitted)
    out = _io.prepare_out_dir(to)
    key = {"design_sha256": src.digest, "formats": list(fmts), "samples": int(len(t))}
    with _io.run_in(out, "export", key, EXPORT_OUTPUTS, overwrite) as manifest:
        with _io.output_set(out, manifest) as stage:
            if "urdf" in fmts:
                (stage / "robot.urdf").write_text(simulators.urdf(si, src.digest, masses))
                (stage / "robot.yaml").write_text(simulators.robot_yaml(si, src.digest))
            if "mjcf" in fmts:
                (stage / "robot.xml").write_text(simulators.mjcf(si, src.digest, home_si, masses))
            if "dxf" in fmts:
                for body, pins in tree.pins().items():
                    if len(pins) >= 2:
                        drawings.link_dxf(tree, body, width, src.unit, src.digest).saveas(stage / f"link-{body}.dxf")
            if "svg" in fmts:
                drawings.draw_svg(src, tree, home, (px, py), stage / "mechanism.svg", src.digest)
            if "csv" in fmts:
                _write_path_csv(stage / "path.csv", tree, t, q, px, py, src.digest)
            if "gif" in fmts:
                info["frames"] = drawings.write_gif(src, tree, q, px, py, stage / "path.gif", src.digest)
                info["frame_step"] = drawings.frame_step(len(t))
            info["files"] = {p.name: _io.sha256_file(p) for p in sorted(stage.iterdir()) if p.is_file()}
            info["wall_time_s"] = time.perf_counter() - t0
            _io.write_json(info, stage / "export.json")
    return info


def _write_path_csv(path: Path, tree, t, q, px, py, digest) -> None:
    """``path.csv`` (:mod:`mechopt.export.drawings`): the digest line, then ``t, q1, q2, x, y``."""
    import pandas as pd

    a1, a2 = tree.actuated
    df = pd.DataFrame({"t": t, "q1": q[a1], "q2": q[a2], "x": px, "y": py})
    with open(path, "w") as fh:
        fh.write(f"# mechopt design sha256 {digest}\n")
        df.to_csv(fh, index=False, float_format="%.17g")
