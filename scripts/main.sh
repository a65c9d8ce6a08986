#!/usr/bin/env bash
# The main job: set up, build in Release, and write the comparison figure (figure.png, crops.png,
# heatmaps.png, rays.svg, compare.md/csv) of the built-in procedural model on its sphere to out/figure.
# Any argument goes to `hairshadow figure`, e.g. the Sintel hair on its head:
#   bash scripts/main.sh --model ../shared/data/sintel/sintel_hair.16points.tfx --mesh ../shared/data/sintel/sintel_head.obj
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
out=(--out out/figure)
for arg in "$@"; do [ "$arg" = "--out" ] && out=(); done
./build/tools/hairshadow figure "${out[@]}" "$@"
