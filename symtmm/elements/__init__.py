"""Elements of MS-TMM: field elements (beam segments) and point elements (springs, ...).

Every element exposes the same interface (:class:`~symtmm.elements.base.Element`):
the state variables it acts on, its parameters, and ``transfer_matrix(lam)``
as an exact SymPy matrix.
"""

from .base import STATE, Element, FieldElement, PointElement
from .beam import EulerBernoulliSegment
from .point import LumpedMass, RotationalCoupling, RotationalGroundSpring
from .spring import Coupling, GroundSpring
from .theories import THEORIES, BeamSegment

__all__ = ["STATE", "Element", "FieldElement", "PointElement", "EulerBernoulliSegment",
           "BeamSegment", "THEORIES",
           "Coupling", "GroundSpring", "LumpedMass", "RotationalCoupling",
           "RotationalGroundSpring"]
