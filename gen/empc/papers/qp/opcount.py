"""Floating-point operation counting for the solvers and controllers.

Solvers call the helpers below for every vector/matrix operation they perform,
so the counts follow the iterations actually taken (instrumented, not a worst
case).  Categories: ``add`` (+, -), ``mul`` (*), ``div`` (/), ``sqrt``, ``cmp``
(comparisons, not counted as flops).  ``flops = add + mul + div + sqrt``.
"""
from __future__ import annotations

from dataclasses import dataclass, fields


@dataclass
class OpCount:
    add: int = 0
    mul: int = 0
    div: int = 0
    sqrt: int = 0
    cmp: int = 0

    @property
    def flops(self) -> int:
        return self.add + self.mul + self.div + self.sqrt

    def reset(self) -> None:
        for f in fields(self):
            setattr(self, f.name, 0)

    def as_dict(self) -> dict:
        d = {f.name: getattr(self, f.name) for f in fields(self)}
        d["flops"] = self.flops
        return d

    def __iadd__(self, other: "OpCount") -> "OpCount":
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name) + getattr(other, f.name))
        return self

    # --- primitive operations ---
    def dot(self, n: int, times: int = 1) -> None:
        """Inner product of length n: n multiplies, n-1 additions."""
        if n > 0:
            self.mul += n * times
            self.add += (n - 1) * times

    def matvec(self, m: int, n: int) -> None:
        """(m x n) @ (n,)"""
        self.dot(n, m)

    def matmul(self, m: int, k: int, n: int) -> None:
        """(m x k) @ (k x n)"""
        self.dot(k, m * n)

    def axpy(self, n: int) -> None:
        """y + a x"""
        self.mul += n
        self.add += n

    def vadd(self, n: int) -> None:
        self.add += n

    def vmul(self, n: int) -> None:
        self.mul += n

    def vdiv(self, n: int) -> None:
        self.div += n

    def cholesky(self, n: int) -> None:
        """Cholesky factor of an n x n SPD matrix (column algorithm)."""
        for j in range(n):
            self.dot(j)              # diagonal: a_jj - sum l_jk^2
            self.add += 1 if j else 0
            self.sqrt += 1
            rows = n - j - 1
            self.dot(j, rows)        # column below the diagonal
            self.add += rows if j else 0
            self.div += rows

    def trisolve(self, n: int, unit: bool = False) -> None:
        """Triangular solve with one right-hand side."""
        for i in range(n):
            self.dot(i)
            self.add += 1 if i else 0
            if not unit:
                self.div += 1

    def chol_solve(self, n: int) -> None:
        """Solve with a given Cholesky factor (forward + backward)."""
        self.trisolve(n)
        self.trisolve(n)


class NullCount(OpCount):
    """Counter that ignores everything (default when the caller does not ask)."""

    def __setattr__(self, name, value):
        object.__setattr__(self, name, 0)
