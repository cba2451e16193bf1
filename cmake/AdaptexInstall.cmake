include(CMakePackageConfigHelpers)
install(DIRECTORY include/adaptex DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS adaptex adaptex_core adaptex_io adaptex_param adaptex_paint adaptex_adapt
        EXPORT adaptexTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT adaptexTargets NAMESPACE adaptex:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/adaptex)
configure_package_config_file(cmake/adaptexConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/adaptexConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/adaptex)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/adaptexConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/adaptexConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/adaptexConfigVersion.cmake
              cmake/AdaptexDependencies.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/adaptex)
