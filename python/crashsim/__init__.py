from crashsim import _core  # placeholder
