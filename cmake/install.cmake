# Install rules and the exported CMake package, all in one place:
#   cmake --install build --prefix PREFIX
# installs bin/rtm and bin/rtm-make-media, lib/rtm/librtm_imageio.so (the image module they load), the static
# libraries as lib/librtm_<name>.a, their headers under include/rtm/<name>/ (each library's include directory is
# include/rtm, so a header's own includes such as "warp/image.h" resolve as in the source tree),
# include/rtm/rtm_version.h, and lib/cmake/rtm/ with rtmConfig.cmake,
# its version file and the exported targets: another project's find_package(rtm) then gives rtm::warp,
# rtm::formats, rtm::texmap, rtm::procedural, rtm::truth, rtm::perpixel, rtm::objects, rtm::measure and rtm::mesh
# (examples/prewarp_relief).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(RTM_LIBRARIES warp formats texmap procedural truth perpixel objects measure mesh)
set(RTM_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/rtm)

# librtm_warp.a rather than libwarp.a: the installed names must not clash with other projects' libraries.
foreach(lib ${RTM_LIBRARIES})
  set_target_properties(${lib} PROPERTIES OUTPUT_NAME rtm_${lib})
endforeach()

install(TARGETS rtm rtm-make-media RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The image module beside them, where formats/image_io.cpp looks (formats/CMakeLists.txt).
install(TARGETS rtm_imageio LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/rtm)

# rtm_flags and rtm_glad are exported only because the static libraries link them privately: a consumer gets
# $<LINK_ONLY:...> of them, i.e. the glad loader's object code and the sanitizer link options of an RTM_SANITIZE
# build, never the project's warning and optimisation flags or the glad headers (which are not installed).
install(TARGETS ${RTM_LIBRARIES} rtm_flags rtm_glad EXPORT rtmTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
foreach(lib ${RTM_LIBRARIES})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${lib}/ DESTINATION include/rtm/${lib} FILES_MATCHING PATTERN "*.h")
endforeach()
install(FILES ${PROJECT_BINARY_DIR}/generated/rtm_version.h DESTINATION include/rtm)

install(EXPORT rtmTargets NAMESPACE rtm:: DESTINATION ${RTM_INSTALL_CMAKEDIR})
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/rtmConfig.cmake.in ${PROJECT_BINARY_DIR}/rtmConfig.cmake
                              INSTALL_DESTINATION ${RTM_INSTALL_CMAKEDIR})
# 0.x: a minor version may break the interfaces, so only the same minor version is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/rtmConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/rtmConfig.cmake ${PROJECT_BINARY_DIR}/rtmConfigVersion.cmake
        DESTINATION ${RTM_INSTALL_CMAKEDIR})
