"""Published numbers of the source papers and their side-by-side comparison.

Each paper's printed values live in ``mechopt/data/<paper>.csv`` with their
source (section, table, figure or equation). A reproduced value *matches* when
it lies within the acceptance tolerance of its row:

    tol = max(half a unit of the last printed digit, rel_tol * |published|)

``rel_tol`` is the acceptance level of the quantity's class (e.g. 0.5 % for a
MIC radius, 1 % for a global mean whose quadrature the paper does not state),
named in every table row; it is never tuned per row.
"""
from __future__ import annotations

from importlib import resources

import numpy as np
import pandas as pd

__all__ = ["TABLE_COLUMNS", "load", "printed_half_unit", "comparison_row"]

TABLE_COLUMNS = ("quantity", "source", "paper", "reproduced", "unit", "rel_error", "status", "note")


def load(paper: str) -> pd.DataFrame:
    """The published values of ``paper`` (e.g. ``"liu2006"``) as a DataFrame."""
    name = f"{paper}.csv"
    try:
        with resources.files("mechopt.data").joinpath(name).open("r") as fh:
            return pd.read_csv(fh, comment="#", dtype={"design": str})
    except FileNotFoundError:
        raise ValueError(f"paper must name a data file of mechopt/data, got {paper!r}") from None


def printed_half_unit(digits: int) -> float:
    """Half a unit of the last printed decimal: 0.00005 for 4 decimals."""
    return 0.5 * 10.0 ** (-int(digits))


def comparison_row(quantity, source, paper, reproduced, unit, digits, rel_tol, note=""):
    """One row of a reproduction table (columns :data:`TABLE_COLUMNS`).

    ``status`` is ``match`` within the tolerance of the module docstring,
    ``differs`` otherwise, ``not-reported`` when the paper prints no value.
    """
    if paper is None or (isinstance(paper, float) and np.isnan(paper)):
        return dict(quantity=quantity, source=source, paper=np.nan, reproduced=reproduced,
                    unit=unit, rel_error=np.nan, status="not-reported", note=note)
    tol = max(printed_half_unit(digits), rel_tol * abs(paper))
    err = reproduced - paper
    rel = err / abs(paper) if paper != 0 else np.inf
    status = "match" if abs(err) <= tol else "differs"
    tol_note = f"tol {tol:.3g} (max of half last digit, {rel_tol:.1%})"
    note = f"{note}; {tol_note}" if note else tol_note
    return dict(quantity=quantity, source=source, paper=float(paper), reproduced=float(reproduced),
                unit=unit, rel_error=float(rel), status=status, note=note)
