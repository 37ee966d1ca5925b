"""Everything the command line does, as one import for notebooks and scripts::

    from symtmm import api
    model = api.load("examples/paper_ex1_ff_cc.toml", K=1000)
    api.solve(model, count=5)                  # a table; in Jupyter an HTML table
    api.modes(model, count=4).plot()           # a matplotlib figure
    api.sweep(model, "x1", 0, 0.5, 26, count=10).plot()
    api.scan(model, omega_max=200).plot()

Models come from files (:func:`load`), from TOML text (:func:`loads`), from plain
dicts laid out like a file (:func:`from_dict`) or are built in code from
:class:`Beam`, :class:`Spring`, :class:`Mass`, :class:`RigidBody` (with its
:class:`Attachment` points), :func:`joint` (beam ends joined at one point),
:func:`oscillator` (a sprung mass) and :class:`Layer` (a continuous elastic or
viscoelastic layer between two beams). Results print as tables,
render as HTML/LaTeX in Jupyter, and have ``to_dict()``/``to_json()`` (the
command line's JSON) and ``plot()`` (a :class:`matplotlib.figure.Figure`).

==============================  =========================================
command line                    Python
==============================  =========================================
``symtmm solve M --count N``    ``solve(model, count=N)``
``solve M --certified`` (damped) ``solve(model, ..., prove_count=True)`` and
                                ``certify(model, spectrum)``
``symtmm modes M --count N``    ``modes(model, count=N)``
``symtmm sweep M --param P …``  ``sweep(model, "P", A, B, steps, count=K)``
``symtmm scan M --omega-max W`` ``scan(model, omega_max=W)``
``symtmm derive M``             ``derive(model)`` (SymPy expressions, LaTeX)
``symtmm codegen M --lang L``   ``codegen(model, "L")`` (the source text)
``--set NAME=VALUE``            ``load(path, NAME=VALUE)`` or
                                ``model.with_parameters(NAME=VALUE)``
``--plot FILE``                 ``result.plot().savefig(FILE)``
``--json``                      ``result.to_json()``
``symtmm draw M --plot FILE``   ``draw_model(model).savefig(FILE)``
``draw --mode N --animate``     ``animate_mode(model, mode, FILE)``
==============================  =========================================

Examples
--------
A model built in code:

>>> from symtmm.api import Beam, Model, Spring, solve
>>> model = Model((Beam("a", EI=1, m=1, L=1, left="clamped", right="free"),
...                Beam("b", EI=1, m=1, L=1, left="clamped", right="free")),
...               (Spring("a", "b", x=1, k="K"),), parameters={"K": 10})
>>> [str(e) for e in solve(model, count=2, digits=10)]     # in phase, then out of phase
['3.516015269i', '8.806312361i']
"""

from __future__ import annotations

from pathlib import Path

from .characteristic import characteristic_equation
from .codegen import generate
from .drawing import animate_mode, draw_model
from .limits import DERIVE_SECONDS
from .model import Attachment, Beam, Layer, Mass, Model, RigidBody, Spring, joint, oscillator
from .modelfile import from_dict as _from_dict
from .modelfile import load as _load_file
from .modelfile import loads as _loads_text
from .modes import evaluate_mode
from .modes import mode_shapes as modes
from .plot import plot_modes, plot_scan, plot_scan_map, plot_sweep
from .roots.certified import certify
from .scan import scan
from .solve import METHODS, solve
from .sweep import sweep

__all__ = ["METHODS", "Attachment", "Beam", "Layer", "Mass", "Model", "RigidBody", "Spring",
           "animate_mode", "certify", "codegen", "derive", "draw_model", "evaluate_mode",
           "from_dict",
           "joint", "load", "loads", "modes", "oscillator",
           "plot_modes", "plot_scan", "plot_scan_map", "plot_sweep", "scan", "solve", "sweep"]


def load(path, **parameters) -> Model:
    """A model file, with parameters overridden by keyword (like ``--set``).

    Parameters
    ----------
    path : str or Path
    **parameters
        New parameter values: numbers (``0.3`` is exactly 3/10) or expression
        strings (``"K/2"``).

    Examples
    --------
    >>> from pathlib import Path
    >>> path = Path(__file__).parent.parent / "examples" / "paper_ex1_ff_cc.toml"
    >>> load(path, K=1000, x1="0.25").resolved().springs[1].x
    3/4
    """
    return _load_file(Path(path), parameters or None)


def loads(text: str, **parameters) -> Model:
    """A model from TOML text, with parameters overridden by keyword.

    Examples
    --------
    >>> m = loads('''
    ... [[beam]]
    ... name = "b"
    ... EI = 1
    ... m = 1
    ... L = "Lb"
    ... left = "pinned"
    ... right = "pinned"
    ... ''', Lb=2)
    >>> m.resolved().beams[0].L
    2
    """
    return _loads_text(text, parameters or None)


def from_dict(data: dict, **parameters) -> Model:
    """A model from a plain dict laid out as a model file, parameters overridden by keyword.

    Examples
    --------
    >>> m = from_dict({"beam": [{"name": "b", "EI": 1, "m": 1, "L": "Lb",
    ...                          "left": "pinned", "right": "pinned"}],
    ...                "oscillator": [{"beam": "b", "x": 0.5, "M": 0.1, "k": 10}]}, Lb=2)
    >>> m.resolved().beams[0].L, m.bodies[0].attachments[0].k
    (2, 10)
    """
    return _from_dict(data, parameters or None)


def derive(model: Model, symbolic=(), max_seconds=DERIVE_SECONDS):
    """The characteristic function in closed form (``symtmm derive``).

    Parameters
    ----------
    model : Model
    symbolic : iterable of str
        Parameters to keep symbolic although the model gives them a value.
    max_seconds : float or None
        Time budget (``--max-seconds``); None for none.

    Returns
    -------
    symtmm.characteristic.CharacteristicEquation
        ``.delta`` (in ``omega`` or ``lam``), ``.delta_Omega``, ``.factors``;
        renders as LaTeX in Jupyter.

    Examples
    --------
    >>> cc = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
    >>> derive(cc).delta_Omega
    (cos(Omega)*cosh(Omega) - 1)/Omega**4
    """
    return characteristic_equation(model, symbolic, max_seconds=max_seconds)


def codegen(model: Model, lang: str, symbolic=()) -> str:
    """Source of a self-contained evaluator of Delta(lam) (``symtmm codegen``).

    Parameters
    ----------
    model : Model
    lang : {"c", "fortran", "octave", "julia", "python"}
    symbolic : iterable of str
        Parameters to make extra arguments although the model gives them a value.

    Examples
    --------
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> "void symtmm_delta(double lam_re, double lam_im," in codegen(pp, "c")
    True
    """
    return generate(model, lang, symbolic)
