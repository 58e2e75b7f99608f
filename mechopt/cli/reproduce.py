"""``mechopt reproduce PAPER [--out DIR] [--quick] [--force]``: a paper's tables and figures
beside the published values.

Runs :func:`mechopt.workflows.reproduce.reproduce` for one paper or ``all`` into
``DIR/<paper>/`` (``table.csv``, ``table.md``, the paper's figures and runs) and the
summary ``DIR/README.md``; progress goes to stderr, the closing line (the counts of
matching and differing values) to stdout. A paper already finished is skipped unless
``--force``.
"""
from __future__ import annotations

import sys

NAME = "reproduce"


def add_parser(subparsers):
    """Register ``reproduce``."""
    rp = subparsers.add_parser(NAME, help="reproduce a paper's tables and figures beside the published values")
    rp.add_argument("paper", help="le2013, stan2008, liu2006, wu2008 or all")
    rp.add_argument("--out", default="results", help="output folder (default results)")
    rp.add_argument("--quick", action="store_true", help="small runs (all four papers in about 20 s on 2 cores; the full run about 2 minutes)")
    rp.add_argument("--force", action="store_true", help="redo papers already finished")


def run(args) -> int:
    """Reproduce, then print the counts line."""
    from mechopt.workflows.reproduce import counts_line, reproduce
    from mechopt.core.published import counts

    def log(msg):
        print(msg, file=sys.stderr, flush=True)

    table = reproduce(args.paper, out=args.out, quick=args.quick, force=args.force, log=log,
                      progress=True)
    print(f"{counts_line(counts(table))}; summary in {args.out}/README.md")
    return 0
