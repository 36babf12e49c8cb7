include(CMakePackageConfigHelpers)

install(TARGETS anascan_processing anascan_drivers anascan_sim anascan_acquisition anascan_gui
        EXPORT anascanTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS anascan RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The screened Poisson module, loaded on first use (processing/src/surface/poisson.cpp finds
# it from the program's folder: BINDIR/../LIBDIR/anascan).
install(TARGETS anascan_open3d_poisson LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/anascan)
foreach(module processing drivers sim acquisition gui)
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${module}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()

install(EXPORT anascanTargets NAMESPACE anascan:: FILE anascanTargets.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anascan)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/anascanConfig.cmake.in
        ${PROJECT_BINARY_DIR}/anascanConfig.cmake
        INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anascan)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/anascanConfigVersion.cmake
        COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/anascanConfig.cmake ${PROJECT_BINARY_DIR}/anascanConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/anascan)
