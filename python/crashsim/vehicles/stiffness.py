"""Crush stiffness of a vehicle's faces (CRASH3 A and B coefficients).

CRASH3 models a face's crush resistance per unit width as a linear spring with a pre-load:
force per unit width F/W = A + B C, for crush depth C (m). A is in N/m (force per unit width
at the onset of permanent crush), B in N/m^2 (force per unit width per metre of crush). Over a
width W of direct contact the face acts as a spring of stiffness k = B W (N/m; seed section
"From k to B").

Faces are named in the vehicle's body frame (ISO 8855: x forward, y left): "front" (+x),
"rear" (-x), "left" (+y, the driver side in right-hand traffic) and "right" (-y).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from crashsim import _core
from crashsim.errors import ParameterError

__all__ = ["FACES", "FaceStiffness", "Stiffness"]

FACES = ("front", "rear", "left", "right")


@dataclass(frozen=True)
class FaceStiffness:
    """One face's CRASH3 coefficients: ``A`` (N/m, >= 0) and ``B`` (N/m^2, > 0)."""

    A: float
    B: float

    def __post_init__(self) -> None:
        for name, value in (("A", self.A), ("B", self.B)):
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise ParameterError(f"stiffness {name} must be a number, got {value!r}")
        _core.check_face_stiffness(float(self.A), float(self.B))  # A >= 0 N/m, B > 0 N/m^2
        object.__setattr__(self, "A", float(self.A))
        object.__setattr__(self, "B", float(self.B))

    def spring_rate(self, width: float) -> float:
        """k = B W (N/m) over a contact width W (m)."""
        return self.B * width

    @classmethod
    def coerce(cls, value: Any, face: str) -> FaceStiffness:
        """A FaceStiffness from itself, a mapping {"A": ..., "B": ...} or a pair (A, B)."""
        if isinstance(value, FaceStiffness):
            return value
        if isinstance(value, Mapping):
            unknown = set(value) - {"A", "B"}
            if unknown or "B" not in value:
                raise ParameterError(
                    f"stiffness of the {face} face must have keys A (N/m) and B (N/m^2), "
                    f"got {sorted(value)}"
                )
            return cls(A=value.get("A", 0.0), B=value["B"])
        try:
            a, b = value
        except (TypeError, ValueError) as e:
            raise ParameterError(
                f"stiffness of the {face} face must be (A, B) in (N/m, N/m^2) or "
                f'{{"A": ..., "B": ...}}, got {value!r}'
            ) from e
        return cls(A=a, B=b)


@dataclass(frozen=True)
class Stiffness:
    """Face stiffness of a vehicle; a face without data is None."""

    front: FaceStiffness | None = None
    rear: FaceStiffness | None = None
    left: FaceStiffness | None = None
    right: FaceStiffness | None = None

    @classmethod
    def coerce(cls, value: Any) -> Stiffness:
        """A Stiffness from itself, None (no data) or a mapping of faces to (A, B) pairs or
        {"A", "B"} mappings. The key "side" sets both "left" and "right"."""
        if value is None:
            return cls()
        if isinstance(value, Stiffness):
            return value
        if not isinstance(value, Mapping):
            raise ParameterError(
                "stiffness must be a mapping such as {'front': (A, B), 'rear': (A, B), "
                f"'side': (A, B)}} (A in N/m, B in N/m^2), got {type(value).__name__}"
            )
        faces: dict[str, FaceStiffness] = {}
        for key, face_value in value.items():
            targets = ("left", "right") if key == "side" else (key,)
            if targets[0] not in FACES:
                raise ParameterError(
                    f"unknown face {key!r} in stiffness: use front, rear, left, right or side"
                )
            for face in targets:
                faces[face] = FaceStiffness.coerce(face_value, face)
        return cls(**faces)

    def face(self, name: str) -> FaceStiffness | None:
        """The named face's coefficients (None without data)."""
        if name not in FACES:
            raise ParameterError(f"unknown face {name!r}: use one of {', '.join(FACES)}")
        return getattr(self, name)

    @property
    def complete(self) -> bool:
        """True when every face has data."""
        return all(self.face(f) is not None for f in FACES)

    def to_dict(self) -> dict[str, dict[str, float] | None]:
        """{face: {"A": N/m, "B": N/m^2} or None}."""
        out: dict[str, dict[str, float] | None] = {}
        for f in FACES:
            s = self.face(f)
            out[f] = None if s is None else {"A": s.A, "B": s.B}
        return out
