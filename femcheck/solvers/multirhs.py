"""One sparse symmetric positive definite system, many right-hand sides: the FE compliances of the rolling
reference load every cell of a contact strip (3 n_s right-hand sides per body and contact zone, hundreds in all),
so the matrix is factorised once and the loads are solved in blocks.

Backends, chosen by measurement on 3D P1 elasticity (2 cores; benchmarks/fe_rolling.py repeats it):
- ``pardiso`` (Intel MKL PARDISO through pypardiso; supernodal Cholesky, METIS nested dissection): 42k DOFs
  factorised in 1.5 s, 147k DOFs in 29 s, then 0.015 s / 0.1 s per right-hand side in blocks of 128;
- ``splu`` (SciPy's SuperLU): > 300 s for the 42k-DOF factorisation with COLAMD or MMD(A^T + A) orderings
  (FEM-NOTES: unusable above ~30k DOFs in 3D), so only for small systems;
- ``cholespy`` (CHOLMOD) was measured too: 22 s at 42k DOFs and 382 s at 147k, not used;
- ``amg``: pyamg smoothed aggregation + CG per column (~22 iterations; ~5 s per right-hand side at 150k DOFs),
  the fallback when pypardiso is missing (e.g. no MKL on the platform).
``auto``: pardiso when importable, else splu up to ``SPLU_MAX`` unknowns, else amg.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
from scipy.sparse import csr_matrix, triu
from scipy.sparse.linalg import splu

from ..errors import ConvergenceError

SPLU_MAX = 15_000
BLOCK = 96
BACKENDS = ("auto", "pardiso", "splu", "amg")


def pardiso_available() -> bool:
    try:
        import pypardiso  # noqa: F401
    except Exception:       # ImportError, or MKL failing to load
        return False
    return True


@dataclass
class FactorStats:
    backend: str
    n: int
    nnz: int
    factor_s: float = 0.0
    solve_s: float = 0.0
    rhs: int = 0
    residual: float = 0.0
    iterations: list[int] = field(default_factory=list)


class SPDFactor:
    """A x = b for many b with A sparse SPD (n x n): ``solve(B)`` for B (n,) or (n, k). The relative residual
    max_k |A x_k - b_k| / |b_k| of every block is checked (``tol``) and the worst kept in ``stats.residual``."""

    def __init__(self, A: csr_matrix, backend: str = "auto", tol: float = 1e-8, near_null: np.ndarray | None = None):
        if backend not in BACKENDS:
            raise ValueError(f"backend must be one of {BACKENDS}, got {backend!r}")
        if backend == "auto":
            backend = "pardiso" if pardiso_available() else ("splu" if A.shape[0] <= SPLU_MAX else "amg")
        self.A = A.tocsr()
        self.tol = tol
        self.stats = FactorStats(backend, A.shape[0], int(A.nnz))
        t0 = time.perf_counter()
        if backend == "pardiso":
            import pypardiso

            self._upper = triu(self.A, format="csr")
            self._upper.sort_indices()
            self._solver = pypardiso.PyPardisoSolver(mtype=2)          # real symmetric positive definite
            self._solver.factorize(self._upper)
        elif backend == "splu":
            self._lu = splu(self.A.tocsc(), permc_spec="MMD_AT_PLUS_A")
        else:
            import pyamg

            self._ml = pyamg.smoothed_aggregation_solver(self.A, B=near_null, symmetry="symmetric")
            self._M = self._ml.aspreconditioner(cycle="V")
        self.stats.factor_s = time.perf_counter() - t0

    def _solve_block(self, B: np.ndarray) -> np.ndarray:
        backend = self.stats.backend
        if backend == "pardiso":
            return np.asarray(self._solver.solve(self._upper, np.ascontiguousarray(B))).reshape(B.shape)
        if backend == "splu":
            return self._lu.solve(B)
        from scipy.sparse.linalg import cg

        X = np.zeros_like(B)
        for k in range(B.shape[1]):
            its = [0]

            def count(_):
                its[0] += 1

            X[:, k], info = cg(self.A, B[:, k], rtol=0.1 * self.tol, atol=0.0, M=self._M, maxiter=500,
                               callback=count)
            self.stats.iterations.append(its[0])
            if info != 0:
                raise ConvergenceError("AMG-preconditioned CG (compliance loads)", its[0], np.nan, self.tol)
        return X

    def solve(self, B: np.ndarray) -> np.ndarray:
        t0 = time.perf_counter()
        B = np.asarray(B, dtype=float)
        vec = B.ndim == 1
        B2 = B[:, None] if vec else B
        X = np.empty_like(B2)
        for k0 in range(0, B2.shape[1], BLOCK):
            blk = B2[:, k0:k0 + BLOCK]
            X[:, k0:k0 + BLOCK] = self._solve_block(blk)
            R = self.A @ X[:, k0:k0 + BLOCK] - blk
            bn = np.linalg.norm(blk, axis=0)
            res = float(np.max(np.linalg.norm(R, axis=0) / np.where(bn > 0, bn, 1.0)))
            self.stats.residual = max(self.stats.residual, res)
            if not np.isfinite(res) or res > self.tol:
                raise ConvergenceError(f"{self.stats.backend} solve", 1, res, self.tol, "inaccurate solution")
        self.stats.rhs += B2.shape[1]
        self.stats.solve_s += time.perf_counter() - t0
        return X[:, 0] if vec else X

    def free(self) -> None:
        """Release the factor (PARDISO keeps it in MKL memory until told)."""
        if self.stats.backend == "pardiso":
            self._solver.free_memory(everything=True)
