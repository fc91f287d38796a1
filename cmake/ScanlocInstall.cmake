# `cmake --install` puts the library, its public headers (scanloc/<layer>/...), the scanloc
# executable and a CMake package (scanlocConfig.cmake, exported target scanloc::scanloc) under the
# prefix, so that another project's find_package(scanloc CONFIG REQUIRED) links it.
# A shared scanloc (the default) keeps its private dependencies (Ceres, PCL, nanoflann, zlib,
# rosbag) to itself; a static one makes the consumer find them too. scripts/check-install.sh checks
# the package from outside.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The installed executable finds the installed library beside it, wherever the prefix is moved.
set_target_properties(scanloc_app PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")

set(SCANLOC_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/scanloc)
install(TARGETS scanloc EXPORT scanlocTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS scanloc_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/scanloc DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT scanlocTargets NAMESPACE scanloc:: DESTINATION ${SCANLOC_INSTALL_CMAKEDIR})

get_target_property(scanloc_type scanloc TYPE)
if(scanloc_type STREQUAL "STATIC_LIBRARY")
  set(SCANLOC_STATIC ON)
else()
  set(SCANLOC_STATIC OFF)
endif()
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/scanlocConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/scanlocConfig.cmake
                              INSTALL_DESTINATION ${SCANLOC_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/scanlocConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/scanlocConfig.cmake
              ${PROJECT_BINARY_DIR}/scanlocConfigVersion.cmake
        DESTINATION ${SCANLOC_INSTALL_CMAKEDIR})
