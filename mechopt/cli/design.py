"""``mechopt design MECHANISM --task TASK --out DIR [requirements] [run options]``: size a
mechanism for a task region.

Reads the task (:func:`mechopt.analysis.task.parse_task`, lengths in ``--unit``: mm, cm,
m or in) and the requirements over the whole task
(:class:`mechopt.requirements.Requirements`: one option per declared
:class:`~mechopt.requirements.base.Option`; angles given in deg, passed on in rad),
then runs :func:`mechopt.workflows.design.design`, which writes ``front.csv``,
``design.json`` (the chosen design: the knee, or the ``--pick`` weights),
``certificate.json`` (each front design's margins and how each is known), ``run.json``,
``history.csv``, ``front.png`` and ``design.png`` into ``DIR``. Prints one line: the
number of certified designs on the front, the chosen design with its objectives in
their units, the wall time [s].
"""
from __future__ import annotations

import json
import math

from mechopt.cli import _common

NAME = "design"


def add_parser(subparsers):
    """Register ``design``: its requirement options and objectives come from the
    declarations of :mod:`mechopt.requirements`, its mechanisms and modes from their
    design specs (one module each)."""
    from mechopt import mechanisms as _mechanisms
    from mechopt import requirements as _req

    names = _mechanisms.designed()
    specs = {n: _mechanisms.design_spec(n) for n in names}
    by_modes = {}
    for n, spec in specs.items():
        by_modes.setdefault(spec.modes, []).append(n)
    modes_text = "; ".join(f"{', '.join(ns)}: {', '.join(m)}" for m, ns in by_modes.items())
    ds = subparsers.add_parser(NAME, help="size a mechanism for a task region (requirements over the whole task)")
    ds.add_argument("mechanism", help=f"{', '.join(names)}, or any: every mechanism (or those of "
                                      f"--mechanisms), their fronts merged into one")
    ds.add_argument("--mechanisms", default=None, metavar="NAME,...",
                    help="with mechanism any: the mechanisms to compare (default: all)")
    ds.add_argument("--task", required=True,
                    help="rect:W,H@X,Y | circle:R@X,Y | polygon:x1,y1;x2,y2;... | points:FILE.csv (the "
                         "points alone) | path:FILE.csv (the polyline through the points, every point of "
                         "it); lengths [unit] of --unit, in the base frame (base midpoint at the origin, "
                         "y away from the base)")
    ds.add_argument("--unit", default="mm",
                    help="length unit of the task and of every length: mm, cm, m or in (default mm)")
    for opt, member in _req.options().values():
        if opt.cli:
            where = [n for n, spec in specs.items() if member.applies(spec)]
            scope = "" if len(where) == len(names) else f" ({', '.join(where)})"
            ds.add_argument(opt.flag, dest=f"req_{opt.name}", default=None, metavar=opt.metavar,
                            help=opt.help + scope)
    ds.add_argument("--mode", default=None, help=f"working mode ({modes_text}) or any")
    ds.add_argument("--place", default="fixed",
                    help="where the task sits: fixed (default: as given by --task), free-y (the search "
                         "also moves it along y; a five-bar of one working mode on both sides of the base "
                         "line) or free (in x and y; starts from the free-y result, never ends worse); the "
                         "placed centre is printed and in front.csv (task_x, task_y)")
    ds.add_argument("--objectives", default="size,min-lci",
                    help=f"comma list of {', '.join(_req.objectives())}")
    ds.add_argument("--max-length", type=float, default=None,
                    help="longest link [unit] (default 4 x the larger of the task's diameter and its "
                         "farthest box coordinate from the base midpoint, |x| or |y|)")
    ds.add_argument("--min-length", type=float, default=None,
                    help="shortest link [unit] (default --max-length / 1000)")
    ds.add_argument("--tolerance", type=float, default=None, metavar="T",
                    help="every front design must also hold for every mechanism whose lengths lie within +-T "
                         "[unit] of its own: the box's corners evaluated and interval "
                         "bounds over the whole box proving LCI, type-II, speed, force and reach; the polish "
                         "keeps designs inside, designs that fail are dropped; each box in certificate.json")
    ds.add_argument("--shape", default=None, metavar="R1,R2,R3",
                    help="fix the link ratios (non-dimensional, one per length of the mechanism); the "
                         "design variable is the scale D [unit] (Liu 2006 sec. 3.2.3)")
    ds.add_argument("--pick", default=None, metavar="[asf:|pseudo:]NAME=W,...",
                    help="choose design.json by weights of the objectives normalised over the front: a "
                         "weighted sum, or with asf: the achievement scalarizing function (reaches "
                         "non-convex parts of a front), pseudo: the nearest pseudo-weights (default: the knee)")
    ds.add_argument("--algorithm", default=None,
                    help="ga, de, nsga2, nsga2-mnn or nsga3 (default: ga for one objective, else nsga2)")
    ds.add_argument("--pop", type=int, default=None, help="population size (default 40)")
    ds.add_argument("--gen", type=int, default=None, help="generations (default 50)")
    ds.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    ds.add_argument("--overwrite", action="store_true",
                    help="replace another run that --out holds (only the files that run wrote)")
    ds.add_argument("--n-jobs", type=int, default=None,
                    help="joblib worker processes (default: auto, as optimize: 1 if a generation "
                         "evaluates in under 0.2 s, else 2; the front does not depend on it)")
    _common.add_dask_options(ds)
    ds.add_argument("--no-polish", action="store_true",
                    help="skip the local polish of each objective's best design (SLSQP, COBYLA and a "
                         "direct search; with a free placement, lengths searched with the best "
                         "height for each)")
    ds.add_argument("--out", required=True, help="output folder")


def _numbers(text, what, n_allowed) -> list:
    """The comma-separated finite numbers of an option, ``len in n_allowed``."""
    from mechopt.core import validation as _v

    vals = [_v.finite_number(what, v) for v in str(text).split(",")]
    if len(vals) not in n_allowed:
        raise ValueError(f"{what} must be {' or '.join(str(k) for k in n_allowed)} comma-separated numbers, "
                         f"got {text!r}")
    return vals


def run(args) -> int:
    """Parse the task and the requirements, run the design, print its one-line summary:
    the chosen design, where the task was placed, and the command's wall time with its
    stages (optimisation, polish, certification, files)."""
    import time
    from pathlib import Path

    from mechopt import mechanisms as _mechanisms
    from mechopt import requirements as _req
    from mechopt.analysis import task as _task
    from mechopt.workflows.design import design

    started = time.perf_counter()
    task = _task.parse_task(args.task, unit=args.unit)
    counts = tuple(sorted({len(_mechanisms.design_spec(n).lengths) for n in _mechanisms.designed()}))
    shape = _numbers(args.shape, "--shape", counts) if args.shape is not None else None
    req = _req.Requirements(**{name: opt.parse(getattr(args, f"req_{name}"))
                               for name, (opt, _) in _req.options().items()
                               if opt.cli and getattr(args, f"req_{name}") is not None})
    objectives = tuple(o.strip() for o in args.objectives.split(",") if o.strip())
    if args.mechanism == "any":
        return _run_any(args, task, req, objectives, shape, started)
    _echo_requirements(req, _mechanisms.design_spec(args.mechanism), task)
    from mechopt.analysis.design_eval import NoFeasibleDesign

    try:
        with _common.dask_client(args) as client:
            res = design(args.mechanism, task, req, objectives, mode=args.mode, place=args.place,
                         min_length=args.min_length, max_length=args.max_length, shape=shape,
                         algorithm=args.algorithm, pop=args.pop, gen=args.gen, seed=args.seed,
                         n_jobs=args.n_jobs, client=client, out=args.out, progress=True, pick=args.pick,
                         polish=not args.no_polish, overwrite=args.overwrite, tolerance=args.tolerance)
    except NoFeasibleDesign as exc:  # an empty result is a result: its files are written
        print(f"{exc}; wrote {args.out}/run.json, population.csv (least violating first), history.csv, "
              f"front.png ({time.perf_counter() - started:.1f} s)")
        return 0
    chosen = json.loads((Path(args.out) / "design.json").read_text())
    obj = ", ".join(f"{k} {v:.5g} {chosen['objective_units'][k]}".rstrip(" -")
                    for k, v in chosen["objectives"].items())
    place = chosen["task_placement"]
    stages = ", ".join(f"{k} {v:.1f}" for k, v in res.info["stage_times_s"].items())
    print(_front_ends(res, chosen["objective_units"]))
    box = (f" (each over its +-{args.tolerance:g} {chosen['unit']} tolerance box; "
           f"{res.info['dropped_by_tolerance']} dropped that do not hold over theirs)" if args.tolerance else "")
    print(f"{len(res.front)} certified designs on the front{box}; chosen ({res.info['chosen']['by']}): "
          f"{chosen['repr']}; {obj}; task centre at ({place['task_x']:.6g}, {place['task_y']:.6g}) "
          f"{chosen['unit']}; wrote {args.out}/front.csv, design.json, run.json, design.png "
          f"({time.perf_counter() - started:.1f} s: {stages})")
    return 0


def _front_ends(res, units) -> str:
    """One line: the front's design at the best end of each objective and the knee,
    each with all its objectives (so the trade-off is seen before the choice)."""
    import numpy as np

    front, names = res.front, list(res.evaluator.objectives)
    best = {n: int(np.argmin(sense * front[n].to_numpy(float))) for n, sense in res.evaluator.senses().items()}

    def objectives(i):
        return ", ".join(f"{n} {front[n].iloc[i]:.5g} {units[n]}".rstrip(" -") for n in names)

    parts = [f"best {n}: {objectives(i)}" for n, i in best.items()]
    if len(names) > 1:
        parts.append(f"knee: {objectives(res.knee())}")
    return "front ends: " + "; ".join(parts)


def _echo_requirements(req, spec, task):
    """One line on stderr: every option given with a unit, in the unit it is used in (a
    bare number is in the task's unit); a warning for a speed or length 100 times below
    the task's scale (``--min-speed 0.5`` meant as m/s but read as mm/s)."""
    import sys

    from mechopt import requirements as _req
    from mechopt.core import units as _u

    checked = req.checked(spec, task.unit)
    parts, warnings = [], []
    for name, (opt, _) in _req.options().items():
        given, value = getattr(req, name), getattr(checked, name)
        if opt.kind is None or given is None:
            continue
        unit = _u.base_unit(opt.kind, task.unit, spec.angular)
        values = value if isinstance(value, tuple) else (value,)  # per actuator: two values
        givens = given if isinstance(given, tuple) else (given,)
        shown = ",".join(f"{v:.6g}" for v in values)
        with_unit = ",".join(str(g) for g in givens) if any(getattr(g, "unit", "") for g in givens) else ""
        parts.append(f"{name} {shown} {unit}" + (f" (given {with_unit})" if with_unit else ""))
        scale = task.diameter  # [unit]: a task's size, or its size per second
        if opt.kind in ("length", "speed") and min(values) < scale / 100:
            warnings.append(f"mechopt: warning: {opt.flag} {value:g} {unit} is over 100 times below the task's "
                            f"size ({scale:g} {task.unit}); give a unit if another was meant (e.g. "
                            f"{given}m{'/s' if opt.kind == 'speed' else ''})")
    if parts:
        print(f"mechopt design: {', '.join(parts)}", file=sys.stderr)
    for w in warnings:
        print(w, file=sys.stderr)


def _run_any(args, task, req, objectives, shape, started) -> int:
    """``mechopt design any``: every mechanism (or ``--mechanisms``), one merged front."""
    import time

    from mechopt.workflows.design_any import design_any

    from mechopt.analysis.design_eval import NoFeasibleDesign

    names = [n.strip() for n in args.mechanisms.split(",") if n.strip()] if args.mechanisms else None
    try:
        with _common.dask_client(args) as client:
            res = design_any(task, req, objectives, mechanisms=names, pick=args.pick, out=args.out,
                             overwrite=args.overwrite, progress=True, mode=args.mode, place=args.place,
                             min_length=args.min_length, max_length=args.max_length, shape=shape,
                             algorithm=args.algorithm, pop=args.pop, gen=args.gen, seed=args.seed,
                             n_jobs=args.n_jobs, client=client, polish=not args.no_polish,
                             tolerance=args.tolerance)
    except NoFeasibleDesign as exc:  # a result: no mechanism has a feasible design (no file written)
        print(f"{exc} ({time.perf_counter() - started:.1f} s)")
        return 0
    counts = res.front["mechanism"].value_counts()
    per = ", ".join(f"{m} {counts.get(m, 0)} of {len(r.front)}" for m, r in res.results.items())
    skipped = "; skipped: " + "; ".join(f"{m} ({why})" for m, why in res.skipped.items()) if res.skipped else ""
    obj = ", ".join(f"{k} {v:.5g} {res.chosen['objective_units'][k]}".rstrip(" -")
                    for k, v in res.chosen["objectives"].items())
    print(f"{len(res.front)} designs on the merged front ({per}){skipped}; chosen "
          f"({res.info['chosen']['by']}): {res.chosen['repr']}; {obj}; wrote {args.out}/front.csv, fronts.csv, "
          f"design.json, run.json, front.png, design.png ({time.perf_counter() - started:.1f} s)")
    return 0
