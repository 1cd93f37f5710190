import sys

from crashsim.cli import main

sys.exit(main())
