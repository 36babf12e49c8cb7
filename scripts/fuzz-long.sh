#!/usr/bin/env bash
# The long fuzz runs, outside CI: every libFuzzer harness (tests/fuzz) built with clang,
# AddressSanitizer and UndefinedBehaviorSanitizer in ./build-fuzz, run for SECONDS each
# (default 600) on a corpus that starts from its seeds in tests/fuzz/corpus and is kept in
# build-fuzz/long/<target>/corpus, so a second run goes on from where the first stopped.
# Prints one Markdown row per target: seconds, executions, executions per second, covered
# edges, corpus size, peak memory and the findings (crash-*, leak-*, timeout-*, oom-* files,
# kept in build-fuzz/long/<target>/). Exits 1 when any target found something.
# Usage: scripts/fuzz-long.sh [SECONDS] [TARGET...]   (NICE=n sets the niceness, default 10;
# PARALLEL=n runs n targets at a time, default 1)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
shift || true
root="$PWD"
tree="$root/build-fuzz"
nice="${NICE:-10}"

clangxx="$(command -v clang++ || command -v clang++-14 || true)"
if [ -z "$clangxx" ]; then
    echo "fuzz-long: clang++ not found (Debian package clang); libFuzzer needs it" >&2
    exit 2
fi
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S tests/fuzz/project -B "$tree" "${launcher[@]}" -DCMAKE_CXX_COMPILER="$clangxx" \
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DANASCAN_ROOT="$root" >/dev/null
nice -n "$nice" cmake --build "$tree" -j "${JOBS:-2}" >/dev/null

targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then
    mapfile -t targets < <(find "$tree" -maxdepth 1 -name 'fuzz_*' -type f -executable -printf '%f\n' | sort)
fi

# The value of a libFuzzer final statistic (stat::NAME: VALUE) in LOG, or "?".
stat_of() { sed -n "s/^stat::$2: *//p" "$1" | tail -n 1 | grep . || echo "?"; }
# The "cov:" and "corp:" figures of the last status line in LOG.
last_status() { grep -E '^#[0-9]+' "$1" | tail -n 1 | sed -n "s/.* $2: \([0-9/a-zA-Z]*\).*/\1/p"; }

# Runs TARGET for the given seconds; writes its table row to build-fuzz/long/TARGET/row.md.
run_target() {
    local target="$1" work="$tree/long/$1" status=0
    mkdir -p "$work/corpus"
    rm -f "$work"/crash-* "$work"/leak-* "$work"/timeout-* "$work"/oom-*
    if [ -d "tests/fuzz/corpus/$target" ]; then cp -n "tests/fuzz/corpus/$target"/* "$work/corpus/" 2>/dev/null || true; fi
    local log="$work/run.log"
    (cd "$work" && nice -n "$nice" "$tree/$target" -max_total_time="$seconds" -rss_limit_mb=2048 \
        -timeout=10 -max_len=65536 -print_final_stats=1 -artifact_prefix="$work/" corpus) \
        >"$log" 2>&1 || status=$?
    local findings
    findings="$(find "$work" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)"
    local per_second
    per_second="$(grep -E '^#[0-9]+' "$log" | tail -n 1 | sed -n 's/.*exec\/s: \([0-9]*\).*/\1/p')"
    local note=""
    if [ "$status" -ne 0 ]; then note=" (exit $status, see $log)"; fi
    echo "| $target | $seconds | $(stat_of "$log" number_of_executed_units) | ${per_second:-?} | $(last_status "$log" cov) | $(last_status "$log" corp) | $(stat_of "$log" peak_rss_mb) MB | $findings$note |" >"$work/row.md"
}

# PARALLEL targets at a time (default 1): each is one process on one core.
parallel="${PARALLEL:-1}"
for target in "${targets[@]}"; do
    while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
    run_target "$target" &
done
wait

echo "| target | seconds | executions | per second | edges covered | corpus | peak RSS | findings |"
echo "|---|---|---|---|---|---|---|---|"
found=0
for target in "${targets[@]}"; do
    row="$(cat "$tree/long/$target/row.md")"
    echo "$row"
    case "$row" in *"| 0 |") ;; *) found=1 ;; esac
done
exit "$found"
