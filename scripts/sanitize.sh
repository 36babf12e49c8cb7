#!/usr/bin/env bash
# The sanitizer part of CI (scripts/test.sh runs it after the Release suite): the tests built
# with AddressSanitizer + UndefinedBehaviorSanitizer in ./build-asan and with ThreadSanitizer
# in ./build-tsan, each tree holding only the targets its set needs (-O1, no benchmarks, no
# fuzzers). A test fails on any finding, in the test itself or in a child it runs (the
# `anascan` and `anascan-field` commands are instrumented too): reports go to
# <tree>/sanitizer-reports/, and any report there fails this script, whatever the exit code
# the test saw. Usage: scripts/sanitize.sh [ci|asan|tsan|all] (default all; `ci` is what CI
# runs: the reduced ASan + UBSan set, in ./build-asan too, and the TSan set but for the
# `anascan capture` tests). The sets, why they are what they
# are, and the time each takes: docs/reliability.md.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${JOBS:-$(nproc)}"
nice="${NICE:-0}"
which="${1:-all}"

# ASan + UBSan: the unit and integration tests, except the long registration runs
# (minutes each in Release; their code runs under ASan in the unit tests and the CLI tests).
asan_targets=(anascan_session_store_tests anascan anascan_cli_session_tests
    anascan_cli_capture_tests anascan_cli_capture_crash_tests anascan_acquisition_tests
    anascan_processing_tests anascan_drivers_tests anascan_sl_tests
    anascan_drivers_umockdev_tests anascan_devices_cli_tests anascan_sim_tests
    anascan_sim_scanner_tests anascan_sim_device_tests anascan_device_control_tests
    anascan_live_registration_quick_tests anascan_cli_tests anascan_cli_sl_tests
    fuzz_ply_replay fuzz_text_points_replay fuzz_ptx_replay fuzz_stanford_conf_replay
    fuzz_xf_replay fuzz_obj_replay fuzz_stl_replay fuzz_e57_replay fuzz_recording_replay
    fuzz_calibration_replay fuzz_session_db_replay fuzz_grey_image_replay
    fuzz_campaign_store_replay fuzz_block_files_replay)
# The CI set, ASan + UBSan: the processing library (every parser and every algorithm) with
# its unit tests and the corpus replays of every processing parser's fuzz harness (the
# recording, calibration, session-database and grey-image harnesses need the driver and
# acquisition libraries: full `asan` set). Projected to fit CI's budget
# (about 25 minutes on 2 cores, build included; docs/reliability.md); the acquisition,
# driver and command-line tests need three more libraries built: full `asan` set only.
ci_targets=(anascan_processing_tests fuzz_ply_replay fuzz_text_points_replay fuzz_ptx_replay
    fuzz_stanford_conf_replay fuzz_xf_replay fuzz_obj_replay fuzz_stl_replay fuzz_e57_replay)

# TSan: everything that runs threads of its own: the capture session (scanner, persistence
# and registration threads), the session store under concurrent writers, the device
# layer's stream runner and watcher, the field app's session link and workers, and the
# campaign job (in one process and on two MPI ranks). CI runs it without CliCapture (below).
tsan_targets=(anascan anascan-field anascan_acquisition_tests anascan_session_store_tests
    anascan_device_control_tests anascan_drivers_tests anascan_drivers_umockdev_tests
    anascan_sim_device_tests anascan_cli_capture_tests anascan_field_session_tests
    anascan_field_device_tests anascan_cli_campaign_tests)
tsan_suites='CaptureSessionTest|SessionStoreTest|SessionFaultTest|DeviceControlTest|StreamRunner'
tsan_suites+='|Watcher|DepthCameraScanner|ScanRecording|Conformance|V4l2Test|UsbTest|SimTofDevice'
tsan_suites+='|SimStructuredLightDevice|CliCapture|FieldSession|FieldDevice|CampaignCli|CampaignDamage'
tsan_regex="(^|/)($tsan_suites)\\."
# CI's TSan set: the whole set but `anascan capture` (CliCapture: 572 of the set's 1500 s of
# test time under TSan, all of it simulation and registration run instrumented; its threads
# are the capture session's, which CaptureSessionTest and the field app's tests run).
tsan_ci_targets=()
for target in "${tsan_targets[@]}"; do
    if [ "$target" != anascan_cli_capture_tests ]; then tsan_ci_targets+=("$target"); fi
done
# Not under TSan: the simulated scanner renders the connect preview in more than the app's
# 5 s preview timeout there (ray casting instrumented, TBB serial), so the test fails on
# time, not on a race; the device link's threads run in the other FieldDevice tests.
tsan_exclude='^FieldDevice\.ConnectShowsBothCamerasAndAppliesTypedSettings$'


# Tests of targets not in a tree's set show up as `<target>_NOT_BUILT`; the install and
# layout checks are build-system tests, not code under test.
common_exclude='_NOT_BUILT$|^install\.|^layout\.|^anascan_live_registration_tests$'

configure_and_build() {
    local tree="$1" sanitizers="$2"
    shift 2
    local launcher=()
    if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
    cmake -S . -B "$tree" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1" \
        -DANASCAN_SANITIZE="$sanitizers" -DANASCAN_BUILD_BENCH=OFF -DANASCAN_BUILD_FUZZ=OFF \
        >/dev/null || return 1
    nice -n "$nice" cmake --build "$tree" -j "$jobs" --target "$@"
}

# Runs ctest in a tree; fails when a test fails or any sanitizer report was written.
run_tests() {
    local tree="$1"
    shift
    local reports="$PWD/$tree/sanitizer-reports"
    rm -rf "$reports" && mkdir -p "$reports"
    local status=0
    ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:exitcode=86:verify_asan_link_order=0:log_path=$reports/asan" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:exitcode=86:log_path=$reports/ubsan" \
    TSAN_OPTIONS="halt_on_error=1:exitcode=86:second_deadlock_stack=1:log_path=$reports/tsan" \
    LP_NUM_THREADS=0 \
        ctest --test-dir "$tree" --output-on-failure -j "$jobs" -LE 'hw|data' "$@" ||
        status=1
    if compgen -G "$reports/*" >/dev/null; then
        echo "sanitizer reports in $reports:" >&2
        head -n 60 "$reports"/* >&2
        status=1
    fi
    return "$status"
}

# CPU seconds (user + sys) of this shell's finished children, from the `times` output in
# $cpu_file: `times` must run in this shell (a command substitution's subshell has none).
cpu_file="$(mktemp)"
trap 'rm -f "$cpu_file"' EXIT
children_cpu_s() {
    awk 'NR == 2 {
        n = split($0, f, " "); s = 0
        for (i = 1; i <= n; i++) { split(f[i], ms, "m"); s += ms[1] * 60 + ms[2] }
        print s }' "$cpu_file"
}

# Runs one part and prints its wall time and its CPU time (user + sys of everything it ran):
# on a loaded machine the CPU time, divided by the cores, projects the wall time on idle ones.
part() {
    local name="$1"
    shift
    local start=$SECONDS status=0 cpu0
    times >"$cpu_file"
    cpu0=$(children_cpu_s)
    "$@" || status=$?
    times >"$cpu_file"
    echo "sanitize: $name took $((SECONDS - start)) s wall," \
        "$(awk -v a="$cpu0" -v b="$(children_cpu_s)" 'BEGIN { printf "%.0f", b - a }') s CPU" \
        "(exit $status)"
    return "$status"
}

status=0
if [ "$which" = ci ]; then
    part "asan (CI set) build" configure_and_build build-asan "address;undefined" \
        "${ci_targets[@]}"
    # The replays of the recording, calibration, session-database, grey-image, campaign-store
    # and blocks-folder harnesses need the driver and acquisition libraries, which this set
    # does not build.
    part "asan (CI set) tests" run_tests build-asan -E \
        "$common_exclude|^fuzz_(recording|calibration|session_db|grey_image|campaign_store|block_files)_replay\$" ||
        status=1
fi
if [ "$which" = asan ] || [ "$which" = all ]; then
    part "asan build" configure_and_build build-asan "address;undefined" "${asan_targets[@]}"
    part "asan tests" run_tests build-asan -E "$common_exclude" || status=1
fi
if [ "$which" = ci ]; then
    part "tsan (CI set) build" configure_and_build build-tsan "thread" "${tsan_ci_targets[@]}"
    part "tsan (CI set) tests" run_tests build-tsan \
        -E "$common_exclude|$tsan_exclude|^CliCapture\\." -R "$tsan_regex" || status=1
fi
if [ "$which" = tsan ] || [ "$which" = all ]; then
    part "tsan build" configure_and_build build-tsan "thread" "${tsan_targets[@]}"
    part "tsan tests" run_tests build-tsan -E "$common_exclude|$tsan_exclude" -R "$tsan_regex" ||
        status=1
fi
exit "$status"
