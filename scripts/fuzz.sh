#!/usr/bin/env bash
# Builds every fuzz target under tests/fuzz/ with clang's libFuzzer, ASan and UBSan, and runs each for
# SECONDS (default 60) over its committed corpus, two at a time. New inputs go to build-fuzz/corpus/,
# never into the committed corpus. Exits 1 if any target finds a crash, leak, timeout or out-of-memory;
# its reproducer is then in build-fuzz/artifacts/TARGET/: copy it to tests/data/fuzz/TARGET/, where the
# ordinary test suite replays it, and fix the defect.
#   bash scripts/fuzz.sh [SECONDS]        FUZZ_JOBS=N runs N targets at once (default 2)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
jobs="${FUZZ_JOBS:-2}"
build="${FUZZ_BUILD_DIR:-build-fuzz}"
targets=(hair data tfx obj points procedural_spec light_spec method_spec deep_exr)

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
    -DHAIRSHADOW_FUZZ=ON -DHAIRSHADOW_BUILD_TOOLS=OFF -DHAIRSHADOW_BUILD_EXAMPLES=OFF -DHAIRSHADOW_BUILD_BENCH=OFF \
    -DHAIRSHADOW_INSTALL=OFF > "$build.configure.log" 2>&1 || { cat "$build.configure.log"; exit 1; }
# Only the fuzz targets (and the CPU registry that method_spec links): the whole project would also
# compile the GL registry, which no target links, last and alone.
cmake --build "$build" -j"${JOBS:-2}" --target "${targets[@]/#/hairshadow_fuzz_}" hairshadow_method_spec_dictionary > "$build.build.log" 2>&1 || { tail -50 "$build.build.log"; exit 1; }
# The method specs' dictionary comes from the registered families.
"$build/tests/fuzz/hairshadow_method_spec_dictionary" > "$build/method_spec.dict"

export ASAN_OPTIONS="detect_leaks=1:allocator_may_return_null=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
run_target() {
    local t="$1" corpus="$build/corpus/$1" artifacts="$build/artifacts/$1/" dict=()
    mkdir -p "$corpus" "$artifacts"
    [ -f "tests/fuzz/$t.dict" ] && dict=(-dict="tests/fuzz/$t.dict")
    [ -f "$build/$t.dict" ] && dict=(-dict="$build/$t.dict")
    local seeds=("tests/fuzz/corpus/$t")
    [ -d "tests/data/fuzz/$t" ] && seeds+=("tests/data/fuzz/$t")
    "$build/tests/fuzz/hairshadow_fuzz_$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
        -artifact_prefix="$artifacts" "${dict[@]}" "$corpus" "${seeds[@]}" > "$build/$t.log" 2>&1
}

failed=()
pids=()
names=()
for t in "${targets[@]}"; do
    run_target "$t" &
    pids+=($!)
    names+=("$t")
    if [ ${#pids[@]} -ge "$jobs" ]; then
        wait "${pids[0]}" || failed+=("${names[0]}")
        pids=("${pids[@]:1}")
        names=("${names[@]:1}")
    fi
done
for i in "${!pids[@]}"; do wait "${pids[$i]}" || failed+=("${names[$i]}"); done

printf '| target | executions | seconds | corpus |\n|---|---|---|---|\n'
for t in "${targets[@]}"; do
    # (a crashed run prints neither line: no failure here, so that its report below still prints)
    runs=$(grep -oE 'stat::number_of_executed_units: *[0-9]+' "$build/$t.log" | grep -oE '[0-9]+$' | tail -1 || true)
    secs=$(grep -oE 'Done [0-9]+ runs in [0-9]+ second' "$build/$t.log" | grep -oE 'in [0-9]+' | grep -oE '[0-9]+' | tail -1 || true)
    printf '| %s | %s | %s | %s |\n' "$t" "${runs:-?}" "${secs:-?}" "$(ls "$build/corpus/$t" | wc -l)"
done
if [ ${#failed[@]} -gt 0 ]; then
    for t in "${failed[@]}"; do
        echo "fuzz: $t failed; the end of its log ($build/$t.log):" >&2
        tail -40 "$build/$t.log" >&2
        ls "$build/artifacts/$t/" >&2
    done
    exit 1
fi
echo "fuzz: ${#targets[@]} targets, ${seconds} s each, no failure"
