"""What a user would write or install instead of symtmm.

* :func:`grid_bisection` -- sign changes of ``Delta(i omega)`` on a uniform
  grid in double precision, then bisection of each to a relative width of
  ``1e-12``. It cannot see a root of even multiplicity (no sign change), two
  roots in one grid cell cancel, and where ``Delta`` loses more digits than
  double precision holds the signs are noise.
* :class:`NaiveTransfer` -- the straightforward transfer-matrix code: for
  each ``lam``, every segment's 4x4 matrix from the closed form in
  ``beta``, the full ``4n x 4n`` stacked matrices multiplied in a Python
  loop, ``R`` extracted, :func:`numpy.linalg.det`.
* :func:`cxroots_search` -- the contour-integral root finder cxroots on
  ``Delta(lam)`` over a rectangle, under a wall-clock budget.

Each counts its evaluations of ``Delta`` the way symtmm does: one per ``lam``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

__all__ = ["GridResult", "grid_bisection", "NaiveTransfer", "CxrootsResult", "cxroots_search"]

#: Grid points over the frequency band (the paper's fMin1D uses the same number).
GRID_POINTS = 500
#: Relative bracket width at which bisection stops.
BISECTION_TOL = 1e-12


@dataclass
class GridResult:
    """Roots found by :func:`grid_bisection`."""

    omegas: list
    evaluations: int
    seconds: float
    band: float
    notes: list = field(default_factory=list)


def grid_bisection(delta, count: int, first_guess: float, points: int = GRID_POINTS,
                   tol: float = BISECTION_TOL) -> GridResult:
    """The first ``count`` sign changes of ``delta(i omega)`` on a grid, bisected.

    Parameters
    ----------
    delta : callable
        ``lam`` (complex numpy array) -> ``Delta(lam)``, vectorised; its real
        part is used (``Delta`` is real on the frequency axis of an undamped model).
    count : int
        Roots wanted. The band ``[0, W]`` starts at ``W = 2 first_guess`` and
        is doubled until the grid shows ``count`` sign changes.
    first_guess : float
        A frequency of the order of the lowest one.

    Examples
    --------
    >>> f = lambda lam: np.sin(np.sqrt(np.abs(lam)))      # roots at (n pi)^2
    >>> r = grid_bisection(f, 3, 10.0)
    >>> [round(float(w) / np.pi**2, 9) for w in r.omegas]
    [1.0, 4.0, 9.0]
    """
    start = time.perf_counter()
    evaluations = 0

    def f(omega):
        nonlocal evaluations
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        evaluations += omega.size
        return np.real(delta(1j * omega))

    band = 2.0 * first_guess
    while True:
        grid = np.linspace(0.0, band, points)[1:]
        values = f(grid)
        signs = np.sign(values)
        cells = np.nonzero(signs[:-1] * signs[1:] < 0)[0]
        if len(cells) >= count or band > 1e9:
            break
        band *= 2.0
    roots = []
    for i in cells[:count]:
        a, b = grid[i], grid[i + 1]
        fa = values[i]
        while b - a > tol * b:
            mid = 0.5 * (a + b)
            fm = f(mid)[0]
            if fm == 0:
                a = b = mid
                break
            if (fm > 0) == (fa > 0):
                a, fa = mid, fm
            else:
                b = mid
        roots.append(0.5 * (a + b))
    notes = [f"{points} points over [0, {band:.6g}] rad/s, bisection to {tol:g} relative"]
    if len(cells) < count:
        notes.append(f"only {len(cells)} sign changes below {band:.3g}")
    return GridResult(roots, evaluations, time.perf_counter() - start, band, notes)


# -- the naive transfer-matrix product -----------------------------------------------------
_UNKNOWN = {"free": (0, 1), "clamped": (2, 3), "pinned": (1, 3), "sliding": (0, 2)}
_ZERO = {"free": (2, 3), "clamped": (0, 1), "pinned": (0, 2), "sliding": (1, 3)}


def _segment(EI, m, l, lam):
    """The 4x4 transfer matrix of a beam segment, closed form in ``beta``."""
    beta = (-m * lam * lam / EI) ** 0.25
    bl = beta * l
    ch, c, sh, s = np.cosh(bl), np.cos(bl), np.sinh(bl), np.sin(bl)
    S, T, U, V = (ch + c) / 2, (sh + s) / 2, (ch - c) / 2, (sh - s) / 2
    b2, b3 = beta * beta, beta ** 3
    return np.array([
        [S, T / beta, U / (EI * b2), V / (EI * b3)],
        [beta * V, S, T / (EI * beta), U / (EI * b2)],
        [EI * b2 * U, EI * beta * V, S, T / beta],
        [EI * b3 * T, EI * b2 * U, beta * V, S],
    ], dtype=complex)


class NaiveTransfer:
    """``Delta(lam)`` by the textbook product of stacked ``4n x 4n`` matrices.

    Handles models whose beams all span the same interval (every level is cut
    at every spring position), as in the benchmarks.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> bool(abs(NaiveTransfer(pp).delta(np.array([1j * np.pi**2]))[0]) < 1e-12)
    True
    """

    def __init__(self, model):
        model = model.resolved()
        if model.masses or any(b.kw != 0 for b in model.beams) or \
                any(s.kind != "translational" for s in model.springs):
            raise ValueError("the naive product handles beams and translational springs only")
        self.beams = [(float(b.EI), float(b.m), float(b.x0), float(b.x1), b.left, b.right)
                      for b in model.beams]
        x0s = {b[2] for b in self.beams}
        x1s = {b[3] for b in self.beams}
        if len(x0s) != 1 or len(x1s) != 1:
            raise ValueError("the naive product needs beams over one common interval")
        self.x0, self.x1 = x0s.pop(), x1s.pop()
        index = {b.name: i for i, b in enumerate(model.beams)}
        self.springs = [(index[s.a], None if s.grounded else index[s.b], float(s.x),
                         float(s.k), float(s.c)) for s in model.springs]
        self.cuts = sorted({x for _, _, x, _, _ in self.springs})
        self._cut_set = set(self.cuts)
        n = len(self.beams)
        self.n = n
        self.columns = [4 * i + j for i, b in enumerate(self.beams) for j in _UNKNOWN[b[4]]]
        self.rows = [4 * i + j for i, b in enumerate(self.beams) for j in _ZERO[b[5]]]
        self.evaluations = 0

    def _station(self, x, lam):
        P = np.eye(4 * self.n, dtype=complex)
        for a, b, xs, k, c in self.springs:
            if xs != x:
                continue
            kk = k + c * lam
            # Q_a += kk (Y_b - Y_a), Q_b -= kk (Y_b - Y_a); to ground: Q_a -= kk Y_a
            P[4 * a + 3, 4 * a] -= kk
            if b is not None:
                P[4 * a + 3, 4 * b] += kk
                P[4 * b + 3, 4 * b] -= kk
                P[4 * b + 3, 4 * a] += kk
        return P

    def delta_one(self, lam: complex) -> complex:
        """``Delta`` at one ``lam`` (the per-point loop a user would write)."""
        self.evaluations += 1
        T = np.eye(4 * self.n, dtype=complex)
        x = self.x0
        for xc in self.cuts + [self.x1]:
            l = xc - x
            if l > 0:
                B = np.zeros((4 * self.n, 4 * self.n), dtype=complex)
                for i, (EI, m, *_rest) in enumerate(self.beams):
                    B[4 * i:4 * i + 4, 4 * i:4 * i + 4] = _segment(EI, m, l, lam)
                T = B @ T
            if xc in self._cut_set:
                T = self._station(xc, lam) @ T
            x = xc
        R = T[np.ix_(self.rows, self.columns)]
        return np.linalg.det(R)

    def delta(self, lam) -> np.ndarray:
        """``Delta`` on an array, one point after another."""
        lam = np.asarray(lam, dtype=complex)
        return np.array([self.delta_one(z) for z in lam.reshape(-1)]).reshape(lam.shape)


# -- cxroots ---------------------------------------------------------------------------------
@dataclass
class CxrootsResult:
    """What cxroots returned (or how far it got)."""

    status: str                  # "ok", "not installed", "timeout", "error: ..."
    roots: list = field(default_factory=list)
    multiplicities: list = field(default_factory=list)
    evaluations: int = 0
    seconds: float = 0.0
    counted: int | None = None   # roots cxroots counted in the whole rectangle


def _cxroots_child(conn, counter, delta, re_range, im_range, int_method):
    """Runs in a forked process: cxroots on ``delta``, its states sent through ``conn``."""
    import logging
    import warnings

    from cxroots import Rectangle
    from cxroots.root_finding import find_roots_gen

    def f(z):
        z = np.asarray(z, dtype=complex)
        with counter.get_lock():
            counter.value += max(z.size, 1)
        return delta(z)

    # scipy.integrate warns on every noisy edge, cxroots logs every recount
    logging.getLogger("cxroots").setLevel(logging.ERROR)
    counted = None
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for state in find_roots_gen(Rectangle(list(re_range), list(im_range)), f,
                                        int_method=int_method):
                if counted is None:
                    counted = state.num_remaining_roots + sum(state.multiplicities)
                conn.send(("state", [complex(z) for z in state.roots],
                           list(state.multiplicities), counted))
        conn.send(("done", None, None, counted))
    except Exception as exc:  # noqa: BLE001 - cxroots fails in many ways; report, go on
        conn.send(("error", f"{type(exc).__name__}: {exc}"[:200], None, counted))


def cxroots_search(delta, re_range, im_range, budget: float,
                   int_method: str = "romb") -> CxrootsResult:
    """All zeros of ``delta`` in a rectangle by cxroots, stopped after ``budget`` seconds.

    ``delta`` is vectorised over complex numpy arrays. cxroots estimates the
    derivative itself (no ``df`` given), counts zeros by integrating
    ``delta'/delta`` along the edges and subdivides. ``int_method="romb"``
    (Romberg on whole arrays of points) is much faster here than cxroots'
    default ``"quad"``, which calls ``delta`` one point at a time.

    cxroots runs in a forked child process, ended when the budget is spent
    (it can spend long stretches on cached values without calling ``delta``,
    so a check inside ``delta`` would not stop it); the result holds the
    zeros it had located by then.
    """
    try:
        import cxroots  # noqa: F401
    except ImportError:
        return CxrootsResult("not installed")
    import multiprocessing as mp

    ctx = mp.get_context("fork")
    counter = ctx.Value("q", 0)
    parent, child = ctx.Pipe(duplex=False)
    start = time.perf_counter()
    proc = ctx.Process(target=_cxroots_child,
                       args=(child, counter, delta, re_range, im_range, int_method), daemon=True)
    proc.start()
    child.close()
    status, roots, mult, counted = "timeout", [], [], None
    try:
        while True:
            left = budget - (time.perf_counter() - start)
            if left <= 0 or not parent.poll(left):
                break
            try:
                kind, a, b, counted = parent.recv()
            except EOFError:
                status = "error: cxroots process ended without a result"
                break
            if kind == "state":
                roots, mult = a, b
            elif kind == "done":
                status = "ok"
                break
            else:
                status = f"error: {a}"
                break
    finally:
        if proc.is_alive():
            proc.terminate()
        proc.join()
    return CxrootsResult(status, roots, mult, int(counter.value), time.perf_counter() - start,
                         counted)
