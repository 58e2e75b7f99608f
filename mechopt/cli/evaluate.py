"""``mechopt evaluate MECHANISM --OPTION VALUE ... [--json]``: evaluate one design.

One sub-command per mechanism of :func:`mechopt.mechanisms.registry`, generated from
the mechanism's declared ``parameters`` and, for a mechanism with disk indices, the
disk-mean options :data:`mechopt.analysis.evaluate.DISK_OPTIONS` (:func:`options`
lists them; the fuzz test draws its arguments from it). Prints the result of
:func:`mechopt.analysis.evaluate.evaluate`: a table (title, ``inputs``, one value a
line) or, with ``--json``, one JSON object (inputs echoed, NaN and inf as null).
Lengths [L] are in the one unit of the given lengths, areas in its square, angles in
deg, the indices dimensionless; docs/outputs.md lists every key with its unit.

With ``--error-model FILE --at X,Y [--at X,Y ...]`` (a mechanism with an error model)
it also prints the proven worst-case position error [um] at those poses
(:func:`mechopt.analysis.accuracy.errors_at`, keys
:data:`mechopt.analysis.accuracy.POSE_KEYS`; ``--unit`` the unit of the lengths).
"""
from __future__ import annotations

import json
import math

from mechopt.cli._common import Parser

NAME = "evaluate"

#: how a declared parameter kind is read from the command line (checks follow in the
#: constructors, with one-line errors)
_KIND_TYPES = {"length": float, "length0": float, "position": float, "angle_deg": float,
               "fraction": float, "choice": str}


def _disk_options(cls) -> tuple:
    if not cls.disk_indices:
        return ()
    # the analysis layer only for a mechanism that has disk means to set
    from mechopt.analysis.evaluate import DISK_OPTIONS

    return DISK_OPTIONS


def options(cls) -> tuple:
    """The :class:`~mechopt.core.protocol.Parameter` of every option of ``mechopt evaluate``
    for the mechanism class ``cls``, in the order of its ``--help``: the declared
    parameters, then the disk-mean options."""
    return cls.parameters + _disk_options(cls)


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


def add_parser(subparsers):
    """Register ``evaluate`` and one sub-command per registered mechanism."""
    from mechopt.mechanisms import registry

    ev = subparsers.add_parser(NAME, help="evaluate one design (every registered mechanism)",
                               description="Evaluate one design of a registered mechanism. Lengths [L] "
                                           "are in any one unit: the printed lengths are in that unit, "
                                           "areas in its square, angles in deg, the indices "
                                           "dimensionless (docs/outputs.md lists every key with its unit).")
    evs = ev.add_subparsers(dest="mechanism", required=True, parser_class=Parser)
    for name, cls in registry().items():
        mp = evs.add_parser(name, help=cls.cli_help,
                            description=f"{cls.cli_help}. Lengths [L] in any one unit; the output's "
                                        "lengths are in that unit, its areas in that unit squared.")
        for p in options(cls):
            _add_parameter(mp, p)
        if cls.error_spec is not None:
            mp.add_argument("--error-model", default=None, metavar="FILE|KEY=VALUE,...",
                            help="also print the proven worst-case position error [um] at the poses --at under "
                                 "these tolerances: a JSON or TOML file, or key=value pairs "
                                 "(encoder_counts=16384,clearance_um=5; keys in docs/outputs.md)")
            mp.add_argument("--at", action="append", default=None, metavar="X,Y",
                            help="a pose [L] in the mechanism's frame for --error-model (repeat it for more)")
            mp.add_argument("--unit", default="mm", choices=("mm", "cm", "m", "in"),
                            help="the unit of the lengths for --error-model's um: mm, cm, m or in (default mm)")
        mp.add_argument("--json", action="store_true",
                        help="print one JSON object (inputs echoed; NaN and inf as null; keys and "
                             "units: docs/outputs.md)")


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


def run(args) -> int:
    """Build the design from its options, evaluate it, print the result."""
    from mechopt.analysis.evaluate import evaluate
    from mechopt.mechanisms import get

    cls = get(args.mechanism)
    mech = cls.from_parameters(**{p.name: getattr(args, p.name) for p in cls.parameters})
    errors = _errors(mech, args)
    res = evaluate(mech, **{p.name: getattr(args, p.name) for p in _disk_options(cls)})
    if errors:
        res.inputs.update(errors.pop("inputs"))
    if args.json:
        print(json.dumps({k: _json_safe(v) for k, v in {**res.as_dict(), **errors}.items()}, allow_nan=False))
    else:
        _print_table({"inputs": res.inputs, **res.values, **errors}, res.mechanism)
    return 0


def _errors(mech, args) -> dict:
    """The error at the poses ``--at`` under ``--error-model``
    (:func:`mechopt.analysis.accuracy.errors_at`) and the ``inputs`` it echoes; ``{}``
    without ``--error-model``."""
    model, at = getattr(args, "error_model", None), getattr(args, "at", None)
    if model is None:
        if at:
            raise ValueError("--at gives the poses of --error-model: give --error-model too")
        return {}
    if not at:
        raise ValueError("--error-model needs the poses: give --at X,Y (repeat it for more)")
    from dataclasses import asdict

    from mechopt.analysis.accuracy import errors_at, parse_error_model

    model = parse_error_model(model)
    out = errors_at(mech, model, at, args.unit)
    return {"inputs": {"error_model": asdict(model), "unit": args.unit}, **out}
