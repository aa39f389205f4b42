"""Write a :class:`~femcheck.export.model.Deck` as an Abaqus or CalculiX keyword deck (``.inp``).

Both codes read the same keyword language; the two spellings differ where the codes differ:
- rigid body: CalculiX ``*RIGID BODY, NSET=, REF NODE=, ROT NODE=`` (rotations on a second node), Abaqus
  ``*RIGID BODY, ELSET=, REF NODE=`` (rotations are dofs 4-6, or 6 in 2D, of the reference node);
- the linear pressure-overclosure law: CalculiX ``K, sigma_inf`` (a small positive tension at large clearance:
  zero is replaced by 1.5 MPa), Abaqus ``K`` alone;
- output: CalculiX ``*NODE FILE`` / ``*EL FILE`` / ``*CONTACT FILE`` (``.frd``) and ``*NODE PRINT`` (``.dat``);
  Abaqus ``*OUTPUT, FIELD`` with ``*NODE OUTPUT``, ``*ELEMENT OUTPUT``, ``*CONTACT OUTPUT`` (``.odb``).

Contact pressure to read: on linear faces (C3D4, CPE3) the contact stress CPRESS (CalculiX CSTR block,
Abaqus CSTRESS); on quadratic faces (C3D10, CPE6) the nodal stress -S33 (3D) / -S22 (2D) at the contact-face
nodes, because the contact stress of quadratic faces splits unevenly between corner and mid-side nodes
(CalculiX's CPRESS nodal peak is off by +256-268 % on C3D10). Numbers are written with at most 12 significant
digits (CalculiX rejects wider node fields); at most 16 entries per data line (the Abaqus limit).
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from .model import Deck

PER_LINE = 16


def _num(v: float) -> str:
    return f"{v:.12g}"


def _ids(values, per_line: int = PER_LINE) -> list[str]:
    v = [str(int(x)) for x in values]
    return [", ".join(v[i:i + per_line]) for i in range(0, len(v), per_line)]


def _heading(d: Deck, fmt: str) -> list[str]:
    lines = ["*HEADING", d.title]
    info = d.info
    lines += [f"** written by femcheck export --format {fmt}; units SI (m, N, Pa)",
              f"** element {info['element']}, level {info['level']}, contact element size "
              f"{info['h_contact']:.6g} m ({info['h_over_a']:.4g} of the contact's semi-axis or half-width), "
              f"{info['block_nodes']} deformable nodes, {info['block_dofs']} DOFs"]
    if "equivalent_block" in info:
        lines.append(f"** equivalent block: E = {_num(info['equivalent_block']['E'])} Pa, nu = "
                     f"{_num(info['equivalent_block']['nu'])} (contact modulus of the scene's pair on a rigid "
                     "indenter)")
    lines.append(f"** symmetry: {info['symmetry']}; load on the modelled part {_num(d.force)} N"
                 + (" (per unit thickness 1 m)" if d.dim == 2 else ""))
    lines += [f"** contact: {c.formulation}; K = {_num(c.stiffness)} Pa/m" for c in d.all_contacts]
    lines += [f"** {n}" for n in d.notes]
    lines.append("** contact pressure: " + ("CPRESS (linear faces)" if info["order"] == 1 else
                                            f"-S{d.dim}{d.dim} at the contact-face nodes (quadratic faces: CPRESS "
                                            "is split unevenly between corner and mid-side nodes)"))
    return lines


def _bcs(d: Deck, fmt: str) -> list[str]:
    out = []
    rot_sets = {r.rot_set for r in d.all_rigid}
    for f in d.fixed:
        if fmt == "abaqus" and f.nset in rot_sets:
            continue
        for dof in f.dofs:
            out.append(f"{f.nset}, {dof}, {dof}")
    if fmt == "abaqus":              # rotations live on the reference node
        rot = (6,) if d.dim == 2 else (4, 5, 6)
        out += [f"{r.ref_set}, {k}, {k}" for r in d.all_rigid for k in rot]
    return out


def _outputs(d: Deck, fmt: str) -> list[str]:
    if fmt == "calculix":
        out = ["*NODE FILE", "U", "*EL FILE", "S", "*CONTACT FILE", "CSTR"]
        for nset, var, totals in d.dat_prints():
            out += [f"*NODE PRINT, NSET={nset}" + (", TOTALS=ONLY" if totals else ""), var]
        return out
    out = ["*OUTPUT, FIELD", "*NODE OUTPUT", "U, RF", "*ELEMENT OUTPUT, DIRECTIONS=YES", "S",
           "*CONTACT OUTPUT", "CSTRESS"]
    for nset, var, totals in d.dat_prints():
        out += [f"*NODE PRINT, NSET={nset}" + (", TOTALS=YES" if totals else ""), var]
    return out


def _interactions(d: Deck, fmt: str) -> list[str]:
    L: list[str] = []
    done: set[str] = set()
    for c in d.all_contacts:
        if c.name in done:
            continue
        done.add(c.name)
        L += [f"*SURFACE INTERACTION, NAME={c.name}", "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR",
              f"{_num(c.stiffness)}, {_num(c.tension)}" if fmt == "calculix" else _num(c.stiffness)]
        if c.friction > 0.0:
            # CalculiX: mu and the stick slope lambda; Abaqus: mu alone (its second field is a slip rate)
            L += ["*FRICTION", f"{_num(c.friction)}, {_num(c.stick_slope)}" if fmt == "calculix"
                  else _num(c.friction)]
    for c in d.all_contacts:
        L += [f"*CONTACT PAIR, INTERACTION={c.name}, TYPE=NODE TO SURFACE", f"{c.slave}, {c.master}"]
    return L


def _rigid(d: Deck, fmt: str) -> list[str]:
    L = []
    for ri in d.all_rigid:
        if fmt == "calculix":
            L.append(f"*RIGID BODY, NSET={ri.nset}, REF NODE={ri.ref + 1}, ROT NODE={ri.rot + 1}")
        elif ri.elset is not None:
            L.append(f"*RIGID BODY, ELSET={ri.elset}, REF NODE={ri.ref + 1}")
        else:
            L.append(f"*RIGID BODY, REF NODE={ri.ref + 1}, TIE NSET={ri.nset}")
    return L


def deck_lines(d: Deck, fmt: str) -> list[str]:
    """The deck's lines (no trailing newlines)."""
    if fmt not in ("calculix", "abaqus"):
        raise ValueError(f"format {fmt!r}")
    L = _heading(d, fmt)
    L.append("*NODE, NSET=NALL")
    coords = d.points[: d.dim]
    L += [", ".join([str(i + 1)] + [_num(c) for c in coords[:, i]]) for i in range(d.n_nodes)]
    for b in d.blocks:
        L.append(f"*ELEMENT, TYPE={b.type}, ELSET={b.elset}")
        cells = b.cells + 1
        L += [", ".join(map(str, [eid, *cells[:, j]])) for j, eid in enumerate(b.ids)]
    for name, nodes in d.nsets.items():
        L.append(f"*NSET, NSET={name}")
        L += _ids(np.asarray(nodes) + 1)
    for s in d.surfaces:
        L.append(f"*SURFACE, NAME={s.name}, TYPE=ELEMENT")
        L += [f"{e}, S{f}" for e, f in zip(s.elements, s.faces)]
    for name, (E, nu) in d.materials.items():
        L += [f"*MATERIAL, NAME={name}", "*ELASTIC", f"{_num(E)}, {_num(nu)}"]
    for b in d.blocks:
        L.append(f"*SOLID SECTION, ELSET={b.elset}, MATERIAL={b.material}")
        if d.dim == 2:
            L.append("1.")                    # plane-strain thickness (m)
    L += _rigid(d, fmt)
    for k, sp in enumerate(d.springs):
        eid = d.last_element_id + k + 1
        L += [f"*ELEMENT, TYPE=SPRING2, ELSET={sp.elset}", f"{eid}, {sp.a + 1}, {sp.b + 1}",
              f"*SPRING, ELSET={sp.elset}", f"{sp.dof}, {sp.dof}", _num(sp.stiffness)]
    for eq in d.equations:
        L += ["*EQUATION", str(len(eq)), ", ".join(f"{n + 1}, {dof}, {_num(c)}" for n, dof, c in eq)]
    L += ["*AMPLITUDE, NAME=FULL", "0., 1., 1., 1."]
    L += _interactions(d, fmt)
    steps = d.load_steps()
    for k, st in enumerate(steps):
        L += [f"** {st.comment}", f"*STEP, INC={st.max_increments}", "*STATIC", f"{_num(st.increment)}, 1."]
        if st.remove:
            L += ["*MODEL CHANGE, TYPE=ELEMENT, REMOVE", ", ".join(st.remove)]
        if st.grow_below is not None:      # I_0, I_R, I_P, I_C, I_L at their defaults, I_G set
            L += ["*CONTROLS, PARAMETERS=TIME INCREMENTATION", f"4, 8, 9, 16, 10, {st.grow_below}"]
        if k == 0 or st.new or st.displacements:
            L += ["*BOUNDARY" + (", OP=NEW" if k > 0 and st.new else ""), *_bcs(d, fmt)]
            L += [f"{n + 1}, {dof}, {dof}, {_num(v)}" for n, dof, v in st.displacements]
        if st.loads:
            L.append("*CLOAD, AMPLITUDE=FULL" if st.full else "*CLOAD")
            L += [f"{n + 1}, {dof}, {_num(v)}" for n, dof, v in st.loads]
        if k == len(steps) - 1:
            L += _outputs(d, fmt)
        L.append("*END STEP")
    return L


def write_deck(d: Deck, fmt: str, path: Path) -> Path:
    """Write the deck atomically (temp file, then rename) and return its path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text("\n".join(deck_lines(d, fmt)) + "\n")
    tmp.replace(path)
    return path
