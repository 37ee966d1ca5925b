"""A sparse LU of a large, sparse ``R``: the null spaces of beams in series.

The boundary matrix of beams joined end to end (a beam over many spans, a frame) is
large and nearly empty: each beam's conditions involve its own unknowns and its
joints' (the 20-span beam: 154 x 154, 513 nonzeros). A dense LU costs ``n**3 / 3``
whatever the zeros (50 ms a shape there, at 200 bits, in Arb's C). Here the columns
are ordered by reverse Cuthill–McKee on the rows' patterns
(:func:`symtmm.numeric.plan.rcm_order`) and the rows eliminated with partial pivoting
among those that reach the column, on dictionaries of nonzeros: the fill stays within
the band that order leaves. A pivot below ``2**-prec`` of the matrix's largest entry
(an exact zero at an exact eigenvalue) is replaced by that guard with its phase, as
:func:`symtmm.numeric.linalg.lu` does: what inverse iteration needs. Every number is
kept a midpoint (radius 0), as Arb's approximate solves keep them: near an eigenvalue
the radii outgrow the values, and Arb then rounds the midpoints to the bits the radii
leave (a solve's residual came to 1e-13 of the 20-span beam's, not 1e-60).

:class:`SparseLU` solves with ``R`` and with ``R^H``; the inverse iteration itself is
:func:`symtmm.numeric.arb_null.null_space`'s.
"""

from __future__ import annotations

__all__ = ["SparseLU", "sparse_factors", "SPARSE_SIZE", "SPARSE_DENSITY", "FILL_LIMIT", "conj",
           "mid"]

#: From this size on, a matrix with at most :data:`SPARSE_DENSITY` of its entries nonzero
#: is factored sparsely (:func:`sparse_factors`)...
SPARSE_SIZE = 32
#: ... the fraction of nonzeros below which the sparse factors pay (the 20-span beam's R:
#: 0.022; a 20-level chain's, whose springs couple every beam to the next: 0.31).
SPARSE_DENSITY = 0.1
#: The factors may hold at most this many times the nonzeros of ``R`` (more: the order
#: left a wide band, and the dense LU serves instead).
FILL_LIMIT = 8


def sparse_factors(n: int, entry, prec: int):
    """The :class:`SparseLU` of the ``n x n`` matrix ``entry(i, j)`` where it is large and
    nearly empty enough to pay (:data:`SPARSE_SIZE`, :data:`SPARSE_DENSITY`,
    :data:`FILL_LIMIT`), else None: the dense LU serves."""
    if n < SPARSE_SIZE:
        return None
    nonzeros = {}
    for i in range(n):
        for j in range(n):
            v = entry(i, j)
            if v != 0:
                nonzeros[(i, j)] = v
    if len(nonzeros) > SPARSE_DENSITY * n * n:
        return None
    lu = SparseLU(n, nonzeros, prec)
    return lu if lu.ok else None


class SparseLU:
    """``P R Q = L U`` of a square ``R`` given by its nonzeros, in Arb numbers.

    Parameters
    ----------
    n : int
    nonzeros : dict
        ``(row, column) -> value``: Arb numbers (``flint.arb``, ``flint.acb``), kept as
        midpoints, or mpmath numbers of one context (no zeros).
    prec : int
        The bits of the pivot guard (the caller's working precision).

    Attributes
    ----------
    ok : bool
        False where the factors would exceed :data:`FILL_LIMIT` times the nonzeros, or a
        column has no entry (the caller then factors densely).

    Examples
    --------
    >>> import flint
    >>> A = {(0, 0): flint.arb(2), (0, 2): flint.arb(1), (1, 1): flint.arb(3),
    ...      (2, 0): flint.arb(4), (2, 2): flint.arb(1)}
    >>> lu = SparseLU(3, A, 53)
    >>> [round(float(v.mid()), 12) for v in lu.solve([1, 3, 2])]      # A x = (1, 3, 2)
    [0.5, 1.0, 0.0]
    >>> [round(float(v.mid()), 12) for v in lu.solve_adjoint([6, 3, 2])]   # A^T x
    [1.0, 1.0, 1.0]
    """

    def __init__(self, n: int, nonzeros: dict, prec: int):
        from .plan import rcm_order

        self.n = n
        self.ok = False
        by_row: list = [dict() for _ in range(n)]
        for (i, j), v in nonzeros.items():
            by_row[i][j] = v
        # columns in an order that keeps the elimination's band narrow
        order = rcm_order(n, [list(row) for row in by_row if row])
        self.q = order                                  # new column -> old column
        new = [0] * n
        for k, old in enumerate(order):
            new[old] = k
        rows = [{new[j]: v for j, v in row.items()} for row in by_row]
        columns: list = [set() for _ in range(n)]       # new column -> rows reaching it
        for i, row in enumerate(rows):
            for j in row:
                columns[j].add(i)
        top = max((mid(abs(v)) for v in nonzeros.values()), default=None)
        if top is None or not top > 0:
            return
        guard = top * 2.0 ** -prec
        limit = FILL_LIMIT * len(nonzeros)
        stored = 0
        self.p: list = []                                # step -> original row
        self.U: list = []                                # step -> {column: value}
        lower: dict = {}                                 # original row -> {step: factor}
        for k in range(n):
            candidates = columns[k]
            if not candidates:
                return                                   # (a column without entries)
            r = max(sorted(candidates), key=lambda i: mid(abs(rows[i][k])))
            pivot_row = rows[r]
            pivot = pivot_row[k]
            if mid(abs(pivot)) < guard:
                pivot = pivot_row[k] = mid(guard if pivot == 0 else
                                           pivot * (guard / abs(pivot)))
            for j in pivot_row:
                columns[j].discard(r)
            for i in candidates:
                row = rows[i]
                f = mid(row.pop(k) / pivot)
                lower.setdefault(i, {})[k] = f
                for j, v in pivot_row.items():
                    if j == k:
                        continue
                    if j in row:
                        row[j] = mid(row[j] - f * v)
                    else:
                        row[j] = mid(-(f * v))
                        columns[j].add(i)
                stored += 1
            columns[k] = set()
            self.p.append(r)
            self.U.append(pivot_row)
            stored += len(pivot_row)
            if stored > limit:
                return
        # L by steps: L[k] = {earlier step: factor}
        self.L = [lower.get(r, {}) for r in self.p]
        self.ok = True

    def solve(self, b) -> list:
        """``R^-1 b`` (``b`` a sequence of ``n`` numbers; a list of Arb numbers)."""
        n, L, U = self.n, self.L, self.U
        z = [b[self.p[k]] for k in range(n)]
        for k in range(n):                               # L z = P b, unit diagonal
            for j, f in L[k].items():
                z[k] = mid(z[k] - f * z[j])
        y: list = [None] * n
        for k in range(n - 1, -1, -1):                   # U y = z
            acc = z[k]
            row = U[k]
            for j, v in row.items():
                if j != k:
                    acc = mid(acc - v * y[j])
            y[k] = mid(acc / row[k])
        x: list = [None] * n
        for k in range(n):                               # x = Q y
            x[self.q[k]] = y[k]
        return x

    def solve_adjoint(self, b) -> list:
        """``R^-H b``: ``R^H = Q U^H L^H P``, solved by scatters over the rows of ``U``
        and ``L``."""
        n, L, U = self.n, self.L, self.U
        c = [b[self.q[k]] for k in range(n)]             # Q^T b
        for k in range(n):                               # U^H w = c, lower triangular
            row = U[k]
            c[k] = mid(c[k] / conj(row[k]))
            for j, v in row.items():
                if j != k:
                    c[j] = mid(c[j] - conj(v) * c[k])
        for k in range(n - 1, -1, -1):                   # L^H v = w, unit upper
            for j, f in L[k].items():
                c[j] = mid(c[j] - conj(f) * c[k])
        x: list = [None] * n
        for k in range(n):                               # P x = v
            x[self.p[k]] = c[k]
        return x


def conj(v):
    """The conjugate of a number (an Arb ``arb`` is its own)."""
    return v.conjugate() if hasattr(v, "conjugate") else v


def mid(v):
    """A ball's midpoint (radius 0); an mpmath number as it is."""
    return v.mid() if hasattr(v, "mid") else v
