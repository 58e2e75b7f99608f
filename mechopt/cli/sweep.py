"""``mechopt sweep PROBLEM --out DIR [--weights W] [run options]``: weighted-sum optima of a
2-objective problem for a range of weights.

Runs :func:`mechopt.run.runner.sweep` over the weights of objective 1 (``start:stop:step``
or a comma list, in [0, 1]; :func:`mechopt.run.runner.parse_weights`) and writes
``sweep.csv``, ``sweep.png`` and the front run's ``front.csv`` (with its ``history.csv``,
``run.json``, ``front.png``) into ``DIR``. Prints one line: the number of weighted-sum
optima (and of the weights without a feasible design), or, when nothing is feasible,
:func:`mechopt.run.runner.infeasible_line` (exit status 0); ``--json``: one JSON object
(``weights``, ``feasible_weights``, ``evaluations``, ``feasible``, ``files``, ...). The run options are those of
``mechopt optimize`` (:func:`mechopt.cli._common.add_run_options`).
"""
from __future__ import annotations

from mechopt.cli import _common

NAME = "sweep"


def add_parser(subparsers):
    """Register ``sweep``: the shared run options and the weights."""
    sw = subparsers.add_parser(NAME, help="weighted-sum optima of a 2-objective problem for a range of weights")
    _common.add_run_options(sw)
    sw.add_argument("--weights", default="0:1:0.1", help="start:stop:step or a comma list, in [0, 1]")


def run(args) -> int:
    """Run the sweep, print its one-line summary."""
    from mechopt.problems import get
    from mechopt.run.runner import infeasible_line, parse_weights, sweep

    problem = get(args.problem, **_common.problem_options(args))
    weights = parse_weights(args.weights)
    with _common.dask_client(args) as client:
        table = sweep(problem, weights, args.pop, args.gen, _common.seed(args), args.n_jobs, client,
                      args.out, overwrite=args.overwrite, **_common.run_settings(args))
    info = table.attrs["sweep"]
    if args.json:
        _common.print_json({"command": NAME, "out": str(args.out), "problem": problem.name,
                            "settings": problem.settings, **info, "infeasible": infeasible_line(info),
                            "files": ["sweep.csv", "sweep.png", "front.csv", "history.csv", "run.json",
                                      "front.png"]})
        return 0
    if infeasible_line(info):
        print(infeasible_line(info))
        return 0
    missing = len(table) - info["feasible_weights"]
    print(f"{info['feasible_weights']} weighted-sum optima"
          + (f" ({missing} weights without a feasible design)" if missing else "")
          + f"; wrote {args.out}/sweep.csv, sweep.png, front.csv")
    return 0
