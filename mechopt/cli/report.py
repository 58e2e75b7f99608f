"""``mechopt report [RESULTS_DIR] [--out FILE]``: one self-contained HTML page of a reproduction.

Reads the folder written by ``mechopt reproduce`` (default ``results``) and writes
:func:`mechopt.workflows.report.write_report`'s page (tables, figures, fronts; every
image embedded) to ``FILE`` (default ``RESULTS_DIR/report.html``); prints its absolute path.
"""
from __future__ import annotations

NAME = "report"


def add_parser(subparsers):
    """Register ``report``."""
    rr = subparsers.add_parser(NAME, help="one self-contained HTML page of a reproduction (tables, figures, fronts)")
    rr.add_argument("results", nargs="?", default="results", metavar="RESULTS_DIR",
                    help="folder written by `mechopt reproduce` (default results)")
    # dest html, not out: mechopt.cli.main locks and cleans up the folder of an ``out``,
    # and this --out is a file
    rr.add_argument("--out", dest="html", default=None, metavar="FILE",
                    help="HTML file to write (default RESULTS_DIR/report.html)")


def run(args) -> int:
    """Write the page, print where."""
    from pathlib import Path

    from mechopt.workflows.report import write_report

    path = write_report(args.results, out=args.html)
    print(f"report: {Path(path).resolve()}")
    return 0
