# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS cubespring_core EXPORT cubespringTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS cubespring_validation EXPORT cubespringTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY validation/include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
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
if(TARGET cubespring_mesh)
  install(TARGETS cubespring_mesh EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY plugins/mesh/include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_view)
  install(TARGETS cubespring_view EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY plugins/render/include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_render)
  install(TARGETS cubespring_render EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_bullet)
  install(TARGETS cubespring_bullet EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY plugins/bullet/include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_scene_world)
  install(TARGETS cubespring_scene_world EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(DIRECTORY scenes/include/cubespring DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_scene)
  install(TARGETS cubespring_scene EXPORT cubespringTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
endif()
if(TARGET cubespring_app)
  install(TARGETS cubespring_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
if(TARGET cubespring_bench)  # beside cubespring, which runs it for `cubespring bench...`
  install(TARGETS cubespring_bench RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
