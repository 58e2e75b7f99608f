"""docs/cli.md, the command-line reference: current (docs/gen_cli.py), and for every
command it lists exactly the options that ``mechopt <command> --help`` prints."""
import contextlib
import importlib.util
import io
import re
from pathlib import Path

import pytest

from mechopt.cli import main

DOCS = Path(__file__).resolve().parents[1] / "docs"


def _gen():
    spec = importlib.util.spec_from_file_location("gen_cli", DOCS / "gen_cli.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _sections() -> dict:
    """``{"mechopt optimize": {"--pop", ...}}`` from the page: the flags of each table."""
    out, current = {}, None
    for line in (DOCS / "cli.md").read_text().splitlines():
        m = re.match(r"## `(mechopt[^`]*)`", line)
        if m:
            current = out.setdefault(m.group(1), set())
        elif current is not None and line.startswith("| `"):
            first = line.split("|")[1]
            current.update(re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", first))
    return out


def _help_flags(path) -> set:
    """The option flags ``mechopt <path> --help`` prints: each option line's first column."""
    with contextlib.redirect_stdout(io.StringIO()) as buf:
        assert main([*path, "--help"]) == 0
    body = buf.getvalue().split("\n\n", 1)[1]  # after the usage block: the option list
    flags = set()
    for line in body.splitlines():
        if re.match(r"^\s{2,}-", line):
            flags.update(re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", re.split(r"\s{2,}", line.strip())[0]))
    return flags


def test_page_is_current():
    assert _gen().render() == (DOCS / "cli.md").read_text(), \
        "docs/cli.md is not current: run .venv/bin/python docs/gen_cli.py"


SECTIONS = _sections()


def test_every_command_has_a_section():
    from mechopt.cli import COMMANDS

    assert {f"mechopt {c.NAME}" for c in COMMANDS} <= set(SECTIONS)
    assert {"mechopt atlas five-bar", "mechopt evaluate gantry"} <= set(SECTIONS)


@pytest.mark.parametrize("section", sorted(SECTIONS))
def test_section_lists_what_help_prints(section):
    path = section.split()[1:]
    printed = _help_flags(path)
    assert printed, section
    assert SECTIONS[section] == printed, (SECTIONS[section] ^ printed)
