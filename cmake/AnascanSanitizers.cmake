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
    # Frame pointers and line tables (-g1: functions and lines, no variables; a third less
    # compile time than -g) make the reports readable; a finding ends the process (no
    # recover), so a test with a finding fails instead of printing and passing.
    add_compile_options(-fsanitize=${anascan_sanitize_list} -fno-omit-frame-pointer -g1
                        -fno-sanitize-recover=all)
    add_link_options(-fsanitize=${anascan_sanitize_list})
    message(STATUS "anascan: building with -fsanitize=${anascan_sanitize_list}")
endif()

# ThreadSanitizer: every executable gets cmake/tsan_serial_tbb.cpp, which keeps TBB (not
# instrumented) from running loops on worker threads TSan cannot follow (the file says why).
# Deferred to the end of the top-level directory, when every executable exists.
function(anascan_executables_under dir out)
    get_property(targets DIRECTORY "${dir}" PROPERTY BUILDSYSTEM_TARGETS)
    set(found "")
    foreach(target IN LISTS targets)
        get_target_property(type ${target} TYPE)
        if(type STREQUAL "EXECUTABLE")
            list(APPEND found ${target})
        endif()
    endforeach()
    get_property(subdirs DIRECTORY "${dir}" PROPERTY SUBDIRECTORIES)
    foreach(subdir IN LISTS subdirs)
        anascan_executables_under("${subdir}" below)
        list(APPEND found ${below})
    endforeach()
    set(${out} ${found} PARENT_SCOPE)
endfunction()

function(anascan_serialize_tbb_for_tsan)
    anascan_executables_under("${CMAKE_SOURCE_DIR}" executables)
    foreach(exe IN LISTS executables)
        target_sources(${exe} PRIVATE "${CMAKE_SOURCE_DIR}/cmake/tsan_serial_tbb.cpp")
        target_link_libraries(${exe} PRIVATE TBB::tbb)
    endforeach()
endfunction()

if("thread" IN_LIST ANASCAN_SANITIZE)
    cmake_language(DEFER DIRECTORY "${CMAKE_SOURCE_DIR}" CALL anascan_serialize_tbb_for_tsan)
endif()
