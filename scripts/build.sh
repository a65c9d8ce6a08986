#!/usr/bin/env bash
# Configures and builds hairshadow in Release into build/ (set BUILD_DIR to change it).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build_dir" -j"${JOBS:-2}"
