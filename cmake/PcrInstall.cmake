include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS pcr_core pcr_rods pcr_robots EXPORT pcrTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(dir libpcr rods robots)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${dir}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endforeach()
install(EXPORT pcrTargets NAMESPACE pcr:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pcr)

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/pcrConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/pcrConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pcr)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/pcrConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/pcrConfig.cmake ${PROJECT_BINARY_DIR}/pcrConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/pcr)
