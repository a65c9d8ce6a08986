#!/usr/bin/env bash
# The main job: set up, build in Release, and render the exact reference's transmittance of the
# built-in procedural model, as seen from the light, to out/reference.png, and compare every
# published method with it (out/compare/compare.md and .csv).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
./build/tools/hairshadow info procedural:curly
./build/tools/hairshadow render procedural:curly --method dsm --light dir:0,-1,-1 --res 512 --out out/reference.png
./build/tools/hairshadow compare procedural:curly --light dir:0,-1,-1 --res 512 --out out/compare
