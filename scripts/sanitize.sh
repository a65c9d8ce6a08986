#!/usr/bin/env bash
# The CPU test suite under clang's AddressSanitizer and UndefinedBehaviorSanitizer (every report is
# fatal), and the parallel kernels' tests under ThreadSanitizer (not the [dense] one, whose 1.5M-segment
# model takes minutes under TSan and whose threads do what the smaller [tiled] cases' do; nor the
# [raster] ones, whose time under TSan goes to walking tiles on one thread: their threads only project
# and bin, as the [tiled] build tests' do). Each builds in its own folder. CI (.ci/run) runs this after
# the README's test command.
#   bash scripts/sanitize.sh [address|thread]    (both by default)
set -euo pipefail
cd "$(dirname "$0")/.."
which="${1:-all}"

build_suite() { # FOLDER SANITIZERS TARGET...
    cmake -S . -B "$1" -DCMAKE_BUILD_TYPE= -DCMAKE_CXX_FLAGS="-O1" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DHAIRSHADOW_SANITIZE="$2" -DHAIRSHADOW_BUILD_EXAMPLES=OFF -DHAIRSHADOW_BUILD_BENCH=OFF -DHAIRSHADOW_INSTALL=OFF \
        > "$1.configure.log" 2>&1 || { cat "$1.configure.log"; exit 1; }
    local folder="$1"
    shift 2
    cmake --build "$folder" -j"${JOBS:-2}" --target "$@" > "$folder.build.log" 2>&1 || { tail -50 "$folder.build.log"; exit 1; }
}

if [ "$which" = all ] || [ "$which" = address ]; then
    build_suite build-asan address,undefined hairshadow_tests hairshadow_cli
    echo "sanitize: the CPU suite under ASan and UBSan"
    ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
        build-asan/tests/hairshadow_tests --order rand --rng-seed 1
fi
if [ "$which" = all ] || [ "$which" = thread ]; then
    build_suite build-tsan thread hairshadow_parallel_tests
    echo "sanitize: the parallel kernels' tests under TSan"
    TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1" build-tsan/tests/hairshadow_parallel_tests "[tiled]~[dense]~[raster],[parallel],[determinism]"
fi
