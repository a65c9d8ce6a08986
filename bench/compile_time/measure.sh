#!/usr/bin/env bash
# What a user pays to compile hairshadow (issue 40's target: the single-header program in 3.5 s or
# less with g++ -O2): each program compiled RUNS times (default 5) with g++ -std=c++20 -O2, the
# median wall time and the peak memory printed, then the same with -fsyntax-only, with the AVX-512
# paths left out (-DHAIRSHADOW_NO_AVX512) and with the kernels compiled once apart
# (-DHAIRSHADOW_SEPARATE_KERNELS; the file that compiles them, tools/kernels.cpp, once at the end).
# ROOT, another checkout, compiles the same programs against its headers instead (old against new);
# a tree without the per-method header says so.
#   bash bench/compile_time/measure.sh [RUNS] [ROOT]
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-5}"
root="$(cd "${2:-.}" && pwd)"
timing="$(mktemp)"
trap 'rm -f "$timing"' EXIT
median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
measure() { # label, then the compiler's arguments
    local label="$1"; shift
    local times=() peak=0
    for _ in $(seq "$runs"); do
        if ! /usr/bin/time -o "$timing" -f '%e %M' g++ -std=c++20 -O2 "$@" -o /dev/null > /dev/null 2>&1; then
            printf '%-52s does not compile in %s\n' "$label" "$root"
            return 0
        fi
        local out
        out="$(tail -1 "$timing")"
        times+=("${out% *}")
        peak=$(( ${out#* } > peak ? ${out#* } : peak ))
    done
    printf '%-52s median %5.2f s of %d   peak %4d MB\n' "$label" "$(printf '%s\n' "${times[@]}" | median)" "$runs" $(( peak / 1024 ))
}
for program in single_header_user per_method_user; do
    include="$root/include"
    [ "$program" = single_header_user ] && include="$root/single_include"
    src="bench/compile_time/$program.cpp"
    measure "$program -O2" -I"$include" -c "$src"
    measure "$program -O2 -fsyntax-only" -I"$include" -fsyntax-only "$src"
    measure "$program -O2 -DHAIRSHADOW_NO_AVX512" -I"$include" -DHAIRSHADOW_NO_AVX512 -c "$src"
    measure "$program -O2 -DHAIRSHADOW_SEPARATE_KERNELS" -I"$include" -DHAIRSHADOW_SEPARATE_KERNELS -c "$src"
done
measure "tools/kernels.cpp -O2 (once per program)" -I"$root/include" -DHAIRSHADOW_SEPARATE_KERNELS -c tools/kernels.cpp
