"""Developed (x, s) contact grids for the 3D frictional FE reference: the interface between the geometry
(pose, exact gap, rigid slip, kappa; spec srb-rolling §2.3-2.5) and the FE compliances and contact solver.

A contact's potential surface is prismatic (seed 000 §3.2, Fig. 4; spec §2.3): a profile circle of radius r_g
and centre G in the plane through the reference point perpendicular to the rolling direction e_x, extruded along
e_x. With m0 the unit vector from G to the reference point s = 0 and tau0 the profile tangent there (+s):

    P0(x, s) = G + r_g (cos(s/r_g) m0 + sin(s/r_g) tau0) + x e_x                      (m)
    n(s) = -(cos(s/r_g) m0 + sin(s/r_g) tau0)   unit normal into body 1 (towards G: a concave groove)
    t(s) = -sin(s/r_g) m0 + cos(s/r_g) tau0      unit tangent, +s

(the same fields and formulas as the conformal CECT's ``ProfileSurface``, so its developed grids plug in through
:meth:`ContactGrid.of`). ``radius = inf`` is the planar limit: then ``centre`` is the reference point itself,
P0 = centre + s tau0 + x e_x and n = -m0 (used for the half-space checks).

Conventions (femcheck's exact theory, :mod:`femcheck.cect.exact`): body 1 is the roller (the crowned body),
tractions p = (p_x, p_s, p_n) act on body 1 in the local frame (e_x, t(s), n(s)), p_n > 0 compressive; the
material of both bodies flows through the grid along -e_x (leading edge at +x); u = u(body 1) - u(body 2), whose
normal component is the elastic opening of the gap. The triad (e_x, t, n) may be left-handed; everything is
written with explicit vectors.

Cells: ``x`` (nx,) and ``s`` (ns,) cell centres with constant spacings dx, ds (m), element area dx ds (the
x-curvature metric correction is O(x^2/rho^2) < 1e-4, spec §2.3). Arrays on a grid are (nx, ns).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


@dataclass(frozen=True, eq=False)
class ContactGrid:
    """One contact's developed grid (module docstring). Vectors are 3-vectors in the frame of the model that
    built the grid (for the bearing: the roller frame of the FE model, see :mod:`femcheck.fem.srb_rolling`)."""

    centre: np.ndarray
    radius: float
    m0: np.ndarray
    tau0: np.ndarray
    ex: np.ndarray
    x: np.ndarray
    s: np.ndarray
    name: str = "contact"

    def __post_init__(self):
        for k in ("centre", "m0", "tau0", "ex"):
            object.__setattr__(self, k, np.asarray(getattr(self, k), dtype=float).reshape(3))
        for k in ("m0", "tau0", "ex"):
            object.__setattr__(self, k, _unit(getattr(self, k)))
        object.__setattr__(self, "x", np.asarray(self.x, dtype=float).ravel())
        object.__setattr__(self, "s", np.asarray(self.s, dtype=float).ravel())
        if abs(self.m0 @ self.tau0) > 1e-9 or abs(self.m0 @ self.ex) > 1e-9 or abs(self.tau0 @ self.ex) > 1e-9:
            raise ValueError("m0, tau0 and ex must be mutually orthogonal")
        for name, v in (("x", self.x), ("s", self.s)):
            if v.size > 1 and not np.allclose(np.diff(v), v[1] - v[0], rtol=1e-9, atol=0.0):
                raise ValueError(f"{name} cell centres must be equally spaced")
        if not self.radius > 0:
            raise ValueError("the profile radius must be > 0 (inf: planar)")

    @classmethod
    def of(cls, developed, name: str = "contact") -> "ContactGrid":
        """From any developed grid with attributes ``surface`` (``centre``, ``radius``, ``m0``, ``tau0``,
        ``ex``), ``x`` and ``s`` (the conformal CECT's ``DevelopedGrid``)."""
        sf = developed.surface
        return cls(sf.centre, float(sf.radius), sf.m0, sf.tau0, sf.ex, developed.x, developed.s, name)

    # geometry -------------------------------------------------------------------------------------------------
    @property
    def nx(self) -> int:
        return self.x.size

    @property
    def ns(self) -> int:
        return self.s.size

    @property
    def dx(self) -> float:
        return float(self.x[1] - self.x[0]) if self.nx > 1 else float("nan")

    @property
    def ds(self) -> float:
        return float(self.s[1] - self.s[0]) if self.ns > 1 else float("nan")

    @property
    def cell_area(self) -> float:
        return self.dx * self.ds

    @property
    def planar(self) -> bool:
        return not np.isfinite(self.radius)

    def _cs(self, s):
        th = np.asarray(s, dtype=float)[..., None] / self.radius
        return np.cos(th), np.sin(th)

    def profile_point(self, s) -> np.ndarray:
        """P0(0, s) (..., 3) (m)."""
        s = np.asarray(s, dtype=float)
        if self.planar:
            return self.centre + s[..., None] * self.tau0
        c, sn = self._cs(s)
        return self.centre + self.radius * (c * self.m0 + sn * self.tau0)

    def normal(self, s) -> np.ndarray:
        """n(s) (..., 3): unit normal into body 1."""
        s = np.asarray(s, dtype=float)
        if self.planar:
            return np.broadcast_to(-self.m0, s.shape + (3,)).copy()
        c, sn = self._cs(s)
        return -(c * self.m0 + sn * self.tau0)

    def tangent(self, s) -> np.ndarray:
        """t(s) (..., 3): unit profile tangent (+s)."""
        s = np.asarray(s, dtype=float)
        if self.planar:
            return np.broadcast_to(self.tau0, s.shape + (3,)).copy()
        c, sn = self._cs(s)
        return -sn * self.m0 + c * self.tau0

    def frame(self, s) -> np.ndarray:
        """(..., 3, 3) local frames, rows e_x, t(s), n(s): the (x, s, n) components of a vector v are frame @ v."""
        t, n = self.tangent(s), self.normal(s)
        return np.stack([np.broadcast_to(self.ex, t.shape), t, n], axis=-2)

    def point(self, x, s) -> np.ndarray:
        """P0(x, s) (..., 3) (m), x and s broadcast."""
        x, s = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(s, dtype=float))
        return self.profile_point(s) + x[..., None] * self.ex

    def cell_centres(self) -> np.ndarray:
        """(nx, ns, 3) element centres P0(x_i, s_k)."""
        return self.point(self.x[:, None], self.s[None, :])

    def developed(self, P: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Developed coordinates of points P (..., 3) near the surface: (x, s, nu) with nu the offset along n
        (m; > 0 towards body 1). Inverse of :meth:`point` for points on the surface."""
        P = np.asarray(P, dtype=float)
        if self.planar:
            d = P - self.centre
            return d @ self.ex, d @ self.tau0, -(d @ self.m0)
        d = P - self.centre
        x = d @ self.ex
        a, b = d @ self.m0, d @ self.tau0
        s = self.radius * np.arctan2(b, a)
        return x, s, self.radius - np.hypot(a, b)

    def transformed(self, rotation: np.ndarray, translation: np.ndarray) -> "ContactGrid":
        """The same grid in another frame: P' = rotation @ P + translation (rotation proper orthogonal)."""
        R = np.asarray(rotation, dtype=float)
        return ContactGrid(R @ self.centre + np.asarray(translation, dtype=float), self.radius, R @ self.m0,
                           R @ self.tau0, R @ self.ex, self.x, self.s, self.name)

    def with_cells(self, x, s) -> "ContactGrid":
        return ContactGrid(self.centre, self.radius, self.m0, self.tau0, self.ex, x, s, self.name)


def refined_count(n0: int, factor: float) -> int:
    """Cells of a level refined by ``factor`` from ``n0`` coarsest cells: n0 factor rounded up to an odd count (a
    cell centred on the reference point). The caller widens its window by n / (n0 factor) (less than two cells)
    so that the cell size is the coarsest one's / factor exactly (a constant refinement ratio for the
    certificates)."""
    k = int(np.ceil(n0 * factor - 1e-9))
    return k if k % 2 else k + 1


def centred_cells(half: float, n: int, centre: float = 0.0) -> np.ndarray:
    """n equal cells over centre + [-half, half] (m): their centres."""
    d = 2.0 * half / n
    return centre + (np.arange(n) - 0.5 * (n - 1)) * d


@dataclass
class ContactInput:
    """What the FE contact solver needs of one contact at a given pose (spec §2.4-2.5, §4.2 step 2):
    ``grid``; ``gap`` h (nx, ns) (m; > 0 open, the rigid approach included; np.inf where no body surface);
    ``slip`` rigid slip (w_x, w_s) (2, nx, ns) (m/s) of body 1 relative to body 2 along e_x and t(s);
    ``speed`` V_ref (m/s); ``kappa`` (ns,) = V(s)/V_ref (variable rolling step, eq 21; None = 1)."""

    grid: ContactGrid
    gap: np.ndarray
    slip: np.ndarray
    speed: float
    kappa: np.ndarray | None = None
    extra: dict = field(default_factory=dict)

    def __post_init__(self):
        shape = (self.grid.nx, self.grid.ns)
        self.gap = np.asarray(self.gap, dtype=float)
        self.slip = np.asarray(self.slip, dtype=float)
        if self.gap.shape != shape or self.slip.shape != (2,) + shape:
            raise ValueError(f"gap must be {shape} and slip (2,) + {shape}")
        if self.kappa is None:
            self.kappa = np.ones(self.grid.ns)
        self.kappa = np.asarray(self.kappa, dtype=float).ravel()
        if self.kappa.size != self.grid.ns or not np.all(self.kappa > 0):
            raise ValueError("kappa must be (ns,) and > 0")
        if not self.speed > 0:
            raise ValueError("the reference rolling speed V_ref must be > 0")
