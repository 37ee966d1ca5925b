"""LU with partial pivoting of a long, narrow band: determinants and solves in ``O(n b**2)``.

The stiffness ``K`` of a plan is stored as its symmetric upper band (``K[r, j] =
K[r, r + j]``, half-bandwidth ``b``). Where the band elimination without pivoting
cannot be trusted (a nearly singular leading minor: a sub-structure's eigenvalue
near the point) the determinant is taken with partial pivoting. Densely that is
``O(n**3)``, and a beam on a stiff foundation is cut into thousands of pieces (6561
freedoms: a dense SVD for one point ran for minutes). Within the band it is ``O(n
b**2)``: the pivot of column ``k`` is chosen among the ``b`` rows below the diagonal,
and the rows of ``U`` reach ``2 b`` beyond it (LAPACK's ``gbtrf``).

Written once over the numbers' own operators: floats and complex numbers, mpmath
numbers and Arb balls. In balls every operation encloses its exact result, so the
determinant encloses the exact one's for the pivots chosen (the choice needs no
proof); a pivot whose ball holds 0 leaves it infinite, which the callers read as
not decided.

Examples
--------
>>> lu = BandLU([[0.0, 1.0], [0.0, 2.0], [0.0, 3.0], [0.0, 0.0]], 1, keep=True)
>>> lu.det                       # tridiagonal, no leading minor regular: det = 9
9.0
>>> [round(v, 12) for v in lu.solve([1.0, 0.0, 0.0, 0.0])]     # the first column of K^-1
[0.0, 1.0, 0.0, -0.666666666667]
"""

from __future__ import annotations

__all__ = ["BandLU", "condition_estimate"]


def _size(v) -> float:
    """How large ``v`` is, to choose pivots by: the modulus, for a ball the upper bound
    of it (the classical choice, which keeps the multipliers' midpoints within 1; a
    ball's radius says nothing about which row is best, as in
    :func:`symtmm.numeric.linalg.det`)."""
    upper = getattr(v, "abs_upper", None)
    return float(upper()) if upper is not None else float(abs(v))


class BandLU:
    """``P K = L U`` of the symmetric matrix with upper band ``upper`` (rows of ``band + 1``
    numbers, ``upper[r][j] = K[r, r + j]``), with partial pivoting within the band.

    Parameters
    ----------
    upper : sequence of sequences
        The band, ``n`` rows of ``band + 1`` numbers (entries beyond ``n`` ignored).
    band : int
        The half-bandwidth.
    keep : bool
        Keep the factors for :meth:`solve` and :meth:`solve_adjoint` (a determinant alone
        keeps none).

    Attributes
    ----------
    det : number
        ``det K``, in the numbers' arithmetic (``0 * pivot`` where a column has no
        nonzero candidate: ``K`` is singular).
    pivots : list
        ``U``'s diagonal (up to the column found singular), whose product with
        ``(-1)**swaps`` is ``det``: its logarithm where the product leaves the range.
    swaps : int
        The row interchanges.
    singular : bool
        A column had no nonzero candidate.
    """

    def __init__(self, upper, band: int, keep: bool = False):
        if getattr(upper, "dtype", object) != object:
            upper = upper.tolist()          # (Python numbers: numpy's scalars cost twice)
        n = len(upper)
        self.n = n
        rows = [dict() for _ in range(n)]
        for r in range(n):
            row = upper[r]
            for j in range(min(band + 1, n - r)):
                v = row[j]
                # (an exact zero is outside the pattern; a ball holding 0 is not, and for
                # balls "!=" means "surely different")
                if not (v == 0):  # noqa: SIM201
                    rows[r][r + j] = v
                    if j:
                        rows[r + j][r] = v
        self._steps: list = []              # per column: (pivot row, multipliers)
        self._u: list = []                  # per column: U's row, {column: value}
        self.pivots: list = []
        self.singular = False
        self.swaps = 0
        value = None
        for k in range(n):
            reach = range(k, min(n, k + band + 1))
            candidates = [i for i in reach if k in rows[i]]
            if not candidates:
                value = rows[k].get(k, 0) * 0 if value is None else value * 0
                self.singular = True
                break
            p = max(candidates, key=lambda i: _size(rows[i][k]))
            if rows[p][k] == 0:
                # (every candidate cancelled to an exact zero: K is singular)
                value = rows[p][k] if value is None else value * 0
                self.singular = True
                break
            if p != k:
                rows[k], rows[p] = rows[p], rows[k]
                self.swaps += 1
            pivot_row = rows[k]
            pivot = pivot_row[k]
            self.pivots.append(pivot)
            value = pivot if value is None else value * pivot
            multipliers = []
            for i in candidates:
                if i == k:
                    continue
                target = rows[i]
                a = target.pop(k, None)
                if a is None:
                    continue
                f = a / pivot
                multipliers.append((i, f))
                for c, v in pivot_row.items():
                    if c > k:
                        t = f * v
                        target[c] = target[c] - t if c in target else -t
            if keep:
                self._steps.append((p, multipliers))
                self._u.append(pivot_row)
            rows[k] = None
        if value is None:
            value = 1.0
        self.det = -value if self.swaps % 2 else value
        if not keep or self.singular:
            self._steps = self._u = None
        else:
            # (how far U's rows reach beyond their diagonal: at most 2 band)
            self._reach = max((max(row) - k for k, row in enumerate(self._u)), default=0)

    def solve(self, b) -> list:
        """``K^-1 b`` (a list of ``n`` numbers)."""
        y = list(b)
        for k, (p, multipliers) in enumerate(self._steps):
            if p != k:
                y[k], y[p] = y[p], y[k]
            for i, f in multipliers:
                y[i] = y[i] - f * y[k]
        for k in range(self.n - 1, -1, -1):
            row = self._u[k]
            s = y[k]
            for c, v in row.items():
                if c > k:
                    s = s - v * y[c]
            y[k] = s / row[k]
        return y

    def solve_adjoint(self, b) -> list:
        """``K^-H b``: with ``M K = U`` (``M`` the swaps and eliminations of the columns in
        turn), ``K^-H = M^H U^-H``: ``U^H`` forward, then the columns' steps undone from
        the last to the first, each conjugated."""
        conj = _conjugate
        n = self.n
        z = list(b)
        for k in range(n):
            s = z[k]
            for r in range(max(0, k - self._reach), k):
                v = self._u[r].get(k)
                if v is not None:
                    s = s - conj(v) * z[r]
            z[k] = s / conj(self._u[k][k])
        for k in range(n - 1, -1, -1):
            p, multipliers = self._steps[k]
            for i, f in multipliers:
                z[k] = z[k] - conj(f) * z[i]
            if p != k:
                z[k], z[p] = z[p], z[k]
        return z


def _conjugate(v):
    c = getattr(v, "conjugate", None)
    return c() if c is not None else v


def condition_estimate(lu: BandLU, upper, band: int) -> float:
    """An estimate of the 1-norm condition number of ``K`` (Hager's method, as LAPACK's
    ``gbcon``: a few solves with the factors), floats and complex numbers."""
    n = lu.n
    if n == 0:
        return 1.0
    sums = [0.0] * n
    for r in range(n):
        for j in range(min(band + 1, n - r)):
            a = abs(upper[r][j])
            sums[r] += a
            if j:
                sums[r + j] += a
    norm = max(sums)
    x = [1.0 / n] * n
    estimate = 0.0
    for _ in range(5):
        y = lu.solve(x)
        estimate = sum(abs(v) for v in y)
        if not estimate < float("inf"):
            return float("inf")
        xi = [v / abs(v) if v != 0 else 1.0 for v in y]
        z = lu.solve_adjoint(xi)
        j = max(range(n), key=lambda i: abs(z[i]))
        if abs(z[j]) <= sum(_conjugate(zz) * xx for zz, xx in zip(z, x)).real:
            break
        x = [0.0] * n
        x[j] = 1.0
    return norm * estimate
