"""Write ``docs/cli.md``: every command and option of ``mechopt``, from its parser.

    python docs/gen_cli.py            # rewrite docs/cli.md
    python docs/gen_cli.py --check    # exit status 1 if docs/cli.md is not current

The page is :func:`mechopt.cli.build_parser` walked: for ``mechopt`` and each command
(and sub-command), its usage line, description and one table row per option (its
flags, metavar, default and help text, which states the unit where a value has one).
``tests/test_docs.py`` checks that the page is current and that it lists exactly the
options ``mechopt <command> --help`` prints.
"""
from __future__ import annotations

import argparse
import sys
from pathlib import Path

PAGE = Path(__file__).resolve().parent / "cli.md"


def _commands(parser, path=("mechopt",)):
    """``(path, parser)`` of ``mechopt`` and every command below it, in help order."""
    yield path, parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, child in action.choices.items():
                yield from _commands(child, (*path, name))


def _cell(text) -> str:
    return " ".join(str(text).split()).replace("|", "\\|")


def options(parser) -> list:
    """``[(flags, metavar, default, help)]`` of the options and positionals of ``parser``."""
    rows = []
    for a in parser._actions:
        if isinstance(a, argparse._SubParsersAction):
            rows.append((", ".join(a.choices), "COMMAND", "", "the command (one section each below)"))
            continue
        if a.help == argparse.SUPPRESS:
            continue
        flags = ", ".join(a.option_strings) if a.option_strings else a.dest
        takes = a.nargs != 0 and not isinstance(a, (argparse._StoreTrueAction, argparse._HelpAction,
                                                   argparse._VersionAction))
        metavar = (a.metavar or (a.dest.upper() if a.option_strings else a.dest)) if takes else ""
        if a.choices and takes and not a.metavar:
            metavar = "{" + ",".join(map(str, a.choices)) + "}"
        default = "" if a.default in (None, False, argparse.SUPPRESS) or not takes else repr(a.default)
        rows.append((flags, metavar, default, a.help or ""))
    return rows


def render() -> str:
    from mechopt.cli import build_parser

    parser = build_parser()
    out = ["# Command-line reference", "",
           "Generated from the parser by `docs/gen_cli.py` (`tests/test_docs.py` checks it against "
           "`mechopt <command> --help`). `--quiet`, `--verbose` and `--traceback` are accepted "
           "before or after the command; the exit statuses are in the README (0 done, 1 an "
           "unexpected error, 2 bad input, 3 a runtime failure, 130/143 interrupted). The files "
           "and columns each command writes are in {doc}`outputs`.", ""]
    for path, p in _commands(parser):
        out += [f"## `{' '.join(path)}`", ""]
        if p.description:
            out += [_cell(p.description), ""]
        usage = " ".join(p.format_usage().split())
        out += ["```text", usage, "```", "", "| option | value | default | meaning |", "| --- | --- | --- | --- |"]
        for flags, metavar, default, help_ in options(p):
            out.append(f"| `{flags}` | {'`' + metavar + '`' if metavar else ''} | "
                       f"{'`' + _cell(default) + '`' if default else ''} | {_cell(help_)} |")
        out.append("")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true", help="exit status 1 if the page is not current")
    args = ap.parse_args(argv)
    text = render()
    if args.check:
        return 0 if PAGE.exists() and PAGE.read_text() == text else 1
    PAGE.write_text(text)
    print(f"wrote {PAGE.name} ({len(text.splitlines())} lines)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
