"""``mechopt atlas five-bar --out DIR [options]``: performance atlases over a whole design space.

``five-bar`` (the one atlas so far) evaluates every design of the Liu 2006 space
r1 + r2 + r3 = 3, 0 <= r3 <= 1.5, r1, r2 > 0 (non-dimensional link ratios) on a lattice of
``--step`` with :func:`mechopt.run.atlas.run_atlas`, which writes ``atlas.csv``,
``atlas.json``, one ``atlas_<index>.png`` per index and, with ``--where``, ``region.csv``
into ``DIR``; the same command again resumes from the finished chunks. ``--json`` prints
``atlas.json`` (with ``command`` and ``out``) as one JSON object instead of the lines.
"""
from __future__ import annotations

from mechopt.cli import _common

NAME = "atlas"


def add_parser(subparsers):
    """Register ``atlas`` and its sub-command ``five-bar``."""
    at = subparsers.add_parser(NAME, help="performance atlases over a whole design space")
    ats = at.add_subparsers(dest="mechanism", required=True, parser_class=_common.Parser)
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
    _common.add_dask_options(fb, par, help="run the chunks on an existing Dask scheduler, e.g. "
                                           "tcp://10.0.0.5:8786")
    fb.add_argument("--out", required=True, help="output folder")
    fb.add_argument("--where", default=None,
                    help="optimum region, e.g. \"r_mic > 0.8 and gci > 0.6\": outlined on the "
                         "atlases, its designs written to region.csv")
    fb.add_argument("--chunk-size", type=int, default=None, help="designs per work unit")
    fb.add_argument("--no-figures", action="store_true", help="write the tables only")
    fb.add_argument("--overwrite", action="store_true",
                    help="replace an atlas of other settings that --out holds (files it wrote only)")
    _common.add_json_option(fb)


def run(args) -> int:
    """Compute, write and draw the atlas of ``args.mechanism`` (five-bar)."""
    # here, not at the top: every command builds this parser, and only this one needs the
    # atlas module
    from mechopt.run.atlas import DEFAULT_INDICES, run_atlas

    import logging

    quiet = logging.getLogger("mechopt").level > logging.INFO
    manifest = run_atlas(args.out, step=args.step, indices=args.index or DEFAULT_INDICES,
                         quadrature=args.quadrature, mode=args.mode,
                         n_jobs=2 if args.n_jobs is None else args.n_jobs, dask=args.dask, where=args.where,
                         figures=not args.no_figures, chunk_size=args.chunk_size,
                         dask_timeout=args.dask_timeout, overwrite=args.overwrite,
                         verbose=not (args.json or quiet))
    if args.json:
        _common.print_json({"command": NAME, "out": str(args.out), **manifest})
    return 0
