"""`python -m crashsim ...` runs the command line (see crashsim.cli)."""

import sys

from crashsim.cli import main

sys.exit(main())
