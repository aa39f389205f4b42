"""Contact quantities from a solved deck: the contact pressure on the block's contact face and femcheck's own
estimators on it (:mod:`femcheck.qoi`), SI units.

Pressure: on linear 3D faces (C3D4) CalculiX's contact stress CPRESS at the slave nodes (0 where a node has no
contact element); on quadratic faces (C3D10, CPE6) the nodal stress -sigma_zz (3D) / -sigma_yy (2D) at the
contact-face nodes (CalculiX's nodal stresses: extrapolated from the integration points and averaged), since
CPRESS of quadratic faces is split unevenly between corner and mid-side nodes. In 2D CalculiX reports CPRESS on
the nodes of the wedges it expands CPE elements into, whose coordinates the .frd does not carry, so CPE3 also
takes -sigma_yy (constant per element, averaged at the nodes). Tension is clipped to 0.

Estimators: 3D :func:`femcheck.qoi.symmetric_contact` (even quartic about the centre for ``p_max``, power-law
edges for the semi-axes), 2D :func:`femcheck.qoi.peak` (even quartic about x = 0) and :func:`femcheck.qoi.edge`;
``p_max_nodal`` the largest nodal value. ``approach`` (m): the rigid indenter's displacement; ``total_force``:
the bottom reaction scaled to the full contact (x 4 for the quarter, x 2 for the half model).
:func:`read_srb` reads the two-contact deck of srb-normal (:mod:`femcheck.export.srb`) per contact,
:func:`read_roller` the finite roller's (roller-finite, roller-crowned) centre pressure and half-width.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ..qoi import centre_value_2d, edge, peak, symmetric_contact
from . import frd as frd_reader
from . import inp


def _cpress(res: frd_reader.Frd, nodes: np.ndarray) -> np.ndarray:
    """CalculiX's contact pressure CPRESS (Pa) at node ids ``nodes`` (0 where a node has no contact element);
    KeyError where the .frd has no contact block."""
    c = res.last("CONTACT")
    cp = dict(zip(c.nodes.tolist(), c.column("CPRESS")))
    return np.array([cp.get(int(n), 0.0) for n in nodes])


def read(deck_path: Path) -> dict[str, float | str]:
    """Quantities of the solved deck ``deck_path`` (its ``.frd`` and ``.dat`` beside it)."""
    deck_path = Path(deck_path)
    cards = inp.parse(deck_path.read_text())
    etype = inp.element_types(cards)["EBLOCK"]
    dim = 2 if etype.startswith("CPE") else 3
    quadratic = etype in ("C3D10", "CPE6")
    top = inp.node_sets(cards)["NTOP"]
    res = frd_reader.read_frd(deck_path.with_suffix(".frd"))
    dat = frd_reader.read_dat(deck_path.with_suffix(".dat"))
    X = res.coords_of(top)
    stress = res.last("STRESS")
    srow = {int(n): i for i, n in enumerate(stress.nodes)}
    normal = "SZZ" if dim == 3 else "SYY"
    p_stress = np.array([-stress.values[srow[int(n)], stress.components.index(normal)] for n in top])
    p_cpress = np.zeros(top.size)
    try:
        p_cpress = _cpress(res, top)
    except KeyError:
        pass
    by_stress = quadratic or dim == 2
    p = np.clip(p_stress if by_stress else p_cpress, 0.0, None)
    out: dict = {"p_max_nodal": float(p.max()), "p_max_nodal_stress": float(p_stress.max()),
                             "contact_nodes": int((p > 0).sum()), "pressure_from": "-S" if by_stress else "CPRESS"}
    if dim == 3:
        out["p_max_nodal_cpress"] = float(p_cpress.max())
    if dim == 3:
        fit = symmetric_contact(X[0], X[1], p)
        out.update({k: float(fit[k]) for k in ("p_max", "semi_axis_x", "semi_axis_y", "p_max_std",
                                                 "semi_axis_x_std", "semi_axis_y_std")})
    else:
        order = np.argsort(X[0])
        x, pp = X[0][order], p[order]
        pk = peak(x, pp, centre=0.0)
        e = edge(x, pp)
        out.update({"p_max": pk.value, "p_max_std": pk.std, "half_width": e.position, "half_width_std": e.std})
    u = dat[("displacements", "NREF")]
    out["approach"] = float(-u[0, dim])
    out["total_force"] = float(dat[("total force", "NBOTTOM")][0, dim]) * (4.0 if dim == 3 else 2.0)
    out["n_nodes"] = int(res.nodes.size)
    return out


def read_srb(deck_path: Path, nodal: bool = False) -> dict[str, dict]:
    """Per raceway contact ("inner", "outer") of a solved srb-normal deck (:func:`femcheck.export.srb.srb`):
    CPRESS at the roller's contact-face nodes (the slave side, as femcheck's two-body solver reports its pressure)
    in the contact's local frame (x rolling, y along the roller axis, origin on the x = 0 symmetry plane below the
    roller's reference node), the estimators of :func:`femcheck.qoi.symmetric_contact` about the loaded patch's
    mid-length as :func:`femcheck.fem.srb_conformal.solve_contact` takes them; ``approach`` (m) the roller's rigid
    displacement along -z, ``total_force`` (N) twice the raceway's bottom reaction (half model); with ``nodal``
    also the face nodes ``nodes_x`` (3, n) (m, undeformed, local frame) and their CPRESS ``nodes_pressure`` (Pa)."""
    deck_path = Path(deck_path)
    cards = inp.parse(deck_path.read_text())
    sets = inp.node_sets(cards)
    res = frd_reader.read_frd(deck_path.with_suffix(".frd"))
    dat = frd_reader.read_dat(deck_path.with_suffix(".dat"))
    out = {}
    for contact, tag in (("inner", "I"), ("outer", "O")):
        top = sets[f"NTOP_{tag}"]
        X = res.coords_of(top)
        x_ref = res.coords_of(sets[f"NREF_{tag}"])[0, 0]
        p = np.clip(_cpress(res, top), 0.0, None)
        x, y = X[0] - x_ref, X[1]
        loaded = y[p > 0]
        centre_y = 0.5 * (loaded.min() + loaded.max())
        fit = symmetric_contact(x, y - centre_y, p)
        q = {k: float(fit[k]) for k in ("p_max", "semi_axis_x", "semi_axis_y", "p_max_std", "semi_axis_x_std",
                                        "semi_axis_y_std")}
        q["contact_area"] = float(np.pi * q["semi_axis_x"] * q["semi_axis_y"])
        q.update({"centre_y": float(centre_y), "p_max_nodal": float(p.max()), "contact_nodes": int((p > 0).sum()),
                  "approach": float(-dat[("displacements", f"NREF_{tag}")][0, 3]),
                  "total_force": 2.0 * float(dat[("total force", f"NBOTTOM_{tag}")][0, 3])})
        if nodal:
            q.update(nodes_x=np.vstack([x, y, X[2]]), nodes_pressure=p)
        out[contact] = q
    return out


def read_roller(deck_path: Path, half_width_hertz: float, length: float) -> dict[str, float]:
    """The finite roller's quarter deck (:func:`femcheck.export.scenes.roller`): CPRESS at the block's contact-face
    nodes, ``p_centre`` (Pa) the centre value of :func:`femcheck.qoi.centre_value_2d` over 0.5 a_H across and
    L/8 along the roller (the window of :func:`femcheck.fem.roller_contact.centre_quantities`), ``half_width``
    (m) the power-law edge of :func:`femcheck.qoi.edge` over the central band y < L/8, their standard errors
    ``<q>_std``; ``half_width_hertz`` a_H (m), ``length`` L (m)."""
    deck_path = Path(deck_path)
    top = inp.node_sets(inp.parse(deck_path.read_text()))["NTOP"]
    res = frd_reader.read_frd(deck_path.with_suffix(".frd"))
    dat = frd_reader.read_dat(deck_path.with_suffix(".dat"))
    x, y = res.coords_of(top)[:2]
    p = np.clip(_cpress(res, top), 0.0, None)
    centre = centre_value_2d(x, y, p, 0.5 * half_width_hertz, length / 8.0)
    band = y < length / 8.0
    width = edge(x[band], p[band], band=0.5, min_points=8, transverse=y[band])
    return {"p_centre": centre.value, "p_centre_std": centre.std, "half_width": width.position,
            "half_width_std": width.std, "p_max_nodal": float(p.max()),
            "approach": float(-dat[("displacements", "NREF")][0, 3]),
            "total_force": float(dat[("total force", "NBOTTOM")][0, 3]) * 4.0}
