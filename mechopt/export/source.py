"""What an export starts from: a ``design.json`` of ``mechopt design``, its ``run.json``,
the design's digest and the path along its task.

:func:`load` reads ``design.json`` and the ``run.json`` next to it (the task is in
``run.json``; ``design.json`` holds the variables, the working mode, the task
placement, the strokes or angular joint ranges and the mechanism's ``repr``), rebuilds the
mechanism from its design specification and checks that it is the one ``repr`` names.

The digest (:func:`design_digest`) is the sha256 of ``design.json``'s canonical
content: the parsed JSON dumped with sorted keys, separators ``","`` and ``":"``, ASCII
only, so two files with the same content in another layout have the same digest. Every
exported file carries it (:mod:`mechopt.export`).
"""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = ["DesignSource", "load", "design_digest", "canonical_json", "task_from_dict", "path_samples"]

#: the keys every design.json of ``mechopt design`` holds
_DESIGN_KEYS = ("mechanism_name", "variables", "task_placement", "repr", "unit")


def canonical_json(obj) -> str:
    """``obj`` as canonical JSON: sorted keys, no spaces, ASCII, no NaN.

    Parameters
    ----------
    obj : object
        Plain JSON data.

    Returns
    -------
    str
        The text.
    """
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=True, allow_nan=False)


def design_digest(record: dict) -> str:
    """sha256 (hex) of :func:`canonical_json` of a design record (module docstring).

    Parameters
    ----------
    record : dict
        A design record.

    Returns
    -------
    str
        The digest (hex).
    """
    return hashlib.sha256(canonical_json(record).encode("ascii")).hexdigest()


def _read_json(path: Path, what: str) -> dict:
    try:
        data = json.loads(path.read_text())
    except FileNotFoundError:
        raise ValueError(f"{what} {str(path)!r} does not exist") from None
    except IsADirectoryError:
        raise ValueError(f"{what} {str(path)!r} is a folder, not a design.json") from None
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise ValueError(f"{what} {str(path)!r} is not readable JSON ({type(exc).__name__})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{what} {str(path)!r} is not a JSON object")
    return data


def task_from_dict(d: dict):
    """The :class:`~mechopt.analysis.task.Task` of ``Task.to_dict()`` (run.json's
    ``design.task``): :meth:`~mechopt.analysis.task.Task.from_dict`.

    Parameters
    ----------
    d : dict
        What ``Task.to_dict()`` wrote.

    Returns
    -------
    mechopt.analysis.task.Task
        The task.

    Raises
    ------
    ValueError
        One line, for an invalid task.
    """
    from mechopt.analysis.task import Task

    try:
        return Task.from_dict(d)
    except ValueError as exc:
        raise ValueError(f"run.json's {exc}") from None


@dataclass(frozen=True)
class DesignSource:
    """A loaded design: ``record`` (design.json as read), ``digest``, ``spec`` and
    ``mech`` (rebuilt), ``task`` (placed where the design covers it, task frame),
    ``unit`` (the length unit [L]) and ``metres`` (one [L] in m).

    Parameters
    ----------
    record : dict
        design.json as read.
    digest : str
        Its digest.
    spec : mechopt.core.design_spec.DesignSpec
        The design spec.
    mech : PlanarMechanism
        The mechanism, rebuilt.
    task : mechopt.analysis.task.Task
        The placed task.
    unit : str
        The length unit [L].
    metres : float
        One [L] in m.
    """

    record: dict
    digest: str
    spec: object
    mech: object
    task: object
    unit: str
    metres: float

    def tree(self):
        """The mechanism's :class:`~mechopt.core.kinematic_tree.KinematicTree` in the task
        frame [L], with the angular motors limited to the design's joint ranges (the strokes are
        the mechanism's own).

        Returns
        -------
        mechopt.core.kinematic_tree.KinematicTree
            The tree.
        """
        tree = self.mech.kinematic_tree()
        ox, oy = self.spec.to_mech(self.mech, 0.0, 0.0)
        tree = tree.shifted(-float(ox), -float(oy))
        ranges = self.record.get("joint_ranges_deg")
        if ranges:
            tree = tree.with_limits({n: (math.radians(lo), math.radians(hi))
                                     for n, (lo, hi) in zip(tree.actuated, ranges)})
        return tree

    def configuration(self, x, y) -> dict:
        """Every joint of :meth:`tree` with the platform at task-frame points ``(x, y)`` [L].

        Parameters
        ----------
        x, y : array_like
            Task-frame points [L].

        Returns
        -------
        dict
            ``{joint: ndarray}`` [rad or L].
        """
        mx, my = self.spec.to_mech(self.mech, np.asarray(x, float), np.asarray(y, float))
        return self.mech.tree_configuration(mx, my)

    def home(self):
        """The task's centre ``(x, y)`` [L] (a region's bounding-box centre, a point
        task's mean), or the first path sample if the centre is out of reach.

        Returns
        -------
        x, y : float
            [L].
        """
        t = self.task
        x, y = t.reference if t.is_region else (float(t.pts[:, 0].mean()), float(t.pts[:, 1].mean()))
        q = self.configuration(np.array([x]), np.array([y]))
        if not all(np.isfinite(v).all() for v in q.values()):
            _, px, py = path_samples(t, 8)
            x, y = float(px[0]), float(py[0])
        return x, y


def load(path) -> DesignSource:
    """Read ``design.json`` at ``path`` and the ``run.json`` in its folder (module
    docstring). ValueError (one line) for a file of another tool, a run.json of another
    run, an unknown mechanism, a mechanism that is not the one ``repr`` names or one
    without a kinematic tree.

    Parameters
    ----------
    path : str or Path
        design.json.

    Returns
    -------
    DesignSource
        The design.

    Raises
    ------
    ValueError
        One line, for the cases above.
    """
    from mechopt.analysis.design_eval import get_spec
    from mechopt.analysis.task import UNITS

    path = Path(path)
    rec = _read_json(path, "DESIGN.json")
    missing = [k for k in _DESIGN_KEYS if k not in rec]
    if missing:
        raise ValueError(f"{str(path)!r} is not a design.json of mechopt design (no {', '.join(missing)})")
    run_path = path.parent / "run.json"
    run = _read_json(run_path, "run.json")
    settings = run.get("design")
    if run.get("problem") != "design" or not isinstance(settings, dict) or "task" not in settings:
        raise ValueError(f"{str(run_path)!r} is not the run.json of a mechopt design run")
    name = rec["mechanism_name"]
    if settings.get("mechanism") != name:
        raise ValueError(f"{str(run_path)!r} is a run of {settings.get('mechanism')!r}, design.json of {name!r}")
    spec = get_spec(name)
    v = rec["variables"]
    try:
        lengths = {n: float(v[n]) for n in spec.lengths}
        mode = v["mode"]
        strokes = [tuple(map(float, s)) for s in rec["strokes"]] if spec.derived_strokes else None
        place = rec["task_placement"]
        tx, ty = float(place["task_x"]), float(place["task_y"])
    except (KeyError, TypeError, ValueError) as exc:
        raise ValueError(f"{str(path)!r} lacks a design variable, stroke or placement ({exc})") from None
    mech = spec.build(lengths, mode, strokes=strokes)
    if repr(mech) != rec["repr"]:
        raise ValueError(f"{str(path)!r}: its variables build {mech!r}, not the {rec['repr']} it names")
    if not callable(getattr(mech, "kinematic_tree", None)):
        raise ValueError(f"{name} declares no kinematic tree (kinematic_tree, tree_configuration): not exportable")
    task = task_from_dict(settings["task"]).moved_to(tx, ty)
    unit = rec["unit"]
    if unit not in UNITS or task.unit != unit:
        raise ValueError(f"{str(path)!r}: unit {unit!r} is not the task's ({task.unit!r}) or not one of {tuple(UNITS)}")
    return DesignSource(rec, design_digest(rec), spec, mech, task, unit, UNITS[unit])


def path_samples(task, n: int):
    """``(t, x, y)``: the task's path. A region: its boundary, counter-clockwise from
    its first vertex (a circle: from angle 0), at ``n`` points of uniform arc length,
    ``t = k / n`` the arc-length fraction (``k = 0 .. n - 1``: the closing point is not
    repeated). A point task: its points in their order, ``t`` the fraction of the
    polyline's length up to each (``n`` ignored). Lengths [L].

    Parameters
    ----------
    task : mechopt.analysis.task.Task
        The task.
    n : int
        Points of a region's boundary.

    Returns
    -------
    t : ndarray
        Arc-length fractions.
    x, y : ndarray
        Points [L].
    """
    if task.is_region:
        n = int(n)
        t = np.arange(n) / n
        x, y = task.boundary_at(t)
        return t, np.asarray(x, float), np.asarray(y, float)
    p = task.pts
    seg = np.hypot(*np.diff(p, axis=0).T) if len(p) > 1 else np.zeros(0)
    cum = np.r_[0.0, np.cumsum(seg)]
    t = cum / cum[-1] if cum[-1] > 0 else np.zeros(len(p))
    return t, p[:, 0].copy(), p[:, 1].copy()
