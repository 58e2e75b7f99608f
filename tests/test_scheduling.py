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


#: the session fixture each TOGETHER group shares
SHARED = {"le2013_default_runs": "default_run", "numpy_atlas": "numpy_atlas_reference"}


def _fixtures_using(path: Path, fixture: str) -> set:
    """Names of the fixtures of a module that take ``fixture`` as an argument."""
    tree = ast.parse(path.read_text(), filename=str(path))
    return {n.name for n in tree.body if isinstance(n, ast.FunctionDef) and "fixture" in ast.unparse(n)
            and any("fixture" in ast.unparse(d) for d in n.decorator_list) and fixture in [a.arg for a in n.args.args]}


def test_together_names_existing_tests_that_use_the_shared_fixture():
    assert set(SHARED) == set(conftest.TOGETHER)
    for group, ids in conftest.TOGETHER.items():
        shared = SHARED[group]
        for nodeid in ids:
            path, name = nodeid.split("::")
            args = _test_functions(ROOT / path).get(name)
            assert args is not None, f"{nodeid} (group {group}) is not a test function"
            # directly, or through a fixture of its module that uses it
            users = {shared} | _fixtures_using(ROOT / path, shared)
            assert users & set(args), f"{nodeid} does not use {shared}"
            assert conftest.scope_of(nodeid, {}) == group
            assert conftest.scope_of(nodeid + "[x]", {}) == group


def test_split_and_spread_name_existing_modules():
    for module in (*conftest.SPLIT, *conftest.SPREAD):
        assert (ROOT / "tests" / f"{module}.py").is_file(), module


def test_each_split_group_holds_every_test_of_its_fixture():
    """A SPLIT word names tests of its module, and every test of the module that uses
    the module fixture of a group's tests carries the group's word (else it would build
    that fixture once more, wherever it runs alone)."""
    import re

    for module, words in conftest.SPLIT.items():
        path = ROOT / "tests" / f"{module}.py"
        tests = _test_functions(path)
        fixtures = set(re.findall(r"@pytest\.fixture\(scope=\"module\"\)\ndef (\w+)", path.read_text()))
        for word in words:
            members = {n: args for n, args in tests.items() if word in n}
            assert members, (module, word)
            used = fixtures & {a for args in members.values() for a in args}
            assert used, (module, word)
            for name, args in tests.items():
                assert not (used & set(args)) or word in name, (module, name, used)
