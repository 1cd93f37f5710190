#!/usr/bin/env bash
# The README's test command: set up and run every test (Rust and Python).
# Installs the project with its test extras (this builds the Rust extension), then runs
# the core's cargo tests and the pytest suite. Meshes are read from ../shared/meshes.
set -euo pipefail
cd "$(dirname "$0")/.."
python3 -m pip install --quiet ".[test]"
cargo test --workspace --exclude crashsim-py --quiet
# Run pytest from tests/ so the installed package (not the source tree) is imported.
python3 -m pytest tests
