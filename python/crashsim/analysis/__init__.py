"""What is read off a run: the reconstruction report, the depth-of-penetration toolkit and its
Monte Carlo, and the python-fcl cross-check of the engine's contacts."""
