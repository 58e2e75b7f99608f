"""The ``mechopt`` command: evaluate, optimize, sweep, design, atlas, reproduce, report.

Every bad input ends with one line ``mechopt: error: <message>`` on stderr and
exit status 2, never a traceback; SIGINT/SIGTERM end a run with one line and exit
status 130/143; an empty result (no feasible design, an empty GCW) is a result,
exit status 0.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys

from mechopt import __version__

EXIT_USAGE = 2
#: what ``mechopt --help`` says above the commands
DESCRIPTION = ("Dimensional synthesis of 2-DOF planar parallel manipulators: evaluate a "
               "design, optimize a published formulation, size a mechanism for a task, "
               "draw atlases, reproduce the papers.")

class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block) and exit status 2."""

    def error(self, message):
        raise _UsageError(message)


class _UsageError(Exception):
    pass



def _fmt(v):
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, list):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    return str(v)


def _print_table(d: dict, title: str):
    print(title)
    w = max(len(k) for k in d)
    for k, v in d.items():
        print(f"  {k:<{w}}  {_fmt(v)}")


def _cmd_evaluate(args):
    """``mechopt evaluate <mechanism> ...``: any registered mechanism (generated from its
    declared parameters, :func:`_add_evaluate_parsers`)."""
    from mechopt.analysis.evaluate import evaluate
    from mechopt.mechanisms import get

    cls = get(args.mechanism)
    mech = cls.from_parameters(**{p.name: getattr(args, p.name) for p in cls.parameters})
    options = {p.name: getattr(args, p.name) for p in _disk_options(cls)}
    res = evaluate(mech, **options)
    if args.json:
        _print_result(res.as_dict(), res.mechanism, True)
    else:
        _print_result({"inputs": res.inputs, **res.values}, res.mechanism, False)
    return 0


def _disk_options(cls):
    if not cls.disk_indices:
        return ()
    from mechopt.analysis.evaluate import DISK_OPTIONS

    return DISK_OPTIONS


#: how a declared parameter kind is read from the command line (checks follow in the
#: constructors, with one-line errors)
_KIND_TYPES = {"length": float, "length0": float, "position": float, "angle_deg": float,
               "fraction": float, "choice": str}


def _add_parameter(parser, p):
    """One ``--name`` option of a declared :class:`~mechopt.core.protocol.Parameter`."""
    unit = f" [{p.unit}]" if p.unit not in ("-", "") and f"[{p.unit}]" not in p.help else ""
    extra = ""
    if p.choices and not all(c in p.help for c in p.choices):
        extra = f": {', '.join(p.choices)}"
    default = "" if p.required or p.default is None else f" (default {p.default})"
    parser.add_argument(p.option, dest=p.name, type=_KIND_TYPES[p.kind], required=p.required,
                        default=None if p.required else p.default,
                        help=f"{p.help}{unit}{extra}{default}")


def _add_evaluate_parsers(sub):
    from mechopt.mechanisms import registry

    ev = sub.add_parser("evaluate", help="evaluate one design (every registered mechanism)",
                        description="Evaluate one design of a registered mechanism. Lengths [L] are in "
                                    "any one unit: the printed lengths are in that unit, areas in its "
                                    "square, angles in deg, the indices dimensionless (docs/outputs.md "
                                    "lists every key with its unit).")
    evs = ev.add_subparsers(dest="mechanism", required=True, parser_class=_Parser)
    for name, cls in registry().items():
        mp = evs.add_parser(name, help=cls.cli_help,
                            description=f"{cls.cli_help}. Lengths [L] in any one unit; the output's "
                                        "lengths are in that unit, its areas in that unit squared.")
        for p in cls.parameters + _disk_options(cls):
            _add_parameter(mp, p)
        mp.add_argument("--json", action="store_true",
                        help="print one JSON object (inputs echoed; NaN and inf as null; keys and "
                             "units: docs/outputs.md)")
        mp.set_defaults(func=_cmd_evaluate)


def _json_safe(v):
    """Standard JSON has no NaN or Infinity: such values (an empty workspace's
    mean, an unbounded k_av) are printed as null."""
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if isinstance(v, list):
        return [_json_safe(x) for x in v]
    if isinstance(v, dict):
        return {k: _json_safe(x) for k, x in v.items()}
    return v


def _print_result(res: dict, title: str, as_json: bool):
    if as_json:
        print(json.dumps({k: _json_safe(v) for k, v in res.items()}, allow_nan=False))
    else:
        _print_table(res, title)


def _cmd_reproduce(args):
    from mechopt.workflows.reproduce import reproduce

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    from mechopt.core.published import counts
    from mechopt.workflows.reproduce import counts_line

    table = reproduce(args.paper, out=args.out, quick=args.quick, force=args.force, log=log,
                      progress=True)
    print(f"{counts_line(counts(table))}; summary in {args.out}/README.md")
    return 0


def _cmd_report(args):
    from pathlib import Path

    from mechopt.workflows.report import write_report

    path = write_report(args.results, out=args.html)
    print(f"report: {Path(path).resolve()}")
    return 0


def _cmd_problems(args):
    from mechopt.problems import available

    rows = available()
    w = max(len(n) for n, _ in rows)
    for name, summary in rows:
        print(f"{name:<{w}}  {summary}")
    return 0


def _client(args):
    from mechopt.run.parallel import connect

    return connect(args.dask) if args.dask else None


def _cmd_optimize(args):
    from mechopt.problems import get
    from mechopt.run.runner import infeasible_line, optimize, resume

    if args.resume is not None:
        args.out = args.resume
        expect = {"problem": args.problem, "algorithm": args.algorithm, "pop": args.pop, "gen": args.gen,
                  "seed": args.seed, "checkpoint_every": args.checkpoint_every, **_run_settings(args),
                  "settings": _problem_options(args)}
        if args.overwrite:
            raise ValueError("--overwrite starts a new run; it does not go with --resume")
        client = _client(args)
        try:
            res = resume(args.resume, args.n_jobs, client, expect=expect)
        finally:
            if client is not None:
                client.close()
    else:
        if args.problem is None or args.out is None:
            raise ValueError("optimize needs PROBLEM and --out (or --resume DIR)")
        problem = get(args.problem, **_problem_options(args))
        client = _client(args)
        try:
            res = optimize(problem, args.algorithm, args.pop, args.gen, _seed(args), args.n_jobs, client,
                           args.out, progress=True, checkpoint_every=args.checkpoint_every,
                           overwrite=args.overwrite, **_run_settings(args))
        finally:
            if client is not None:
                client.close()
    if infeasible_line(res.info):  # an empty front is an answer: one line, status 0
        print(infeasible_line(res.info))
        return 0
    print(f"{len(res.front)} designs on the front; wrote {args.out}/front.csv, history.csv, "
          f"run.json, front.png ({res.info['wall_time_s']:.1f} s)")
    return 0


def _cmd_sweep(args):
    from mechopt.problems import get
    from mechopt.run.runner import infeasible_line, parse_weights, sweep

    problem = get(args.problem, **_problem_options(args))
    weights = parse_weights(args.weights)
    client = _client(args)
    try:
        table = sweep(problem, weights, args.pop, args.gen, _seed(args), args.n_jobs, client, args.out,
                      overwrite=args.overwrite, **_run_settings(args))
    finally:
        if client is not None:
            client.close()
    info = table.attrs["sweep"]
    if infeasible_line(info):
        print(infeasible_line(info))
        return 0
    missing = len(table) - info["feasible_weights"]
    print(f"{info['feasible_weights']} weighted-sum optima"
          + (f" ({missing} weights without a feasible design)" if missing else "")
          + f"; wrote {args.out}/sweep.csv, sweep.png, front.csv")
    return 0


def _cmd_design(args):
    """``mechopt design MECHANISM --task ... --out DIR``: size a mechanism for a task."""
    import math

    from mechopt.analysis import task as _task
    from mechopt.workflows.design import design
    from mechopt.core import validation as _v

    def pair_list(text, what, n_allowed):
        vals = [_v.finite_number(what, v) for v in str(text).split(",")]
        if len(vals) not in n_allowed:
            raise ValueError(f"{what} must be {' or '.join(str(k) for k in n_allowed)} comma-separated numbers, "
                             f"got {text!r}")
        return vals

    task = _task.parse_task(args.task, unit=args.unit)
    jl = None
    if args.joint_limits is not None:
        vals = [math.radians(v) for v in pair_list(args.joint_limits, "--joint-limits (deg)", (2, 4))]
        jl = (vals[:2], vals[2:] if len(vals) == 4 else vals[:2])
    la = None
    if args.link_angle is not None:
        la = tuple(math.radians(v) for v in pair_list(args.link_angle, "--link-angle (deg)", (2,)))
    shape = pair_list(args.shape, "--shape", (1, 2, 3)) if args.shape is not None else None
    req = _task.Requirements(min_lci=args.min_lci, joint_limits=jl, link_angle=la, max_stroke=args.max_stroke,
                          min_speed=args.min_speed, min_force=args.min_force,
                          actuator_speed=args.actuator_speed, actuator_torque=args.actuator_torque,
                          payload=args.payload)
    objectives = tuple(o.strip() for o in args.objectives.split(",") if o.strip())
    client = _client(args)
    try:
        res = design(args.mechanism, task, req, objectives, mode=args.mode, place=args.place,
                        min_length=args.min_length, max_length=args.max_length, shape=shape,
                        algorithm=args.algorithm, pop=args.pop, gen=args.gen, seed=args.seed,
                        n_jobs=args.n_jobs, client=client, out=args.out, progress=True, pick=args.pick,
                        polish=not args.no_polish, overwrite=args.overwrite)
    finally:
        if client is not None:
            client.close()
    chosen = json.loads((__import__("pathlib").Path(args.out) / "design.json").read_text())
    obj = ", ".join(f"{k} {v:.5g} {chosen['objective_units'][k]}".rstrip(" -")
                    for k, v in chosen["objectives"].items())
    print(f"{len(res.front)} certified designs on the front; chosen ({res.info['chosen']['by']}): "
          f"{chosen['repr']}; {obj}; wrote {args.out}/front.csv, design.json, run.json, design.png "
          f"({res.info['wall_time_s']:.1f} s)")
    return 0


def _problem_options(args) -> dict:
    """Problem constructor options given on the command line (only those set)."""
    return {k: v for k, v in (("quadrature", args.quadrature),) if v is not None}


def _seed(args) -> int:
    return 1 if args.seed is None else args.seed


def _run_settings(args) -> dict:
    """The termination and operator options of a run (optimize, sweep)."""
    return {"tol": args.tol, "crossover_prob": args.crossover_prob, "mutation_prob": args.mutation_prob,
            "crossover_eta": args.crossover_eta, "mutation_eta": args.mutation_eta}


def _add_run_options(p, resumable=False):
    p.add_argument("problem", nargs="?" if resumable else None,
                   help="a registered problem (see: mechopt problems)")
    p.add_argument("--pop", type=int, default=None, help="population size (default: the problem's)")
    p.add_argument("--gen", type=int, default=None,
                   help="generations (default: the problem's); with --tol their maximum (default 1000)")
    p.add_argument("--tol", type=float, default=None, metavar="FTOL",
                   help="stop when the objectives settle: pymoo's default termination with this ftol")
    p.add_argument("--crossover-prob", type=float, default=None, metavar="P",
                   help="probability that a mating is crossed (SBX; CR for de); default: the algorithm's")
    p.add_argument("--crossover-eta", type=float, default=None, metavar="ETA",
                   help="distribution index of the SBX crossover (default: the algorithm's)")
    p.add_argument("--mutation-prob", type=float, default=None, metavar="P",
                   help="probability that an offspring is mutated (polynomial mutation); default: the algorithm's")
    p.add_argument("--mutation-eta", type=float, default=None, metavar="ETA",
                   help="distribution index of the polynomial mutation (default: the algorithm's)")
    # default None (meaning 1): --resume must tell a seed given from the default
    p.add_argument("--seed", type=int, default=None, help="random seed (default 1)")
    p.add_argument("--n-jobs", type=int, default=None,
                   help="joblib worker processes (default: auto, 1 if a generation evaluates in under "
                        "0.2 s, else 2; recorded in run.json)")
    p.add_argument("--dask", metavar="SCHEDULER_ADDRESS", default=None,
                   help="evaluate on a Dask cluster instead of joblib")
    p.add_argument("--out", required=not resumable, default=None, help="output folder")
    p.add_argument("--quadrature", default=None, choices=None,
                   help="rule of the disk means of the Liu 2006 problems: polar (default, the "
                        "paper's) or area; recorded in run.json")
    p.add_argument("--overwrite", action="store_true",
                   help="replace another run that --out holds (only the files that run wrote)")


def _first_missing(path):
    """The outermost folder of ``path`` that does not exist yet (None if ``path`` exists)."""
    try:
        p = os.path.abspath(path)
    except (TypeError, ValueError):
        return None
    if os.path.lexists(p):
        return None
    while not os.path.lexists(os.path.dirname(p)) and os.path.dirname(p) != p:
        p = os.path.dirname(p)
    return p


def _remove_if_we_made_it_empty(out_before):
    """Nothing is left behind on failure: drop the output folder (and the parents)
    this run created, unless it already holds finished work (a reproduced paper's
    ``table.csv``, written last, is complete and is kept for the next run to skip)."""
    if out_before:
        import shutil
        from pathlib import Path

        if any(Path(out_before).rglob("table.csv")) or any(Path(out_before).rglob("checkpoint.pkl")) \
                or any(Path(out_before).rglob(".atlas_chunks")):
            return
        shutil.rmtree(out_before, ignore_errors=True)


def _cmd_atlas_five_bar(args):
    from mechopt.run.atlas import run_atlas

    from mechopt.run.atlas import DEFAULT_INDICES

    run_atlas(args.out, step=args.step, indices=args.index or DEFAULT_INDICES, quadrature=args.quadrature,
              mode=args.mode, n_jobs=2 if args.n_jobs is None else args.n_jobs, dask=args.dask,
              where=args.where,
              figures=not args.no_figures, chunk_size=args.chunk_size,
              dask_timeout=args.dask_timeout, overwrite=args.overwrite)
    return 0


def _add_atlas_parsers(subparsers):
    """``mechopt atlas five-bar`` (:func:`mechopt.run.atlas.run_atlas`)."""
    # the atlas module (and numba with it) is imported by the command only: every other
    # command starts without it
    at = subparsers.add_parser("atlas", help="performance atlases over a whole design space")
    ats = at.add_subparsers(dest="mechanism", required=True, parser_class=_Parser)
    fb = ats.add_parser(
        "five-bar",
        help="Liu 2006 atlases (GCI, MCI, GVI, GPI, GSI, r_MIC) over r1 + r2 + r3 = 3",
        description="Evaluate every design of r1 + r2 + r3 = 3, 0 <= r3 <= 1.5, r1, r2 > 0 "
                    "on a lattice; write atlas.csv, atlas.json and one PNG per index.")
    fb.add_argument("--index", default=None,
                    help="comma-separated index groups: gci, mci, gvi, gpi, gsi, r_mic (default: all)")
    fb.add_argument("--step", type=float, default=0.01, help="lattice step of the non-dimensional "
                    "link ratios (r1 + r2 + r3 = 3), in [0.001, 0.5] (default 0.01)")
    fb.add_argument("--quadrature", default="area", help="area (default) or polar")
    fb.add_argument("--mode", default="+-", help="working mode: +-, -+, ++ or -- (default +-)")
    par = fb.add_mutually_exclusive_group()
    # default None (meaning 2): argparse only sees a conflict with --dask when the value
    # given is not the default object
    par.add_argument("--n-jobs", type=int, default=None, help="joblib worker processes (default 2)")
    par.add_argument("--dask", metavar="SCHEDULER_ADDRESS", default=None,
                     help="run the chunks on an existing Dask scheduler, e.g. tcp://10.0.0.5:8786")
    fb.add_argument("--dask-timeout", type=float, default=10.0,
                    help="time to wait for the Dask scheduler [s] (default 10)")
    fb.add_argument("--out", required=True, help="output folder")
    fb.add_argument("--where", default=None,
                    help="optimum region, e.g. \"r_mic > 0.8 and gci > 0.6\": outlined on the "
                         "atlases, its designs written to region.csv")
    fb.add_argument("--chunk-size", type=int, default=None, help="designs per work unit")
    fb.add_argument("--no-figures", action="store_true", help="write the tables only")
    fb.add_argument("--overwrite", action="store_true",
                    help="replace an atlas of other settings that --out holds (files it wrote only)")
    fb.set_defaults(func=_cmd_atlas_five_bar)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="mechopt", description=DESCRIPTION)
    p.add_argument("--version", action="version", version=f"mechopt {__version__}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    _add_evaluate_parsers(sub)

    rp = sub.add_parser("reproduce", help="reproduce a paper's tables and figures beside the published values")
    rp.add_argument("paper", help="le2013, stan2008, liu2006, wu2008 or all")
    rp.add_argument("--out", default="results", help="output folder (default results)")
    rp.add_argument("--quick", action="store_true", help="small runs (all four papers in about 20 s on 2 cores; the full run about 2 minutes)")
    rp.add_argument("--force", action="store_true", help="redo papers already finished")
    rp.set_defaults(func=_cmd_reproduce)

    rr = sub.add_parser("report", help="one self-contained HTML page of a reproduction (tables, figures, fronts)")
    rr.add_argument("results", nargs="?", default="results", metavar="RESULTS_DIR",
                    help="folder written by `mechopt reproduce` (default results)")
    rr.add_argument("--out", dest="html", default=None, metavar="FILE",
                    help="HTML file to write (default RESULTS_DIR/report.html)")
    rr.set_defaults(func=_cmd_report)

    pr = sub.add_parser("problems", help="list every registered problem, one line each")
    pr.set_defaults(func=_cmd_problems)

    op = sub.add_parser("optimize", help="run a problem with a seeded pymoo algorithm")
    _add_run_options(op, resumable=True)
    op.add_argument("--checkpoint-every", type=int, default=None, metavar="K",
                    help="save the algorithm state every K generations (resume with --resume)")
    op.add_argument("--resume", metavar="DIR", default=None,
                    help="continue the checkpointed run in DIR (run options given with it must "
                         "equal the run's; --n-jobs and --dask may change)")
    op.add_argument("--algorithm", default=None,
                    help="ga, de, nsga2, nsga2-mnn or nsga3 (default: the problem's)")
    op.set_defaults(func=_cmd_optimize)

    sw = sub.add_parser("sweep", help="weighted-sum optima of a 2-objective problem for a range of weights")
    _add_run_options(sw)
    sw.add_argument("--weights", default="0:1:0.1", help="start:stop:step or a comma list, in [0, 1]")
    sw.set_defaults(func=_cmd_sweep)

    ds = sub.add_parser("design", help="size a mechanism for a task region (requirements over the whole task)")
    ds.add_argument("mechanism", help="five-bar, biglide, bipod or gantry")
    ds.add_argument("--task", required=True,
                    help="rect:W,H@X,Y | circle:R@X,Y | polygon:x1,y1;x2,y2;... | points:FILE.csv; "
                         "lengths [unit] of --unit, in the base frame (base midpoint at the origin, "
                         "y away from the base)")
    ds.add_argument("--unit", default="mm",
                    help="length unit of the task and of every length: mm, cm, m or in (default mm)")
    ds.add_argument("--min-lci", type=float, default=None,
                    help="LCI >= this everywhere on the task (dimensionless, in (0, 1))")
    ds.add_argument("--mode", default=None, help="working mode (five-bar: +-, -+, ++, --; bipod: up, down) or any")
    ds.add_argument("--place", default="fixed", help="fixed (default), free-y or free: task placement")
    ds.add_argument("--objectives", default="size,min-lci",
                    help="comma list of size, footprint, min-lci, mean-lci, speed, force, torque")
    ds.add_argument("--max-length", type=float, default=None, help="longest link [unit] (default 4 x task extent)")
    ds.add_argument("--min-length", type=float, default=None, help="shortest link [unit]")
    ds.add_argument("--joint-limits", default=None, metavar="LO,HI[,LO2,HI2]", help="crank angle limits [deg]")
    ds.add_argument("--link-angle", default=None, metavar="LO,HI",
                    help="|link angle from the slider axis| limits [deg] (gantry, biglide; Wu: 15,75)")
    ds.add_argument("--max-stroke", type=float, default=None, help="longest actuator stroke [unit] (sliders)")
    ds.add_argument("--shape", default=None, metavar="R1,R2,R3",
                    help="fix the link ratios (non-dimensional); the design variable is the scale "
                         "D [unit] (Liu 2006 sec. 3.2.3)")
    ds.add_argument("--actuator-speed", type=float, default=None, help="actuator speed limit [rad/s or unit/s]")
    ds.add_argument("--actuator-torque", type=float, default=None, help="actuator torque limit [N m or N]")
    ds.add_argument("--min-speed", type=float, default=None, help="guaranteed speed in every direction [unit/s]")
    ds.add_argument("--min-force", type=float, default=None, help="guaranteed force in every direction [N]")
    ds.add_argument("--payload", type=float, default=None, help="payload force [N] for the torque objective")
    ds.add_argument("--pick", default=None, metavar="NAME=W,...",
                    help="choose design.json by weights of the normalised objectives (default: the knee)")
    ds.add_argument("--algorithm", default=None,
                    help="ga, de, nsga2, nsga2-mnn or nsga3 (default: ga for one objective, else nsga2)")
    ds.add_argument("--pop", type=int, default=None, help="population size (default 40)")
    ds.add_argument("--gen", type=int, default=None, help="generations (default 50)")
    ds.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    ds.add_argument("--overwrite", action="store_true",
                    help="replace another run that --out holds (only the files that run wrote)")
    ds.add_argument("--n-jobs", type=int, default=2, help="joblib worker processes (default 2)")
    ds.add_argument("--dask", metavar="SCHEDULER_ADDRESS", default=None, help="evaluate on a Dask cluster")
    ds.add_argument("--no-polish", action="store_true",
                    help="skip the local polish of each objective's best design (SLSQP, COBYLA and a "
                         "direct search; with a free placement, lengths searched with the best "
                         "height for each)")
    ds.add_argument("--out", required=True, help="output folder")
    ds.set_defaults(func=_cmd_design)

    _add_atlas_parsers(sub)
    return p


class _Terminated(BaseException):
    """SIGTERM, raised in the main thread like KeyboardInterrupt for SIGINT."""


def _on_sigterm(signum, frame):
    raise _Terminated()


#: exit statuses of a run stopped by SIGINT and SIGTERM (128 + signal number)
EXIT_SIGINT, EXIT_SIGTERM = 130, 143


def _resume_hint(out) -> str:
    if out is None:
        return ""
    from pathlib import Path

    out = Path(out)
    if (out / "checkpoint.pkl").exists():
        return f"; resume with `mechopt optimize --resume {out}`"
    if (out / ".atlas_chunks").is_dir():
        return "; run the same command again to resume (finished chunks are kept)"
    if any(out.glob("*/table.csv")):
        return "; run the same command again to go on (finished papers are kept)"
    return ""


def _run_locked(args, out):
    """Run the command holding its output folder's lock (mechopt.run.io.out_lock)."""
    if out is None:
        return args.func(args)
    from mechopt.run.io import out_lock

    with out_lock(out):
        return args.func(args)


def main(argv=None) -> int:
    import signal
    import threading

    parser = build_parser()
    out_before = out = None
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help and --version have printed; no exception escapes
            return exc.code if isinstance(exc.code, int) else 0
        out = getattr(args, "out", None) or getattr(args, "resume", None)
        out_before = _first_missing(out) if out else None
        return _run_locked(args, out)
    except (_UsageError, ValueError) as exc:
        _remove_if_we_made_it_empty(out_before)
        msg = " ".join(str(exc).split())
        print(f"mechopt: error: {msg}", file=sys.stderr)
        return EXIT_USAGE
    except (KeyboardInterrupt, _Terminated) as exc:
        from mechopt.run.parallel import stop_workers

        stop_workers()
        _remove_if_we_made_it_empty(out_before)
        print(f"mechopt: interrupted{_resume_hint(out)}", file=sys.stderr)
        return EXIT_SIGINT if isinstance(exc, KeyboardInterrupt) else EXIT_SIGTERM
    except OSError as exc:  # the disk, not the input: no space, quota, permission, name too long
        from mechopt.run.parallel import stop_workers

        stop_workers()
        _remove_if_we_made_it_empty(out_before)
        where = f" {exc.filename}" if exc.filename else (f" in {out}" if out else "")
        print(f"mechopt: error: cannot write{where}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_USAGE
    finally:
        if previous is not None:
            signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
