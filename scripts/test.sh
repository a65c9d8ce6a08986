#!/usr/bin/env bash
# Set up, build in Release and run the whole test suite; then the CPU suite under ASan and UBSan, the
# parallel kernels' tests under TSan (scripts/sanitize.sh), and every fuzz target for 30 s over its
# corpus (scripts/fuzz.sh). Any failure or sanitizer report fails the command.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"${JOBS:-2}"
bash scripts/sanitize.sh
bash scripts/fuzz.sh "${FUZZ_SECONDS:-30}"
