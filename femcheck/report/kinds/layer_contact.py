"""Report section of the layer_contact kind: the layered BEM's two estimates of the contact size (the power-law edge
fitted to the pressure, and the contact cells' own count or area) side by side, with a note where they disagree
by more than a cell plus the fit's bias bound (stats ``edge_estimates``,
:func:`femcheck.problems.layer_contact.edge_estimates`)."""
from __future__ import annotations

from pathlib import Path

from ...result import RunResult
from . import KindSection, Table


def _rows(stats: dict, label: str) -> tuple[list, str]:
    e = stats.get("edge_estimates")
    if not e:
        return [], ""
    row = [label, 1e6 * e["fitted"], 1e6 * e["counted"], f"{100.0 * e['difference']:+.2f} %",
           f"{100.0 * e['allowed']:.2f} %", e["fit_exponent"], e["fit_band"], "disagree" if e["disagree"] else ""]
    return row, e.get("note", "")


def section(run: RunResult, outdir: Path, prefix: str) -> KindSection:
    m = run.models.get("bem")
    if m is None or m.status != "ok":
        return KindSection()
    rows, notes = [], []
    parts = [(k, v) for k, v in m.stats.items() if isinstance(v, dict) and "edge_estimates" in v]
    for label, stats in (parts or [("", m.stats)]):
        row, note = _rows(stats, label or "contact")
        if row:
            rows.append(row)
        if note:
            notes.append(f"{label + ': ' if label else ''}{note}")
    if not rows:
        return KindSection()
    text = ("size: half-width (line) or radius (point, sqrt of the semi-axes' product) in um. fitted: the "
            "power-law edge with its exponent fitted, the band narrowed while the exponent drifts across it "
            "(a thin layer's edge boundary layer); counted: half the contact strips times their width, or the "
            "radius of the contact cells' area, within a cell. allowed: a cell + the fit's bias bound "
            "+ 2 standard errors, relative.")
    if notes:
        text += " " + " ".join(notes)
    return KindSection(tables=[Table("Layered BEM: contact size, fitted edge and contact cells",
                                     ["contact", "fitted (um)", "counted (um)", "difference", "allowed",
                                      "exponent", "band"] + ["verdict"], rows, text)])
