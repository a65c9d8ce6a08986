#!/usr/bin/env bash
# Configures and builds hairshadow in Release into build/ (set BUILD_DIR to change it), with Ninja
# where it is installed (a folder configured before keeps its generator). Arguments: CMake options
# (-D...) for the configuration, and --target NAME (repeatable) to build only those targets.
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${BUILD_DIR:-build}
config=()
targets=()
while [ $# -gt 0 ]; do
    case "$1" in
        --target) targets+=(--target "$2"); shift 2 ;;
        *) config+=("$1"); shift ;;
    esac
done
generator=()
if [ ! -f "$build_dir/CMakeCache.txt" ] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S . -B "$build_dir" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release "${config[@]}" >/dev/null
cmake --build "$build_dir" -j"${JOBS:-2}" "${targets[@]}"
