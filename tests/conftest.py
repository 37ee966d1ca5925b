import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(Path(__file__).resolve().parent))

EXAMPLES = ROOT / "examples"


@pytest.fixture
def examples_dir():
    return EXAMPLES


@pytest.fixture(autouse=True)
def _ambient_mpmath_precision():
    """A test that sets mpmath's ambient precision for its references leaves it as it was:
    ``str`` of an mpf prints at it, and a later test's comparison of such strings read 40
    digits where it meant 15."""
    import mpmath
    prec = mpmath.mp.prec
    yield
    mpmath.mp.prec = prec
