"""The entry points: ``main`` (the exit code; every error one line on stderr) and
``console_main`` (the executable)."""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from collections.abc import Callable, Sequence
from typing import Any, NoReturn

from crashsim.cli.common import EXIT_FAILED, EXIT_INPUT, EXIT_INTERRUPTED, RunFailed
from crashsim.cli.parser import _parser
from crashsim.errors import CrashsimError, SimulationError


def _show_warning(
    message: Warning | str,
    category: type[Warning],
    filename: str,
    lineno: int,
    file: Any = None,
    line: str | None = None,
) -> None:
    print(f"crashsim: warning: {' '.join(str(message).split())}", file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``crashsim`` command; returns the exit code (0 success, 1 the run
    or check failed, 2 bad input, 130 interrupted). Bad arguments exit 2 through SystemExit,
    as argparse does."""
    args = _parser().parse_args(argv)
    func: Callable[[argparse.Namespace], int] = args.func
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("default")  # every warning once, as one line on stderr
            warnings.showwarning = _show_warning
            code = int(func(args))
        sys.stdout.flush()  # here, so a closed pipe is caught below
        return code
    except KeyboardInterrupt:
        print("crashsim: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except (SimulationError, RunFailed) as e:
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_FAILED
    except CrashsimError as e:  # the input is at fault
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_INPUT
    except BrokenPipeError:  # stdout's reader stopped (crashsim run ... | head)
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no error at exit
        return EXIT_FAILED
    except OSError as e:  # writing an output failed (disk full, permissions, ...)
        print(f"crashsim: error: {' '.join(str(e).split())}", file=sys.stderr)
        return EXIT_FAILED


def console_main() -> NoReturn:
    """The ``crashsim`` executable: :func:`main`, then the exit. After Ctrl-C it exits at once
    (the streams flushed, the interpreter's teardown skipped: it took about 0.5 s with the
    scientific libraries loaded, and the README promises a stop within 0.5 s)."""
    code = main()
    if code == EXIT_INTERRUPTED:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(code)
    sys.exit(code)
