#!/usr/bin/env bash
# Set up, build everything in Release (the library's tests, examples, benchmarks and the command) and
# run the whole test suite with ctest. The sanitizer builds and the fuzz runs are apart, in CI
# (.ci/run): scripts/sanitize.sh and scripts/fuzz.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh -DHAIRSHADOW_BUILD_TESTS=ON -DHAIRSHADOW_BUILD_EXAMPLES=ON -DHAIRSHADOW_BUILD_BENCH=ON
ctest --test-dir build --output-on-failure -j"${JOBS:-2}"
