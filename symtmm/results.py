"""Result objects: eigenvalues and spectra."""

from __future__ import annotations

import functools
import json
from dataclasses import dataclass, field, replace

import mpmath

from .display import html_table, latex_array, latex_text

__all__ = ["first", "Eigenvalue", "Spectrum", "decimal_string"]


def decimal_string(value, digits: int) -> str:
    """``value`` as a plain decimal string with ``digits`` significant digits.

    Examples
    --------
    >>> decimal_string(mpmath.mpf("123.456789"), 5)
    '123.46'
    >>> decimal_string(mpmath.mpf(0), 5)
    '0'
    >>> decimal_string(mpmath.mpf("1.5e-7"), 3)
    '0.000000150'
    """
    if value == 0:
        return "0"
    ctx = _context(digits + 10)
    return ctx.nstr(ctx.mpf(value), digits, strip_zeros=False, min_fixed=-ctx.inf,
                    max_fixed=ctx.inf)


def first(eigenvalues, count: int) -> list:
    """The eigenvalues (in their order) up to ``count`` counted with multiplicity; a
    multiple one that straddles ``count`` is kept whole.

    Examples
    --------
    >>> e = [Eigenvalue(mpmath.mpc(0, w), m) for w, m in ((1, 1), (2, 3), (3, 1))]
    >>> [x.multiplicity for x in first(e, 2)]
    [1, 3]
    """
    kept, total = [], 0
    for e in eigenvalues:
        if total >= count:
            break
        kept.append(e)
        total += e.multiplicity
    return kept


@functools.lru_cache(maxsize=32)
def _context(dps: int) -> mpmath.MPContext:
    """A private mpmath context at ``dps`` digits (the ambient precision is never set)."""
    ctx = mpmath.MPContext()
    ctx.dps = dps
    return ctx


def _global(x) -> mpmath.mpf:
    """A number of a private context as a global mpmath number, unrounded."""
    return mpmath.mp.make_mpf(x._mpf_)


@dataclass(frozen=True)
class Eigenvalue:
    """One eigenvalue ``lam = -sigma + i omega`` with ``Im lam >= 0``.

    Attributes
    ----------
    lam : mpmath.mpc
        The value, accurate to :attr:`digits` significant digits.
    multiplicity : int
    digits : int
        Significant digits guaranteed correct in both parts.
    bracket : tuple or None
        For undamped roots, ``(lo, hi)`` with the root(s) inside, proved by
        the eigenvalue count or by a sign change of Delta.
    proof : str
        What backs the printed digits (``"count (ball arithmetic)"``, ...;
        empty when nothing is claimed beyond the method's own checks).
    """

    lam: mpmath.mpc
    multiplicity: int = 1
    digits: int = 15
    bracket: tuple | None = None
    proof: str = ""

    @property
    def omega(self):
        """Circular frequency ``Im lam`` (rad/s), at the precision it was computed in."""
        return self.lam.imag

    @property
    def sigma(self):
        """Decay rate ``-Re lam`` (1/s)."""
        # (exactly: ``-x`` would round to the ambient precision)
        return mpmath.mp.make_mpf(mpmath.libmp.mpf_neg(self.lam.real._mpf_))

    def to_dict(self) -> dict:
        """JSON-ready ``{"real", "imag", "multiplicity"[, "proof"]}`` with :attr:`digits` digits."""
        out = {"real": decimal_string(self.lam.real, self.digits),
               "imag": decimal_string(self.lam.imag, self.digits),
               "multiplicity": self.multiplicity}
        if self.proof:
            out["proof"] = self.proof
        return out

    def __str__(self) -> str:
        d = self.to_dict()
        if d["real"] == "0":
            return f"{d['imag']}i" + (f" (x{self.multiplicity})" if self.multiplicity > 1 else "")
        sign = "" if d["imag"].startswith("-") else "+"
        return f"{d['real']}{sign}{d['imag']}i" + (
            f" (x{self.multiplicity})" if self.multiplicity > 1 else "")


@dataclass(frozen=True)
class Spectrum:
    """Eigenvalues of a model, ascending by ``Im lam``, with how they were found.

    Iterating gives the :class:`Eigenvalue` objects; ``len`` counts them
    without multiplicity, :attr:`total` with it.
    """

    eigenvalues: tuple
    digits: int
    method: str
    evaluations: int
    seconds: float
    model_name: str = ""
    omega_scale: tuple | None = None  # (beam name, sqrt(EI/(m L^4))) for Omega = beta L
    notes: tuple = field(default_factory=tuple)

    def __iter__(self):
        return iter(self.eigenvalues)

    def __len__(self):
        return len(self.eigenvalues)

    def __getitem__(self, i):
        return self.eigenvalues[i]

    @property
    def total(self) -> int:
        """Number of eigenvalues counted with multiplicity."""
        return sum(e.multiplicity for e in self.eigenvalues)

    def omegas(self, expand: bool = False) -> list:
        """Circular frequencies (mpmath numbers); with ``expand``, repeated by multiplicity."""
        out = []
        for e in self.eigenvalues:
            out += [e.omega] * (e.multiplicity if expand else 1)
        return out

    def Omegas(self, expand: bool = False) -> list:
        """Frequency parameters ``Omega = (omega^2 m L^4/EI)^(1/4)`` of the reference beam."""
        if not self.omega_scale:
            raise ValueError("no reference beam")
        return [_global(self._Omega(w)) for w in self.omegas(expand)]

    def _Omega(self, omega):
        """``sqrt(omega / scale)`` at the spectrum's digits (a private context's number)."""
        ctx = _context(self.digits + 10)
        return ctx.sqrt(ctx.mpf(omega) / ctx.mpf(self.omega_scale[1]))

    def proofs(self) -> dict:
        """What backs the eigenvalues: proof -> the positions (1-based) it backs."""
        out: dict = {}
        for i, e in enumerate(self.eigenvalues, 1):
            if e.proof:
                out.setdefault(e.proof, []).append(i)
        return out

    def with_model_name(self, name: str) -> Spectrum:
        """The same spectrum labelled with ``name`` (the model file, in JSON)."""
        return replace(self, model_name=name)

    def to_dict(self) -> dict:
        """The JSON object of ``symtmm solve --json``."""
        return {
            "model": self.model_name,
            "digits": self.digits,
            "eigenvalues": [e.to_dict() for e in self.eigenvalues],
            "stats": {"evaluations": self.evaluations, "seconds": round(self.seconds, 6),
                      "method": self.method},
        }

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        return json.dumps(self.to_dict(), indent=2)

    def table(self) -> str:
        """A readable table (the ``symtmm solve`` output)."""
        damped = any(e.lam.real != 0 for e in self.eigenvalues)
        head = ["#", "Re lam [1/s]", "Im lam = omega [rad/s]"] if damped else \
            ["#", "omega [rad/s]"]
        ref = None
        if self.omega_scale and not damped:
            ref = self.omega_scale[0]
            head.append(f"Omega (beam {ref})")
        head.append("mult.")
        rows = []
        for i, e in enumerate(self.eigenvalues, 1):
            d = e.to_dict()
            row = [str(i)] + ([d["real"]] if damped else []) + [d["imag"]]
            if ref:
                row.append(decimal_string(self._Omega(e.omega), self.digits))
            row.append(str(e.multiplicity))
            rows.append(row)
        widths = [max(len(h), *(len(r[k]) for r in rows)) if rows else len(h)
                  for k, h in enumerate(head)]
        lines = ["  ".join(h.rjust(w) for h, w in zip(head, widths))]
        lines.append("  ".join("-" * w for w in widths))
        lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
        lines.append(f"{self.total} eigenvalue(s) with multiplicity, {self.digits} significant "
                     f"digits; method {self.method}, {self.evaluations} evaluations, "
                     f"{self.seconds:.3f} s")
        proofs = self.proofs()
        if proofs:
            lines.append("proved by " + "; ".join(
                f"{proof} ({', '.join(map(str, numbers))})" if len(proofs) > 1 else proof
                for proof, numbers in proofs.items()))
        lines += list(self.notes)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.table()

    # -- Jupyter --------------------------------------------------------------------
    def _display_rows(self):
        """Header and rows shared by the HTML and LaTeX forms."""
        damped = any(e.lam.real != 0 for e in self.eigenvalues)
        ref = self.omega_scale[0] if self.omega_scale and not damped else None
        head = ["#", "Re λ [1/s]", "Im λ = ω [rad/s]"] if damped else ["#", "ω [rad/s]"]
        if ref:
            head.append(f"Ω (beam {ref})")
        head.append("mult.")
        rows = []
        for i, e in enumerate(self.eigenvalues, 1):
            d = e.to_dict()
            row = [str(i)] + ([d["real"]] if damped else []) + [d["imag"]]
            if ref:
                row.append(decimal_string(self._Omega(e.omega), self.digits))
            rows.append(row + [str(e.multiplicity)])
        return head, rows

    def _repr_html_(self) -> str:
        """An HTML table (Jupyter)."""
        head, rows = self._display_rows()
        return html_table(head, rows, note=(
            f"{self.total} eigenvalue(s) with multiplicity, {self.digits} significant digits; "
            f"method {self.method}, {self.evaluations} evaluations, {self.seconds:.3f} s"))

    def _repr_latex_(self) -> str:
        """A LaTeX array (Jupyter, documents)."""
        head, rows = self._display_rows()
        tex = {"#": r"\#", "ω [rad/s]": r"\omega\ [\mathrm{rad/s}]",
               "Re λ [1/s]": r"\mathrm{Re}\,\lambda\ [1/\mathrm{s}]",
               "Im λ = ω [rad/s]": r"\mathrm{Im}\,\lambda = \omega\ [\mathrm{rad/s}]",
               "mult.": r"\mathrm{mult.}"}
        ref = self.omega_scale[0] if self.omega_scale else ""
        return latex_array([tex.get(h, r"\Omega\ (" + latex_text("beam " + ref) + ")")
                            for h in head], rows)
