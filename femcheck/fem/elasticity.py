"""Linear elasticity of one body with scikit-fem (plane strain in 2D), and its condensed compliance."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.sparse import csc_matrix
from scipy.sparse.linalg import splu
from skfem import Basis, ElementTriP1, ElementTriP2, ElementVector, MeshTri, asm
from skfem.models.elasticity import linear_elasticity

from ..materials import Elastic
from .mesh2d import TriMesh

_ELEMENTS = {1: ElementTriP1, 2: ElementTriP2}


@dataclass
class Body:
    """A meshed elastic body: scikit-fem ``basis`` (vector P1/P2), stiffness ``K`` (N/m per m thickness)."""

    basis: Basis
    K: csc_matrix
    material: Elastic

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]


def make_body(mesh: TriMesh, material: Elastic, order: int) -> Body:
    """Assemble the plane-strain stiffness a(u, v) = int C eps(u) : eps(v) dx on ``mesh`` with P``order``.

    Quadrature is exact for the element order (2*(order-1)), which FEM-NOTES found matters for speed.
    """
    if order not in _ELEMENTS:
        raise ValueError(f"element order {order} not supported (1 or 2)")
    m = MeshTri(mesh.points, mesh.triangles)
    basis = Basis(m, ElementVector(_ELEMENTS[order]()), intorder=max(1, 2 * (order - 1)))
    lam, mu = material.lame()
    K = asm(linear_elasticity(lam, mu), basis).tocsc()
    return Body(basis, K, material)


def boundary_dofs(basis: Basis, where, component: int) -> np.ndarray:
    """Global DOFs of displacement ``component`` (0 = x, 1 = y) on boundary facets whose midpoints satisfy
    ``where(x)``, sorted by the DOF's x coordinate."""
    d = basis.get_dofs(where)
    name = f"u^{component + 1}"
    dofs = np.concatenate([d.nodal.get(name, np.empty(0, int)), d.facet.get(name, np.empty(0, int))])
    dofs = np.unique(dofs)
    return dofs[np.argsort(basis.doflocs[0, dofs], kind="stable")]


class CondensedBody:
    """Static condensation of a body onto a set of DOFs: K_ff factorised once (SuperLU), then the compliance
    C = P K_ff^-1 P^T at the contact DOFs and responses to prescribed displacements by back substitution."""

    def __init__(self, body: Body, fixed: np.ndarray):
        self.body = body
        n = body.n_dofs
        self.fixed = np.unique(fixed)
        self.free = np.setdiff1d(np.arange(n), self.fixed)
        self._index = np.full(n, -1)
        self._index[self.free] = np.arange(self.free.size)
        # Minimum degree on A^T + A with symmetric mode suits SPD stiffness matrices: on a 164k-DOF P2 block
        # it halved both fill and factorisation time compared with COLAMD.
        self._lu = splu(body.K[self.free][:, self.free].tocsc(), permc_spec="MMD_AT_PLUS_A",
                        options={"SymmetricMode": True})

    def compliance(self, dofs: np.ndarray) -> np.ndarray:
        """Dense matrix C_ij = displacement at dof i per unit force at dof j (m per N/m)."""
        idx = self._index[dofs]
        if (idx < 0).any():
            raise ValueError("a contact DOF is constrained")
        rhs = np.zeros((self.free.size, dofs.size))
        rhs[idx, np.arange(dofs.size)] = 1.0
        return self._lu.solve(rhs)[idx]

    def response(self, prescribed: dict[int, float] | np.ndarray, dofs: np.ndarray) -> np.ndarray:
        """Displacements at ``dofs`` (free) when the fixed DOFs take the values ``prescribed`` (full-length
        vector over all DOFs, fixed entries used) and no force acts: u_f = -K_ff^-1 K_fd u_d."""
        ud = np.asarray(prescribed, dtype=float)
        rhs = -(self.body.K[self.free][:, self.fixed] @ ud[self.fixed])
        uf = self._lu.solve(rhs)
        return uf[self._index[dofs]]
