"""The package's imports form layers without cycles: a module imports only from its
own layer or below (the README's architecture section draws the same layers).

Imports are read from the source (every ``import`` statement, top level or inside a
function), so a lazy import counts as a dependency too."""
import ast
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
#: installed package name -> source folder (pyproject's package-dir)
SOURCES = {"mechopt": ROOT / "mechopt", "mechopt.problems": ROOT / "problems",
           "mechopt.experiments": ROOT / "experiments"}

#: layer of each module (longest matching prefix), lowest first
LAYERS = [
    ("core", ["mechopt.validation", "mechopt.indices", "mechopt.quadrature", "mechopt.geometry",
              "mechopt.kernels", "mechopt.fast_lci", "mechopt.progress", "mechopt.conditions",
              "mechopt.io", "mechopt.published", "mechopt.data", "mechopt.numerics"]),
    ("mechanisms", ["mechopt.mechanisms", "mechopt.dynamics", "mechopt.motion"]),
    ("analysis", ["mechopt.workspace", "mechopt.performance", "mechopt.evaluate"]),
    # the runner drives any pymoo Problem; the problem base class and the weighted sum
    # of a sweep are its machinery, the paper formulations sit above it
    ("run", ["mechopt.parallel", "mechopt.atlas", "mechopt.plotting", "mechopt.runner", "mechopt.checkpoint",
             "mechopt.budget",
             "mechopt.problems.base", "mechopt.problems.weighted"]),
    ("problems", ["mechopt.problems", "mechopt.design"]),
    ("reproduction", ["mechopt.experiments", "mechopt.reproduce", "mechopt.report"]),
    ("cli", ["mechopt.cli"]),
]


def _modules():
    mods = {}
    for pkg, folder in SOURCES.items():
        for p in folder.rglob("*.py"):
            rel = p.relative_to(folder).with_suffix("").parts
            name = ".".join((pkg, *rel))
            if name.endswith(".__init__"):
                name = name[: -len(".__init__")]
            if pkg == "mechopt" and rel[0] in ("problems", "experiments"):
                continue
            mods[name] = p
    return mods


MODULES = _modules()


def _layer(name):
    best = None
    for i, (_, prefixes) in enumerate(LAYERS):
        for pre in prefixes:
            if (name == pre or name.startswith(pre + ".")) and (best is None or len(pre) > best[1]):
                best = (i, len(pre))
    return None if best is None else best[0]


def _imports(name, path):
    pkg = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
    out = set()
    for node in ast.walk(ast.parse(path.read_text())):
        targets = []
        if isinstance(node, ast.Import):
            targets = [a.name for a in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = pkg.split(".")[: len(pkg.split(".")) - node.level + 1]
                mod = ".".join(base + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            targets = [mod] + [f"{mod}.{a.name}" for a in node.names]
        for t in targets:
            if t.startswith("problems") or t.startswith("experiments"):
                t = "mechopt." + t  # the test suite's view of the installed names
            while t and t not in MODULES and "." in t:
                t = t.rsplit(".", 1)[0]
            if t in MODULES and t not in (name, "mechopt"):
                out.add(t)
    return out


GRAPH = {m: _imports(m, p) for m, p in MODULES.items()}


def test_every_module_has_a_layer():
    missing = sorted(m for m in MODULES if m != "mechopt" and _layer(m) is None)
    assert not missing, f"modules without a layer in tests/test_architecture.py: {missing}"


@pytest.mark.parametrize("module", sorted(m for m in MODULES if m != "mechopt"))
def test_no_import_from_a_higher_layer(module):
    mine = _layer(module)
    up = sorted(t for t in GRAPH[module] if _layer(t) is not None and _layer(t) > mine)
    assert not up, f"{module} ({LAYERS[mine][0]}) imports higher layers: {up}"


def test_no_import_cycle():
    index, low, stack, on, cycles = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in GRAPH[v]:
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
                cycles.append(sorted(comp))

    for v in GRAPH:
        if v not in index:
            visit(v)
    assert not cycles, f"import cycles: {cycles}"


def test_the_checker_sees_imports():
    """The graph is not empty by accident: known edges are found."""
    assert "mechopt.mechanisms.base" in GRAPH["mechopt.mechanisms.five_bar"]
    assert "mechopt.runner" in GRAPH["mechopt.cli"]
    assert "mechopt.atlas" in GRAPH["mechopt.problems.liu2006"]
