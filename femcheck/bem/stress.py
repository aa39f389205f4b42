"""Sub-surface stresses in an elastic half-space under a gridded normal pressure (3D).

Influence coefficients: stresses at depth z below the centre of the evaluation cell due to unit pressure on a
dx x dy rectangle, in closed form from Love's potentials (Johnson, *Contact Mechanics*, 1985, §3.2, eq 3.4
with tangential tractions zero):

    sigma_x = (1/2pi)[2 nu dpsi/dz - z d2psi/dx2 - (1 - 2 nu) d2Phi/dx2]
    sigma_y = (1/2pi)[2 nu dpsi/dz - z d2psi/dy2 - (1 - 2 nu) d2Phi/dy2]
    sigma_z = (1/2pi)[dpsi/dz - z d2psi/dz2]
    tau_xy  = -(1/2pi)[(1 - 2 nu) d2Phi/dxdy + z d2psi/dxdy]
    tau_xz  = -(1/2pi) z d2psi/dxdz,     tau_yz = -(1/2pi) z d2psi/dydz

psi = int int p / rho dA, Phi = int int p ln(rho + z) dA. For uniform p on a rectangle every derivative is a
corner difference D[f] = f(a2, b2) - f(a1, b2) - f(a2, b1) + f(a1, b1) of elementary functions of the corner
offsets (a, b) = (xi - x, eta - y), R = sqrt(a^2 + b^2 + z^2) (derived in this module, verified against
quadrature of Boussinesq's point-load stresses in the tests):

    dpsi/dz   = -D[atan(a b / (z R))]              d2psi/dz2 = D[a b (R^2 + z^2) / (R (a^2 + z^2)(b^2 + z^2))]
    d2psi/dx2 = D[a / (R (R + b))]                 d2psi/dy2 = D[b / (R (R + a))]
    d2psi/dxdy = D[1 / R]                          d2psi/dxdz = -D[z / (R (R + b))],  d2psi/dydz = -D[z / (R (R + a))]
    d2Phi/dx2 = D[atan(b/a) - atan(b z / (a R))]   d2Phi/dy2 = D[atan(a/b) - atan(a z / (b R))]
    d2Phi/dxdy = D[ln(R + z)]

Stresses are then DC-FFT convolutions of the pressure with these kernels, one depth at a time (the kernel
spectra per depth are computed on the fly and not stored). Tension positive; z > 0 into the body.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .convolution import DCFFT
from .halfspace import Grid

COMPONENTS = ("sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_xz", "tau_yz")


def _over(num: np.ndarray, R: np.ndarray, s: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """num / (R (R + s)) without cancellation when s < 0: R + s = (R^2 - s^2)/(R - s) = q2/(R - s)."""
    return np.where(s >= 0, num / (R * (R + s)), num * (R - s) / (R * q2))


@np.errstate(divide="ignore", invalid="ignore")
def _corner_terms(a: np.ndarray, b: np.ndarray, z: float) -> dict[str, np.ndarray]:
    # a or b = 0 (a corner on the evaluation point's edge line): atan(+-inf) differences cancel exactly
    R = np.sqrt(a * a + b * b + z * z)
    a2z, b2z = a * a + z * z, b * b + z * z
    return {
        "psi_z": -np.arctan(a * b / (z * R)),
        "psi_zz": a * b * (R * R + z * z) / (R * a2z * b2z),
        "psi_xx": _over(a, R, b, a2z),
        "psi_yy": _over(b, R, a, b2z),
        "psi_xy": 1.0 / R,
        "psi_xz": -_over(np.full_like(R, z), R, b, a2z),
        "psi_yz": -_over(np.full_like(R, z), R, a, b2z),
        "phi_xx": np.arctan(b / a) - np.arctan(b * z / (a * R)),
        "phi_yy": np.arctan(a / b) - np.arctan(a * z / (b * R)),
        "phi_xy": np.log(R + z),
    }


def rectangle_stress(tx: np.ndarray, ty: np.ndarray, z: float, dx: float, dy: float, nu: float
                     ) -> dict[str, np.ndarray]:
    """Six stress components (Pa per Pa) at depth ``z`` (m) and lateral offset (tx, ty) (m) from the centre of a
    dx x dy rectangle carrying unit pressure. Offsets must not lie on a rectangle edge (cell centres never do)."""
    tx, ty = np.broadcast_arrays(np.asarray(tx, dtype=float), np.asarray(ty, dtype=float))
    a1, a2 = -tx - 0.5 * dx, -tx + 0.5 * dx          # corner offsets xi - x of the loaded cell
    b1, b2 = -ty - 0.5 * dy, -ty + 0.5 * dy
    t22, t12, t21, t11 = (_corner_terms(a, b, z) for a, b in ((a2, b2), (a1, b2), (a2, b1), (a1, b1)))
    D = {k: t22[k] - t12[k] - t21[k] + t11[k] for k in t22}
    c = 1.0 / (2.0 * np.pi)
    return {
        "sigma_x": c * (2 * nu * D["psi_z"] - z * D["psi_xx"] - (1 - 2 * nu) * D["phi_xx"]),
        "sigma_y": c * (2 * nu * D["psi_z"] - z * D["psi_yy"] - (1 - 2 * nu) * D["phi_yy"]),
        "sigma_z": c * (D["psi_z"] - z * D["psi_zz"]),
        "tau_xy": -c * ((1 - 2 * nu) * D["phi_xy"] + z * D["psi_xy"]),
        "tau_xz": -c * z * D["psi_xz"],
        "tau_yz": -c * z * D["psi_yz"],
    }


def graded_depths(z_max: float, n: int, grading: float = 1.5) -> np.ndarray:
    """n depths in (0, z_max], spacing growing with depth: z_k = z_max (k/n)^grading."""
    return z_max * (np.arange(1, n + 1) / n) ** grading


@dataclass
class StressField:
    """Stresses (Pa) on the grid's cell centres at ``depths`` (m): components[name] has shape (nz, nx, ny)."""

    grid: Grid
    depths: np.ndarray
    components: dict[str, np.ndarray]

    def von_mises(self) -> np.ndarray:
        s = self.components
        return np.sqrt(0.5 * ((s["sigma_x"] - s["sigma_y"]) ** 2 + (s["sigma_y"] - s["sigma_z"]) ** 2
                              + (s["sigma_z"] - s["sigma_x"]) ** 2)
                       + 3.0 * (s["tau_xy"] ** 2 + s["tau_xz"] ** 2 + s["tau_yz"] ** 2))

    def tresca(self) -> np.ndarray:
        """(sigma_1 - sigma_3)/2 from the eigenvalues of the 3x3 stress tensor at every point."""
        s = self.components
        T = np.stack([np.stack([s["sigma_x"], s["tau_xy"], s["tau_xz"]], -1),
                      np.stack([s["tau_xy"], s["sigma_y"], s["tau_yz"]], -1),
                      np.stack([s["tau_xz"], s["tau_yz"], s["sigma_z"]], -1)], -2)
        ev = np.linalg.eigvalsh(T)
        return 0.5 * (ev[..., -1] - ev[..., 0])


def subsurface_stresses(pressure: np.ndarray, grid: Grid, depths: np.ndarray, nu: float,
                        workers: int = -1) -> StressField:
    """Stress field below a gridded pressure (Pa): for every depth, six DC-FFT convolutions with the rectangle
    kernels (each kernel spectrum built once for that depth)."""
    out = {k: np.empty((depths.size, grid.nx, grid.ny)) for k in COMPONENTS}
    for iz, z in enumerate(depths):
        kernels: dict[str, np.ndarray] = {}

        def kernel(name):
            def f(tx, ty):
                if not kernels:
                    kernels.update(rectangle_stress(tx, ty, z, grid.dx, grid.dy, nu))
                return kernels[name]
            return f

        for name in COMPONENTS:
            op = DCFFT(kernel(name), (grid.nx, grid.ny), (grid.dx, grid.dy), workers=workers)
            out[name][iz] = op(pressure)
    return StressField(grid, np.asarray(depths, dtype=float), out)


def _vertex(x: np.ndarray, f: np.ndarray) -> tuple[float, float]:
    """Vertex (position, value) of the parabola through three points (x need not be uniform)."""
    (x0, x1, x2), (f0, f1, f2) = x, f
    d = (x0 - x1) * (x0 - x2) * (x1 - x2)
    A = (x2 * (f1 - f0) + x1 * (f0 - f2) + x0 * (f2 - f1)) / d
    B = (x2 * x2 * (f0 - f1) + x1 * x1 * (f2 - f0) + x0 * x0 * (f1 - f2)) / d
    if A >= 0:
        return float(x1), float(f1)
    xv = -B / (2 * A)
    C = f0 - A * x0 * x0 - B * x0
    return float(xv), float(A * xv * xv + B * xv + C)


def maximum(values: np.ndarray, depths: np.ndarray, grid: Grid) -> dict[str, float]:
    """Largest value of a field V[z, x, y] and its position, refined by a parabola through the neighbours along
    each axis (grid spacing alone would limit the depth to the depth step)."""
    k = np.unravel_index(np.argmax(values), values.shape)
    out = {"value": float(values[k])}
    best = out["value"]
    for axis, coords, name in ((0, depths, "depth"), (1, grid.x, "x"), (2, grid.y, "y")):
        i = k[axis]
        pos = float(coords[i])
        if 0 < i < values.shape[axis] - 1:
            idx = [list(k), list(k), list(k)]
            for j, off in enumerate((-1, 0, 1)):
                idx[j][axis] = i + off
            pos, val = _vertex(coords[i - 1:i + 2], np.array([values[tuple(t)] for t in idx]))
            best = max(best, val)
        out[name] = pos
    out["value"] = best
    return out
