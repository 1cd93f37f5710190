"""Vehicles: loading meshes (meshio), the body generator, the vehicle-class table, face
stiffness and the Vehicle itself (mass, CG, inertia and where each came from)."""
