"""Command-line interface: ``mechopt evaluate ...`` and ``mechopt run``.

Every bad input ends with one line ``mechopt: error: <message>`` on stderr and
exit status 2, never a traceback.
"""
from __future__ import annotations

import argparse
import json
import sys

from . import __version__

EXIT_USAGE = 2

#: modules that define ``register(subparsers)`` adding their own sub-command
#: (each handler is set with ``set_defaults(func=...)`` and returns an exit status)
_COMMAND_MODULES: tuple[str, ...] = ()


class _Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block) and exit status 2."""

    def error(self, message):
        raise _UsageError(message)


class _UsageError(Exception):
    pass


Parser = _Parser  # for register() hooks: parser_class=cli.Parser


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


def _cmd_evaluate_five_bar(args):
    from .evaluate import evaluate_five_bar
    from .mechanisms.five_bar import FiveBar

    fb = FiveBar(args.r1, args.r2, args.r3, mode=args.mode)
    res = evaluate_five_bar(fb, quadrature=args.quadrature, gamma=args.gamma)
    if args.json:
        print(json.dumps(res))
    else:
        _print_table(res, repr(fb))
    return 0


def _cmd_run(args):
    import pandas as pd

    from .experiments.liu2006 import reproduce_section3

    table = reproduce_section3(quadratures=(args.quadrature,))
    cols = ["design", "quantity", "paper", "reproduced", "rel_error", "status"]
    with pd.option_context("display.width", 120):
        print(table[cols].to_string(index=False, float_format=lambda v: f"{v:.5g}"))
    counts = table["status"].value_counts()
    print(f"\n{counts.get('match', 0)} match, {counts.get('differs', 0)} differ "
          f"(quadrature {args.quadrature}; notes: python -m mechopt.experiments.liu2006)")
    return 0


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(prog="mechopt", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"mechopt {__version__}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=_Parser)

    ev = sub.add_parser("evaluate", help="evaluate one design")
    evs = ev.add_subparsers(dest="mechanism", required=True, parser_class=_Parser)
    fb = evs.add_parser("five-bar", help="symmetric 5R mechanism (Liu 2006 indices)")
    fb.add_argument("--r1", type=float, required=True, help="crank length")
    fb.add_argument("--r2", type=float, required=True, help="distal link length")
    fb.add_argument("--r3", type=float, required=True, help="half base distance")
    fb.add_argument("--mode", default="+-", help="working mode: +-, -+, ++ or -- (default +-)")
    fb.add_argument("--quadrature", default="area", help="area (default) or polar")
    fb.add_argument("--gamma", type=float, default=0.5, help="LCI level of the GCW, in (0, 1)")
    fb.add_argument("--json", action="store_true", help="print one JSON object")
    fb.set_defaults(func=_cmd_evaluate_five_bar)

    run = sub.add_parser("run", help="the main job: evaluate Liu 2006's five example designs")
    run.add_argument("--quadrature", default="polar", choices=("area", "polar"),
                     help="quadrature of the disk means (default polar, the one of the paper)")
    run.set_defaults(func=_cmd_run)

    # sub-commands that live with their own module register themselves here
    for module in _COMMAND_MODULES:
        import importlib

        importlib.import_module(module).register(sub)
    return p


def main(argv=None) -> int:
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        return args.func(args)
    except (_UsageError, ValueError) as exc:
        msg = " ".join(str(exc).split())
        print(f"mechopt: error: {msg}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
