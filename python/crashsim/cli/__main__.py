"""`python -m crashsim.cli ...` runs the command line, as the old module did."""

from crashsim.cli import console_main

console_main()
