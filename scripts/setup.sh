#!/usr/bin/env bash
# Installs, with apt-get, every Debian 12 package hairshadow builds, tests or benchmarks with
# (only those missing). Run as root, or with sudo available.
set -euo pipefail
packages=(build-essential cmake pkg-config python3 libglm-dev catch2 libstb-dev libcli11-dev
          libbenchmark-dev python3-glad libosmesa6-dev libegl-dev libgl1-mesa-dri glslang-tools libglfw3-dev xvfb xauth
          clang libclang-rt-14-dev)
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
