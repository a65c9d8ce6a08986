#!/usr/bin/env bash
# Installs, with apt-get, the Debian 12 packages hairshadow needs (only those missing). Run as root,
# or with sudo available.
#   bash scripts/setup.sh        everything: the build, the tests, the benchmarks, the viewer, the
#                                sanitizer and fuzz checks
#   bash scripts/setup.sh main   only what the command line needs (the main job: the figure)
set -euo pipefail
main=(build-essential cmake ninja-build pkg-config python3 libglm-dev libstb-dev libcli11-dev python3-glad libosmesa6-dev libegl-dev
      libgl1-mesa-dri libopenexr-dev)
rest=(catch2 libbenchmark-dev glslang-tools libglfw3-dev xvfb xauth clang libclang-rt-14-dev python3-dev pybind11-dev python3-numpy python3-pytest
      python3-matplotlib)
case "${1:-all}" in
    main) packages=("${main[@]}") ;;
    all) packages=("${main[@]}" "${rest[@]}") ;;
    *) echo "usage: bash scripts/setup.sh [main|all]" >&2; exit 2 ;;
esac
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    [ "$(id -u)" -eq 0 ] || sudo="sudo"
    echo "setup: installing ${missing[*]}"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
