"""Division-free determinants in the ring: constant pivots, blocks, minors.

Step 3 of the method (:mod:`symtmm.characteristic`), first half: entries of
``R`` that are nonzero rational constants are eliminated exactly
(:func:`_eliminate_constants`), the rest splits into independent blocks
(:func:`_blocks`) and each block's determinant is expanded by minors
(:func:`_det_minors`), which needs no division and keeps products intact.
"""

from __future__ import annotations

from itertools import combinations

import sympy as sp

from .algebra import _Algebra
from .budget import spend, spend_product


def _eliminate_constants(alg: _Algebra, M) -> tuple[sp.Rational, list]:
    """Eliminate on pivots that are nonzero rational constants: ``det M = factor * det M'``.

    Each step is an exact Schur complement on one pivot ``p`` (Markowitz's
    choice: fewest other entries in its row and column); ``det M = (-1)**(i+j)
    p det(M')``. The equations of rigid bodies and joints (compatibility,
    equilibrium) have such pivots in the scaled state, so they vanish before
    the expansion by minors.
    """
    ring = alg.ring
    M = [row[:] for row in M]
    factor = sp.Integer(1)
    while M:
        rows_nz = [sum(1 for x in row if x != 0) for row in M]
        cols_nz = [sum(1 for row in M if row[j] != 0) for j in range(len(M))]
        best = None
        for i, row in enumerate(M):
            for j, x in enumerate(row):
                if x == 0:
                    continue
                value = ring.constant_value(x)
                if value is None:
                    continue
                cost = (rows_nz[i] - 1) * (cols_nz[j] - 1)
                if best is None or cost < best[0]:
                    best = (cost, i, j, value)
        if best is None:
            break
        _, i, j, p = best
        factor *= p * (-1) ** (i + j)
        inv = ring.coefficient(1 / p)
        pivot_row = M[i]
        nxt = []
        for r, row in enumerate(M):
            if r == i:
                continue
            if row[j] != 0:
                f = row[j] * inv
                row = [alg.reduce(x - f * y) if y != 0 else x for x, y in zip(row, pivot_row)]
            nxt.append(row[:j] + row[j + 1:])
        M = nxt
    return factor, M


def _det_minors(M, zero, one, reduce=None):
    """Division-free determinant: expansion along rows with memoised minors.

    ``O(2**n n)`` products; exact in any commutative ring, and it keeps the
    product structure of block-decoupled matrices (no reduction in between, unless
    ``reduce`` is given: then each minor is reduced, which layered members need, whose
    ``p`` and ``1/p`` cancel only in the normal form).
    """
    n = len(M)
    if n == 0:
        return one
    minors = {(): one}
    for r in range(n):
        new = {}
        for cols in combinations(range(n), r + 1):
            acc = zero
            for pos, c in enumerate(cols):
                a = M[r][c]
                if a == 0:
                    continue
                m = minors.get(cols[:pos] + cols[pos + 1:])
                if m is None or m == 0:
                    continue
                spend_product(a, m)
                acc = acc - a * m if (r - pos) % 2 else acc + a * m
                spend(acc)
            if reduce is not None and acc != 0:
                acc = reduce(acc)
            if acc != 0:
                new[cols] = acc
        minors = new
    return minors.get(tuple(range(n)), zero)


def _blocks(M) -> tuple[int, list]:
    """Split ``M`` into independent square blocks (connected rows and columns).

    Returns the sign of the permutation and the blocks; ``det M = sign *
    prod(det(block))``, or ``(0, [])`` if a block is not square (then
    ``det M = 0``).
    """
    n = len(M)
    parent = list(range(2 * n))  # rows 0..n-1, columns n..2n-1

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for j in range(n):
            if M[i][j] != 0:
                parent[find(i)] = find(n + j)
    comps: dict = {}
    for i in range(2 * n):
        comps.setdefault(find(i), ([], []))[i >= n].append(i if i < n else i - n)
    row_order, col_order, blocks = [], [], []
    for rows, cols in sorted(comps.values(), key=lambda rc: (rc[0] + rc[1])[:1]):
        if len(rows) != len(cols):
            return 0, []
        row_order += rows
        col_order += cols
        blocks.append([[M[i][j] for j in cols] for i in rows])
    return _perm_sign(row_order) * _perm_sign(col_order), blocks


def _perm_sign(perm) -> int:
    sign, seen = 1, set()
    for i in range(len(perm)):
        if i in seen:
            continue
        j, length = i, 0
        while j not in seen:
            seen.add(j)
            j = perm[j]
            length += 1
        if length % 2 == 0:
            sign = -sign
    return sign


def _decouple_pairs(alg: _Algebra, M) -> tuple[sp.Rational, list]:
    """Identical beams joined by a layer, mirrored: ``det M = factor * det M'`` with their
    sums and differences in place of their rows and columns.

    When swapping the two beams of a layered member leaves ``M`` as it is (the same right-
    and left-end conditions, the same entries, every other row and column alike for both),
    the sums of their rows and columns and the differences make ``M'`` block-triangular:
    the in-phase and out-of-phase families are separate blocks (:func:`_blocks`), whose
    determinants are far smaller than the expansion of ``M``, where they cancel.
    """
    layout = alg.problem.layout
    rows = list(layout.conditions) + [None] * (len(M) - len(layout.conditions))
    cols = list(layout.unknowns) + [None] * (len(M) - len(layout.unknowns))
    M = [row[:] for row in M]
    factor = sp.Integer(1)
    for a, b in dict.fromkeys(member.levels for member in alg.problem.members):
        ra = [i for i, rc in enumerate(rows) if rc and rc[0] == a]
        rb = [i for i, rc in enumerate(rows) if rc and rc[0] == b]
        ca = [j for j, rc in enumerate(cols) if rc and rc[0] == a]
        cb = [j for j, rc in enumerate(cols) if rc and rc[0] == b]
        if [rows[i][1] for i in ra] != [rows[i][1] for i in rb] \
                or [cols[j][1] for j in ca] != [cols[j][1] for j in cb]:
            continue
        swap_r = dict(zip(ra, rb)) | dict(zip(rb, ra))
        swap_c = dict(zip(ca, cb)) | dict(zip(cb, ca))
        if any(M[i][j] != M[swap_r.get(i, i)][swap_c.get(j, j)]
               for i in range(len(M)) for j in range(len(M))):
            continue
        for i, k in zip(ra, rb):
            M[i], M[k] = [x + y for x, y in zip(M[i], M[k])], [x - y for x, y in zip(M[i], M[k])]
        for row in M:
            for j, k in zip(ca, cb):
                row[j], row[k] = row[j] + row[k], row[j] - row[k]
        # det [[I, I], [I, -I]] = (-2)**n on each side
        factor /= sp.Integer(-2) ** (len(ra) + len(ca))
    return factor, M
