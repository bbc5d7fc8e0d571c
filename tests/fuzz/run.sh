#!/usr/bin/env bash
# run.sh - runs the fuzz harnesses built by tools/make/fuzz.mk.
#
#   run.sh TARGET SECONDS     every input of tests/fuzz/corpus/TARGET/, then
#                             fuzzing from them for SECONDS; one line with
#                             executions and coverage, or the crash, its input
#                             and how to reproduce it (exit 1)
#   run.sh --known TARGET...  each reproducer in tests/fuzz/known/TARGET/
#                             without the known defects' suppressions: it
#                             must still fail as its .expect says, or pass
#                             (then the defect was fixed: the line says what
#                             to do); anything else fails
#
# FUZZ_DIR (build/fuzz) holds the binaries (bin/) and each target's run
# (run/TARGET/: log, new inputs in new/, crash-* files).  The committed
# corpus is only read.
set -uo pipefail
cd "$(dirname "$0")/../.."
FUZZ_DIR=${FUZZ_DIR:-build/fuzz}
SUPP=$PWD/tests/fuzz/known_defects.supp
# Leaks count as defects; OSMesa's own (tests/lsan.supp) do not.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/tests/lsan.supp}

fuzz_one() {
    local t=$1 secs=$2 bin=$FUZZ_DIR/bin/$1 work=$FUZZ_DIR/run/$1
    rm -rf "$work" && mkdir -p "$work/new"
    # -timeout: one input stuck for 20 s is a hang, and a defect;
    # -rss_limit_mb: the sanitizers' own memory included.
    UBSAN_OPTIONS=suppressions=$SUPP "$bin" -max_total_time="$secs" -timeout=20 -rss_limit_mb=2560 \
        -artifact_prefix="$work/" "$work/new" "tests/fuzz/corpus/$t" > "$work/log" 2>&1
    local rc=$?
    if [ $rc -ne 0 ]; then
        local crash
        crash=$(ls "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-* 2>/dev/null | head -1)
        # What the harness or a sanitizer said, without libFuzzer's own stack.
        grep -B4 -A1 -E 'ERROR|runtime error|property failed' "$work/log" | grep -vE '^ +#[0-9]|^#[0-9]+ ' | head -30
        grep -E '^ +#[0-9]+ .* in (LLVMFuzzerTestOneInput|[a-z_]+ /)' "$work/log" | head -12
        echo "fuzz $t: FAILED (status $rc); log $work/log"
        [ -n "$crash" ] && echo "fuzz $t: input $crash; reproduce with: $bin $crash"
        return 1
    fi
    # libFuzzer's own figures: "Done N runs in S second(s)", the last
    # status line's coverage (cov: edges, ft: features) and corpus.
    local runs took cov corpus
    read -r runs took < <(sed -nE 's/^Done ([0-9]+) runs in ([0-9]+) second.*/\1 \2/p' "$work/log")
    cov=$(grep -oE 'cov: [0-9]+ ft: [0-9]+' "$work/log" | tail -1)
    corpus=$(grep -oE 'corp: [0-9]+/[0-9]+[a-zA-Z]*' "$work/log" | tail -1)
    printf 'fuzz %s: %s runs in %s s (%s/s), %s, %s, %s new inputs, no crash\n' \
        "$t" "$runs" "$took" "$((runs / (took > 0 ? took : 1)))" "$cov" "$corpus" "$(ls "$work/new" | wc -l)"
}

known() {
    local rc=0 t f out
    for t in "$@"; do
        for f in tests/fuzz/known/"$t"/*; do
            [ -f "$f" ] && [ "${f%.expect}" = "$f" ] || continue
            out=$("$FUZZ_DIR/bin/$t" "$f" 2>&1)
            if [ $? -eq 0 ]; then
                echo "fuzz known $f: no longer fails, its defect was fixed: move it into" \
                     "tests/fuzz/corpus/$t/ and drop its line from tests/fuzz/known_defects.supp"
            elif grep -qE "$(cat "$f.expect")" <<<"$out"; then
                echo "fuzz known $f: still fails as expected ($(grep -m1 -oE 'runtime error: .*' <<<"$out"))"
            else
                echo "$out" | tail -30
                echo "fuzz known $f: FAILED otherwise than $f.expect says"
                rc=1
            fi
        done
    done
    return $rc
}

if [ "${1:-}" = --known ]; then
    shift
    known "$@"
else
    fuzz_one "$1" "$2"
fi
