"""Studies: many variants of one scene (sweeps, Monte Carlo, sensitivity), on this machine
or a Dask cluster (docs/studies.md).

    import crashsim as cs
    from crashsim.studies import linspace, normal, uniform
    study = cs.sweep(scene, {"red.speed": linspace(10, 20, 5), "restitution": [0, 0.1, 0.2]},
                     duration=0.5)
    study = cs.monte_carlo(scene, {"red.speed": normal(15, 1)}, n=1000, seed=1)
    study.frame, study.summary(), study.to_parquet("study.parquet")

Parameter paths (what varies) are crashsim.studies.paths's; the runs go through the batch
engine (crashsim.batch.run_batch) in chunks.
"""

from crashsim.studies.backends import Backend, Variants, backend_names, register_backend
from crashsim.studies.design import Linspace, grid, linspace, monte_carlo_sample, one_at_a_time
from crashsim.studies.distributions import (
    Choice,
    ClassTable,
    Distribution,
    Normal,
    Triangular,
    Uniform,
    choice,
    class_table,
    normal,
    triangular,
    uniform,
)
from crashsim.studies.paths import parse_path, valid_paths, with_
from crashsim.studies.run import FailedVariant, Study, monte_carlo, run_study, sweep
from crashsim.studies.sensitivity import Sobol, Tornado, sobol, tornado

__all__ = [
    "Backend",
    "Choice",
    "ClassTable",
    "Distribution",
    "FailedVariant",
    "Linspace",
    "Normal",
    "Sobol",
    "Study",
    "Tornado",
    "Triangular",
    "Uniform",
    "Variants",
    "backend_names",
    "choice",
    "class_table",
    "grid",
    "linspace",
    "monte_carlo",
    "monte_carlo_sample",
    "normal",
    "one_at_a_time",
    "parse_path",
    "register_backend",
    "run_study",
    "sobol",
    "sweep",
    "tornado",
    "triangular",
    "uniform",
    "valid_paths",
    "with_",
]
