"""What the vehicles move in: the ground (plane or terrain, friction, friction zones), the
table of road surfaces (:mod:`crashsim.environment.surfaces`), and fixed obstacles."""

from crashsim.environment import surfaces
from crashsim.environment.ground import FrictionZone, Ground
from crashsim.environment.obstacles import Obstacle
from crashsim.environment.surfaces import Surface, surface

__all__ = ["FrictionZone", "Ground", "Obstacle", "Surface", "surface", "surfaces"]
