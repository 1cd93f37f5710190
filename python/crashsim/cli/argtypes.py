"""The argparse types of the options' values: times, the demo's speed, counts, seeds
(a bad value: argparse's one-line error, exit 2)."""

from __future__ import annotations

import argparse
import math
from collections.abc import Callable

from crashsim.errors import ParameterError
from crashsim.io.scenefile import parse_quantity
from crashsim.units import mph


def _positive_time(what: str, example: str) -> Callable[[str], float]:
    """argparse type: a time ("2 ms", "0.5 s" or a number of seconds) that must be > 0;
    ``what`` names it in the message ("the time step"), ``example`` is a valid value."""

    def parse(text: str) -> float:
        try:
            value = parse_quantity(_number_or_text(text), "time")
        except ParameterError as e:
            raise argparse.ArgumentTypeError(str(e)) from None
        if not value > 0.0:  # also NaN
            raise argparse.ArgumentTypeError(
                f"{text!r} is {value:g} s: {what} must be > 0 (e.g. {example!r})"
            )
        return value

    return parse


_step = _positive_time("the time step", "1 ms")
_duration = _positive_time("the simulated time", "0.5 s")
_record_interval = _positive_time("the recording interval", "10 ms")


def _demo_speed(text: str) -> float:
    """argparse type of the demo's speed: a number of mph or a speed with its unit ("60
    km/h"), > 0; m/s."""
    number = _number_or_text(text)
    try:
        value = mph(number) if isinstance(number, float) else parse_quantity(number, "speed")
    except ParameterError:
        raise argparse.ArgumentTypeError(f"{text!r}: give a number of mph or a speed with its "
                                         'unit, e.g. 30 or "50 km/h"') from None  # fmt: skip
    if not (value > 0.0 and math.isfinite(value)):
        raise argparse.ArgumentTypeError(
            f"{text!r}: red must drive towards blue, give a finite speed > 0 (e.g. 30)"
        )
    return value


def _number_or_text(text: str) -> float | str:
    try:
        return float(text)
    except ValueError:
        return text


def _positive_int(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 1")
    return value


def _seed(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text!r} must be >= 0")
    return value
