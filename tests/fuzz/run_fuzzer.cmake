# Runs one libFuzzer target for SECONDS on a scratch copy of its seed corpus.
# A crash, leak or sanitizer finding makes the fuzzer exit non-zero and fails the test;
# the reproducer is left in WORK (crash-*, leak-*, timeout-*).
# The random seed is fixed (SEED, default 1): the same build walks the same inputs every time,
# so a red test can be rerun; a change to the code or the seeds changes the walk. Exploring
# new inputs is the long runs' job (scripts/fuzz-long.sh, random seeds).
if(NOT DEFINED SEED)
    set(SEED 1)
endif()
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/corpus)
file(GLOB seeds ${SEEDS}/*)
if(seeds)
    file(COPY ${seeds} DESTINATION ${WORK}/corpus)
endif()
execute_process(
    COMMAND ${FUZZER} -seed=${SEED} -max_total_time=${SECONDS} -rss_limit_mb=2048 -timeout=10
            -max_len=65536 -print_final_stats=1 -artifact_prefix=${WORK}/ ${WORK}/corpus
    WORKING_DIRECTORY ${WORK}
    RESULT_VARIABLE result)
if(NOT result EQUAL 0)
    message(FATAL_ERROR "${FUZZER} found a problem (exit ${result}); reproducer in ${WORK}")
endif()
