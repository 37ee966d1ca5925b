"""Signs of life on long work: progress bars where someone is watching.

Work that can take more than a second reports through :func:`bar` or
:func:`stages`; whether anything shows is decided once, by whoever called:

* the command line shows bars on a terminal, never with ``--json`` or ``--quiet``
  and never when standard error is not a terminal (the output stays clean);
* in Python, bars show on a terminal or in Jupyter by default; :func:`shown`
  turns them on or off for a block (``with progress.shown(False): ...``).

A bar appears only once its work has taken a second (``tqdm``'s ``delay``), so
quick calls print nothing. Bars need tqdm (the ``progress`` extra); without it
the work runs silently.

Examples
--------
>>> with shown(False):
...     with stages("solve", ["counting", "proving"]) as next_stage:
...         next_stage("proving")
"""

from __future__ import annotations

import contextlib
import contextvars
import sys

__all__ = ["shown", "bar", "stages", "active"]

#: True, False, or None for the default (a terminal or Jupyter).
_SHOWN: contextvars.ContextVar = contextvars.ContextVar("symtmm_progress", default=None)
#: Seconds of work before a bar appears.
DELAY = 1.0
#: Seconds between redraws of a bar.
MININTERVAL = 0.1


@contextlib.contextmanager
def shown(on: bool = True):
    """Show progress bars (or not) for the work inside the block."""
    token = _SHOWN.set(bool(on))
    try:
        yield
    finally:
        _SHOWN.reset(token)


def _in_jupyter() -> bool:
    shell = sys.modules.get("IPython")
    try:
        return shell is not None and "IPKernelApp" in shell.get_ipython().config
    except AttributeError:
        return False


def active() -> bool:
    """Whether bars show here and now."""
    on = _SHOWN.get()
    if on is None:
        on = bool(getattr(sys.stderr, "isatty", lambda: False)()) or _in_jupyter()
    return on


class _Silent:
    """What :func:`bar` gives when no bar shows: the same calls, doing nothing."""

    def update(self, n=1):
        pass

    def set_description(self, desc=None, refresh=True):
        pass

    def close(self):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def bar(total=None, desc: str = "", unit: str = "it"):
    """A tqdm bar on standard error (or in Jupyter), or a silent stand-in."""
    if not active():
        return _Silent()
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return _Silent()
    return tqdm(total=total, desc=desc, unit=unit, leave=False, delay=DELAY,
                mininterval=MININTERVAL, file=sys.stderr)


@contextlib.contextmanager
def stages(name: str, names):
    """A bar over the named stages of one piece of work; yields ``next_stage(stage)``."""
    names = list(names)
    b = bar(total=len(names), desc=f"{name}: {names[0]}", unit="stage")

    def next_stage(stage: str):
        b.update()
        b.set_description(f"{name}: {stage}")
    try:
        yield next_stage
    finally:
        b.close()
