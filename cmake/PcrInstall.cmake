# Installs what a downstream user needs: the libraries, public headers and CMake package (find_package(pcr)),
# the pcr tool, the models and the documentation (README.md, "A five-minute tour").
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

# The pcr tool, the shipped models and the documentation (README.md, with docs/ beside it so that its
# links hold) under the prefix: bin/pcr, share/pcr/models/*.urdf, share/doc/pcr/.
install(TARGETS pcr RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/ DESTINATION ${CMAKE_INSTALL_DATADIR}/pcr/models
        FILES_MATCHING PATTERN "*.urdf")
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
