# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# Each part's library, and its public headers where the part has an include folder of its own.
function(cubespring_install_part target headers)
  if(NOT TARGET ${target})
    return()
  endif()
  install(TARGETS ${target} EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  if(headers)
    install(DIRECTORY ${headers}/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  endif()
endfunction()
cubespring_install_part(cubespring_core include)
cubespring_install_part(cubespring_validation validation/include)
cubespring_install_part(cubespring_mesh plugins/mesh/include)
cubespring_install_part(cubespring_view plugins/render/include)
cubespring_install_part(cubespring_render "")  # its headers are view's folder
cubespring_install_part(cubespring_bullet plugins/bullet/include)
cubespring_install_part(cubespring_haptics plugins/haptics/include)
cubespring_install_part(cubespring_scene_world scenes/include)
cubespring_install_part(cubespring_scene "")  # its headers are scene_world's folder
install(EXPORT cubespringTargets NAMESPACE cubespring::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cubespring)

configure_package_config_file(cmake/cubespringConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/cubespringConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cubespring)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/cubespringConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/cubespringConfig.cmake
  ${CMAKE_CURRENT_BINARY_DIR}/cubespringConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/cubespring)
if(TARGET cubespring_app)
  install(TARGETS cubespring_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
if(TARGET cubespring_bench)  # beside cubespring, which runs it for `cubespring bench...`
  install(TARGETS cubespring_bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
