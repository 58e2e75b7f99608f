"""The xdist grouping of tests/conftest.py names tests that exist: a renamed test would
silently leave its group (and compute the shared fixture once more)."""
import ast
from pathlib import Path

import conftest

ROOT = Path(__file__).resolve().parents[1]


def _test_functions(path: Path) -> dict:
    """``{name: argument names}`` of the test functions of a module."""
    tree = ast.parse(path.read_text(), filename=str(path))
    return {n.name: [a.arg for a in n.args.args] for n in tree.body
            if isinstance(n, ast.FunctionDef) and n.name.startswith("test_")}


def test_together_names_existing_tests_that_use_the_shared_fixture():
    for group, ids in conftest.TOGETHER.items():
        for nodeid in ids:
            path, name = nodeid.split("::")
            args = _test_functions(ROOT / path).get(name)
            assert args is not None, f"{nodeid} (group {group}) is not a test function"
            assert "default_run" in args, f"{nodeid} does not use default_run"
            assert conftest.scope_of(nodeid, {}) == group
            assert conftest.scope_of(nodeid + "[x]", {}) == group


def test_split_and_spread_name_existing_modules():
    for module in (*conftest.SPLIT, *conftest.SPREAD):
        assert (ROOT / "tests" / f"{module}.py").is_file(), module
