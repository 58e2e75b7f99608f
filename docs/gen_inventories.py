"""Write the small intersphinx inventories the documentation ships (``docs/_inv/*.inv``).

Sphinx's intersphinx links a name such as ``numpy.ndarray`` to another project's page
through that project's ``objects.inv``, which it normally downloads at build time. The
documentation is built offline (``make docs`` in CI, with no network), so the build
reads these inventories instead: for each project, the few names the docstrings and
pages use, each mapped to its page in that project's documentation (the URIs are the
projects' stable documentation layout; pymoo publishes no API inventory, so its names
point at its user-guide pages). ``MECHOPT_DOCS_ONLINE=1 make docs`` uses the projects'
full inventories instead (network needed).

Run ``python docs/gen_inventories.py`` after changing the table below; the inventories
are committed (tests/test_docs.py checks they are current and that each one loads).
"""
from __future__ import annotations

import zlib
from pathlib import Path

HERE = Path(__file__).resolve().parent
OUT = HERE / "_inv"

_EXC = "library/exceptions.html#"

#: project -> (base URL, version, [(name, domain:role, uri[, title]), ...]); a uri
#: ending in "$" ends in the name (the inventory's shorthand); a label has a title
#: (what a reference without its own text shows)
INVENTORIES = {
    "python": ("https://docs.python.org/3/", "3", [
        ("float", "py:class", "library/functions.html#$"),
        ("int", "py:class", "library/functions.html#$"),
        ("bool", "py:class", "library/functions.html#$"),
        ("str", "py:class", "library/stdtypes.html#$"),
        ("list", "py:class", "library/stdtypes.html#$"),
        ("tuple", "py:class", "library/stdtypes.html#$"),
        ("dict", "py:class", "library/stdtypes.html#$"),
        ("callable", "py:function", "library/functions.html#$"),
        ("None", "py:data", "library/constants.html#$"),
        ("ValueError", "py:exception", _EXC + "$"),
        ("TypeError", "py:exception", _EXC + "$"),
        ("KeyError", "py:exception", _EXC + "$"),
        ("RuntimeError", "py:exception", _EXC + "$"),
        ("OSError", "py:exception", _EXC + "$"),
        ("FileExistsError", "py:exception", _EXC + "$"),
        ("TimeoutError", "py:exception", _EXC + "$"),
        ("NotImplementedError", "py:exception", _EXC + "$"),
        ("pathlib.Path", "py:class", "library/pathlib.html#$"),
        ("logging.Logger", "py:class", "library/logging.html#$"),
        ("argparse.ArgumentParser", "py:class", "library/argparse.html#$"),
        ("argparse.Namespace", "py:class", "library/argparse.html#$"),
        ("collections.abc.Callable", "py:class", "library/collections.abc.html#$"),
        ("collections.abc.Iterable", "py:class", "library/collections.abc.html#$"),
        ("collections.abc.Sequence", "py:class", "library/collections.abc.html#$"),
        ("collections.abc.Mapping", "py:class", "library/collections.abc.html#$"),
        ("dataclasses.dataclass", "py:function", "library/dataclasses.html#$"),
        ("True", "py:data", "library/constants.html#$"),
        ("False", "py:data", "library/constants.html#$"),
        ("contextlib.contextmanager", "py:function", "library/contextlib.html#$"),
        ("collections.namedtuple", "py:function", "library/collections.html#$"),
        ("bltin-boolean-values", "std:label", "library/stdtypes.html#$", "Boolean Type - bool"),
        ("iterable", "std:term", "glossary.html#term-iterable"),
        ("sequence", "std:term", "glossary.html#term-sequence"),
        ("generator", "std:term", "glossary.html#term-generator"),
        ("mapping", "std:term", "glossary.html#term-mapping"),
    ]),
    "numpy": ("https://numpy.org/doc/stable/", "2", [
        ("numpy.ndarray", "py:class", "reference/generated/numpy.ndarray.html#$"),
        ("numpy.random.Generator", "py:class", "reference/random/generator.html#$"),
        ("numpy.random.default_rng", "py:function", "reference/random/generator.html#$"),
        ("numpy.float64", "py:attribute", "reference/arrays.scalars.html#$"),
        ("numpy.bool_", "py:attribute", "reference/arrays.scalars.html#$"),
        ("numpy.linalg.cond", "py:function", "reference/generated/numpy.linalg.cond.html#$"),
        ("array_like", "std:term", "glossary.html#term-array_like"),
        ("array-like", "std:term", "glossary.html#term-array_like"),
        ("numpy.random.RandomState", "py:class", "reference/random/legacy.html#$"),
        ("numpy.inf", "py:data", "reference/constants.html#$"),
        ("numpy.nan", "py:data", "reference/constants.html#$"),
        ("numpy", "py:module", "reference/index.html#module-$"),
        ("arrays.scalars", "std:label", "reference/arrays.scalars.html#$", "Scalars"),
    ]),
    "pandas": ("https://pandas.pydata.org/docs/", "2", [
        ("pandas.DataFrame", "py:class", "reference/api/pandas.DataFrame.html#$"),
        ("pandas.Series", "py:class", "reference/api/pandas.Series.html#$"),
        ("pandas.read_csv", "py:function", "reference/api/pandas.read_csv.html#$"),
        ("pandas.DataFrame.query", "py:method", "reference/api/pandas.DataFrame.query.html#$"),
    ]),
    "matplotlib": ("https://matplotlib.org/stable/", "3", [
        ("matplotlib.figure.Figure", "py:class", "api/_as_gen/matplotlib.figure.Figure.html#$"),
        ("matplotlib.axes.Axes", "py:class", "api/_as_gen/matplotlib.axes.Axes.html#$"),
    ]),
    "pymoo": ("https://pymoo.org/", "0.6", [
        ("pymoo.core.problem.Problem", "py:class", "problems/definition.html"),
        ("pymoo.core.result.Result", "py:class", "interface/result.html"),
        ("pymoo.core.callback.Callback", "py:class", "interface/callback.html"),
        ("pymoo.optimize.minimize", "py:function", "interface/minimize.html"),
        ("pymoo.core.algorithm.Algorithm", "py:class", "algorithms/index.html"),
        ("pymoo.core.problem.StarmapParallelization", "py:class", "problems/parallelization.html"),
    ]),
}


def render(project: str) -> bytes:
    """The bytes of ``project``'s inventory (Sphinx inventory format version 2).

    Parameters
    ----------
    project : str
        A key of :data:`INVENTORIES`.

    Returns
    -------
    bytes
        The four header lines, then the zlib-compressed entries ``name domain:role
        priority uri dispname`` (priority 1, -1 for labels; display name ``-``: the name
        itself).
    """
    _, version, entries = INVENTORIES[project]
    head = (f"# Sphinx inventory version 2\n# Project: {project}\n# Version: {version}\n"
            "# The remainder of this file is compressed using zlib.\n").encode()
    body = "".join(f"{e[0]} {e[1]} {-1 if e[1] == 'std:label' else 1} {e[2]} {e[3] if len(e) > 3 else '-'}\n"
                   for e in entries).encode()
    return head + zlib.compress(body, 9)


def main() -> None:
    """Write ``docs/_inv/<project>.inv`` for every project of :data:`INVENTORIES`."""
    OUT.mkdir(exist_ok=True)
    for project in INVENTORIES:
        (OUT / f"{project}.inv").write_bytes(render(project))


if __name__ == "__main__":
    main()
