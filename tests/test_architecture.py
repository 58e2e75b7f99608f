"""The package's layers: no module imports a higher layer, and no import cycle.

Reads every module of ``mechopt`` (with ``mechopt.problems`` and
``mechopt.experiments``, installed from ``problems/`` and ``experiments/``) as text
(``ast``, no import is executed) and collects every import, at module level and
inside functions (a function's import is a dependency too: it runs the first time the
function does). The layers, lowest first (README, "Architecture")::

    core  <  mechanisms  <  analysis, requirements  <  run  <  problems  <  workflows, experiments  <  cli

The package root ``mechopt`` (the version and the lazily loaded public names) may be
imported from anywhere and imports nothing at module level.
"""
from __future__ import annotations

import ast
import importlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

LAYERS = {
    "mechopt.core": 0, "mechopt.data": 0,
    "mechopt.mechanisms": 1,
    "mechopt.analysis": 2, "mechopt.requirements": 2,
    "mechopt.run": 3,
    "mechopt.problems": 4,
    "mechopt.workflows": 5, "mechopt.experiments": 5, "mechopt.export": 5,
    "mechopt.cli": 6,
}
LAYER_NAMES = {0: "core", 1: "mechanisms", 2: "analysis/requirements", 3: "run", 4: "problems",
               5: "workflows/experiments", 6: "cli"}


def _module_files() -> dict:
    files = {}
    for folder, package in (("mechopt", "mechopt"), ("problems", "mechopt.problems"),
                            ("experiments", "mechopt.experiments")):
        for f in sorted((ROOT / folder).rglob("*.py")):
            parts = list(f.relative_to(ROOT / folder).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts = parts[:-1]
            files[".".join([package, *parts])] = f
    return files


FILES = _module_files()


def layer_of(module: str):
    """The layer of ``module`` (None for the package root)."""
    for prefix in sorted(LAYERS, key=len, reverse=True):
        if module == prefix or module.startswith(prefix + "."):
            return LAYERS[prefix]
    if module == "mechopt":
        return None
    raise AssertionError(f"{module} belongs to no layer: add its package to LAYERS and to the README")


def imports_of(module: str, path: Path, top_level_only: bool = False) -> set:
    """The mechopt modules ``module`` imports (a ``from P import name`` counts as
    ``P.name`` when that is a module, else as ``P``)."""
    tree = ast.parse(path.read_text(), filename=str(path))
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    nodes = tree.body if top_level_only else ast.walk(tree)
    found = set()
    for node in nodes:
        if isinstance(node, ast.Import):
            found.update(a.name for a in node.names if a.name.split(".")[0] == "mechopt")
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "mechopt":
                continue
            for a in node.names:
                sub = f"{target}.{a.name}"
                found.add(sub if sub in FILES else target)
    return found


GRAPH = {m: imports_of(m, f) - {m} for m, f in FILES.items()}


def test_every_module_belongs_to_a_layer():
    assert len(FILES) > 40
    for m in FILES:
        layer_of(m)


@pytest.mark.parametrize("module", sorted(FILES))
def test_no_import_from_a_higher_layer(module):
    mine = layer_of(module)
    if mine is None:  # the package root: lazy public names only
        assert imports_of(module, FILES[module], top_level_only=True) == set()
        return
    for dep in sorted(GRAPH[module]):
        theirs = layer_of(dep)
        assert theirs is None or theirs <= mine, (
            f"{module} ({LAYER_NAMES[mine]}) imports {dep} ({LAYER_NAMES[theirs]})")


def _cycles(graph: dict) -> list:
    """Strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in graph.get(v, ()):
            if w not in graph:
                continue
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def test_no_import_cycle():
    # a package imports its own modules in __init__ (re-exports) and its modules may
    # import the package for a shared name: those edges are not cycles of the design
    graph = {m: {d for d in deps if not (m.startswith(d + ".") or d.startswith(m + "."))}
             for m, deps in GRAPH.items()}
    assert _cycles(graph) == []


def test_the_cycle_finder_finds_cycles():
    """The check above can fail: a two- and a three-module cycle are found, a chain is not."""
    assert _cycles({"a": {"b"}, "b": {"a"}, "c": set()}) == [["a", "b"]]
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == [["a", "b", "c"]]
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": set()}) == []


def test_the_layer_check_sees_lazy_imports(tmp_path):
    """An import inside a function counts: a core module that imports the runner in a
    function is caught."""
    f = tmp_path / "x.py"
    f.write_text("def f():\n    from mechopt.run import runner\n    from ..run.io import write_csv\n")
    deps = imports_of("mechopt.core.x", f)
    assert "mechopt.run.runner" in deps and any(d.startswith("mechopt.run.io") or d == "mechopt.run.io"
                                                 for d in deps)
    assert max(layer_of(d) for d in deps) > layer_of("mechopt.core.x")


def test_the_checker_sees_imports():
    """The graph is not empty by accident: known edges are found."""
    assert "mechopt.core.protocol" in GRAPH["mechopt.mechanisms.five_bar.model"]
    assert "mechopt.run.runner" in GRAPH["mechopt.cli.optimize"]
    assert "mechopt.mechanisms.five_bar.batch" in GRAPH["mechopt.problems.liu2006"]
    assert "mechopt.run.atlas" in GRAPH["mechopt.experiments.liu2006_figures"]


@pytest.mark.parametrize("module", sorted(m for m in FILES if ".cli" not in m and not m.endswith("__main__")))
def test_all_lists_the_public_definitions(module):
    """``__all__`` is the module's public surface (the API page documents it): every
    name in it exists, and every top-level function or class without a leading
    underscore is in it (a public definition left out is either private or missing)."""
    tree = ast.parse(FILES[module].read_text())
    names = None
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "__all__" for t in node.targets):
            try:
                names = ast.literal_eval(node.value)
            except ValueError:  # built from other names (the root's lazy table)
                names = importlib.import_module(module).__all__
    if names is None:  # a package docstring only, or a package that re-exports nothing
        assert not [n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))], module
        return
    defined = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    bound = set(defined)
    for node in ast.walk(tree):
        if isinstance(node, (ast.Assign, ast.AnnAssign)):
            for t in (node.targets if isinstance(node, ast.Assign) else [node.target]):
                bound.update(x.id for x in ast.walk(t) if isinstance(x, ast.Name))
        elif isinstance(node, (ast.Import, ast.ImportFrom)):
            bound.update((a.asname or a.name).split(".")[0] for a in node.names)
    if module == "mechopt":  # the public names are loaded on first use (PEP 562)
        import mechopt

        bound |= set(mechopt._PUBLIC)
    assert sorted(set(names) - bound) == [], f"{module}: __all__ names nothing called so"
    assert sorted(n for n in defined if not n.startswith("_") and n not in names) == [], (
        f"{module}: public definitions missing from __all__")


def test_problems_and_experiments_are_imported_as_mechopt_subpackages():
    """``problems/`` and ``experiments/`` are installed as ``mechopt.problems`` and
    ``mechopt.experiments``; run from the repository, ``import problems`` also works but
    loads a second copy of every module (its own memos and classes: an object of one
    copy fails ``isinstance`` against the other)."""
    top = {"problems", "experiments"}
    bad = []
    for folder in ("mechopt", "problems", "experiments", "tests", "benchmarks", "docs"):
        for f in sorted((ROOT / folder).rglob("*.py")):
            for node in ast.walk(ast.parse(f.read_text(), filename=str(f))):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                         else [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level
                         else [])
                bad += [f"{f.relative_to(ROOT)}:{node.lineno} imports {n}" for n in names
                        if n.split(".")[0] in top]
    assert not bad, bad
