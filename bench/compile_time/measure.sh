#!/usr/bin/env bash
# What a user pays to compile hairshadow (issue 40's target: the single-header program in 3.5 s or
# less with g++ -O2): each program compiled RUNS times (default 5) with g++ -std=c++20 -O2, the
# median wall time and the peak memory printed, then the same with -fsyntax-only and with the
# AVX-512 paths left out (-DHAIRSHADOW_NO_AVX512).
#   bash bench/compile_time/measure.sh [RUNS]
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-5}"
median() { sort -n | awk '{v[NR] = $1} END {print v[int((NR + 1) / 2)]}'; }
measure() { # label, then the compiler's arguments
    local label="$1"; shift
    local times=() peak=0
    for _ in $(seq "$runs"); do
        local out
        out="$( { /usr/bin/time -f '%e %M' g++ -std=c++20 -O2 "$@" -o /dev/null 2>&1 1>/dev/null; } 2>&1 | tail -1)"
        times+=("${out% *}")
        peak=$(( ${out#* } > peak ? ${out#* } : peak ))
    done
    printf '%-44s median %5.2f s of %d   peak %4d MB\n' "$label" "$(printf '%s\n' "${times[@]}" | median)" "$runs" $(( peak / 1024 ))
}
for program in single_header_user per_method_user; do
    include=include
    [ "$program" = single_header_user ] && include=single_include
    src="bench/compile_time/$program.cpp"
    measure "$program -O2" -I"$include" -c "$src"
    measure "$program -O2 -fsyntax-only" -I"$include" -fsyntax-only "$src"
    measure "$program -O2 -DHAIRSHADOW_NO_AVX512" -I"$include" -DHAIRSHADOW_NO_AVX512 -c "$src"
done
