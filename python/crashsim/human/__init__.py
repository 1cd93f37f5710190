"""The multibody human (pedestrians, cyclists): its body segment data (anthropometry.py)."""

from crashsim.human.anthropometry import (
    ContactShape,
    Joint,
    Segment,
    body_segments,
    chain_factor,
    stature_at_percentile,
    whole_body_cg,
)

__all__ = [
    "ContactShape",
    "Joint",
    "Segment",
    "body_segments",
    "chain_factor",
    "stature_at_percentile",
    "whole_body_cg",
]
