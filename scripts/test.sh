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
# In the background, beside the two builds (the install is about 40 s of CPU). Two alternated
# pairs on clean clones at load 3 (2026-11-28): 605 and 686 s against 698 and 677 s in the
# foreground, within the noise. A failed install fails the command, as in the foreground.
apt_pid=""
apt_log="$(mktemp)"
if [ ${#missing[@]} -gt 0 ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}") \
        >"$apt_log" 2>&1 &
    apt_pid=$!
fi
python3 -m pip install --quiet ".[test]"
# Not incremental: the test build starts from an empty target folder here, and writing the
# incremental caches costs about 10 s of its 95 (benches/README.md, "The test run").
CARGO_INCREMENTAL=0 cargo test --workspace --exclude crashsim-py --quiet
if [ -n "$apt_pid" ] && ! wait "$apt_pid"; then
    echo "installing ${missing[*]} with apt-get failed:" >&2
    cat "$apt_log" >&2
    exit 1
fi
rm -f "$apt_log"
# pytest on every core (pytest-xdist: each test runs whole in one worker, so what a test
# checks is unchanged).
python3 -m pytest -n auto tests
