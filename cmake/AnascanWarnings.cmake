# Warnings for our own targets only (never for third-party headers, which are SYSTEM).
function(anascan_set_warnings target)
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow
                                             -Wnon-virtual-dtor -Wcast-align -Wunused
                                             -Woverloaded-virtual -Wnull-dereference
                                             # Config structs are filled with designated
                                             # initialisers relying on in-class defaults.
                                             -Wno-missing-field-initializers)
    if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
        # GCC 12 reports false -Wrestrict on std::string concatenation (GCC bug 105329).
        target_compile_options(${target} PRIVATE -Wno-restrict)
    endif()
    if(ANASCAN_WERROR)
        target_compile_options(${target} PRIVATE -Werror)
    endif()
endfunction()

# Declares a module library `anascan_<name>` with alias `anascan::<name>`.
# Only <module>/include is public, so a header of another module is reachable only
# through an explicit link dependency: a forbidden include fails to compile.
function(anascan_add_module name)
    cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
    add_library(anascan_${name} ${ARG_SOURCES})
    add_library(anascan::${name} ALIAS anascan_${name})
    set_target_properties(anascan_${name} PROPERTIES EXPORT_NAME ${name})
    target_include_directories(anascan_${name}
        PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
               $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
        PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
    target_link_libraries(anascan_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    target_compile_features(anascan_${name} PUBLIC cxx_std_23)
    anascan_set_warnings(anascan_${name})
endfunction()
