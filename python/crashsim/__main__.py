"""`python -m crashsim ...` runs the command line (see crashsim.cli)."""

from crashsim.cli import console_main

console_main()
