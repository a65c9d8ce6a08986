#!/usr/bin/env bash
# The main job: set up what the command line needs, build it alone in Release, and write the
# comparison figure (figure.png, crops.png, heatmaps.png, rays.svg, memory.svg, compare.md/csv) of the built-in
# procedural model on its sphere to out/figure. Any argument goes to `hairshadow figure`, e.g. the
# Sintel hair on its head:
#   bash scripts/main.sh --model ../shared/data/sintel/sintel_hair.16points.tfx --mesh ../shared/data/sintel/sintel_head.obj
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh main
# Only the command: the tests, examples and benchmarks are the test command's (scripts/test.sh turns
# them on again in the same folder, reusing what this built).
bash scripts/build.sh -DHAIRSHADOW_BUILD_TESTS=OFF -DHAIRSHADOW_BUILD_EXAMPLES=OFF -DHAIRSHADOW_BUILD_BENCH=OFF --target hairshadow_cli
out=(--out out/figure)
for arg in "$@"; do [ "$arg" = "--out" ] && out=(); done
./build/tools/hairshadow figure "${out[@]}" "$@"
