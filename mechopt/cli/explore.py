"""``mechopt explore DIR [--out PAGE.html] [--where COND] [--serve]``: an interactive page of a run.

Reads the ``--out`` folder of ``mechopt design``, ``optimize``, ``sweep`` or ``atlas`` and
writes :func:`mechopt.workflows.explore.write_page`'s self-contained HTML page (Plotly
and the data embedded; it works offline) to ``PAGE.html`` (default ``DIR/explore.html``);
prints its absolute path. ``--serve`` then serves it on ``http://127.0.0.1:PORT/`` and
opens it in the default browser until Ctrl-C.
"""
from __future__ import annotations

NAME = "explore"


def add_parser(subparsers):
    """Register ``explore``."""
    ex = subparsers.add_parser(NAME, help="an interactive, self-contained HTML page of a design, optimisation "
                                          "or atlas run folder")
    ex.add_argument("folder", metavar="DIR",
                    help="the --out folder of `mechopt design`, `optimize`, `sweep` or `atlas`")
    # dest html, not out: mechopt.cli.main locks and cleans up the folder of an ``out``,
    # and this --out is a file
    ex.add_argument("--out", dest="html", default=None, metavar="PAGE.html",
                    help="HTML file to write (default DIR/explore.html)")
    ex.add_argument("--where", action="append", default=None, metavar="COND",
                    help="an atlas region to draw, in the syntax of `mechopt atlas --where` "
                         "(e.g. \"r_mic > 0.8 and gci > 0.6\"); repeat for several")
    ex.add_argument("--serve", action="store_true",
                    help="serve the page on 127.0.0.1 and open it in the default browser (Ctrl-C stops)")
    ex.add_argument("--port", type=int, default=0,
                    help="port of --serve (default 0: a free one)")


def run(args) -> int:
    """Write the page, print where; with ``--serve`` serve it until interrupted."""
    from pathlib import Path

    from mechopt.workflows.explore import serve, write_page

    if not 0 <= args.port <= 65535:
        raise ValueError(f"--port must lie in [0, 65535], got {args.port}")
    path = write_page(args.folder, out=args.html, where=tuple(args.where or ()))
    print(f"explore: {Path(path).resolve()}", flush=True)
    if args.serve:
        serve(path, port=args.port)
    return 0
