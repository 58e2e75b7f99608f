"""What the command modules share: the parser class, the run options of ``optimize``
and ``sweep`` and the Dask client of a run.

Imports only the standard library at module level: every command, ``mechopt
evaluate`` among them, loads this module while the parser is built.
"""
from __future__ import annotations

import argparse
import contextlib
import re


class UsageError(Exception):
    """A bad command line; :func:`mechopt.cli.main` prints it as one line, exit status 2."""


#: an option's value that argparse would take for an option: a working mode made of
#: signs (``-+``, ``--``) or a negative number or list (``-60,240``)
_DASHED_VALUE = re.compile(r"[+-]{1,3}|-\.?\d[\d.,;eE+-]*")


class Parser(argparse.ArgumentParser):
    """argparse with one-line errors (no usage block) and exit status 2, and option values
    that start with a dash given as the next word (``--mode -+``, ``--joint-limits
    -60,240``), which argparse alone refuses as "expected one argument"."""

    def error(self, message):
        raise UsageError(message)

    def parse_known_args(self, args=None, namespace=None):
        if args is not None:
            args = self._join_dashed_values(list(args))
        return super().parse_known_args(args, namespace)

    def _get_values(self, action, arg_strings):
        # argparse drops a value "--" (its end-of-options marker) even given as
        # "--mode=--": the five-bar's working mode "--" is a value here
        if action.nargs is None and action.option_strings and arg_strings == ["--"]:
            value = self._get_value(action, "--")
            self._check_value(action, value)
            return value
        return super()._get_values(action, arg_strings)

    def _join_dashed_values(self, args):
        """``[opt, value]`` -> ``["opt=value"]`` where ``opt`` takes one value and ``value``
        starts with a dash but is no option of this parser."""
        takes_value = {s for a in self._actions if a.nargs is None and a.option_strings
                       and not isinstance(a, (argparse._StoreConstAction, argparse._HelpAction,
                                              argparse._VersionAction, argparse._CountAction))
                       for s in a.option_strings}
        known = {s for a in self._actions for s in a.option_strings}
        out, i = [], 0
        while i < len(args):
            a = args[i]
            if (a in takes_value and i + 1 < len(args) and args[i + 1] not in known
                    and _DASHED_VALUE.fullmatch(args[i + 1])):
                out.append(f"{a}={args[i + 1]}")
                i += 2
            else:
                out.append(a)
                i += 1
        return out


def add_run_options(p, resumable=False):
    """The positional problem and the options of a seeded run (``optimize``, ``sweep``).

    ``resumable``: the problem and ``--out`` may be left out (``optimize --resume DIR``).
    """
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
    add_dask_options(p)
    p.add_argument("--out", required=not resumable, default=None, help="output folder")
    p.add_argument("--quadrature", default=None, choices=None,
                   help="rule of the disk means of the Liu 2006 problems: polar (default, the "
                        "paper's) or area; recorded in run.json")
    p.add_argument("--overwrite", action="store_true",
                   help="replace another run that --out holds (only the files that run wrote)")


def add_dask_options(p, group=None, help="evaluate on a Dask cluster instead of joblib"):
    """``--dask`` (in ``group``, a mutually exclusive group, where given) and
    ``--dask-timeout``, which :func:`dask_client` reads."""
    (group or p).add_argument("--dask", metavar="SCHEDULER_ADDRESS", default=None, help=help)
    p.add_argument("--dask-timeout", type=float, default=10.0, metavar="SECONDS",
                   help="time to wait for the Dask scheduler and its first worker [s] (default 10)")


def problem_options(args) -> dict:
    """Problem constructor options given on the command line (only those set)."""
    return {k: v for k, v in (("quadrature", args.quadrature),) if v is not None}


def seed(args) -> int:
    """``--seed``, 1 when not given."""
    return 1 if args.seed is None else args.seed


def run_settings(args) -> dict:
    """The termination and operator options of a run (optimize, sweep)."""
    return {"tol": args.tol, "crossover_prob": args.crossover_prob, "mutation_prob": args.mutation_prob,
            "crossover_eta": args.crossover_eta, "mutation_eta": args.mutation_eta}


@contextlib.contextmanager
def dask_client(args):
    """The client of ``--dask`` (None without it: joblib), closed when the run ends,
    however it ends."""
    if not args.dask:
        yield None
        return
    # here, not at the top: evaluate loads this module and must start without the run layer
    from mechopt.run.parallel import close_client, connect

    client = connect(args.dask, timeout=args.dask_timeout)
    try:
        yield client
    finally:
        close_client(client)
