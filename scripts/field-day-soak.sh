#!/usr/bin/env bash
# A long field day, simulated and headless: STONES stones (simulated structured light, the
# scenes below in turn), each captured in one `anascan capture` run of SCANS/STONES views and
# turned over half way, then re-registered in part (`session register --scan`), one scan
# excluded, and checked. While each capture runs, its resident memory (VmRSS), open file
# descriptors and threads are sampled every second. Prints, per stone: RSS (its peak over the
# scans right after warm-up, the first 10 % of the scans, against its peak over the last ones;
# the end) and descriptors, and the time per scan (saved
# to registered, and between two registrations) over the first 10 scans against the last 10;
# the database size. Usage: scripts/field-day-soak.sh [SCANS] [STONES] [BUILD_DIR] [OUT_DIR]
# (defaults 300, 3, build, a new temporary folder). Kept there: capture logs and samples.
# FIELD_DAY_GUI=1: each stone is captured by the field app (`anascan-field --capture-views
# --log-events`) drawing on a virtual X server (Xvfb :97), the GUI attached; the samples are
# then the app's. FIELD_DAY_SCENES: the scenes taken in turn (default "small-block
# octagon-block large-block"; one scene makes the stones comparable across the day).
set -euo pipefail
cd "$(dirname "$0")/.."
scans="${1:-300}"
stones="${2:-3}"
build="${3:-build}"
out="${4:-$(mktemp -d /tmp/field-day.XXXXXX)}"
cli="$PWD/$build/acquisition/anascan"
field="$PWD/$build/gui/anascan-field"
read -r -a scenes <<<"${FIELD_DAY_SCENES:-small-block octagon-block large-block}"
per_stone=$((scans / stones))
mkdir -p "$out"
: >"$out/peaks"
echo "field day: $stones stones x $per_stone scans in $out"

# Samples PID every second into FILE: seconds since start, scans saved so far, RSS kB, fds,
# threads; until the process ends.
sample() {
    local pid="$1" file="$2" log="$3" start=$SECONDS
    while [ -d "/proc/$pid" ]; do
        local rss fds threads saved
        rss=$(awk '/^VmRSS:/ { print $2 }' "/proc/$pid/status" 2>/dev/null) || break
        threads=$(awk '/^Threads:/ { print $2 }' "/proc/$pid/status" 2>/dev/null) || break
        fds=$(find "/proc/$pid/fd" -mindepth 1 -maxdepth 1 2>/dev/null | wc -l)
        saved=$(grep -c '^saved scan ' "$log" || true)
        [ -n "$rss" ] && echo "$((SECONDS - start)) $saved $rss $fds $threads" >>"$file"
        sleep 1
    done
}

# The figures of one stone from its samples and capture log.
report() {
    local samples="$1" log="$2" n="$3"
    awk -v n="$n" '
        { t[NR] = $1; s[NR] = $2; rss[NR] = $3; fd[NR] = $4; th[NR] = $5 }
        END {
            # Warm-up: the first 10 % of the scans. Each figure is the peak over a window of
            # as many scans (the working set of a scan, its transients included), right
            # after warm-up and at the last scans.
            warm = int(n / 10); if (warm < 1) warm = 1
            for (i = 1; i <= NR; i++) {
                if (s[i] > warm && s[i] <= 2 * warm && rss[i] > first) first = rss[i]
                if (s[i] > n - warm && s[i] < n && rss[i] > last) last = rss[i]
                if (s[i] > warm) {
                    if (!w) w = i
                    if (rss[i] > maxrss) maxrss = rss[i]
                    if (fd[i] > maxfd) maxfd = fd[i]
                    if (th[i] > maxth) maxth = th[i]
                }
            }
            if (!first) first = rss[w]
            printf "  RSS peak over scans %d-%d (after warm-up) %d kB, over scans %d-%d %d kB (%+.1f %%, %.2f MB per scan); peak after warm-up %d kB (%+.1f %%), at the end %d kB\n",
                warm + 1, 2 * warm, first, n - warm + 1, n - 1, last, 100 * (last - first) / first,
                (last - first) / 1000 / (n - 2 * warm), maxrss, 100 * (maxrss - first) / first, rss[NR]
            printf "  descriptors after warm-up %d, peak after it %d, at the end %d; threads %d, peak %d\n",
                fd[w], maxfd, fd[NR], th[w], maxth
            printf "%d\n", maxrss > "/dev/stderr"
        }' "$samples"
    grep -o 'registered scan [0-9]*: .*, [0-9.]* s after saving' "$log" |
        awk -v n="$n" '{ lat[NR] = $(NF - 3) }
            END {
                k = 10; if (NR < 2 * k) k = int(NR / 2)
                for (i = 1; i <= k; i++) { a += lat[i]; b += lat[NR - k + i] }
                printf "  saved to registered: first %d scans %.2f s, last %d %.2f s (%+.0f %%)\n",
                    k, a / k, k, b / k, 100 * (b - a) / a }'
    grep '^[0-9.]* registered scan ' "$log.timed" |
        awk '{ t[NR] = $1 } END {
            k = 10; if (NR < 2 * k + 1) k = int((NR - 1) / 2)
            a = (t[k + 1] - t[1]) / k; b = (t[NR] - t[NR - k]) / k
            printf "  between registrations: first %d scans %.2f s, last %d %.2f s (%+.0f %%)\n",
                k, a, k, b, 100 * (b - a) / a }'
}

# One stone's capture, in the foreground of its (background) caller: `anascan capture`, or
# with FIELD_DAY_GUI=1 the field app capturing through its capture action on the day's
# virtual X server (rendering every frame: the GUI attached).
capture_stone() {
    local scene="$1" session="$2" i="$3"
    if [ -n "${FIELD_DAY_GUI:-}" ]; then
        exec "$field" --session "$session" --device "sim:structured-light/$scene" \
            --capture-views "$per_stone" --tour-views "$per_stone" \
            --flip-after $((per_stone / 2)) --frames 3 --log-events \
            --session-timeout-s 7200 --width 1280 --height 800
    fi
    exec "$cli" ${FIELD_DAY_VERBOSE:+-v} --accept-poor capture --device sim:structured-light \
        --scene "$scene" --session "$session" --views "$per_stone" \
        --flip-after $((per_stone / 2)) --tour-seed $((i + 1)) --no-coverage
}

if [ -n "${FIELD_DAY_GUI:-}" ]; then
    Xvfb :97 -screen 0 1280x800x24 -nolisten tcp >/dev/null 2>&1 &
    xvfb=$!
    trap 'kill "$xvfb" 2>/dev/null || true' EXIT
    export DISPLAY=:97 LP_NUM_THREADS=2
    sleep 2
fi

for ((i = 0; i < stones; i++)); do
    scene="${scenes[i % ${#scenes[@]}]}"
    session="$out/stone-$((i + 1))"
    log="$out/stone-$((i + 1)).log"
    samples="$out/stone-$((i + 1)).samples"
    : >"$samples"
    start=$SECONDS
    # Each line stamped with the time it arrived (registration times per scan).
    capture_stone "$scene" "$session" "$i" > >(tee "$log" |
        while IFS= read -r line; do echo "$(date +%s.%N) $line"; done >"$log.timed") 2>&1 &
    pid=$!
    sample "$pid" "$samples" "$log"
    wait "$pid" || { echo "stone $((i + 1)): capture failed (exit $?), see $log" >&2; exit 1; }
    sleep 1
    echo "stone $((i + 1)) ($scene): $per_stone scans in $((SECONDS - start)) s"
    report "$samples" "$log" "$per_stone" 2>>"$out/peaks"
    "$cli" --accept-poor session register "$session" --scan 2 --scan $((per_stone / 2 + 1)) \
        >"$out/stone-$((i + 1)).register.log" 2>&1
    "$cli" session exclude "$session" 3 >/dev/null
    "$cli" session check "$session" | tail -n 1
    echo "  database $(du -k "$session/session.sqlite" | cut -f1) kB," \
        "scans folder $(du -sk "$session/scans" | cut -f1) kB"
done
# Across the day (each stone its own process): every stone's peak against the first's.
awk 'NR == 1 { first = $1 } { printf "stone %d: peak RSS %d kB (%+.1f %% of stone 1)\n", NR, $1, 100 * ($1 - first) / first }' "$out/peaks"
