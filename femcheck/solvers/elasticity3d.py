"""3D linear elasticity with scikit-fem, and the AMG-preconditioned CG solver the 3D contact models share.

Stiffness: vector P1 (or P2) tetrahedra, skfem's ``linear_elasticity`` form with an explicit quadrature order
(FEM-NOTES: the default rule is 2-3x slower for no gain). Solver: pyamg smoothed aggregation built once per
mesh on the matrix of the free DOFs, with the six rigid-body modes as near-null space (FEM-NOTES: 22-23 CG
iterations at any size, 37 without them), used as preconditioner to CG.

Contact sets change the Dirichlet set between active-set iterations but not the matrix. Rather than rebuild the
hierarchy each time, :meth:`AMGElasticity.solve` runs CG on the subspace of DOFs not prescribed (operator and
preconditioner both masked: P K P and P M P, symmetric on that subspace), with the one hierarchy.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import pyamg
from scipy.sparse import csr_matrix
from scipy.sparse import diags
from scipy.sparse.linalg import LinearOperator, cg, splu
from skfem import Basis, ElementTetP1, ElementTetP2, ElementVector, MeshTet, asm
from skfem.models.elasticity import linear_elasticity

from ..errors import ConvergenceError
from ..materials import Elastic
from ..meshes.block import TetMesh

_ELEMENTS = {1: (ElementTetP1, 1), 2: (ElementTetP2, 2)}     # element, quadrature order (exact for K)


@dataclass
class Solid:
    """A meshed 3D body: skfem ``basis`` (vector, DOFs interleaved x, y, z per node) and stiffness ``K``."""

    basis: Basis
    K: csr_matrix
    material: Elastic

    @property
    def n_dofs(self) -> int:
        return self.K.shape[0]


def make_solid(mesh: TetMesh, material: Elastic, order: int = 1) -> Solid:
    """Assemble the stiffness of ``mesh`` (N/m) for an isotropic ``material``."""
    if material.rigid:
        raise ValueError("a rigid body has no stiffness to assemble")
    elem, intorder = _ELEMENTS[order]
    m = MeshTet(np.ascontiguousarray(mesh.points), np.ascontiguousarray(mesh.tets))
    basis = Basis(m, ElementVector(elem()), intorder=intorder)
    lam, mu = material.lame()
    K = asm(linear_elasticity(lam, mu), basis).tocsr()
    return Solid(basis, K, material)


def rigid_body_modes(x: np.ndarray) -> np.ndarray:
    """(3N, 6) translations and infinitesimal rotations of nodes ``x`` (3, N), interleaved DOF order."""
    n = x.shape[1]
    B = np.zeros((3 * n, 6))
    for k in range(3):
        B[k::3, k] = 1.0
    c = x - x.mean(axis=1, keepdims=True)
    B[0::3, 3], B[1::3, 3] = -c[1], c[0]          # rotation about z
    B[1::3, 4], B[2::3, 4] = -c[2], c[1]          # about x
    B[0::3, 5], B[2::3, 5] = c[2], -c[0]          # about y
    return B


@dataclass
class SolveInfo:
    iterations: int
    residual: float
    time_s: float


class AMGElasticity:
    """CG with a smoothed-aggregation AMG preconditioner on the DOFs ``free`` of ``solid``.

    ``dof_points`` (3, n_dofs) are the locations of the DOFs (the rigid-body modes are built from the node of
    each DOF). ``tol`` is CG's relative residual; a solve that misses it raises :class:`ConvergenceError`.
    """

    def __init__(self, solid: Solid, free: np.ndarray, tol: float = 1e-10, max_iter: int = 500):
        t0 = time.perf_counter()
        self.solid, self.free, self.tol, self.max_iter = solid, np.asarray(free), tol, max_iter
        self.A = solid.K[self.free][:, self.free].tocsr()
        nodes = solid.basis.doflocs[:, ::3]                  # one location per node (x, y, z DOFs share it)
        B = rigid_body_modes(nodes)[self.free]
        self.amg = pyamg.smoothed_aggregation_solver(self.A, B=B, symmetry="symmetric",
                                                     presmoother=("block_gauss_seidel", {"sweep": "symmetric"}),
                                                     postsmoother=("block_gauss_seidel", {"sweep": "symmetric"}))
        self.M = self.amg.aspreconditioner(cycle="V")
        self.setup_s = time.perf_counter() - t0

    def solve(self, rhs: np.ndarray, prescribed: np.ndarray | None = None, values: np.ndarray | None = None,
              x0: np.ndarray | None = None, spring: np.ndarray | None = None) -> tuple[np.ndarray, SolveInfo]:
        """Solve (K + diag(spring)) u = rhs on the free DOFs with u[prescribed] = values (indices into the free
        DOFs; ``spring`` in N/m per DOF, e.g. contact penalties).

        Returns u on the free DOFs. The prescribed values enter as -K[:, P] u_P on the right-hand side and CG
        runs on the remaining DOFs, preconditioned by the one AMG hierarchy of K masked to them (the springs
        only stiffen the operator, so the hierarchy stays a good preconditioner).
        """
        t0 = time.perf_counter()
        n = self.A.shape[0]
        mask = np.ones(n)
        u_p = np.zeros(n)
        if prescribed is not None and len(prescribed):
            mask[prescribed] = 0.0
            u_p[prescribed] = values
        b = mask * (rhs - self.A @ u_p)
        k = np.zeros(n) if spring is None else mask * spring
        op = LinearOperator((n, n), matvec=lambda x: mask * (self.A @ (mask * x)) + k * x, dtype=float)
        pre = LinearOperator((n, n), matvec=lambda r: mask * self.M(mask * r), dtype=float)
        its = [0]

        def count(_):
            its[0] += 1

        start = None if x0 is None else mask * x0
        bnorm = float(np.linalg.norm(b)) or 1.0
        x, info = cg(op, b, x0=start, rtol=self.tol, atol=0.0, maxiter=self.max_iter, M=pre, callback=count)
        res = float(np.linalg.norm(b - op(x)) / bnorm)
        if info != 0 or res > 10 * self.tol:
            raise ConvergenceError("AMG-preconditioned CG", its[0], res, self.tol)
        return mask * x + u_p, SolveInfo(its[0], res, time.perf_counter() - t0)


class DirectElasticity:
    """Sparse LU (SuperLU, COLAMD ordering) on the DOFs ``free`` of ``solid``, with the interface of
    :class:`AMGElasticity`. Each distinct Dirichlet set / spring vector is factorised once (an active-set
    iteration solves twice with the same one). For small meshes only: FEM-NOTES measured SuperLU unusable above
    ~30k DOFs in 3D."""

    def __init__(self, solid: Solid, free: np.ndarray, tol: float = 1e-10):
        t0 = time.perf_counter()
        self.solid, self.free, self.tol = solid, np.asarray(free), tol
        self.A = solid.K[self.free][:, self.free].tocsr()
        self._key, self._lu, self._keep, self._M = None, None, None, None
        self.setup_s = time.perf_counter() - t0

    def solve(self, rhs: np.ndarray, prescribed: np.ndarray | None = None, values: np.ndarray | None = None,
              x0: np.ndarray | None = None, spring: np.ndarray | None = None) -> tuple[np.ndarray, SolveInfo]:
        t0 = time.perf_counter()
        n = self.A.shape[0]
        keep = np.ones(n, dtype=bool)
        u = np.zeros(n)
        if prescribed is not None and len(prescribed):
            keep[prescribed] = False
            u[prescribed] = values
        key = (keep.tobytes(), None if spring is None else np.asarray(spring).tobytes())
        if key != self._key:
            self._M = self.A if spring is None else self.A + diags(spring)
            idx = np.flatnonzero(keep)
            self._lu = splu(self._M[idx][:, idx].tocsc(), permc_spec="COLAMD")
            self._key, self._keep = key, idx
        M = self._M
        b = rhs - self.A @ u
        u[self._keep] = self._lu.solve(b[self._keep])
        r = (M @ u - rhs)[self._keep]
        res = float(np.linalg.norm(r) / (np.linalg.norm(b[self._keep]) or 1.0))
        if not np.isfinite(res) or res > 1e3 * self.tol:
            raise ConvergenceError("sparse LU", 1, res, 1e3 * self.tol, "inaccurate factorisation")
        return u, SolveInfo(1, res, time.perf_counter() - t0)


# AMG-CG beat SuperLU already at 6k DOFs on the hertz-point contact solve (0.32 s against 0.51 s; at 40k DOFs
# 5.1 s against 27.6 s), so LU is only chosen for tiny models, where the AMG set-up would dominate.
DIRECT_MAX_DOFS = 3_000


def elasticity_solver(solid: Solid, free: np.ndarray, tol: float = 1e-10, kind: str = "auto"):
    """``"direct"`` (sparse LU), ``"amg"`` (AMG-preconditioned CG) or ``"auto"``: LU up to DIRECT_MAX_DOFS free
    DOFs, AMG-CG above."""
    if kind == "auto":
        kind = "direct" if len(free) <= DIRECT_MAX_DOFS else "amg"
    if kind == "direct":
        return DirectElasticity(solid, free, tol)
    if kind == "amg":
        return AMGElasticity(solid, free, tol)
    raise ValueError(f"solver must be auto, direct or amg, got {kind!r}")
