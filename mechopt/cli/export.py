"""``mechopt export DESIGN.json --to DIR [--format urdf,mjcf,dxf,svg,csv,gif]``: a design
of ``mechopt design`` as simulator models (URDF for Pinocchio, MJCF for MuJoCo), CAD
(DXF per link, SVG) and its task's path (CSV, GIF), each file carrying the design's
digest (:func:`mechopt.export.export`). Prints one line: the files written, the digest,
the wall time [s].
"""
from __future__ import annotations

NAME = "export"


def add_parser(subparsers):
    """Register ``export``."""
    from mechopt.export import DEFAULT_SAMPLES, FORMATS

    ex = subparsers.add_parser(NAME, help="export a design.json to URDF, MJCF, DXF, SVG, a path CSV and a GIF")
    ex.add_argument("design", help="design.json of mechopt design (its run.json beside it holds the task)")
    ex.add_argument("--to", required=True, dest="out", help="output folder")
    ex.add_argument("--format", default=None,
                    help=f"comma list of {', '.join(FORMATS)} (default: all)")
    ex.add_argument("--samples", type=int, default=DEFAULT_SAMPLES,
                    help=f"path samples along a region task's boundary, uniform in arc length "
                         f"(default {DEFAULT_SAMPLES}; a point task uses its points)")
    ex.add_argument("--overwrite", action="store_true",
                    help="replace another run that --to holds (only the files that run wrote)")


def run(args) -> int:
    """Export, print the one-line summary."""
    from mechopt.export import export

    info = export(args.design, args.out, args.format, samples=args.samples, overwrite=args.overwrite)
    print(f"exported {info['mechanism']} (design sha256 {info['design_sha256'][:12]}...) to {args.out}: "
          f"{', '.join(info['files'])} ({info['wall_time_s']:.1f} s)")
    return 0
