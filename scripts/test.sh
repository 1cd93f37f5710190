#!/usr/bin/env bash
# The README's test command: set up and run every test (Rust and Python).
# Installs the project with its test extras (this builds the Rust extension), then runs
# the core's cargo tests and the pytest suite. Meshes are read from ../shared/meshes.
set -euo pipefail
cd "$(dirname "$0")/.."
# The case viewer's browser tests (tests/test_view.py) need Debian's chromium and its driver;
# libjs-three is the three.js r111 the viewer vendors (python/crashsim/io/viewer/static/three).
# Installed only when missing, and only as root (elsewhere the tests say what is missing).
missing=()
for pkg in chromium chromium-driver libjs-three; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
done
if [ ${#missing[@]} -gt 0 ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
fi
python3 -m pip install --quiet ".[test]"
# Not incremental: the test build starts from an empty target folder here, and writing the
# incremental caches costs about 10 s of its 95 (benches/README.md, "The test run").
CARGO_INCREMENTAL=0 cargo test --workspace --exclude crashsim-py --quiet
# pytest on every core (pytest-xdist: each test runs whole in one worker, so what a test
# checks is unchanged).
python3 -m pytest -n auto tests
