"""The ``crashsim`` command line.

``crashsim run case.toml`` loads a scene file (crashsim.io.scenefile; docs/scene-format.md), runs
it, prints the report's summary table and writes report.json, the time histories (CSV), the
top-down pictures (PNG) and the 3-D motion (GLB) into a folder; with ``--html`` also the case
page (one offline HTML file: the 3-D scene, a timeline and the report; crashsim.io.viewer).

``crashsim view out/report.json`` writes the case page of a run from the report.json that
``crashsim run --out`` wrote and the files beside it (the time histories and the meshes).

``crashsim check case.toml`` runs a scene file and checks the engine's first overlaps against
the independent python-fcl cross-check; it fails (exit 1) when they disagree.

``crashsim demo`` runs the built-in intersection case to rest (crashsim.demo: two generated
cars on dry asphalt, the struck one into a lamp post), prints the report's essentials and
writes the report, pictures and case page into a folder (``--out``, else crashsim-demo-out);
``--impact-only`` runs the seed's first worked example instead (two box cars, no ground,
the first exchange, printed only).

``crashsim sweep case.toml --vary red.speed=10:20:5 --vary restitution=0,0.1,0.2`` and
``crashsim montecarlo case.toml -n 1000 --seed 1 --dist "red.speed=normal(15 m/s, 1 m/s)"`` run
a study of the scene (crashsim.studies; docs/studies.md), or the file's ``[study]`` table; they
print the percentiles of every output, write the variants as CSV or Parquet (``--out``) and
the pictures (``--plots DIR``), on this machine or a Dask cluster (``--backend dask``).

``crashsim fit case.toml`` fits the unknowns of the file's ``[fit]`` table to its
``[[evidence]]`` (crashsim.io.fitfile, crashsim.fit; docs/fitting.md): it prints the best values
with their 95 % ranges and every item's residual in the file's units, and the fit's verdict
(fits, poor fit: a warning, does not fit: exit 1 with the reasons), and writes fit.json,
fit.png and the fitted run's report; Ctrl-C prints and writes the best so far (exit 130).

``crashsim dtp-montecarlo`` samples the depth of penetration dt_p = sqrt(m'/k') over pairs of
the built-in vehicle classes (crashsim.analysis.montecarlo) and prints its percentiles in ms.

Exit codes: 0 success; 1 the run or the check failed (or writing an output failed after the
run, e.g. a full disk); 2 bad input (a malformed scene file, bad arguments, vehicles
overlapping at t = 0, an output folder that cannot be created or written: all found before
the run); 130 interrupted (Ctrl-C). Every error is one line on stderr starting
``crashsim: error:``.

Option values that look like options (``--dt -1ms``, ``--speed -5``) are taken as values, so
that they get this command's own message rather than argparse's "expected one argument".

The package, by topic: parser.py (the argument parser), scenes.py (run, view, check),
builtin.py (demo, dtp-montecarlo), studies.py (sweep, montecarlo), fits.py (fit), output.py
(the files a run writes), argtypes.py (the options' value types), common.py (exit codes,
the progress bar, the output folder's checks), entry.py (main, console_main). This file
keeps every name crashsim.cli had that others import.
"""

from __future__ import annotations

# the names others import from crashsim.cli (tests, crashsim.__main__, the console script)
from crashsim.cli.builtin import DEMO_MAX_DURATION as DEMO_MAX_DURATION
from crashsim.cli.builtin import DEMO_OUT as DEMO_OUT
from crashsim.cli.common import EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED
from crashsim.cli.common import ProgressBar as ProgressBar
from crashsim.cli.common import RunFailed as RunFailed
from crashsim.cli.entry import console_main as console_main
from crashsim.cli.entry import main
from crashsim.cli.fits import FIT_JSON as FIT_JSON
from crashsim.cli.fits import FIT_PICTURE as FIT_PICTURE
from crashsim.cli.fits import FITTED_REPORT as FITTED_REPORT
from crashsim.cli.output import CSV_FILE as CSV_FILE
from crashsim.cli.output import GLB_FILE as GLB_FILE
from crashsim.cli.output import REPORT_FILE as REPORT_FILE
from crashsim.cli.output import TRAJECTORIES_FILE as TRAJECTORIES_FILE
from crashsim.cli.output import write_csv
from crashsim.cli.parser import _parser as _parser
from crashsim.io.scenefile import SceneFile as SceneFile

__all__ = ["EXIT_FAILED", "EXIT_INPUT", "EXIT_INTERRUPTED", "main", "write_csv"]
