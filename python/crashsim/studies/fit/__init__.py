"""Fitting the unknowns of a scene to the evidence (the inverse problem; docs/fitting.md).

    import crashsim as cs
    from crashsim.studies.evidence import RestPosition, RestHeading
    fit = cs.fit(scene, {"red.speed": (10, 25), "blue.heading": (1.2, 1.9)},
                 [RestPosition("red", 12.1, 3.4, 0.3), RestHeading("red", 0.61, 0.05)])
    fit.values, fit.ranges, fit.summary(), fit.plot("fit.png")

Unknowns are parameter paths (crashsim.studies.paths, SI) with bounds (lo, hi); the evidence
items (crashsim.studies.evidence) each give a residual divided by their tolerance, so the
objective, the sum of their squares (chi^2), is dimensionless. The solver works in scaled
unknowns u = (x - lo) / (hi - lo) in [0, 1]:

- ``method="least_squares"``: scipy.optimize.least_squares (trust region reflective, bounds)
  from ``start``, with a central-difference Jacobian whose 2k candidates run as one batch;
  its step (``step``, 1e-2 of each range) is wider than the small jumps the residuals of a
  run to rest have (docs/fitting.md), so they do not pass for slopes;
- ``method="global"``: scipy.optimize.differential_evolution over the bounds, each
  generation's population evaluated as one batch (``vectorized``), the first a seeded Latin
  hypercube with the start as one member; it stops when ``patience`` generations gained
  less than 1 in chi^2 at a chi^2 the noise can give (99 % of chi^2 with m - k degrees of
  freedom), then the least-squares solve polishes its best.

Candidates run through the batch engine (crashsim.batch.run_batch) when every item reads
the batch's columns (rest positions and headings, EDR delta-V); an impact point, a tyre mark
or a post-impact speed needs each run's Result, and the candidates then run as Scenes
(paths.apply_overrides, the same variants) on a thread pool. Ctrl-C stops the fit and returns
the best candidate so far (``interrupted``).

The uncertainty, the tolerances taken as one standard deviation (so chi^2 is not rescaled):

- the covariance (J^T J)^-1 of the Jacobian J (residuals in tolerances per SI unit of the
  unknowns) at the optimum, J taken twice: at ``step``, then as the secant over +-1.96
  sigma of each unknown; the 95 % range is +-1.96 sigma (``ranges``, within the bounds);
- importance sampling of the posterior (flat within the bounds, likelihood exp(-chi^2/2)):
  ``samples`` candidates in two batches, from a Student-t on the Jacobian's covariance and
  then on the first batch's weighted covariance; the 95 % range is the weighted 2.5 and
  97.5 % quantiles (``sample_ranges``), which sees nonlinearity and jumps the Jacobian
  does not;
- a scan of the objective along each unknown (the others held at the optimum): where chi^2
  rises by at most 3.84 (``scan_ranges``), narrower than the others when unknowns are
  correlated; for the picture.

The verdict (crashsim.studies.verdict, ``verdict``): chi^2 over the items the fitted run
gives against its degrees of freedom (a p-value), the unknowns at a bound, the items the
fitted run cannot give; fits, poor fit (the ranges widened by the Birge ratio; withheld for
an unknown at a bound) or does not fit (the ranges withheld). Every range above is returned
as the verdict quotes it.

The package, by concept: driver.py (fit: checks, the solve, the fitted run, the verdict),
problem.py (candidates to residuals, cached; the checks of the unknowns and the start),
solvers.py (the Jacobian, least squares, differential evolution), uncertainty.py
(covariance, importance sampling, scans), result.py (FitResult, ItemResidual). This file
keeps the names of the module it was: the public ones, the constants and the parts the
tests call.
"""

from __future__ import annotations

from crashsim.studies.evidence import FitError
from crashsim.studies.fit.driver import METHODS as METHODS
from crashsim.studies.fit.driver import STEP as STEP
from crashsim.studies.fit.driver import fit as fit
from crashsim.studies.fit.result import FitResult as FitResult
from crashsim.studies.fit.result import ItemResidual as ItemResidual
from crashsim.studies.fit.solvers import FTOL as FTOL
from crashsim.studies.fit.solvers import GTOL as GTOL
from crashsim.studies.fit.solvers import JUMP as JUMP
from crashsim.studies.fit.solvers import XTOL as XTOL
from crashsim.studies.fit.solvers import _differences as _differences
from crashsim.studies.fit.solvers import _jacobian as _jacobian
from crashsim.studies.fit.uncertainty import CHI2_95 as CHI2_95
from crashsim.studies.fit.uncertainty import NU as NU
from crashsim.studies.fit.uncertainty import SPREAD as SPREAD
from crashsim.studies.fit.uncertainty import Z_95 as Z_95
from crashsim.studies.fit.uncertainty import _covariance as _covariance
from crashsim.studies.fit.uncertainty import _sample as _sample
from crashsim.studies.fit.uncertainty import _scan as _scan
from crashsim.studies.fit.uncertainty import _uncertainty as _uncertainty

__all__ = ["FitError", "FitResult", "ItemResidual", "fit"]
