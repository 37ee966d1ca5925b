"""Root search: isolate, count, refine (undamped on the frequency axis)."""

from .undamped import rigid_body_modes, solve_undamped

__all__ = ["solve_undamped", "rigid_body_modes"]
