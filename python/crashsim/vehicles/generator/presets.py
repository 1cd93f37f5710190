"""The generator's class table: its presets, their dimensions from the built-in vehicle-class
table (default_dims), the shape parameters (SHAPE_PARAMETERS: name -> meaning and unit) and
each preset's nominal shape (_DEFAULTS: rules in m or shares of the dimensions).

All lengths in metres; heights above the ground; positions "from the front" are distances
rearwards from the front face (model frame: x forward, y left, z up, ground z = 0).
"""

from __future__ import annotations

from typing import NoReturn

from crashsim.errors import ParameterError

PRESETS = ("sedan", "suv", "pickup", "van", "bus")


def default_dims(preset: str) -> dict[str, float]:
    """length, width, height (roof above the ground) and wheelbase (m) of the preset's vehicle
    class in the built-in table (crashsim.vehicles.vehicle_data; sources in
    docs/vehicle-data.md)."""
    from crashsim.vehicles.vehicle_data import vehicle_class  # a data module: no import cycle

    if preset not in PRESETS:
        _fail(f"preset = {preset!r} is unknown: use one of {', '.join(PRESETS)}")
    vc = vehicle_class(preset)
    return {
        "length": vc.length.value,
        "width": vc.width.value,
        "height": vc.height.value,
        "wheelbase": vc.wheelbase.value,
    }


# The shape parameters: name -> (meaning, unit). All lengths in metres; heights are above the
# ground; positions "from the front" are distances rearwards from the front face.
SHAPE_PARAMETERS: dict[str, str] = {
    "front_overhang": "m, front face to the front axle (the rear axle is wheelbase behind it)",
    "ground_clearance": "m, height of the underside between the axles (the body's lowest point)",
    "wheel_radius": "m, tyre radius; the wheel centres are at this height above the ground",
    "arch_gap": "m, radial gap between tyre and wheel arch (arch radius = wheel_radius + gap)",
    "arch_depth": "m, how far each wheel-arch cut reaches in from the body side (tyre width)",
    "bumper_bottom": "m, lower edge of the front and rear ends (the underside rises to it "
    "from ground_clearance at the axles)",
    "nose_height": "m, top of the front face (leading edge of the hood)",
    "hood_height": "m, top of the hood at the windshield base",
    "windshield_base": "m from the front, where the windshield meets the hood (cabin start)",
    "roof_start": "m from the front, top of the windshield (its slope: rise over run from "
    "windshield_base)",
    "roof_end": "m from the front, end of the roof (top of the rear window or back of the cab)",
    "rear_window_end": "m from the front, bottom of the rear window or of the cab back (start "
    "of the trunk lid, bed or tailgate)",
    "deck_height": "m, height at rear_window_end (trunk lid, pickup bed deck, tailgate top)",
    "tail_height": "m, top of the rear face",
    "beltline": "m, lower edge of the side windows; above it the sides lean in",
    "tumblehome": "m, inward offset of the roof edge from the body side, per side (>= 0)",
    "bumper_radius": "m, plan-view radius of the four corners (rounded bumpers)",
    "edge_radius": "m, side-view radius of the top and bottom edges of the front and rear faces",
    "shoulder_radius": "m, cross-section radius where the sides meet the roof, hood and deck",
}

# Nominal shape per preset: name -> (rule, factor). Rules: "m" absolute metres; "L", "W", "H"
# a fraction of length, width or height; "overhang" a share of (length - wheelbase). Five of
# them are then adapted to the dimensions (see _ADAPTIVE below): wheel_radius,
# ground_clearance, bumper_bottom, edge_radius and bumper_radius. The van is the class's
# 1990s minivan (one-box, short sloping hood), the sedan a low 1990s mid-size car.
_DEFAULTS: dict[str, dict[str, tuple[str, float]]] = {
    "sedan": {
        "front_overhang": ("overhang", 0.46),
        "ground_clearance": ("m", 0.14),
        "wheel_radius": ("m", 0.31),
        "arch_gap": ("m", 0.04),
        "arch_depth": ("m", 0.25),
        "bumper_bottom": ("H", 0.21),
        "nose_height": ("H", 0.56),
        "hood_height": ("H", 0.71),
        "windshield_base": ("L", 0.35),
        "roof_start": ("L", 0.51),
        "roof_end": ("L", 0.70),
        "rear_window_end": ("L", 0.835),
        "deck_height": ("H", 0.75),
        "tail_height": ("H", 0.72),
        "beltline": ("H", 0.70),
        "tumblehome": ("W", 0.07),
        "bumper_radius": ("W", 0.24),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.12),
    },
    "suv": {
        "front_overhang": ("overhang", 0.45),
        "ground_clearance": ("m", 0.20),
        "wheel_radius": ("m", 0.37),
        "arch_gap": ("m", 0.05),
        "arch_depth": ("m", 0.28),
        "bumper_bottom": ("H", 0.23),
        "nose_height": ("H", 0.51),
        "hood_height": ("H", 0.63),
        "windshield_base": ("L", 0.305),
        "roof_start": ("L", 0.45),
        "roof_end": ("L", 0.925),
        "rear_window_end": ("L", 0.975),
        "deck_height": ("H", 0.64),
        "tail_height": ("H", 0.61),
        "beltline": ("H", 0.64),
        "tumblehome": ("W", 0.055),
        "bumper_radius": ("W", 0.21),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.12),
    },
    "pickup": {
        "front_overhang": ("overhang", 0.43),
        "ground_clearance": ("m", 0.23),
        "wheel_radius": ("m", 0.40),
        "arch_gap": ("m", 0.06),
        "arch_depth": ("m", 0.30),
        "bumper_bottom": ("H", 0.26),
        "nose_height": ("H", 0.57),
        "hood_height": ("H", 0.68),
        "windshield_base": ("L", 0.27),
        "roof_start": ("L", 0.37),
        "roof_end": ("L", 0.60),
        "rear_window_end": ("L", 0.615),
        "deck_height": ("H", 0.68),
        "tail_height": ("H", 0.665),
        "beltline": ("H", 0.69),
        "tumblehome": ("W", 0.05),
        "bumper_radius": ("W", 0.17),
        "edge_radius": ("m", 0.10),
        "shoulder_radius": ("m", 0.10),
    },
    "van": {
        "front_overhang": ("overhang", 0.50),
        "ground_clearance": ("m", 0.16),
        "wheel_radius": ("m", 0.32),
        "arch_gap": ("m", 0.045),
        "arch_depth": ("m", 0.26),
        "bumper_bottom": ("H", 0.17),
        "nose_height": ("H", 0.45),
        "hood_height": ("H", 0.62),
        "windshield_base": ("L", 0.20),
        "roof_start": ("L", 0.43),
        "roof_end": ("L", 0.93),
        "rear_window_end": ("L", 0.975),
        "deck_height": ("H", 0.60),
        "tail_height": ("H", 0.57),
        "beltline": ("H", 0.60),
        "tumblehome": ("W", 0.05),
        "bumper_radius": ("W", 0.17),
        "edge_radius": ("m", 0.12),
        "shoulder_radius": ("m", 0.15),
    },
    "bus": {
        "front_overhang": ("overhang", 0.45),
        "ground_clearance": ("m", 0.25),
        "wheel_radius": ("m", 0.50),
        "arch_gap": ("m", 0.06),
        "arch_depth": ("m", 0.32),
        "bumper_bottom": ("H", 0.125),
        "nose_height": ("H", 0.96),
        "hood_height": ("H", 0.98),
        "windshield_base": ("L", 0.01),
        "roof_start": ("L", 0.0375),
        "roof_end": ("L", 0.97),
        "rear_window_end": ("L", 0.99),
        "deck_height": ("H", 0.98),
        "tail_height": ("H", 0.96),
        "beltline": ("m", 1.25),
        "tumblehome": ("W", 0.02),
        "bumper_radius": ("W", 0.14),
        "edge_radius": ("m", 0.15),
        "shoulder_radius": ("m", 0.18),
    },
}


def _fail(message: str) -> NoReturn:
    raise ParameterError(message)
