"""``mechopt optimize PROBLEM --out DIR [run options]`` or ``mechopt optimize --resume DIR``:
run a registered problem with a seeded pymoo algorithm.

Runs :func:`mechopt.run.runner.optimize` (or continues a checkpointed run with
:func:`mechopt.run.runner.resume`) and writes ``front.csv``, ``history.csv``,
``run.json`` and ``front.png`` into ``DIR`` (``checkpoint.pkl`` with
``--checkpoint-every``). Prints one line: the number of designs on the front and the
wall time [s], or, when no design is feasible, :func:`mechopt.run.runner.infeasible_line`
(an answer, exit status 0); with ``--json`` one JSON object (``n_front``, ``feasible``,
``evaluations``, ``generations``, ``wall_time_s``, ``infeasible``, ``files``, ...). The run options are those of ``mechopt sweep``
(:func:`mechopt.cli._common.add_run_options`).
"""
from __future__ import annotations

from mechopt.cli import _common

NAME = "optimize"


def add_parser(subparsers):
    """Register ``optimize``: the shared run options, checkpoints, resume, the algorithm."""
    op = subparsers.add_parser(NAME, help="run a problem with a seeded pymoo algorithm")
    _common.add_run_options(op, resumable=True)
    op.add_argument("--checkpoint-every", type=int, default=None, metavar="K",
                    help="save the algorithm state every K generations (resume with --resume)")
    op.add_argument("--resume", metavar="DIR", default=None,
                    help="continue the checkpointed run in DIR (run options given with it must "
                         "equal the run's; --n-jobs and --dask may change)")
    op.add_argument("--algorithm", default=None,
                    help="ga, de, nsga2, nsga2-mnn or nsga3 (default: the problem's)")


def run(args) -> int:
    """Start or resume the run, print its one-line summary."""
    from pathlib import Path

    from mechopt.problems import get
    from mechopt.run.runner import RUN_OUTPUTS, infeasible_line, optimize, resume

    if args.resume is not None:
        args.out = args.resume
        # what the command line says of the run; resume refuses a run recorded otherwise
        expect = {"problem": args.problem, "algorithm": args.algorithm, "pop": args.pop, "gen": args.gen,
                  "seed": args.seed, "checkpoint_every": args.checkpoint_every,
                  **_common.run_settings(args), "settings": _common.problem_options(args)}
        if args.overwrite:
            raise ValueError("--overwrite starts a new run; it does not go with --resume")
        with _common.dask_client(args) as client:
            res = resume(args.resume, args.n_jobs, client, expect=expect)
    else:
        if args.problem is None or args.out is None:
            raise ValueError("optimize needs PROBLEM and --out (or --resume DIR)")
        problem = get(args.problem, **_common.problem_options(args))
        with _common.dask_client(args) as client:
            res = optimize(problem, args.algorithm, args.pop, args.gen, _common.seed(args), args.n_jobs,
                           client, args.out, progress=True, checkpoint_every=args.checkpoint_every,
                           overwrite=args.overwrite, **_common.run_settings(args))
    if args.json:
        _common.print_json({"command": NAME, "out": str(args.out), "problem": res.info["problem"],
                            "settings": res.info["settings"], "n_front": len(res.front),
                            "feasible": res.info["feasible"], "evaluations": res.info["evaluations"],
                            "generations": res.info["generations"], "wall_time_s": res.info["wall_time_s"],
                            "infeasible": infeasible_line(res.info),
                            "files": sorted(p.name for p in Path(args.out).iterdir()
                                            if p.name in RUN_OUTPUTS)})
        return 0
    if infeasible_line(res.info):  # an empty front is an answer: one line, status 0
        print(infeasible_line(res.info))
        return 0
    print(f"{len(res.front)} designs on the front; wrote {args.out}/front.csv, history.csv, "
          f"run.json, front.png ({res.info['wall_time_s']:.1f} s)")
    return 0
