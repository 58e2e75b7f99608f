"""The published numbers of the source papers: ``<paper>.csv``, one row per printed value.

Each file starts with ``#`` lines naming the paper (authors, title, journal or book,
DOI or ISBN) and how its rows are read, then the columns ``design, quantity, value,
unit, digits, source, accuracy``: ``source`` is where the paper prints the value
(section, table, figure or equation; the plain-text extractions have no page numbers),
``digits`` its printed decimals and ``accuracy`` the class of its tolerance
(:data:`mechopt.core.published.ACCURACY`; ``printed``: half a unit of the last digit). :mod:`mechopt.core.published` compares reproductions with
them (pandas); :func:`published_values` reads them without pandas, for the library
code that takes a paper's inputs from them (Wu 2008's Table 1 design, its Table 2
inertias, its Table 3 motion).
"""
from __future__ import annotations

import csv
from functools import lru_cache
from importlib import resources

__all__ = ["published_values"]


@lru_cache(maxsize=None)
def _rows(paper: str) -> tuple:
    name = f"{paper}.csv"
    try:
        fh = resources.files(__name__).joinpath(name).open("r")
    except FileNotFoundError:
        raise ValueError(f"paper must name a data file of mechopt/data, got {paper!r}") from None
    with fh:
        rows = (line for line in fh if not line.startswith("#"))
        return tuple(
            ((r["design"], r["quantity"]), (float(r["value"]), r["unit"], int(r["digits"]), r["source"]))
            for r in csv.DictReader(rows))


def published_values(paper: str) -> dict:
    """Rows of ``mechopt/data/<paper>.csv`` as ``{(design, quantity): (value, unit, digits,
    source)}`` (a new dict on each call; the file is read once).

    Parameters
    ----------
    paper : str
        The paper's key (``"liu2006"``).

    Returns
    -------
    dict
        ``{(design, quantity): (value, unit, digits, source)}``.
    """
    return dict(_rows(paper))
