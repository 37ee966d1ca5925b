"""Parameter sweeps: the eigenvalues of a model as one parameter varies.

The values are exact: ``start + i (stop - start)/(steps - 1)`` for
``i = 0 .. steps - 1``, both ends included, from exact decimals or
expressions (:func:`symtmm.expr.parse_expression`). Every step is an
independent :func:`symtmm.solve.solve`, so the steps run in parallel: in
local processes (``jobs``) or on a Dask cluster (``scheduler``). Each step
also computes coarse mode shapes, from which the branches are tracked.

Branch tracking
---------------
Eigenvalues sorted by frequency swap identity where two branches cross (a
symmetry lets them) and follow the curves through veerings. A branch is
followed by its mode shape instead: between neighbouring steps the modal
assurance criterion ``|<phi_a, phi_b>|**2 / (<phi_a, phi_a> <phi_b, phi_b>)``
(mass-weighted samples of ``Y`` on every beam) pairs each branch with the
eigenvalue whose shape it resembles most. A multiple eigenvalue is a
subspace: a branch entering it is matched by the part of its shape the
subspace holds, and carries that projection on, so that branches keep their
identity through an exact crossing. Tracking starts at the step with the
fewest multiple eigenvalues and proceeds to both ends. A branch that finds no
partner above ``0.5`` ends there; a new one starts (a branch entering the
``count`` window from above, say). Steps must be fine enough for shapes to
change little between neighbours.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field

import mpmath
import numpy as np
import sympy as sp

from . import progress
from .display import html_table, latex_array, latex_text, text_lines
from .errors import ComputationError, ModelError
from .expr import ExpressionError, exact_number, parse_expression
from .jsonout import dumps, header
from .limits import SEARCH_SECONDS
from .model import Model
from .numeric.arith import DOUBLE, MP
from .numeric.linalg import orthonormal
from .numeric.threads import one_blas_thread
from .results import decimal_string
from .tables import Tabular

__all__ = ["Sweep", "sweep", "sweep_values", "track_branches", "value_string"]

#: Smallest modal assurance criterion that continues a branch.
MAC_THRESHOLD = 0.5
#: Sample points per beam of the shapes used for tracking.
TRACK_POINTS = 33
#: Digits of the shapes used for tracking (a modal assurance criterion of 0.5 needs few).
TRACK_DIGITS = 6


def _exact(value, what: str) -> sp.Expr:
    try:
        if isinstance(value, sp.Basic):
            expr = value
        elif isinstance(value, str):
            expr = parse_expression(value)
        else:
            expr = exact_number(value)
    except ExpressionError as exc:
        raise ModelError(str(exc), field=what) from None
    if not expr.is_number or not expr.is_real:
        raise ModelError("must be a real number", field=what)
    return expr


def sweep_values(start, stop, steps: int) -> tuple:
    """``steps`` exact, equally spaced values from ``start`` to ``stop``, both included.

    Examples
    --------
    >>> sweep_values("0", "0.5", 6)
    (0, 1/10, 1/5, 3/10, 2/5, 1/2)
    >>> sweep_values(1, "1/3", 3)
    (1, 2/3, 1/3)
    """
    a, b = _exact(start, "start"), _exact(stop, "stop")
    if int(steps) != steps or steps < 2:
        raise ModelError(f"need at least 2 steps (both ends), got {steps}", field="steps")
    n = int(steps)
    return tuple(a + (b - a) * sp.Rational(i, n - 1) for i in range(n))


def value_string(value) -> str:
    """An exact value as text: a terminating decimal as such, else SymPy's form.

    Examples
    --------
    >>> value_string(sp.Rational(3, 20)), value_string(sp.Rational(1, 3)), value_string(2)
    ('0.15', '1/3', '2')
    """
    value = sp.sympify(value)
    if value.is_Integer:
        return str(value)
    if value.is_Rational:
        q = int(value.q)
        twos = fives = 0
        while q % 2 == 0:
            q //= 2
            twos += 1
        while q % 5 == 0:
            q //= 5
            fives += 1
        if q == 1:
            places = max(twos, fives)
            scaled = abs(int(value.p)) * 10**places // int(value.q)
            text = str(scaled).rjust(places + 1, "0")
            text = (text[:-places] + "." + text[-places:]).rstrip("0").rstrip(".")
            return ("-" if value < 0 else "") + text
    return str(value)


# -----------------------------------------------------------------------------------
# one step (runs in a worker)
# -----------------------------------------------------------------------------------

def _solve_step(payload, before=()):
    """Solve one resolved model; return its spectrum and weighted tracking shapes.

    ``before``: the spectra of the steps just before it (at most two, the nearer
    last), whose frequencies tell the search where to look (:func:`_guesses`).
    """
    model, count, sigma_max, digits, method, points, max_seconds = payload
    from .modes import displacements
    from .solve import solve

    with progress.shown(False):         # the sweep's own bar counts the steps
        spectrum = solve(model, count=count, sigma_max=sigma_max, digits=digits,
                         method=method, guesses=_guesses(before), max_seconds=max_seconds)
    weights = []
    for beam in model.beams:
        w = np.full(points, float(beam.L) / (points - 1) * float(beam.m))
        w[[0, -1]] /= 2                     # trapezoid rule
        weights.append(np.sqrt(w))
    weight = np.concatenate(weights)
    shapes = [Y * weight for Y in displacements(model, list(spectrum), points, TRACK_DIGITS)]
    return spectrum, shapes


#: Relative half-width about a frequency when a step follows one step only: the first
#: step of the paper's figure 10 (the spring moved by a hundredth) shifts its
#: frequencies by up to 3 %.
FIRST_WIDTH = 3e-2
#: The narrowest half-width: closer to a root double precision may not count.
LEAST_WIDTH = 1e-5


def _guesses(before):
    """Estimates ``(omega, relative half-width)`` of a step's frequencies from the spectra
    ``before`` it (the nearer last), or None.

    After two steps, each frequency (by its rank, multiplicity counted) is extrapolated
    along the line through them, give or take half its change over the last step: a
    smooth branch moves on by about as much, and its curvature errs by far less. After
    one, the frequency itself, give or take :data:`FIRST_WIDTH`. A branch that crosses
    another, or a step where a frequency jumps, only widens the search there: the
    search proves what it finds as it would without estimates
    (:meth:`symtmm.roots.undamped._Search.guided`).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> beams = [Model((Beam("b", EI, 1, 1, left="pinned", right="pinned"),)) for EI in (1, 4)]
    >>> [[round(w, 4), d] for w, d in _guesses([solve(m, count=1, digits=8) for m in beams])]
    [[29.6088, 0.16666666666666666]]
    """
    rows = [[float(e.omega) for e in s for _ in range(e.multiplicity)] for s in before
            if not s.damped]
    if not rows:
        return None
    last = rows[-1]
    if len(rows) < 2 or len(rows[-2]) != len(last):
        return [(w, FIRST_WIDTH) for w in last if w > 0]
    out = []
    for w0, w1 in zip(rows[-2], last):
        guess = 2 * w1 - w0
        if w1 > 0 and guess > 0:
            out.append((guess, max(abs(guess - w1) / (2 * guess), LEAST_WIDTH)))
    return out


def _solve_run(payloads, done=None) -> list:
    """:func:`_solve_step` of consecutive steps, each after the ones before it;
    ``done()`` after each (a progress bar's update; in a worker, none)."""
    out = []
    for p in payloads:
        out.append(_solve_step(p, [spectrum for spectrum, _ in out[-2:]]))
        if done is not None:
            done()
    return out


def _progress(total: int, enabled: bool | None):
    """The sweep's bar: shown as :mod:`symtmm.progress` decides, unless ``enabled`` says."""
    if enabled is None:
        return progress.bar(total=total, desc="sweep", unit="step")
    with progress.shown(enabled):
        return progress.bar(total=total, desc="sweep", unit="step")


def _dask_client(scheduler):
    try:
        from distributed import Client
    except ImportError:
        raise ModelError("a scheduler needs Dask: pip install 'symtmm[dask]'",
                         field="scheduler") from None
    if isinstance(scheduler, Client):
        return scheduler, False
    try:
        return Client(scheduler, timeout="20s"), True
    except (OSError, TimeoutError, ValueError, TypeError) as exc:
        # an unreachable host (OSError, TimeoutError) or a malformed address (ValueError)
        raise ModelError(f"cannot reach the Dask scheduler: {exc}", field="scheduler",
                         source=str(scheduler)) from None


def _process_context():
    """Start method of the worker processes.

    ``fork`` when the caller runs no other thread but the kernel's idle workers
    (:func:`symtmm.forked.no_other_threads`): it needs no main module, so a plain script
    without ``if __name__ == "__main__":`` works. Otherwise (Jupyter, Dask, a GUI)
    forking could copy a lock held by another thread, and ``spawn`` starts fresh
    interpreters; it re-imports the main script by its path, which a main program
    read from standard input does not have.
    """
    import multiprocessing
    import sys

    from .forked import no_other_threads

    methods = multiprocessing.get_all_start_methods()
    main_file = getattr(sys.modules.get("__main__"), "__file__", None)
    unreadable_main = main_file is not None and not os.path.exists(main_file)
    if "fork" in methods and (no_other_threads() or unreadable_main):
        return multiprocessing.get_context("fork")
    return multiprocessing.get_context("spawn")


def _run(payloads, jobs, scheduler, progress):
    n = len(payloads)
    results = [None] * n
    bar = _progress(n, progress)
    try:
        if scheduler is not None:
            from distributed import as_completed as dask_completed
            client, own = _dask_client(scheduler)
            try:
                futures = client.map(_solve_step, payloads, pure=False)
                index = {f.key: i for i, f in enumerate(futures)}
                for fut, res in dask_completed(futures, with_results=True):
                    results[index[fut.key]] = res
                    bar.update()
            finally:
                if own:
                    client.close()
        elif jobs <= 1 or n == 1:
            results = _solve_run(payloads, bar.update)
        else:
            from concurrent.futures import ProcessPoolExecutor, as_completed
            from concurrent.futures.process import BrokenProcessPool

            try:
                # runs of consecutive steps, each solved after the ones before it in its
                # run (:func:`_guesses`): four runs a process balance the load
                size = -(-n // (4 * min(jobs, n)))
                with ProcessPoolExecutor(max_workers=min(jobs, n),
                                         mp_context=_process_context()) as pool:
                    futures = {pool.submit(_solve_run, payloads[i:i + size]): i
                               for i in range(0, n, size)}
                    for fut in as_completed(futures):
                        done = fut.result()
                        results[futures[fut]:futures[fut] + len(done)] = done
                        bar.update(len(done))
            except BrokenProcessPool:
                raise ComputationError(
                    "a worker process died; in a script, call sweep() under "
                    "'if __name__ == \"__main__\":', or use jobs=1 (--jobs 1)") from None
    finally:
        bar.close()
    return results


# -----------------------------------------------------------------------------------
# branch tracking
# -----------------------------------------------------------------------------------

def _orthonormal(vectors):
    """Orthonormal columns spanning the rows of ``vectors`` (m x N), always m of them."""
    return orthonormal(DOUBLE, np.asarray(vectors).T, complete=True)


@one_blas_thread
def track_branches(clusters, threshold: float = MAC_THRESHOLD) -> list:
    """Branch ids for every eigenvalue of every step, from sampled mode shapes.

    Parameters
    ----------
    clusters : list
        Per step, per eigenvalue (ascending) an array ``(multiplicity, N)``
        of mass-weighted shape samples.
    threshold : float
        Smallest modal assurance criterion that continues a branch.

    Returns
    -------
    list
        Per step, per eigenvalue, a tuple of ``multiplicity`` branch ids. Ids
        are numbered by the step a branch first appears at, then by frequency.

    Examples
    --------
    Two shapes that swap order between the steps keep their ids:

    >>> a, b = np.array([[1.0, 0.0]]), np.array([[0.0, 1.0]])
    >>> track_branches([[a, b], [b, a]])
    [[(0,), (1,)], [(1,), (0,)]]
    """
    S = len(clusters)
    if S == 0:
        return []
    bases = [[_orthonormal(c) for c in step] for step in clusters]
    degeneracy = [sum(Q.shape[1] - 1 for Q in step) for step in bases]
    start = int(np.argmin(degeneracy))
    counter = [0]

    def new_id():
        counter[0] += 1
        return counter[0] - 1

    ids = [None] * S
    first_ids, refs = [], {}
    for Q in bases[start]:
        group = []
        for r in range(Q.shape[1]):
            bid = new_id()
            refs[bid] = Q[:, r]
            group.append(bid)
        first_ids.append(tuple(group))
    ids[start] = first_ids
    for order in (range(start + 1, S), range(start - 1, -1, -1)):
        current = dict(refs)
        for s in order:
            ids[s], current = _match(current, bases[s], threshold, new_id)
    # renumber: by first step of appearance, then by position (frequency) there
    first = {}
    for s, step in enumerate(ids):
        for j, group in enumerate(step):
            for r, bid in enumerate(group):
                first.setdefault(bid, (s, j, r))
    mapping = {bid: k for k, bid in enumerate(sorted(first, key=first.get))}
    return [[tuple(mapping[b] for b in group) for group in step] for step in ids]


def _match(refs, bases, threshold, new_id):
    """Continue the branches ``refs`` (id -> unit vector) into the eigenvalues ``bases``."""
    # every branch against every eigenspace in one product: the squared projections of a
    # branch's vector on each eigenspace's columns, summed by eigenspace (a product per
    # pair cost a sweep of example 1 a twentieth of its time)
    ids = list(refs)
    pairs = []
    if ids and bases:
        V = np.stack([refs[bid] for bid in ids], axis=1)              # (N, branches)
        columns = np.concatenate(bases, axis=1)                       # (N, columns)
        starts = np.cumsum([0] + [q.shape[1] for q in bases[:-1]])
        power = np.add.reduceat(np.abs(columns.conj().T @ V) ** 2, starts, axis=0)
        scores = power / np.sum(np.abs(V) ** 2, axis=0)
        pairs = [(float(scores[j, r]), bid, j) for r, bid in enumerate(ids)
                 for j in range(len(bases))]
    pairs.sort(key=lambda t: (-t[0], t[1], t[2]))
    capacity = [Q.shape[1] for Q in bases]
    assigned: dict = {}
    members = [[] for _ in bases]
    for score, bid, j in pairs:
        if score < threshold:
            break
        if bid in assigned or capacity[j] == 0:
            continue
        assigned[bid] = j
        capacity[j] -= 1
        members[j].append(bid)
    out_ids, new_refs = [], {}
    for j, Q in enumerate(bases):
        group, vectors = [], []
        for bid in sorted(members[j]):
            v = refs[bid]
            p = Q @ (Q.conj().T @ v)            # the part of the branch the eigenspace holds
            p = p / np.linalg.norm(p)
            group.append(bid)
            vectors.append(p)
            new_refs[bid] = p
        missing = Q.shape[1] - len(group)
        if missing:
            rest = Q
            if vectors:
                P = np.array(vectors).T
                rest = Q - P @ np.linalg.lstsq(P, Q, rcond=None)[0]
            U, _, _ = np.linalg.svd(rest, full_matrices=False)
            for r in range(missing):
                bid = new_id()
                group.append(bid)
                new_refs[bid] = U[:, r]
        out_ids.append(tuple(group))
    return out_ids, new_refs


# -----------------------------------------------------------------------------------
# the result
# -----------------------------------------------------------------------------------

@dataclass(frozen=True, repr=False)
class Sweep(Tabular):
    """Eigenvalues of a model for a range of values of one parameter.

    Attributes
    ----------
    parameter : str
    values : tuple
        The exact parameter values (SymPy numbers).
    spectra : tuple of Spectrum
        One per value.
    branches : tuple
        Per value, per eigenvalue, a tuple of branch ids (one per multiplicity).
    digits : int
    seconds : float
        Wall time of the whole sweep.
    model_name : str
        The model file (empty for a model built in Python).
    notes : tuple of str
    title : str
        The model's title.
    """

    parameter: str
    values: tuple
    spectra: tuple
    branches: tuple
    digits: int
    seconds: float = 0.0
    model_name: str = ""
    notes: tuple = field(default_factory=tuple)
    title: str = ""

    def __len__(self):
        return len(self.values)

    @property
    def damped(self) -> bool:
        """True when some eigenvalue has a nonzero real part."""
        return any(e.lam.real != 0 for s in self.spectra for e in s)

    @property
    def omega_scale(self):
        """``(beam, scale)`` of the first step (see :attr:`Spectrum.omega_scale`)."""
        return self.spectra[0].omega_scale if self.spectra else None

    def branch_ids(self) -> list:
        """All branch ids, ascending."""
        return sorted({b for step in self.branches for group in step for b in group})

    def branch(self, bid: int, quantity: str = "lam"):
        """One branch: ``(parameter values, quantity)`` as float/complex arrays.

        ``quantity`` is ``"lam"`` (complex), ``"omega"`` (``Im lam``), ``"hz"``
        (``Im lam / 2 pi``), ``"sigma"`` (``-Re lam``), ``"abs"`` (``|lam|``), ``"zeta"``
        (the damping ratio ``-Re lam / |lam|``) or ``"Omega"`` (``sqrt(omega / scale)``
        with each step's reference-beam scale).
        """
        xs, ys = [], []
        for value, spectrum, step in zip(self.values, self.spectra, self.branches):
            for e, group in zip(spectrum, step):
                if bid in group:
                    xs.append(float(value))
                    lam = complex(e.lam)
                    if quantity == "lam":
                        ys.append(lam)
                    elif quantity == "omega":
                        ys.append(lam.imag)
                    elif quantity == "hz":
                        ys.append(lam.imag / (2 * np.pi))
                    elif quantity == "sigma":
                        ys.append(-lam.real)
                    elif quantity == "abs":
                        ys.append(abs(lam))
                    elif quantity == "zeta":
                        ys.append(-lam.real / abs(lam) if lam != 0 else 0.0)
                    elif quantity == "Omega":
                        if not spectrum.omega_scale:
                            raise ValueError("Omega needs a beam (a model of rods has none)")
                        ys.append((lam.imag / float(spectrum.omega_scale[1])) ** 0.5)
                    else:
                        raise ValueError(f"unknown quantity {quantity!r}")
        return np.array(xs), np.array(ys)

    def to_dict(self) -> dict:
        """The JSON object of ``symtmm sweep --json`` (``branches`` is an extra key)."""
        return header(self.model_name, self.title, self.digits, self.notes) | {
            "parameter": self.parameter,
            "values": [value_string(v) for v in self.values],
            "eigenvalues": [[e.to_dict() for e in s] for s in self.spectra],
            "branches": [[list(g) for g in step] for step in self.branches],
        }

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        return dumps(self.to_dict())

    def records(self):
        """``(columns, rows)``: one row per eigenvalue of every step, with the parameter's
        value and the branch ids the tracking gave it (``2+3`` for a double one)."""
        damped = self.damped
        columns = [self.parameter, "index", "branch", "real", "imag", "multiplicity", "hz"]
        columns += ["abs", "zeta"] if damped else []
        rows = []
        for value, spectrum, step in zip(self.values, self.spectra, self.branches):
            for i, (e, group) in enumerate(zip(spectrum, step), 1):
                d, q = e.to_dict(), e.quantities()
                row = [value_string(value), i, "+".join(str(b) for b in group), d["real"],
                       d["imag"], e.multiplicity, q["hz"]]
                rows.append(row + ([q["abs"], q["zeta"]] if damped else []))
        return columns, rows

    def _rows(self, shown: int):
        scale = self.omega_scale if not self.damped else None
        width = max((s.total for s in self.spectra), default=0)
        rows = []
        # a private context: the ambient mpmath precision is neither read nor set
        ctx = MP.from_digits(self.digits + 10).ctx
        for value, spectrum in zip(self.values, self.spectra):
            row = [value_string(value)]
            for e in spectrum:
                if scale:
                    Om = ctx.sqrt(ctx.mpf(e.omega) / ctx.mpf(spectrum.omega_scale[1]))
                    text = decimal_string(mpmath.mp.make_mpf(Om._mpf_), shown)
                elif self.damped:
                    text = (f"{ctx.nstr(ctx.mpf(e.lam.real), shown)}"
                            f"{'+' if e.lam.imag >= 0 else '-'}"
                            f"{ctx.nstr(abs(ctx.mpf(e.lam.imag)), shown)}i")
                else:
                    text = decimal_string(e.omega, shown)
                row += [text] * e.multiplicity
            rows.append(row + [""] * (width + 1 - len(row)))
        head = [self.parameter] + [f"{'Omega' if scale else 'lam' if self.damped else 'omega'}_"
                                   f"{i}" for i in range(1, width + 1)]
        return head, rows

    def table(self, shown: int = 8) -> str:
        """One row per value, eigenvalues (repeated by multiplicity) in columns."""
        head, rows = self._rows(min(shown, self.digits))
        lines = text_lines(head, rows)
        scale = self.omega_scale
        what = (f"Omega = (omega^2 m L^4/EI)^(1/4) of beam {scale[0]}"
                if scale and not self.damped else "rad/s")
        lines.append(f"{len(self.values)} values of {self.parameter}; {what}; "
                     f"{min(shown, self.digits)} of {self.digits} digits shown (--json: all); "
                     f"{len(self.branch_ids())} branches; {self.seconds:.1f} s")
        lines += list(self.notes)
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return html_table(*self._rows(min(8, self.digits)))

    def _repr_latex_(self) -> str:
        head, rows = self._rows(min(8, self.digits))
        symbol = r"\Omega" if self.omega_scale and not self.damped else (
            r"\lambda" if self.damped else r"\omega")
        return latex_array([latex_text(self.parameter)]
                           + [f"{symbol}_{{{i}}}" for i in range(1, len(head))], rows)

    def plot(self, **kwargs):
        """The branches as a matplotlib figure (see :func:`symtmm.plot.plot_sweep`)."""
        from .plot import plot_sweep
        return plot_sweep(self, **kwargs)


# -----------------------------------------------------------------------------------
# the sweep
# -----------------------------------------------------------------------------------

def sweep(model: Model, parameter: str, start, stop, steps: int, count: int = 10,
          digits: int = 12, method: str = "default", sigma_max=None, jobs: int | None = None,
          scheduler=None, progress: bool | None = None,
          track_points: int = TRACK_POINTS,
          max_seconds: float | None = SEARCH_SECONDS) -> Sweep:
    """Eigenvalues of ``model`` at ``steps`` equally spaced values of ``parameter``.

    Parameters
    ----------
    model : Model
    parameter : str
        A parameter of the model (or a symbol left in its fields).
    start, stop : str, number or SymPy number
        First and last value, exact (``"0.3"`` is 3/10).
    steps : int
        Number of values, at least 2.
    count : int
        Eigenvalues per step, counted with multiplicity (as :func:`symtmm.solve.solve`).
    digits : int
        Significant digits of every eigenvalue (default 12, fewer than ``solve``'s
        15 since sweeps solve many models).
    method : str
        Root search, a key of :data:`symtmm.solve.METHODS`.
    sigma_max : float, optional
        Damped models: search region ``-sigma_max <= Re lam <= 0``.
    jobs : int, optional
        Local worker processes (default: the number of CPUs). ``1`` runs in
        this process. In a script, call ``sweep`` under
        ``if __name__ == "__main__":`` (the workers import the main module).
    scheduler : str or distributed.Client, optional
        Address of a Dask scheduler (``"tcp://host:8786"``) or a client: the
        steps run on its workers instead. Workers must have symtmm installed.
    progress : bool or None
        Show a progress bar (needs tqdm; without it, none); None: as
        :mod:`symtmm.progress` decides (a terminal or Jupyter).
    track_points : int
        Sample points per beam of the shapes that track the branches.
    max_seconds : float or None
        Time budget of each step's search (``--max-seconds``); None for none.

    Returns
    -------
    Sweep

    Examples
    --------
    >>> from symtmm.modelfile import loads
    >>> model = loads('''
    ... [parameters]
    ... k = 0
    ... [[beam]]
    ... name = "b"
    ... EI = 1
    ... m = 1
    ... L = 1
    ... left = "pinned"
    ... right = "pinned"
    ... [[spring]]
    ... between = ["b", "ground"]
    ... x = 0.5
    ... k = "k"
    ... ''')
    >>> result = sweep(model, "k", 0, 100, 3, count=2, digits=8, jobs=1)
    >>> print(result.table())                             # doctest: +ELLIPSIS
      k    Omega_1    Omega_2
    ---  ---------  ---------
      0  3.1415927  6.2831853
     50  3.7411454  6.2831853
    100  4.1315393  6.2831853
    3 values of k; Omega = (omega^2 m L^4/EI)^(1/4) of beam b; 8 of 8 digits shown ...
    """
    started = time.perf_counter()
    known = set(model.parameters) | set(model.free_symbols)
    if parameter not in known:
        have = ", ".join(sorted(known)) or "none"
        raise ModelError(f"unknown parameter {parameter!r} (the model's parameters: {have})",
                         field="parameter", source=model.source)
    values = sweep_values(start, stop, steps)
    payloads = []
    for value in values:
        try:
            step_model = model.with_parameters(**{parameter: value}).require_numeric()
        except ModelError as exc:
            raise ModelError(f"{exc.message} (at {parameter} = {value_string(value)})",
                             field=exc.field, source=model.source) from None
        payloads.append((step_model, count, sigma_max, digits, method, track_points,
                         max_seconds))
    jobs = (os.cpu_count() or 1) if jobs is None else int(jobs)
    results = _run(payloads, jobs, scheduler, progress)
    spectra = tuple(r[0] for r in results)
    branches = track_branches([r[1] for r in results])
    name = model.source or ""
    return Sweep(parameter, values, tuple(s.with_model_name(name, model.title) for s in spectra),
                 tuple(tuple(step) for step in branches), digits,
                 time.perf_counter() - started, name, title=model.title)
