"""Published numbers of the source papers and their side-by-side comparison.

Each paper's printed values live in ``mechopt/data/<paper>.csv`` with their
source (section, table, figure or equation), unit and printed decimals; one
:class:`Record` per row (:func:`lookup`). A reproduced value *matches* when it lies
within the acceptance tolerance of its row, in the printed unit::

    tol = max(half a unit of the last printed digit,
              tol_abs,                 # an absolute accuracy in that unit
              tol_rel * |published|)   # a relative accuracy of the quantity's class

``tol_abs`` serves quantities whose error does not scale with their value (an
angle printed to 0.01 deg has the accuracy of the raster it comes from, the same
for 36 deg as for 276 deg); ``tol_rel`` the acceptance level of a quantity class
(e.g. 0.5 % for a MIC radius, 1 % for a global mean whose quadrature the paper does
not state). Both are named in every row and never tuned per row.

Every row has a ``kind`` (:data:`KINDS`), so that the counts are honest:

``computed``  a quantity the paper computed and we recompute: the only rows
              whose ``match``/``differs`` are counted as reproduction results;
``setting``   an input or algorithm setting we echo (population, generations):
              its agreement shows nothing;
``reading``   a value shown on purpose under another reading of the paper or
              another quadrature, beside the literal row;
``claim``     a checkable sentence of the paper, ``holds`` or ``fails`` with the
              computed evidence in the note.

``status`` is one of :data:`STATUSES`; ``not-reported`` when the paper prints no value.
"""
from __future__ import annotations

from dataclasses import dataclass
from importlib import resources

import numpy as np
import pandas as pd

__all__ = ["TABLE_COLUMNS", "STATUSES", "KINDS", "Record", "load", "lookup", "printed_half_unit",
           "compare", "comparison_row", "claim_row", "counts"]

TABLE_COLUMNS = ("quantity", "source", "paper", "reproduced", "unit", "rel_error", "status",
                 "kind", "note")
STATUSES = ("match", "differs", "not-reported", "holds", "fails")
KINDS = ("computed", "setting", "reading", "claim")


@dataclass(frozen=True)
class Record:
    """One printed number: ``value`` [``unit``] printed with ``digits`` decimals."""

    paper: str
    design: str
    quantity: str
    value: float
    unit: str
    digits: int
    source: str

    @property
    def citation(self) -> str:
        """``"<Paper year> <source>"``, e.g. ``"Liu 2006 sec. 3.1.1, text of Fig. 8"``."""
        name, year = self.paper[:-4], self.paper[-4:]
        return f"{name.capitalize()} {year} {self.source}"


def load(paper: str) -> pd.DataFrame:
    """The published values of ``paper`` (e.g. ``"liu2006"``) as a DataFrame."""
    name = f"{paper}.csv"
    try:
        with resources.files("mechopt.data").joinpath(name).open("r") as fh:
            return pd.read_csv(fh, comment="#", dtype={"design": str})
    except FileNotFoundError:
        raise ValueError(f"paper must name a data file of mechopt/data, got {paper!r}") from None


def lookup(paper: str, quantity: str, design: str | None = None) -> Record:
    """The :class:`Record` of ``quantity`` (of ``design``, when the paper prints it for
    several designs) in ``mechopt/data/<paper>.csv``; ValueError if absent or ambiguous."""
    df = load(paper)
    sel = df[df["quantity"] == quantity]
    if design is not None:
        sel = sel[sel["design"] == design]
    if len(sel) != 1:
        where = f" for design {design!r}" if design is not None else ""
        raise ValueError(f"{paper}: {len(sel)} rows of {quantity!r}{where} (need exactly one)")
    r = sel.iloc[0]
    return Record(paper, str(r["design"]), quantity, float(r["value"]), str(r["unit"]),
                  int(r["digits"]), str(r["source"]))


def printed_half_unit(digits: int) -> float:
    """Half a unit of the last printed decimal: 0.00005 for 4 decimals."""
    return 0.5 * 10.0 ** (-int(digits))


def _check_kind(kind):
    if kind not in KINDS:
        raise ValueError(f"kind must be one of {KINDS}, got {kind!r}")


def compare(record: Record, reproduced, *, tol_rel: float = 0.0, tol_abs: float = 0.0,
            note: str = "", kind: str = "computed", quantity: str | None = None) -> dict:
    """One table row comparing ``reproduced`` with ``record`` (see the module docstring).

    ``quantity`` renames the row (e.g. ``"workspace_area[b=62mm]"`` for a reading).
    """
    return comparison_row(quantity or record.quantity, record.citation, record.value, reproduced,
                          record.unit, record.digits, tol_rel, note, kind=kind, abs_tol=tol_abs)


def comparison_row(quantity, source, paper, reproduced, unit, digits, rel_tol, note="",
                   kind: str = "computed", abs_tol: float = 0.0):
    """One row of a reproduction table (columns :data:`TABLE_COLUMNS`).

    ``status`` is ``match`` within the tolerance of the module docstring,
    ``differs`` otherwise, ``not-reported`` when the paper prints no value.
    """
    _check_kind(kind)
    if paper is None or (isinstance(paper, float) and np.isnan(paper)):
        return dict(quantity=quantity, source=source, paper=np.nan, reproduced=reproduced,
                    unit=unit, rel_error=np.nan, status="not-reported", kind=kind, note=note)
    half = printed_half_unit(digits)
    tol = max(half, abs_tol, rel_tol * abs(paper))
    err = reproduced - paper
    rel = err / abs(paper) if paper != 0 else np.inf
    status = "match" if abs(err) <= tol else "differs"
    parts = [f"half last digit {half:.3g}"]
    if abs_tol:
        parts.append(f"{abs_tol:.3g} {unit}")
    if rel_tol:
        parts.append(f"{rel_tol:.1%}")
    tol_note = f"tol {tol:.3g} {unit} (max of {', '.join(parts)})"
    note = f"{note}; {tol_note}" if note else tol_note
    return dict(quantity=quantity, source=source, paper=float(paper), reproduced=float(reproduced),
                unit=unit, rel_error=float(rel), status=status, kind=kind, note=note)


def claim_row(quantity: str, source: str, holds: bool, evidence: str) -> dict:
    """A checked claim of the paper: status ``holds``/``fails``, the evidence in the note
    (``reproduced`` is 1.0 or 0.0 so that the column stays numeric)."""
    return dict(quantity=quantity, source=source, paper=np.nan, reproduced=float(bool(holds)),
                unit="-", rel_error=np.nan, status="holds" if holds else "fails", kind="claim",
                note=evidence)


def counts(table: pd.DataFrame) -> dict:
    """The honest counts of a table: ``match``/``differs`` over the ``computed`` rows
    only; the other kinds and ``not-reported`` rows counted on their own."""
    kind = table["kind"] if "kind" in table else pd.Series("computed", index=table.index)
    status = table["status"]
    comp = kind == "computed"
    return {
        "computed": int((comp & status.isin(["match", "differs"])).sum()),
        "match": int((comp & (status == "match")).sum()),
        "differs": int((comp & (status == "differs")).sum()),
        "readings": int((kind == "reading").sum()),
        "readings matching": int(((kind == "reading") & (status == "match")).sum()),
        "settings": int((kind == "setting").sum()),
        "not-reported": int((status == "not-reported").sum()),
        "claims hold": int((status == "holds").sum()),
        "claims fail": int((status == "fails").sum()),
    }
