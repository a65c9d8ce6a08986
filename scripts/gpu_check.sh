#!/usr/bin/env bash
# The compute build path's GPU run (issue 13) as one command. On a machine with an NVIDIA GPU and its
# EGL driver, it checks the compute-built maps of Sintel and of the 1.5M-segment curly model against
# the CPU's and times both GL build paths by timer queries at 512x512 and 2048x2048
# (bench/gl_gpu_check.cpp), printing the Markdown tables BENCHMARKS.md takes.
#
#   bash scripts/gpu_check.sh --prepare   here: build the program, copy the Sintel hair into .gpu/ and
#                                         download the EGL loader packages into .gl/ (both ignored by git)
#   bash scripts/gpu_check.sh             there (carry .gl, .gpu and build): unpack the loaders, run
set -euo pipefail
cd "$(dirname "$0")/.."
if [ "${1:-}" = "--prepare" ]; then
    cmake --build build --target hairshadow_gl_gpu_check -j"${JOBS:-2}"
    grep -qx '/.gl/' .git/info/exclude || echo /.gl/ >> .git/info/exclude
    grep -qx '/.gpu/' .git/info/exclude || echo /.gpu/ >> .git/info/exclude
    mkdir -p .gpu .gl /tmp/amd64/partial
    cp ../shared/data/sintel/sintel_hair.16points.tfx .gpu/
    o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
    apt-get $o update -qq
    (cd .gl && apt-get $o download libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
    exit 0
fi
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
export __EGL_VENDOR_LIBRARY_FILENAMES=${__EGL_VENDOR_LIBRARY_FILENAMES:-/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json}
build/bench/hairshadow_gl_gpu_check --context egl --large --repeat "${REPEAT:-5}" --model .gpu/sintel_hair.16points.tfx \
    --model procedural:curly:strands=10000:segments=150
