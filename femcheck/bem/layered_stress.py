"""Sub-surface stresses in a layered half-space (layer on an elastic substrate or a rigid base) under a gridded
normal pressure: stress frequency response, fields on depth planes (both sides of the interface), von Mises,
Tresca and their maxima. Companion of :mod:`femcheck.bem.layered` (same body, same boundary-value problem).

Boundary-value problem (as in ``bem/layered.py``; Chen 1971, O'Sullivan & King, J. Tribol. 110, 1988). Body: a
layer 0 <= z <= h (E1, nu1, mu1) bonded to a substrate z >= h (E2, nu2, mu2) or to a rigid base; z into the body,
tension positive. Papkovich-Neuber solution in each material (Barber, *Elasticity*, ch. 20)

    2 mu u = grad(phi + z psi) - 4 (1 - nu) psi e_z,     phi, psi harmonic,
    sigma_ab = phi_ab + z psi_ab - 2 nu delta_ab psi_z          (a, b in-plane)
    sigma_az = phi_az + z psi_az - (1 - 2 nu) psi_a
    sigma_zz = phi_zz + z psi_zz - 2 (1 - nu) psi_z.

For one Fourier mode e^{i k.x} of the surface pressure (k = |k|, n = k/|k|; plane strain: n = sign(kx) e_x) the
potentials are phi = f(z) e^{ik.x}, psi = g(z) e^{ik.x} with f, g in {e^{-kz}, e^{kz}}. Written with s = k z,
t = k h, e1 = e^{-s}, e2 = e^{-(t - s)} (both <= 1: no overflow at large k h),

    layer:      k^2 f = A1 e1 + A2 e2,      k g = B1 e1 + B2 e2
    substrate:  k^2 f = C e3,               k g = D e3,       e3 = e^{-k (z - h)}, z measured from the interface

the stress transforms per unit pressure transform are, with three scalar profiles W = k^2 (f + z g), G = g',
T = k (f' + z g' - (1 - 2 nu) g):

    sigma_ab^ = -n_a n_b W - 2 nu delta_ab G,   sigma_zz^ = W - 2 (1 - nu) G,   sigma_az^ = i n_a T
    layer:  W = (A1 + s B1) e1 + (A2 + s B2) e2,   G = -B1 e1 + B2 e2,
            T = -(A1 + s B1 + (1 - 2 nu1) B1) e1 + (A2 + s B2 - (1 - 2 nu1) B2) e2
    substrate (s' = k (z - h)): W = (C + s' D) e3,  G = -D e3,  T = -(C + s' D + (1 - 2 nu2) D) e3,

and 2 mu k u_a = i n_a W, 2 mu k u_z = -(A1 + s B1) e1 + (A2 + s B2) e2 - (3 - 4 nu)(B1 e1 + B2 e2) (layer;
likewise in the substrate). The six constants (four on a rigid base) solve, per wavenumber (``layer_constants``,
a batched 6 x 6 solve, vectorised over k):

    z = 0:  sigma_zz^ = -1, sigma_az^ = 0;
    z = h:  u continuous (written mu2 (2 mu1 k u) = mu1 (2 mu2 k u)), sigma_zz^ and sigma_az^ continuous,
            or, on a rigid base, u = 0.

With the scaled exponentials the matrix is well conditioned at every k h, including k h -> 0 (measured condition
number 23 at k h = 1e-7 for alumina on steel, about k h at large k h from the column scale). The surface
displacement it gives, u_z^ = 2 (1 - nu1) Phi(kh) / (2 mu1 k), is exactly the closed-form Phi of
``bem/layered.py`` (tested). g = mu1/mu2 = 1, nu1 = nu2 gives the homogeneous half-space: A1 = 1 - 2 nu,
B1 = -1, so W = (1 - 2 nu - s) e^{-s}, G = e^{-s}, T = s e^{-s}, i.e. Johnson (1985) §2.6 / eq. 3.4 in transform.

Long-wave limit (k -> 0) in the layer: sigma_zz = -p, sigma_az = 0 and the in-plane strain of the substrate's
surface, -(1 + nu2)(1 - 2 nu2) p / E2 n n (uniaxial along n), imposed on the layer by Hooke's law give

    sigma_ab(k->0) = -(c1 n_a n_b + c2 delta_ab) p,   c1 = g (1 - 2 nu2),   c2 = nu1 / (1 - nu1) (1 + g (1 - 2 nu2))

(rigid base: c1 = 0, c2 = nu1 / (1 - nu1)); the homogeneous values are c1 = 1 - 2 nu, c2 = 2 nu
(``long_wave_limit``, tested against the BVP at k h = 1e-9). In 3D this limit depends on the direction n, so the
transform is discontinuous at k = 0: sampling it on an FFT grid would make the field that of a periodic array of
contacts, wrong by O(P / L^2) (a few % of p0 for a period L of a few contact sizes).

Fields (``line_stresses``, ``point_stresses``): on every depth plane the stress is split as

    S = S_hom(nu of the material at that depth, z)      exact cell kernels, DC-FFT (linear convolution)
      + images (layer only): -(dc1 n n + dc2 delta) e^{-k zeta} in sigma_ab, zeta = 2h - z,
                              dc1 = c1 - (1 - 2 nu1), dc2 = c2 - 2 nu1       exact cell kernels, DC-FFT
      + residual R(k, z)                                 sampled on a zero-padded grid, FFT

S_hom is the homogeneous half-space: 3D Love's rectangle kernels of :mod:`femcheck.bem.stress`, plane strain the
uniform strip (Johnson 1985 §2.6, derived here from the transform: sigma_x, sigma_z = -(1/pi)[atan(X/z)
-+ z X / (X^2 + z^2)], tau_xz = (z^2/pi) [1/(X^2 + z^2)] over the strip's ends X). The image terms are the cell
integrals of the Poisson kernel (e^{-k zeta}) and of Love's Phi_ab (n_a n_b e^{-k zeta}); they make R vanish at
k = 0 in every direction, so R is continuous with a cone R = O(k) there (kernel tail ~ h / r^3 in 3D, h / x^2 in
2D), and it decays like e^{-k h} (in the layer like e^{-k (2h - z)}, in the substrate like e^{-k z}). R is
sampled at the DFT wavenumbers of a zero-padded grid of period L >= 2 n dx and >= n dx + c l (c = 24 in 3D,
200 in 2D, capped by MAX_POINTS; l >= h the length of R's cone at k = 0, ``slope_length``) and multiplied by the DFT of the pressure and the cell factor sinc(kx dx/2pi)
sinc(ky dy/2pi) (uniform pressure per cell, as in the BEM). Errors: the periodic images of R's kernel, O(l a^2/L^3)
(3D) and O(l a/L^2) (2D) of p0 (measured in 3D, E1/E2 = 2.9, h = 0.1 a, l = 0.59 a: 0.9 % of p0 in sigma_x at
L = 5.2 a, 0.1 % at 10.4 a, 0.01 % at 21 a), and R's content beyond the grid's Nyquist wavenumber, which matters only for
layers thinner than a cell and only within about h of the pressure's cell edges. At z = 0 R_zz = R_az = 0, so
sigma_zz = -p and sigma_az = 0 exactly at the cell centres.

Interface: each depth plane carries its material (``in_layer``); z = h is evaluated on both sides. sigma_zz and
sigma_az are continuous there, the in-plane stresses jump (continuous in-plane strain, different moduli).

SI units: Pa, m, N. Stress components are named sigma_x, sigma_y, sigma_z, tau_xy, tau_xz, tau_yz (as in
:mod:`femcheck.bem.stress`).

Length: above 500 lines because of the derivation above (80 lines); the code (about 510 lines) has one job, the
stress field of one boundary-value problem, and splitting the modal constants from the field evaluation would
separate them from the only code that uses them.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy import fft

from ..analytic import stress as closed_stress
from ..errors import InputError
from . import stress as hs_stress
from .convolution import DCFFT
from .halfspace import Grid
from .layered import LayeredSolid

# Residual period beyond the loaded grid, in layer thicknesses (the residual kernel's tail ~ h/x^2 in 2D,
# h/r^3 in 3D), and the largest residual FFT per axis (2D 2^18 points: ~5 ms a transform here; 3D 768^2).
RESIDUAL_CLEARANCE = {1: 200.0, 2: 24.0}
MAX_POINTS = {1: 1 << 18, 2: 768}


# ---------------------------------------------------------------------------------------------------------------
# Frequency response
# ---------------------------------------------------------------------------------------------------------------

def shear_modulus_ratio(solid: LayeredSolid) -> float:
    """g = mu1 / mu2 (-), inf on a rigid base."""
    if solid.rigid_substrate:
        return np.inf
    return (solid.E_layer / (1.0 + solid.nu_layer)) / (solid.E_substrate / (1.0 + solid.nu_substrate))


def layer_constants(t: np.ndarray, solid: LayeredSolid) -> np.ndarray:
    """Constants (A1, A2, B1, B2, C, D) of the module docstring per unit pressure transform, shape t.shape + (6,)
    (C = D = 0 on a rigid base), for t = |k| h >= 0 (dimensionless). One batched linear solve over all t."""
    t = np.asarray(t, dtype=float)
    flat = t.ravel()
    E = np.exp(-flat)
    o, z = np.ones_like(flat), np.zeros_like(flat)
    nu1 = solid.nu_layer
    n1, m1, q1 = 3.0 - 4.0 * nu1, 2.0 * (1.0 - nu1), 1.0 - 2.0 * nu1
    top = [np.stack([o, E, m1 * o, -m1 * E], -1),             # sigma_zz(0) = -1
           np.stack([-o, E, -q1 * o, -q1 * E], -1)]           # sigma_az(0) = 0
    # layer rows at z = h (e1 = E, e2 = 1): 2 mu k u_a, 2 mu k u_z, sigma_zz, T
    uh = np.stack([E, o, flat * E, flat], -1)
    uz = np.stack([-E, o, -(flat + n1) * E, flat - n1], -1)
    szz = np.stack([E, o, (flat + m1) * E, flat - m1], -1)
    tt = np.stack([-E, o, -(flat + q1) * E, flat - q1], -1)
    rhs = np.zeros((flat.size, 6))
    rhs[:, 0] = -1.0
    if solid.rigid_substrate:
        M = np.stack(top + [uh, uz], axis=1)
        c = np.linalg.solve(M, rhs[:, :4, None])[..., 0]
        c = np.concatenate([c, np.zeros((flat.size, 2))], axis=1)
        return c.reshape(t.shape + (6,))
    g, nu2 = shear_modulus_ratio(solid), solid.nu_substrate
    n2, m2, q2 = 3.0 - 4.0 * nu2, 2.0 * (1.0 - nu2), 1.0 - 2.0 * nu2
    pad = np.zeros((flat.size, 2))
    # substrate at its top (e3 = 1): 2 mu2 k u_a = C, 2 mu2 k u_z = -C - n2 D, sigma_zz = C + m2 D, T = -C - q2 D;
    # displacement continuity mu2 (layer) = mu1 (substrate) in these scaled units: U1 - g U2 = 0
    rows = [np.concatenate([r, pad], -1) for r in top]
    rows.append(np.concatenate([uh, np.stack([-g * o, z], -1)], -1))
    rows.append(np.concatenate([uz, np.stack([g * o, g * n2 * o], -1)], -1))
    rows.append(np.concatenate([szz, np.stack([-o, -m2 * o], -1)], -1))
    rows.append(np.concatenate([tt, np.stack([o, q2 * o], -1)], -1))
    M = np.stack(rows, axis=1)
    c = np.linalg.solve(M, rhs[..., None])[..., 0]
    return c.reshape(t.shape + (6,))


@dataclass
class ModalProfiles:
    """Scalar stress profiles W, G, T (dimensionless, per unit pressure transform) of the module docstring at
    wavenumbers k and one depth z, plus the surface-normalised vertical displacement ``Uz`` = 2 mu k u_z^ and the
    material's Poisson ratio ``nu``. Components: sigma_ab^ = -n_a n_b W - 2 nu delta_ab G,
    sigma_zz^ = W - 2 (1 - nu) G, sigma_az^ = i n_a T."""

    W: np.ndarray
    G: np.ndarray
    T: np.ndarray
    Uz: np.ndarray
    nu: float


def modal_profiles(k: np.ndarray, z: float, solid: LayeredSolid, in_layer: bool | None = None,
                   constants: np.ndarray | None = None) -> ModalProfiles:
    """Profiles W, G, T at depth ``z`` (m) for wavenumbers ``k`` (rad/m, >= 0). ``in_layer`` picks the material
    at z = h (default: layer for z <= h). ``constants`` (from :func:`layer_constants` at t = k h) may be passed to
    reuse one solve for many depths."""
    k = np.abs(np.asarray(k, dtype=float))
    h = solid.thickness
    if z < 0:
        raise InputError("depth", f"{z!r} m; allowed [0, inf)")
    if in_layer is None:
        in_layer = z <= h
    if not in_layer and solid.rigid_substrate:
        raise InputError("depth", f"{z!r} m lies in the rigid base (layer thickness {h:g} m)")
    c = layer_constants(k * h, solid) if constants is None else constants
    A1, A2, B1, B2, C, D = np.moveaxis(c, -1, 0)
    if in_layer:
        nu = solid.nu_layer
        s = k * z
        e1, e2 = np.exp(-s), np.exp(-(k * h - s))
        W = (A1 + s * B1) * e1 + (A2 + s * B2) * e2
        G = -B1 * e1 + B2 * e2
        T = -(A1 + s * B1 + (1 - 2 * nu) * B1) * e1 + (A2 + s * B2 - (1 - 2 * nu) * B2) * e2
        Uz = -(A1 + s * B1) * e1 + (A2 + s * B2) * e2 - (3 - 4 * nu) * (B1 * e1 + B2 * e2)
    else:
        nu = solid.nu_substrate
        s = k * (z - h)
        e3 = np.exp(-s)
        W = (C + s * D) * e3
        G = -D * e3
        T = -(C + s * D + (1 - 2 * nu) * D) * e3
        Uz = -(C + s * D + (3 - 4 * nu) * D) * e3
    return ModalProfiles(W, G, T, Uz, nu)


def homogeneous_profiles(k: np.ndarray, z: float, nu: float) -> ModalProfiles:
    """W, G, T of a homogeneous half-space (A1 = 1 - 2 nu, B1 = -1): W = (1 - 2 nu - s) e^{-s}, G = e^{-s},
    T = s e^{-s}, s = |k| z (Johnson 1985 §2.6 in transform)."""
    s = np.abs(np.asarray(k, dtype=float)) * z
    e = np.exp(-s)
    return ModalProfiles((1 - 2 * nu - s) * e, e, s * e, (2 - 2 * nu + s) * e, nu)


def long_wave_limit(solid: LayeredSolid) -> tuple[float, float]:
    """(c1, c2) of the module docstring: in-plane stress in the layer under a long-wave unit pressure,
    sigma_ab = -(c1 n_a n_b + c2 delta_ab) p (dimensionless)."""
    nu1 = solid.nu_layer
    if solid.rigid_substrate:
        return 0.0, nu1 / (1.0 - nu1)
    c1 = shear_modulus_ratio(solid) * (1.0 - 2.0 * solid.nu_substrate)
    return c1, nu1 / (1.0 - nu1) * (1.0 + c1)


def plane_strain_response(k: np.ndarray, z: float, solid: LayeredSolid, in_layer: bool | None = None
                          ) -> dict[str, np.ndarray]:
    """Plane-strain stress transforms per unit pressure transform at depth z (m) for signed wavenumbers k
    (rad/m): sigma_x = -W - 2 nu G, sigma_z = W - 2 (1 - nu) G, tau_xz = i sign(k) T, sigma_y = -2 nu G
    (= nu (sigma_x + sigma_z)). Convention p(x) = (1/2pi) int p^ e^{ikx} dk; z-axis into the body."""
    k = np.asarray(k, dtype=float)
    m = modal_profiles(k, z, solid, in_layer)
    return {"sigma_x": -m.W - 2 * m.nu * m.G, "sigma_z": m.W - 2 * (1 - m.nu) * m.G,
            "tau_xz": 1j * np.sign(k) * m.T, "sigma_y": -2 * m.nu * m.G}


def response_3d(kx: np.ndarray, ky: np.ndarray, z: float, solid: LayeredSolid, in_layer: bool | None = None
                ) -> dict[str, np.ndarray]:
    """3D stress transforms per unit pressure transform at depth z (m), wavevector (kx, ky) (rad/m, not both 0):
    the module docstring's sigma_ab^ = -n_a n_b W - 2 nu delta_ab G etc."""
    kx, ky = np.broadcast_arrays(np.asarray(kx, dtype=float), np.asarray(ky, dtype=float))
    k = np.hypot(kx, ky)
    nx, ny = kx / k, ky / k
    m = modal_profiles(k, z, solid, in_layer)
    return {"sigma_x": -nx * nx * m.W - 2 * m.nu * m.G, "sigma_y": -ny * ny * m.W - 2 * m.nu * m.G,
            "sigma_z": m.W - 2 * (1 - m.nu) * m.G, "tau_xy": -nx * ny * m.W,
            "tau_xz": 1j * nx * m.T, "tau_yz": 1j * ny * m.T}


# ---------------------------------------------------------------------------------------------------------------
# Depth planes
# ---------------------------------------------------------------------------------------------------------------

def depth_planes(depths: np.ndarray, solid: LayeredSolid, interface: bool = True
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Sorted depth planes (m) and their material (True = layer). Depths <= h are in the layer, deeper ones in
    the substrate (dropped on a rigid base). With ``interface`` the plane z = h is added on both sides."""
    z = np.asarray(depths, dtype=float).ravel()
    if z.size and (not np.all(np.isfinite(z)) or z.min() < 0):
        raise InputError("depths", "finite depths >= 0 m required")
    h = solid.thickness
    zs = [(float(v), bool(v <= h)) for v in z]
    if solid.rigid_substrate:
        zs = [p for p in zs if p[1]]
    if interface:
        zs = [p for p in zs if p[0] != h]
        zs += [(h, True)] + ([] if solid.rigid_substrate else [(h, False)])
    zs = sorted(set(zs), key=lambda p: (p[0], not p[1]))
    return np.array([p[0] for p in zs]), np.array([p[1] for p in zs], dtype=bool)


def default_depths(solid: LayeredSolid, contact_size: float, n: int = 40, depth_max: float = 3.0
                   ) -> np.ndarray:
    """Depths (m): n planes graded towards the surface down to depth_max x contact size, plus 8 uniform planes
    across the layer when it is thinner than that (the interface itself is added by :func:`depth_planes`)."""
    zmax = depth_max * contact_size
    z = np.concatenate([[0.0], hs_stress.graded_depths(zmax, n)])
    if solid.thickness < zmax:
        z = np.concatenate([z, np.linspace(0.0, solid.thickness, 9)[1:-1]])
    return np.unique(z)


# ---------------------------------------------------------------------------------------------------------------
# Closed-form cell kernels
# ---------------------------------------------------------------------------------------------------------------

def strip_stress(t: np.ndarray, z: float, width: float) -> dict[str, np.ndarray]:
    """Plane-strain stresses (Pa per Pa) of the homogeneous half-plane at depth z (m), lateral offset t (m) from
    the centre of a strip of ``width`` (m) carrying unit pressure (the transform pair of W, G, T with nu-free
    sigma_x, sigma_z, tau_xz; Johnson 1985 §2.6): -(1/pi)[atan(X/z) -+ z X/(X^2 + z^2)] and
    (z^2/pi)[1/(X^2 + z^2)], [F] = F(t + w/2) - F(t - w/2). z = 0 gives -1 under the strip, 0 outside."""
    t = np.asarray(t, dtype=float)
    xp, xm = t + 0.5 * width, t - 0.5 * width
    with np.errstate(divide="ignore", invalid="ignore"):
        at = (np.arctan2(xp, z) - np.arctan2(xm, z))
        fz = z * (xp / (xp * xp + z * z) - xm / (xm * xm + z * z)) if z > 0 else np.zeros_like(t)
        tz = z * z * (1.0 / (xp * xp + z * z) - 1.0 / (xm * xm + z * z)) if z > 0 else np.zeros_like(t)
    return {"sigma_x": -(at - fz) / np.pi, "sigma_z": -(at + fz) / np.pi, "tau_xz": tz / np.pi}


def strip_poisson(t: np.ndarray, zeta: float, width: float) -> np.ndarray:
    """Cell integral of the inverse transform of e^{-|k| zeta}, the Poisson kernel zeta / (pi (x^2 + zeta^2)):
    (1/pi)[atan((t + w/2)/zeta) - atan((t - w/2)/zeta)] (-), zeta > 0 (m)."""
    t = np.asarray(t, dtype=float)
    return (np.arctan((t + 0.5 * width) / zeta) - np.arctan((t - 0.5 * width) / zeta)) / np.pi


def rectangle_images(tx: np.ndarray, ty: np.ndarray, zeta: float, dx: float, dy: float) -> dict[str, np.ndarray]:
    """Cell integrals (-) over a dx x dy rectangle of unit pressure, at offset (tx, ty) (m), of the inverse 2D
    transforms of e^{-k zeta} ("E": (1/2pi) D[atan(a b/(zeta R))], Poisson kernel) and of n_a n_b e^{-k zeta}
    ("xx", "yy", "xy": (1/2pi) D[Phi_ab] with Love's Phi = int p ln(R + zeta) dA; Johnson 1985 eq 3.4 and
    femcheck.bem.stress). a, b = corner offsets xi - x, eta - y; R = sqrt(a^2 + b^2 + zeta^2); zeta > 0."""
    tx, ty = np.broadcast_arrays(np.asarray(tx, dtype=float), np.asarray(ty, dtype=float))

    def corner(a, b):
        R = np.sqrt(a * a + b * b + zeta * zeta)
        with np.errstate(divide="ignore", invalid="ignore"):
            return {"E": np.arctan(a * b / (zeta * R)),
                    "xx": np.arctan(b / a) - np.arctan(b * zeta / (a * R)),
                    "yy": np.arctan(a / b) - np.arctan(a * zeta / (b * R)),
                    "xy": np.log(R + zeta)}

    a1, a2 = -tx - 0.5 * dx, -tx + 0.5 * dx
    b1, b2 = -ty - 0.5 * dy, -ty + 0.5 * dy
    c22, c12, c21, c11 = corner(a2, b2), corner(a1, b2), corner(a2, b1), corner(a1, b1)
    return {key: (c22[key] - c12[key] - c21[key] + c11[key]) / (2.0 * np.pi) for key in c22}


# ---------------------------------------------------------------------------------------------------------------
# Residual spectra
# ---------------------------------------------------------------------------------------------------------------

def _residual_profiles(k: np.ndarray, z: float, in_layer: bool, solid: LayeredSolid, constants: np.ndarray
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """(rW, rG2, rZ, rT) = layered minus homogeneous (minus images in the layer) of W, 2 nu G, sigma_zz, T;
    all vanish at k = 0."""
    m = modal_profiles(k, z, solid, in_layer, constants)
    hom = homogeneous_profiles(k, z, m.nu)
    dW, dG = m.W - hom.W, m.G - hom.G
    rW, rG2 = dW, 2 * m.nu * dG
    if in_layer:
        c1, c2 = long_wave_limit(solid)
        img = np.exp(-k * (2 * solid.thickness - z))
        rW = rW - (c1 - (1 - 2 * m.nu)) * img
        rG2 = rG2 - (c2 - 2 * m.nu) * img
    return rW, rG2, dW - 2 * (1 - m.nu) * dG, m.T - hom.T


def slope_length(solid: LayeredSolid, depths: np.ndarray, in_layer: np.ndarray) -> float:
    """Length l (m) of the residual's cone at k = 0, max over the planes and the four residual profiles of
    |R(k1, z)| / k1 at k1 h, k1 z <= 1e-4, and at least h. The residual kernel's tail is ~ l / x^2 (2D) or
    l / r^3 (3D): l is about h for moderate contrasts but reaches 6 h (E1/E2 = 3) to 75 h (E1/E2 = 10, h/a = 0.01)
    for stiff layers (their plate-like bending), so the residual period is set by l, not by h."""
    h = solid.thickness
    out = h
    for z, lay in zip(depths, in_layer):
        k1 = np.array([1e-4 / max(h, float(z))])
        r = _residual_profiles(k1, float(z), bool(lay), solid, layer_constants(k1 * h, solid))
        out = max(out, max(abs(float(v[0])) for v in r) / float(k1[0]))
    return out


def _residual_count(n: int, d: float, dim: int, length: float) -> int:
    """FFT length per axis of the residual grid: period >= 2 n d and >= n d + c l (c = RESIDUAL_CLEARANCE)."""
    period = max(2.0 * n * d, n * d + RESIDUAL_CLEARANCE[dim] * length)
    return int(min(fft.next_fast_len(int(np.ceil(period / d)), real=True), MAX_POINTS[dim]))


# ---------------------------------------------------------------------------------------------------------------
# Fields
# ---------------------------------------------------------------------------------------------------------------

@dataclass
class LayeredStressField:
    """Stresses (Pa) on depth planes below a gridded pressure on a layered solid.

    ``x`` (and ``y`` in 3D, else None) cell centres (m); ``depths`` (nz,) m; ``in_layer`` (nz,) the material of
    each plane (z = h appears twice: layer side then substrate side); ``components[name]`` of shape (nz, nx)
    (plane strain: sigma_x, sigma_y, sigma_z, tau_xz) or (nz, nx, ny) (3D: the six components). ``stats``:
    residual grid and timing."""

    x: np.ndarray
    y: np.ndarray | None
    depths: np.ndarray
    in_layer: np.ndarray
    components: dict[str, np.ndarray]
    solid: LayeredSolid
    stats: dict = field(default_factory=dict)

    def _comp(self, name):
        c = self.components
        return c[name] if name in c else np.zeros_like(c["sigma_z"])

    def von_mises(self) -> np.ndarray:
        """sqrt(1/2 [(sx - sy)^2 + (sy - sz)^2 + (sz - sx)^2] + 3 (txy^2 + txz^2 + tyz^2)) (Pa)."""
        sx, sy, sz = self._comp("sigma_x"), self._comp("sigma_y"), self._comp("sigma_z")
        txy, txz, tyz = self._comp("tau_xy"), self._comp("tau_xz"), self._comp("tau_yz")
        return np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2)
                       + 3.0 * (txy ** 2 + txz ** 2 + tyz ** 2))

    def tresca(self) -> np.ndarray:
        """Maximum shear (sigma_1 - sigma_3)/2 (Pa) from the principal stresses at every point."""
        if self.y is None:
            return closed_stress.tresca(self.components)
        c = self.components
        T = np.stack([np.stack([c["sigma_x"], c["tau_xy"], c["tau_xz"]], -1),
                      np.stack([c["tau_xy"], c["sigma_y"], c["tau_yz"]], -1),
                      np.stack([c["tau_xz"], c["tau_yz"], c["sigma_z"]], -1)], -2)
        ev = np.linalg.eigvalsh(T)
        return 0.5 * (ev[..., -1] - ev[..., 0])

    def interface(self) -> dict[str, np.ndarray]:
        """The planes z = h on both sides: ``layer`` and ``substrate`` dicts of components (substrate absent on
        a rigid base). Normal traction sigma_z and shear tau_xz (tau_yz) must agree; in-plane stresses jump."""
        h = self.solid.thickness
        out = {}
        for side, flag in (("layer", True), ("substrate", False)):
            idx = np.flatnonzero((self.depths == h) & (self.in_layer == flag))
            if idx.size:
                out[side] = {k: v[idx[0]] for k, v in self.components.items()}
        if not out:
            raise InputError("depths", "the interface plane was not evaluated (depth_planes(..., interface=True))")
        return out

    def maxima(self, where: str = "all") -> dict[str, float]:
        """Maxima (Pa) and depths (m): von Mises, Tresca, |tau_xz| (refined by parabolas through neighbours of
        the same material), and on the interface the largest shear traction |tau_xz| (3D: the resultant) and
        normal traction |sigma_z| (from the layer side; the traction is continuous).

        ``where`` = "all", "layer" or "substrate" restricts the von Mises / Tresca / tau_xz maxima to the planes of
        that material. As h -> 0 the substrate's field tends to the homogeneous substrate's, but the layer's
        in-plane stresses do not (they follow the substrate's strain with the layer's moduli): a thin coating can
        hold the largest von Mises stress at the surface."""
        if where not in ("all", "layer", "substrate"):
            raise InputError("where", f"{where!r}; allowed all, layer, substrate")
        sel = np.ones(self.depths.size, bool) if where == "all" else (self.in_layer == (where == "layer"))
        if not sel.any():
            raise InputError("where", f"no depth plane in the {where}")
        out = {}
        for key, vals in (("von_mises_max", self.von_mises()), ("tau_max", self.tresca()),
                          ("tau_xz_max", np.abs(self.components["tau_xz"]))):
            m = _refined_max(vals[sel], self.depths[sel], self.in_layer[sel], self.x, self.y)
            out[key], out[f"{key}_depth"], out[f"{key}_x"] = m["value"], m["depth"], m["x"]
        try:
            side = self.interface()["layer"]
        except InputError:
            return out
        shear = np.hypot(side["tau_xz"], side.get("tau_yz", 0.0))
        out["interface_shear_max"] = float(shear.max())
        out["interface_normal_max"] = float(np.abs(side["sigma_z"]).max())
        return out


def _vertex(x3: np.ndarray, f3: np.ndarray) -> tuple[float, float]:
    """Vertex (position, value) of the parabola through three points; the middle point if it is not a maximum."""
    (x0, x1, x2), (f0, f1, f2) = x3, f3
    d = (x0 - x1) * (x0 - x2) * (x1 - x2)
    A = (x2 * (f1 - f0) + x1 * (f0 - f2) + x0 * (f2 - f1)) / d
    B = (x2 * x2 * (f0 - f1) + x1 * x1 * (f2 - f0) + x0 * x0 * (f1 - f2)) / d
    if A >= 0:
        return float(x1), float(f1)
    xv = float(np.clip(-B / (2 * A), x0, x2))
    return xv, float(f1 + A * (xv * xv - x1 * x1) + B * (xv - x1))


def _refined_max(values, depths, in_layer, x, y=None) -> dict[str, float]:
    k = np.unravel_index(np.argmax(values), values.shape)
    best = float(values[k])
    out = {"value": best}
    axes = [(0, depths, "depth"), (1, x, "x")] + ([(2, y, "y")] if y is not None else [])
    for axis, coords, name in axes:
        i = k[axis]
        pos = float(coords[i])
        ok = 0 < i < values.shape[axis] - 1
        if ok and axis == 0:   # never fit across the interface (the field jumps there)
            ok = in_layer[i - 1] == in_layer[i] == in_layer[i + 1] and coords[i - 1] < coords[i] < coords[i + 1]
        if ok:
            idx = [list(k) for _ in range(3)]
            for j, off in enumerate((-1, 0, 1)):
                idx[j][axis] = i + off
            pos, val = _vertex(np.asarray(coords[i - 1:i + 2], float), np.array([values[tuple(q)] for q in idx]))
            best = max(best, val)
        out[name] = abs(pos) if name == "x" else pos
    out["value"] = best
    return out


def line_stresses(pressure: np.ndarray, dx: float, solid: LayeredSolid, depths: np.ndarray,
                  x: np.ndarray | None = None, interface: bool = True) -> LayeredStressField:
    """Plane-strain stresses below a strip-wise uniform pressure (Pa) on n strips of width ``dx`` (m).

    ``depths`` (m) become planes by :func:`depth_planes` (z = h on both sides with ``interface``). Per plane:
    homogeneous strip kernels (nu of the plane's material) and, in the layer, Poisson image strips, by DC-FFT;
    plus the sampled residual (module docstring). ``x`` (m) only labels the cell centres in the result."""
    t0 = time.perf_counter()
    p = np.asarray(pressure, dtype=float)
    n = p.size
    if x is None:
        x = (np.arange(n) - 0.5 * (n - 1)) * dx
    z, lay = depth_planes(depths, solid, interface)
    h = solid.thickness
    ell = slope_length(solid, z, lay)
    count = _residual_count(n, dx, 1, ell)
    k = 2.0 * np.pi * fft.rfftfreq(count, dx)
    consts = layer_constants(k * h, solid)
    ph = fft.rfft(p, n=count) * np.sinc(k * dx / (2.0 * np.pi))
    c1, c2 = long_wave_limit(solid)
    comps = {name: np.empty((z.size, n)) for name in ("sigma_x", "sigma_y", "sigma_z", "tau_xz")}
    for i, (zi, li) in enumerate(zip(z, lay)):
        nu = solid.nu_layer if li else solid.nu_substrate
        kern: dict[str, np.ndarray] = {}

        def kernel(name, zi=zi, li=li, nu=nu, kern=kern):
            def f(t):
                if not kern:
                    kern.update(strip_stress(t, zi, dx))
                    if li:   # 2D: n n = 1, so both image terms act on sigma_x
                        kern["sigma_x"] = kern["sigma_x"] - (c1 + c2 - 1.0) * strip_poisson(t, 2 * h - zi, dx)
                return kern[name]
            return f

        rW, rG2, rZ, rT = _residual_profiles(k, zi, li, solid, consts)
        res = {"sigma_x": -rW - rG2, "sigma_z": rZ, "tau_xz": 1j * rT}
        for name in ("sigma_x", "sigma_z", "tau_xz"):
            direct = DCFFT(kernel(name), (n,), (dx,), workers=1)(p)
            comps[name][i] = direct + fft.irfft(ph * res[name], n=count)[:n]
        comps["sigma_y"][i] = nu * (comps["sigma_x"][i] + comps["sigma_z"][i])   # plane strain
    stats = {"residual_points": count, "residual_period": count * dx, "residual_slope_length": ell, "planes": int(z.size),
             "time_s": time.perf_counter() - t0}
    return LayeredStressField(np.asarray(x, float), None, z, lay, comps, solid, stats)


def point_stresses(pressure: np.ndarray, grid: Grid, solid: LayeredSolid, depths: np.ndarray,
                   interface: bool = True) -> LayeredStressField:
    """3D stresses (six components) below a cell-wise uniform pressure (Pa) on ``grid``, on the depth planes of
    :func:`depth_planes`: Love's rectangle kernels (:mod:`femcheck.bem.stress`, nu of the plane's material) and,
    in the layer, the image kernels of :func:`rectangle_images`, by DC-FFT; plus the sampled residual."""
    t0 = time.perf_counter()
    p = np.asarray(pressure, dtype=float)
    if p.shape != (grid.nx, grid.ny):
        raise InputError("pressure", f"shape {p.shape} does not match the grid ({grid.nx}, {grid.ny})")
    z, lay = depth_planes(depths, solid, interface)
    h = solid.thickness
    ell = slope_length(solid, z, lay)
    counts = (_residual_count(grid.nx, grid.dx, 2, ell), _residual_count(grid.ny, grid.dy, 2, ell))
    kx = 2.0 * np.pi * fft.fftfreq(counts[0], grid.dx)[:, None]
    ky = 2.0 * np.pi * fft.rfftfreq(counts[1], grid.dy)[None, :]
    kabs = np.hypot(kx, ky)
    # one solve per distinct |k| (the grid's symmetries repeat them)
    uniq, inv = np.unique(kabs, return_inverse=True)
    consts = layer_constants(uniq * h, solid)
    with np.errstate(invalid="ignore", divide="ignore"):
        nx_, ny_ = np.where(kabs > 0, kx / kabs, 0.0), np.where(kabs > 0, ky / kabs, 0.0)
    ph = fft.rfftn(p, s=counts) * (np.sinc(kx * grid.dx / (2 * np.pi)) * np.sinc(ky * grid.dy / (2 * np.pi)))
    c1, c2 = long_wave_limit(solid)
    names = hs_stress.COMPONENTS
    comps = {name: np.empty((z.size, grid.nx, grid.ny)) for name in names}
    shape = (grid.nx, grid.ny)
    for mat in (True, False):
        sel = np.flatnonzero(lay == mat)
        if not sel.size:
            continue
        nu = solid.nu_layer if mat else solid.nu_substrate
        # homogeneous half-space of this material: Love's rectangle kernels (z = 0 is approached from below:
        # the kernels' z -> 0 limit holds at cell centres, a tiny depth avoids 0/0)
        zz = np.maximum(z[sel], 1e-12 * min(grid.dx, grid.dy))
        hom = hs_stress.subsurface_stresses(p, grid, zz, nu, workers=1)
        for name in names:
            comps[name][sel] = hom.components[name]
    for i, (zi, li) in enumerate(zip(z, lay)):
        if li:
            kern: dict[str, np.ndarray] = {}

            def kernel(name, zeta=2 * h - zi, kern=kern):
                def f(tx, ty):
                    if not kern:
                        kern.update(rectangle_images(tx, ty, zeta, grid.dx, grid.dy))
                    return kern[name]
                return f

            img = {key: DCFFT(kernel(key), shape, (grid.dx, grid.dy), workers=1)(p) for key in ("E", "xx", "yy", "xy")}
            comps["sigma_x"][i] -= (c1 - (1 - 2 * solid.nu_layer)) * img["xx"] + (c2 - 2 * solid.nu_layer) * img["E"]
            comps["sigma_y"][i] -= (c1 - (1 - 2 * solid.nu_layer)) * img["yy"] + (c2 - 2 * solid.nu_layer) * img["E"]
            comps["tau_xy"][i] -= (c1 - (1 - 2 * solid.nu_layer)) * img["xy"]
        rW, rG2, rZ, rT = (r[inv].reshape(kabs.shape) for r in _residual_profiles(uniq, zi, li, solid, consts))
        res = {"sigma_x": -nx_ * nx_ * rW - rG2, "sigma_y": -ny_ * ny_ * rW - rG2, "sigma_z": rZ,
               "tau_xy": -nx_ * ny_ * rW, "tau_xz": 1j * nx_ * rT, "tau_yz": 1j * ny_ * rT}
        for name in names:
            comps[name][i] += fft.irfftn(ph * res[name], s=counts)[:grid.nx, :grid.ny]
    stats = {"residual_points": list(counts), "residual_period": [counts[0] * grid.dx, counts[1] * grid.dy],
             "residual_slope_length": ell,
             "planes": int(z.size), "time_s": time.perf_counter() - t0}
    return LayeredStressField(grid.x, grid.y, z, lay, comps, solid, stats)


__all__ = ["shear_modulus_ratio", "layer_constants", "ModalProfiles", "modal_profiles", "homogeneous_profiles",
           "long_wave_limit", "plane_strain_response", "response_3d", "depth_planes", "default_depths",
           "strip_stress", "strip_poisson", "rectangle_images", "LayeredStressField", "line_stresses",
           "point_stresses"]
