"""Batches: many variants of one scene, run in the engine on all cores.

A batch is a base :class:`crashsim.Scene` and per-variant overrides of its inputs (the first
axis of every array is the variant; V = ``len(scene.vehicles)``, P = ``len(scene.pairs())``):

=============================== ============ ================================================
key                             shape        unit / meaning
=============================== ============ ================================================
``position``                    (n, V, 3)    m, world CG position
``orientation``                 (n, V, 4)    quaternion (w, x, y, z), body -> world
``velocity``                    (n, V, 3)    m/s, world, of the CG
``angular_velocity``            (n, V, 3)    rad/s, world
``mass``                        (n, V)       kg; inertia scaled by the same ratio (radii of
                                             gyration kept); a vehicle on wheels keeps its
                                             natural frequencies (static loads, spring rates
                                             and damping scaled with the mass)
``contact.restitution``         (n, P)       1, in ``scene.pairs()`` order
``contact.friction``            (n, P)       1
``contact.depth_of_penetration`` (n, P)      s; NaN = "auto"
``contact.pitch``               (n, P)       rad
``ground.tyre_friction``        (n,)         1, outside friction zones (needs a ground)
``ground.body_friction``        (n,)         1, body-ground (needs a ground)
=============================== ============ ================================================

A key not given keeps the base scene's value; an unknown key or a wrong shape is a
ParameterError naming it; a value out of range fails that variant only (listed in
``BatchResult.errors``). The scene goes to the engine once (:meth:`Scene.to_spec`); each
variant runs single-threaded and keeps no history, so results are the same bits whatever
``threads`` is, and equal to running the same variant alone through :meth:`Scene.run` and
reading the same figures from its Result (``Result.delta_v_body``, ``Impact.pdof_deg``,
``Impact.speed_change``, the trajectories' last samples, ``Result.rest``).

Columns (units m, m/s, s, J; angles in degrees where the name ends ``_deg``), each (n,):
``n_impacts`` (int64, impulse exchanges in the run); for k = 1 .. max_impacts in time order
``impact{k}.time``, ``impact{k}.energy`` (dissipated) and per vehicle N
``impact{k}.{N}.delta_v`` (|delta-V| of the CG; NaN when N is not in impact k),
``.delta_v_x``, ``.delta_v_y`` (world), ``.delta_v_long``, ``.delta_v_lat`` (N's body frame
at the exchange, x forward, lateral +right, as an EDR records), ``.pdof_deg`` (SAE, as the
report gives it); per vehicle ``{N}.total_delta_v`` (sum of the magnitudes over all
impacts), ``{N}.final_x``, ``{N}.final_y``, ``{N}.final_heading_deg``, ``{N}.final_speed``
(|v|) at the end of the run, ``{N}.rest_time``, ``{N}.rest_x``, ``{N}.rest_y``,
``{N}.rest_heading_deg`` (NaN without a ground or when N did not come to rest). A failed or
unfinished variant has NaN in float columns and -1 in int columns.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crashsim import _core
from crashsim.errors import CrashsimError, ParameterError, Place, text
from crashsim.vehicles.checks import _as_float

if TYPE_CHECKING:
    from crashsim.scene import Scene

__all__ = ["BatchResult", "VariantError", "run_batch"]


@dataclass(frozen=True)
class VariantError:
    """A variant that failed: its ``index``, ``kind`` (the crashsim exception class name,
    e.g. "InitialOverlapError", "ParameterError", "SimulationError"), ``message``
    ("variant 17: body 0 ("red"): ..."), ``loc``, where it happened (the exceptions'
    ``.loc``: (kind, index, name) places, outermost first, the variant's own first) and
    ``reason``, the message without the places."""

    index: int
    kind: str
    message: str
    loc: tuple[Place, ...] = ()
    reason: str = ""

    @classmethod
    def of(cls, index: int, error: CrashsimError) -> VariantError:
        """Variant ``index`` failed with ``error`` (raised in Python, for a variant run
        outside the engine's batch)."""
        loc = (("variant", index, None), *error.loc)
        reason = str(error) if error.message is None else error.message
        return cls(index, type(error).__name__, text(loc, reason), loc, reason)

    def within(self) -> str:
        """The text without the variant's own place: the places inside it, then the
        reason."""
        return text(tuple(p for p in self.loc if p[0] != "variant"), self.reason)

    def shifted(self, start: int) -> VariantError:
        """The same error as variant ``index + start`` (a chunk's variant in its study),
        its text rebuilt from its places."""
        loc = tuple(("variant", i + start, n) if k == "variant" else (k, i, n)
                    for k, i, n in self.loc)
        return VariantError(self.index + start, self.kind, text(loc, self.reason), loc,
                            self.reason)


@dataclass(frozen=True)
class BatchResult:
    """What :func:`run_batch` returns (pure data, picklable): ``n`` variants; ``columns``
    {name: (n,) array} in the order of the module's column list; ``errors`` the failed
    variants; ``finished`` (n,) bool, False for variants not run because the batch was
    interrupted (Ctrl-C keeps what finished); ``interrupted``."""

    n: int
    columns: dict[str, NDArray[Any]]
    errors: list[VariantError] = field(default_factory=list)
    finished: NDArray[np.bool_] = field(default_factory=lambda: np.zeros(0, dtype=bool))
    interrupted: bool = False


def _count(value: Any, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise ParameterError(f"{name} must be a whole number, got {value!r}")
    return int(value)


def run_batch(
    scene: Scene,
    overrides: Mapping[str, ArrayLike] | None = None,
    *,
    n: int | None = None,
    duration: float,
    dt: float,
    until: str | None = None,
    threads: int | None = None,
    progress: Callable[[int, int], None] | None = None,
    max_impacts: int = 2,
) -> BatchResult:
    """Run ``n`` variants of ``scene`` (see the module's docstring for the overrides and the
    columns) for ``duration`` s with steps of at most ``dt`` s; with ``until="rest"`` (needs
    a ground) until every vehicle is at rest, ``duration`` being the longest a run may take.
    ``threads``: the pool's size (None: one per core); each variant runs on one thread.
    ``progress(done, n)`` is called from the caller's thread (about every 50 ms while the
    count changes, and at the end). ``max_impacts``: exchanges reported per variant."""
    given: dict[str, NDArray[np.float64]] = {}
    for key, value in (overrides or {}).items():
        if not isinstance(key, str):
            raise ParameterError(f"override keys are strings, got {key!r}")
        try:
            a = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError) as e:
            raise ParameterError(f"override {key!r} must be an array of numbers") from e
        if a.ndim == 0:
            raise ParameterError(
                f"override {key!r} must have one row per variant (shape (n, ...)), got a scalar"
            )
        given[key] = a
    counts = {key: a.shape[0] for key, a in given.items()}
    if n is None:
        if not counts:
            raise ParameterError("give n (the number of variants) when there are no overrides")
        n = next(iter(counts.values()))
    n = _count(n, "n")
    if n < 0:
        raise ParameterError(f"n = {n} is invalid: give a number of variants >= 0")
    for key, k in counts.items():
        if k != n:
            raise ParameterError(
                f"override {key!r} has {k} variants (its first axis) but the batch has n = {n}"
            )
    if threads is not None:
        threads = _count(threads, "threads")
        if threads < 1:
            raise ParameterError(f"threads = {threads} is invalid: give at least 1 (None: all)")
    max_impacts = _count(max_impacts, "max_impacts")
    if max_impacts < 0:
        raise ParameterError(f"max_impacts = {max_impacts} is invalid: give 0 or more")
    # the engine's rules of a run (RunSpec::check, in to_spec): said once, before it starts
    duration = _as_float(duration, "duration", "s")
    dt = _as_float(dt, "dt", "s")
    if until is None:
        spec = scene.to_spec(duration, dt)
    else:
        spec = scene.to_spec(dt=dt, until=until, max_duration=duration)  # type: ignore[arg-type]
    raw = _core.run_batch(
        spec, given, n, threads=threads, progress=progress, max_impacts=max_impacts
    )
    columns = {str(name): np.asarray(values) for name, values in raw["columns"]}
    errors = [
        VariantError(int(i), str(kind), str(message), tuple(loc), str(reason))
        for i, kind, message, loc, reason in raw["errors"]
    ]
    return BatchResult(
        n=n,
        columns=columns,
        errors=errors,
        finished=np.asarray(raw["finished"], dtype=bool),
        interrupted=bool(raw["interrupted"]),
    )
