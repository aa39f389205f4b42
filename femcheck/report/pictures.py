"""3D pictures of FE solutions for the report, rendered off-screen with pyvista (the ``viz`` extra).

Headless machines need no X server: VTK renders through EGL/Mesa when told to use its EGL window
(FEM-NOTES: 1.2 s per picture instead of 4.2 s after a failed X attempt). Without pyvista the report simply
has no 3D pictures; the run itself never depends on them.
"""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..result import RunResult


def _pyvista():
    os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    try:
        import pyvista
    except ImportError:
        return None
    pyvista.OFF_SCREEN = True
    return pyvista


def _surface(pv, m, scalars: np.ndarray, name: str, faces_on_top: bool = False):
    pts = np.asarray(m.fields["view_points"], dtype=float).T * 1e3           # mm
    tri = np.asarray(m.fields["view_triangles"]).T
    if faces_on_top:
        tri = tri[(np.abs(pts[tri, 2]) < 1e-9).all(axis=1)]
    faces = np.hstack([np.full((len(tri), 1), 3), tri]).ravel()
    surf = pv.PolyData(pts, faces)
    surf[name] = np.asarray(scalars, dtype=float)
    return surf


def fem_views(run: RunResult, out: Path, prefix: str) -> dict[str, str]:
    """Two PNGs from the ``fem`` model's surface view: the mesh of the contact region coloured by von Mises
    stress (symmetry-plane sections and contact face), and the contact pressure on the face."""
    m = run.models.get("fem")
    if m is None or m.status != "ok" or "view_points" not in m.fields:
        return {}
    pv = _pyvista()
    if pv is None:
        return {}
    out = Path(out)
    pics = {}
    from .plots import parts, singular_note

    part, grows = parts(run)[0][1], singular_note(run)
    specs = (("mesh3d", "von Mises, GPa", m.fields["view_von_mises"] / 1e9, False, (1.0, -1.6, 0.9)),
             ("pressure3d", "p, GPa", m.fields["view_pressure"] / 1e9, True, (0.0, 0.0, 1.0)))
    pts = np.asarray(m.fields["view_points"], dtype=float)
    span = np.ptp(pts[:2], axis=1)
    # an elongated patch (srb-normal: 42:1) would be a hairline: stretch the short axis, and say so
    stretch = [1.0, 1.0, 1.0]
    if span.max() > 4.5 * span.min() > 0:       # stretch by at least 1.5, or not at all
        stretch[int(np.argmin(span))] = span.max() / (3.0 * span.min())
    edges = len(m.fields["view_triangles"][0]) < 20000       # edges of denser meshes only darken the picture
    for key, name, values, top, view in specs:
        surf = _surface(pv, m, values, name, faces_on_top=top)
        pl = pv.Plotter(off_screen=True, window_size=(900, 640))
        clim = None
        if top and grows:      # a peak that grows with refinement must not set the colour scale
            clim = [0.0, _area_percentile(surf, values, 99.0)]
        pl.add_mesh(surf, scalars=name, show_edges=edges, edge_color="#444444", line_width=0.3, cmap="viridis",
                    clim=clim, above_color="white" if clim else None,
                    scalar_bar_args={"title": name + (" (clipped at 99 % of the\nloaded area)" if clim else ""),
                                     "vertical": True,
                                     "position_x": 0.8, "position_y": 0.1})
        pl.set_scale(*stretch)
        pl.camera_position = "xy" if top else None
        if not top:
            pl.view_vector(view)
        pl.add_axes(xlabel="x", ylabel="y", zlabel="z")
        along = 1 if stretch[0] > 1.0 else 0          # the scale bar goes along an axis that is not stretched
        _scale_bar(pl, pts * 1e3, along)
        where = ", ".join(w for w in ("finest level", part) if w)
        title = (f"{run.scene}: FE mesh near the contact, von Mises on the symmetry sections ({where})"
                 if not top else f"{run.scene}: FE contact pressure on the face z = 0 ({where})")
        if max(stretch) > 1.0:
            title += f"\n{'xy'[int(np.argmax(stretch))]} stretched x{max(stretch):.0f} for display; the scale bar " \
                     f"is along {'xy'[along]}"
        pl.add_text(title, font_size=9)
        path = out / f"{prefix}-{key}.png"
        pl.screenshot(str(path))
        pl.close()
        pics[key] = path.name
    return pics


def _scale_bar(pl, pts_mm: np.ndarray, along: int = 0) -> None:
    """A ruler along axis ``along`` (0: x, 1: y) of a round length (1, 2 or 5 x 10^k mm, about a third of the
    picture's extent that way), at the edge of the region shown, labelled with its true length."""
    lo, hi = pts_mm.min(axis=1), pts_mm.max(axis=1)
    target = (hi[along] - lo[along]) / 3.0
    if target <= 0:
        return
    k = np.floor(np.log10(target))
    length = max(m * 10**k for m in (1.0, 2.0, 5.0) if m * 10**k <= target)
    a = [lo[0], lo[1], hi[2]]
    b = list(a)
    b[along] += length
    pl.add_ruler(a, b, title=f"{length:g} mm", number_labels=2, show_labels=False, font_size_factor=0.8)


def _area_percentile(surf, values: np.ndarray, q: float) -> float:
    """The pressure below which ``q`` % of the loaded face area lies (face value: mean of its nodes). Weighting by
    area keeps the small elements a mesh crowds at a sharp edge from setting the colour scale."""
    faces = surf.faces.reshape(-1, 4)[:, 1:]
    face_p = values[faces].mean(axis=1)
    area = surf.compute_cell_sizes(length=False, volume=False)["Area"]
    loaded = face_p > 0
    if not loaded.any():
        return float(values.max())
    order = np.argsort(face_p[loaded])
    cum = np.cumsum(area[loaded][order])
    return float(face_p[loaded][order][np.searchsorted(cum, q / 100.0 * cum[-1])])
