"""The ``mechopt`` command: evaluate, reproduce, report, problems, optimize, sweep, design, check, motion, export,
accuracy, atlas, explore.

Each command is one module of this package with the same interface: ``NAME`` (the
command), ``add_parser(subparsers)`` (registers it and its options) and ``run(args) ->
int`` (does it, returns the exit status). :func:`build_parser` registers
:data:`COMMANDS` in order; :func:`main` parses, runs the command holding its output
folder's lock and turns every way a run can end into one line and an exit status:

* every bad input ends with one line ``mechopt: error: <message>`` on stderr and exit
  status 2, never a traceback (a failed run removes the output folders it created if
  they are empty, never anything else: :func:`mechopt.run.io.remove_created`);
* a final line that cannot reach standard output (a closed pipe, a full device) is
  one line on stderr and exit status 2; the run's files stay;
* a run that fails for a reason outside its input (the Dask cluster stalls or is lost,
  the disk is full: :class:`mechopt.run.parallel.RunFailure`, OSError) ends with one
  line and exit status 3; an unexpected error (a bug) with one line and exit status 1;
  ``MECHOPT_DEBUG=1`` or ``--traceback`` prints the traceback of either (and of a
  ValueError) first;
* ``--quiet`` shows errors only (no progress, no diagnostics), ``--verbose`` adds
  debugging diagnostics (Python's :mod:`logging`, logger ``"mechopt"``, on stderr);
* SIGINT/SIGTERM end a run with one line (and how to resume, where a run can) and exit
  status 130/143; signals that follow (a second Ctrl-C) are ignored while the run
  stops its workers and, from the command (:func:`console`), while the interpreter
  exits;
* an empty result (no feasible design, an empty GCW) is a result, exit status 0.
"""
from __future__ import annotations

import argparse
import os
import sys

from mechopt import __version__
from mechopt.cli import (accuracy, atlas, check, design, evaluate, explore, export, motion, optimize, problems,
                         report, reproduce, sweep)
from mechopt.cli._common import Parser, UsageError

#: the command modules, in the order of ``mechopt --help``
COMMANDS = (evaluate, reproduce, report, problems, optimize, sweep, design, check, motion, export, accuracy, atlas,
            explore)

EXIT_USAGE = 2
#: a runtime failure (the Dask cluster, the disk) and an unexpected error (a bug)
EXIT_RUNTIME, EXIT_INTERNAL = 3, 1
#: the environment variable that shows tracebacks (any value but "" and "0")
DEBUG_ENV = "MECHOPT_DEBUG"
#: exit statuses of a run stopped by SIGINT and SIGTERM (128 + signal number)
EXIT_SIGINT, EXIT_SIGTERM = 130, 143
#: what ``mechopt --help`` says above the commands
DESCRIPTION = ("Dimensional synthesis of 2-DOF planar parallel manipulators: evaluate a "
               "design, optimize a published formulation, size a mechanism for a task, "
               "draw atlases, reproduce the papers.")


def build_parser() -> argparse.ArgumentParser:
    """The parser of every command of :data:`COMMANDS`."""
    p = Parser(prog="mechopt", description=DESCRIPTION)
    p.add_argument("--version", action="version", version=f"mechopt {__version__}")
    _add_output_options(p, None)
    sub = p.add_subparsers(dest="command", required=True, parser_class=Parser)
    for command in COMMANDS:
        command.add_parser(sub)
    for parser in _subparsers(p):
        _add_output_options(parser, argparse.SUPPRESS)
    return p


class _StdoutLost(Exception):
    """The final line could not be written to standard output (a closed pipe, a full
    device): the run's files are in place and stay."""


def _subparsers(parser):
    """Every parser below ``parser`` (commands and their sub-commands)."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for child in action.choices.values():
                yield child
                yield from _subparsers(child)


def _add_output_options(p, default):
    """``--quiet``, ``--verbose`` and ``--traceback``, on ``mechopt`` itself and on every
    command (``default=SUPPRESS`` there, so that a command does not reset them)."""
    kw = {} if default is None else {"default": default}
    g = p.add_mutually_exclusive_group()
    g.add_argument("-q", "--quiet", action="store_true", help="errors only: no progress, no diagnostics", **kw)
    g.add_argument("-v", "--verbose", action="store_true", help="debugging diagnostics too (logging level DEBUG)",
                   **kw)
    p.add_argument("--traceback", action="store_true",
                   help=f"print the traceback of an error before its one line (or set {DEBUG_ENV}=1)", **kw)


def _debug(args) -> bool:
    return bool(getattr(args, "traceback", False)) or os.environ.get(DEBUG_ENV, "") not in ("", "0")


def configure_logging(quiet: bool = False, verbose: bool = False):
    """The ``"mechopt"`` logger of a command: WARNING with ``quiet``, DEBUG with
    ``verbose``, else INFO (progress and diagnostics), to stderr as ``mechopt: ...``
    (one handler, replaced on each call)."""
    import logging

    log = logging.getLogger("mechopt")
    log.setLevel(logging.WARNING if quiet else logging.DEBUG if verbose else logging.INFO)
    for h in [h for h in log.handlers if getattr(h, "_mechopt", False)]:
        log.removeHandler(h)
    handler = logging.StreamHandler(sys.stderr)
    handler.setFormatter(logging.Formatter("mechopt: %(message)s"))
    handler._mechopt = True
    log.addHandler(handler)
    log.propagate = False
    return log


class _Stdout:
    """Standard output for a command's final lines: a character the stream's encoding
    cannot show is escaped (``\\xe9``) rather than failing, and an error of the stream
    itself is :class:`_StdoutLost` (never taken for an error of the output folder)."""

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        try:
            try:
                n = self._stream.write(text)
            except UnicodeEncodeError:
                enc = getattr(self._stream, "encoding", None) or "ascii"
                n = self._stream.write(text.encode(enc, "backslashreplace").decode(enc, "replace"))
            self._stream.flush()
            return n
        except OSError as exc:
            raise _StdoutLost(exc.strerror or type(exc).__name__) from None

    def flush(self):
        try:
            self._stream.flush()
        except OSError as exc:
            raise _StdoutLost(exc.strerror or type(exc).__name__) from None

    def __getattr__(self, name):
        return getattr(self._stream, name)


class _Terminated(BaseException):
    """SIGTERM, raised in the main thread like KeyboardInterrupt for SIGINT."""


def _on_sigterm(signum, frame):
    raise _Terminated()


def _resume_hint(out) -> str:
    if out is None:
        return ""
    from pathlib import Path

    out = Path(out)
    try:
        if (out / "checkpoint.pkl").exists():
            return f"; resume with `mechopt optimize --resume {out}`"
        if (out / ".atlas_chunks").is_dir():
            return "; run the same command again to resume (finished chunks are kept)"
        if any(out.glob("*/table.csv")):
            return "; run the same command again to go on (finished papers are kept)"
    except (OSError, ValueError):
        pass
    return ""


def _run_locked(args, out):
    """Run the command holding its output folder's lock (mechopt.run.io.out_lock)."""
    command = next(c for c in COMMANDS if c.NAME == args.command)
    if out is None:
        return command.run(args)
    from mechopt.run.io import out_lock

    with out_lock(out):
        return command.run(args)


#: a warnings filter for loky's resource tracker, a helper process that outlives the
#: workers: when an interrupted run kills its workers (SIGKILL, at once), the tracker
#: may find one of their semaphores already gone at its own exit and print a
#: UserWarning and its source line after the run's one-line message
_TRACKER_WARNINGS = "ignore:resource_tracker:UserWarning"


def _quiet_resource_tracker():
    """Pass :data:`_TRACKER_WARNINGS` to the processes this run starts (the tracker
    starts with the first worker pool and reads ``PYTHONWARNINGS`` then)."""
    current = os.environ.get("PYTHONWARNINGS", "")
    if _TRACKER_WARNINGS not in current.split(","):
        os.environ["PYTHONWARNINGS"] = ",".join(filter(None, (current, _TRACKER_WARNINGS)))


def _ignore_interrupts():
    """SIGINT and SIGTERM ignored from now on (in the main thread; elsewhere nothing)."""
    import signal
    import threading

    if threading.current_thread() is threading.main_thread():
        for sig in (signal.SIGINT, signal.SIGTERM):
            signal.signal(sig, signal.SIG_IGN)


def console():
    """The ``mechopt`` command: :func:`main` on ``sys.argv``, then exit with its status.
    After an interrupt, further SIGINT/SIGTERM are ignored until the process ends: the
    worker pools' exit handlers join their threads then, and a second Ctrl-C there
    printed a traceback (or ended the process by SIGINT) after the one-line message."""
    status = main()
    if status in (EXIT_SIGINT, EXIT_SIGTERM):
        _ignore_interrupts()
    try:
        sys.stdout.flush()
    except (OSError, ValueError):  # a closed pipe: nothing more can reach it
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, sys.stdout.fileno())
        except (OSError, ValueError, AttributeError):
            pass
    sys.exit(status)


def main(argv=None) -> int:
    """Run ``mechopt`` with ``argv`` (default ``sys.argv[1:]``); returns the exit status."""
    import signal
    import threading

    from mechopt.run import io as _io

    _quiet_resource_tracker()
    parser = build_parser()
    out = None
    created = len(_io.created_folders())  # the folders made before this command are not its own
    previous = None
    if threading.current_thread() is threading.main_thread():
        previous = (signal.getsignal(signal.SIGINT), signal.signal(signal.SIGTERM, _on_sigterm))
    stdout = sys.stdout
    sys.stdout = _Stdout(stdout)
    args = None
    import logging

    log = logging.getLogger("mechopt")
    saved = (log.level, list(log.handlers), log.propagate)  # put back when the command ends
    try:
        try:
            args = parser.parse_args(argv)
        except SystemExit as exc:  # --help and --version have printed; no exception escapes
            return exc.code if isinstance(exc.code, int) else 0
        configure_logging(args.quiet, args.verbose)
        out = getattr(args, "out", None) or getattr(args, "resume", None)
        return _run_locked(args, out)
    except _StdoutLost as exc:  # the results are written; only the last line was lost
        print(f"mechopt: error: cannot write to standard output ({exc}); the run's files are in place",
              file=sys.stderr)
        return EXIT_USAGE
    except (UsageError, ValueError) as exc:
        _io.remove_created(created)
        from mechopt.run.parallel import RunFailure

        _show_traceback(args)
        msg = " ".join(str(exc).split())
        print(f"mechopt: error: {msg}", file=sys.stderr)
        return EXIT_RUNTIME if isinstance(exc, RunFailure) else EXIT_USAGE
    except (KeyboardInterrupt, _Terminated) as exc:
        _ignore_interrupts()  # a second signal must not interrupt the clean-up
        from mechopt.run.parallel import stop_workers

        stop_workers()
        _io.remove_created(created)
        print(f"mechopt: interrupted{_resume_hint(out)}", file=sys.stderr)
        return EXIT_SIGINT if isinstance(exc, KeyboardInterrupt) else EXIT_SIGTERM
    except OSError as exc:  # the disk, not the input: no space, quota, permission, name too long
        from mechopt.run.parallel import stop_workers

        _show_traceback(args)
        stop_workers()
        _io.remove_created(created)
        where = f" {exc.filename}" if exc.filename else (f" in {out}" if out else "")
        print(f"mechopt: error: cannot write{where}: {exc.strerror or exc}", file=sys.stderr)
        return EXIT_RUNTIME
    except RecursionError:  # input nested too deep for a parser (JSON, a condition)
        _io.remove_created(created)
        print("mechopt: error: an input is nested too deeply to be read", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - a bug: one line, the traceback on request
        from mechopt.run.parallel import stop_workers

        _show_traceback(args)
        stop_workers()
        _io.remove_created(created)
        first = (str(exc).splitlines() or [""])[0]
        hint = "" if _debug(args) else f" ({DEBUG_ENV}=1 or --traceback shows the traceback)"
        print(f"mechopt: internal error: {type(exc).__name__}: {first}{hint}", file=sys.stderr)
        return EXIT_INTERNAL
    finally:
        if isinstance(sys.stdout, _Stdout):
            sys.stdout = stdout
        log.setLevel(saved[0])
        log.handlers[:] = saved[1]
        log.propagate = saved[2]
        if previous is not None:
            signal.signal(signal.SIGINT, previous[0])
            signal.signal(signal.SIGTERM, previous[1])


def _show_traceback(args):
    """The traceback of the error being handled, on stderr, when asked for."""
    if _debug(args):
        import traceback

        traceback.print_exc()


if __name__ == "__main__":  # pragma: no cover
    console()
