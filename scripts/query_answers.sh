#!/usr/bin/env bash
# The answers of `hairshadow query` for every method spec the grammar allows (every size of every
# family, float and 8-bit, and the hybrids, TressFX's and the exact maps), at fixed points of the
# Sintel hair: one line per spec, the spec and the SHA-256 of its answers. Two builds that print the
# same lines answer every query the same, to the byte: the check that a change moved no map.
#   bash scripts/query_answers.sh [HAIRSHADOW] [MODEL] > answers.txt     (default build/tools/hairshadow, Sintel)
set -euo pipefail
cd "$(dirname "$0")/.."
cli="${1:-build/tools/hairshadow}"
model="${2:-../shared/data/sintel/sintel_hair.16points.tfx}"
points="$(mktemp)"
trap 'rm -f "$points"' EXIT
# 2,000 points in the Sintel hair's box (a fixed pseudo-random sequence; another model gets the same
# points, so give it one of about that box).
python3 - "$points" <<'PY'
import random, sys
r = random.Random(39)
with open(sys.argv[1], "w") as f:
    for _ in range(2000):
        f.write("%.6f %.6f %.6f\n" % (r.uniform(-0.12, 0.11), r.uniform(1.39, 1.68), r.uniform(-0.14, 0.14)))
PY
specs=()
for n in 1 2 4 8 16 32 64 128 256 512; do specs+=("osm:$n" "osm:$n:gamma" "osm:$n:8bit" "osm:$n:gamma:8bit"); done
for k in 1 2 3 4 5 6 7 8; do specs+=("dom:$k" "dom:$k:8bit" "dc:$k" "dc:$k:8bit"); done
for s in 32 64 128 256; do for b in 1 2 4 8; do specs+=("occ:$s:$b" "occ:$s:$b:8bit" "docc:$s:$b"); done; done
for n in 4 8 16 32 64 128 256; do specs+=("rosm:$n"); done
specs+=(adsm adsm:auto adsm:0.5:0.01:0.2 adsm:0.5:0.01:0.2:20 dsm dsm:0.01)
answers="$(mktemp)"
trap 'rm -f "$points" "$answers"' EXIT
for spec in "${specs[@]}"; do
    "$cli" query "$model" --method "$spec" --points "$points" --res 128 > "$answers"
    [ "$(wc -l < "$answers")" -eq 2000 ] || { echo "error: $spec gave $(wc -l < "$answers") answers" >&2; exit 1; }
    printf '%s %s\n' "$spec" "$(sha256sum < "$answers" | cut -c1-16)"
done
