"""symtmm: exact free vibration of multilevel beam systems by MS-TMM."""

from .errors import ComputationError, ModelError, SymtmmError
from .model import Beam, Model, Spring

__version__ = "0.1.0"
__all__ = ["Beam", "Model", "Spring", "ModelError", "ComputationError", "SymtmmError"]
