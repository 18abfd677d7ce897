# The installed CMake package: find_package(lodopt) gives lodopt::scenes, lodopt::renderer,
# lodopt::metrics, lodopt::timemodel, lodopt::optimizer, lodopt::evaluation and
# lodopt::scheduler (static libraries; their third-party dependencies are found again by
# lodoptConfig.cmake, because a static library's private dependencies are linked by whoever
# links it). tests/package builds a consumer against it.
include(CMakePackageConfigHelpers)
set(LODOPT_PACKAGE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/lodopt)
install(EXPORT lodoptTargets NAMESPACE lodopt:: DESTINATION ${LODOPT_PACKAGE_DIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/lodoptConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/lodoptConfig.cmake INSTALL_DESTINATION ${LODOPT_PACKAGE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/lodoptConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/lodoptConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/lodoptConfigVersion.cmake
        DESTINATION ${LODOPT_PACKAGE_DIR})
