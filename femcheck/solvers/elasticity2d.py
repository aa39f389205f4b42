"""Linear elasticity of one body with scikit-fem (plane strain in 2D), and its condensed compliance."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import bmat, csc_matrix, diags
from scipy.sparse.linalg import splu
from skfem import BilinearForm, Basis, ElementTriP1, ElementTriP2, ElementVector, MeshTri, asm
from skfem.helpers import ddot, div, sym_grad
from skfem.models.elasticity import linear_elasticity

from ..errors import ConvergenceError
from ..materials import Elastic
from ..meshes.plane import TriMesh

_ELEMENTS = {1: ElementTriP1, 2: ElementTriP2}


@dataclass
class Body:
    """A meshed elastic body: scikit-fem displacement ``basis`` (vector P1/P2) and system matrix ``K``.

    Displacement DOFs come first (numbered as in ``basis``); a mixed body appends its pressure DOFs.
    """

    basis: Basis
    K: csc_matrix
    material: Elastic
    formulation: str = "displacement"

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]

    @property
    def n_displacement_dofs(self) -> int:
        return self.basis.N


@BilinearForm
def _deviatoric_part(u, v, w):
    return 2.0 * ddot(sym_grad(u), sym_grad(v))


@BilinearForm
def _divergence(u, q, w):
    return q * div(u)


@BilinearForm
def _mass(p, q, w):
    return p * q


# Above this Poisson's ratio the displacement formulation locks: measured on hertz-line (P2, 3 levels) the
# extrapolated p_max was 0.03 % off Hertz at nu = 0.45 but 0.31 % at 0.499 and 1.6 % at 0.4999.
MIXED_ABOVE_NU = 0.45


def make_body(mesh: TriMesh, material: Elastic, order: int, formulation: str = "auto") -> Body:
    """Assemble the plane-strain system on ``mesh`` with P``order`` displacements.

    ``displacement``: K = int C eps(u) : eps(v) dx.
    ``mixed`` (Taylor-Hood P2/P1, locking-free up to nu -> 1/2): unknowns (u, p) with p = lambda div u,
        [ int 2 mu eps(u):eps(v)   int p div v      ] = [f]
        [ int q div u             -int p q / lambda ]   [0]
    ``auto`` takes ``mixed`` when nu > MIXED_ABOVE_NU (needs order 2).
    Quadrature is exact for the element order (2*(order-1)), which FEM-NOTES found matters for speed.
    """
    if order not in _ELEMENTS:
        raise ValueError(f"element order {order} not supported (1 or 2)")
    if formulation == "auto":
        formulation = "mixed" if material.nu > MIXED_ABOVE_NU and order == 2 else "displacement"
    m = MeshTri(mesh.points, mesh.triangles)
    basis = Basis(m, ElementVector(_ELEMENTS[order]()), intorder=max(1, 2 * (order - 1)))
    lam, mu = material.lame()
    if formulation == "displacement":
        K = asm(linear_elasticity(lam, mu), basis).tocsc()
    elif formulation == "mixed":
        if order != 2:
            raise ValueError("the mixed formulation is Taylor-Hood P2/P1: element order 2 required")
        bp = basis.with_element(ElementTriP1())
        B = asm(_divergence, basis, bp)
        K = bmat([[mu * asm(_deviatoric_part, basis), B.T], [B, -asm(_mass, bp) / lam]]).tocsc()
    else:
        raise ValueError(f"formulation {formulation!r} unknown (auto, displacement, mixed)")
    return Body(basis, K, material, formulation)


def boundary_dofs(basis: Basis, where, component: int) -> np.ndarray:
    """Global DOFs of displacement ``component`` (0 = x, 1 = y) on boundary facets whose midpoints satisfy
    ``where(x)``, sorted by the DOF's x coordinate. (``Basis.get_dofs(callable)`` alone also takes interior
    facets whose midpoints pass the test.)"""
    d = basis.get_dofs(basis.mesh.facets_satisfying(where, boundaries_only=True))
    name = f"u^{component + 1}"
    dofs = np.concatenate([d.nodal.get(name, np.empty(0, int)), d.facet.get(name, np.empty(0, int))])
    dofs = np.unique(dofs)
    return dofs[np.argsort(basis.doflocs[0, dofs], kind="stable")]


class CondensedBody:
    """Static condensation of a body onto a set of DOFs: K_ff factorised once (SuperLU), then the compliance
    C = P K_ff^-1 P^T at the contact DOFs and responses to prescribed displacements by back substitution.

    K_ff is equilibrated symmetrically first, D K D with D_i = 1/sqrt(max_j |K_ij|): in the mixed
    formulation the constraint rows (entries ~ element size, 1e-5 m) are otherwise 1e16 times smaller than
    the force rows (~ modulus), and the direct solver returned a different, wrong solution with a tiny
    residual.
    """

    def __init__(self, body: Body, fixed: np.ndarray):
        self.body = body
        n = body.n_dofs
        self.fixed = np.unique(fixed)
        self.free = np.setdiff1d(np.arange(n), self.fixed)
        self._index = np.full(n, -1)
        self._index[self.free] = np.arange(self.free.size)
        K = body.K[self.free][:, self.free].tocsc()
        self._d = 1.0 / np.sqrt(abs(K).max(axis=1).toarray().ravel())
        self._Ks = (diags(self._d) @ K @ diags(self._d)).tocsc()
        # Minimum degree on A^T + A, symmetric mode, diagonal pivots only: SPD and quasi-definite
        # ([[A, B^T], [B, -C]], mixed form) matrices factorise stably in any symmetric order (Vanderbei 1995).
        # Against threshold pivoting this cut fill 13x and factorisation time 45x on a mixed P2/P1 block;
        # against COLAMD it halved fill on a 164k-DOF P2 block. Solves are residual-checked (see _solve).
        self._lu = splu(self._Ks, permc_spec="MMD_AT_PLUS_A",
                        options={"SymmetricMode": True, "DiagPivotThresh": 0.0})
        self.pivoting = "diagonal"

    def _solve(self, rhs: np.ndarray) -> np.ndarray:
        d = self._d if rhs.ndim == 1 else self._d[:, None]
        r = d * rhs
        y = self._lu.solve(r)
        if np.abs(self._Ks @ y - r).max() > 1e-9 * max(np.abs(r).max(), 1e-300) and self.pivoting == "diagonal":
            # a tiny diagonal pivot spoiled the solve: refactorise with threshold partial pivoting
            self._lu = splu(self._Ks, permc_spec="MMD_AT_PLUS_A", options={"SymmetricMode": True})
            self.pivoting = "threshold"
            y = self._lu.solve(r)
        residual = np.abs(self._Ks @ y - r).max() / max(np.abs(r).max(), 1e-300)
        if residual > 1e-9:
            raise ConvergenceError("sparse direct solve", 1, residual, 1e-9, "stiffness matrix is singular "
                                   "or too ill-conditioned")
        return d * y

    def compliance(self, dofs: np.ndarray) -> np.ndarray:
        """Dense matrix C_ij = displacement at dof i per unit force at dof j (m per N/m)."""
        idx = self._index[dofs]
        if (idx < 0).any():
            raise ValueError("a contact DOF is constrained")
        rhs = np.zeros((self.free.size, dofs.size))
        rhs[idx, np.arange(dofs.size)] = 1.0
        return self._solve(rhs)[idx]

    def response(self, prescribed: np.ndarray, dofs: np.ndarray) -> np.ndarray:
        """Displacements at ``dofs`` (free) when the fixed DOFs take the values ``prescribed`` (full-length
        vector over all DOFs, fixed entries used) and no force acts: u_f = -K_ff^-1 K_fd u_d."""
        ud = np.asarray(prescribed, dtype=float)
        rhs = -(self.body.K[self.free][:, self.fixed] @ ud[self.fixed])
        return self._solve(rhs)[self._index[dofs]]
