# Sanitizer builds (scripts/sanitize.sh makes them in build-asan and build-tsan).
# ANASCAN_SANITIZE is a list of GCC/Clang sanitizer names, e.g. "address;undefined" or
# "thread"; it applies to every target of the tree, so our libraries, tests and commands are
# all instrumented (third-party Debian libraries are not).
set(ANASCAN_SANITIZE "" CACHE STRING
    "Sanitizers to build with, e.g. address;undefined or thread (empty: none)")

if(ANASCAN_SANITIZE)
    if("thread" IN_LIST ANASCAN_SANITIZE AND "address" IN_LIST ANASCAN_SANITIZE)
        message(FATAL_ERROR "ANASCAN_SANITIZE: thread and address cannot be combined")
    endif()
    list(JOIN ANASCAN_SANITIZE "," anascan_sanitize_list)
    # Frame pointers and debug lines make the reports readable; a finding ends the process
    # (no recover), so a test with a finding fails instead of printing and passing.
    add_compile_options(-fsanitize=${anascan_sanitize_list} -fno-omit-frame-pointer -g
                        -fno-sanitize-recover=all)
    add_link_options(-fsanitize=${anascan_sanitize_list})
    message(STATUS "anascan: building with -fsanitize=${anascan_sanitize_list}")
endif()
