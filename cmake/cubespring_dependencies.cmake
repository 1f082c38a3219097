# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Every dependency is found as an imported target; a missing one stops configuration with the
# Debian package that provides it.

function(cubespring_require found package_name debian_package reason)
  if(NOT ${found})
    message(FATAL_ERROR
      "cubespring: ${package_name} was not found; it is needed for ${reason}. "
      "On Debian install it with: apt-get install ${debian_package}")
  endif()
endfunction()

find_package(Eigen3 3.3 NO_MODULE QUIET)
cubespring_require(Eigen3_FOUND "Eigen3" "libeigen3-dev" "the core library")

if(CUBESPRING_WITH_OPENMP)
  find_package(OpenMP QUIET COMPONENTS CXX)
  cubespring_require(OpenMP_CXX_FOUND "OpenMP" "libgomp1 (part of g++)" "CUBESPRING_WITH_OPENMP=ON")
endif()

if(CUBESPRING_WITH_ASSIMP)
  find_package(assimp 5 QUIET)
  cubespring_require(assimp_FOUND "assimp" "libassimp-dev" "CUBESPRING_WITH_ASSIMP=ON (cubespring::mesh, loading mesh files)")
endif()

if(CUBESPRING_WITH_BULLET OR CUBESPRING_WITH_OSMESA)
  find_package(PkgConfig QUIET)
  cubespring_require(PKG_CONFIG_FOUND "pkg-config" "pkg-config" "finding Bullet and OSMesa")
endif()

if(CUBESPRING_WITH_BULLET)
  # Debian ships Bullet twice: an application must link the same precision as the plugin
  if(CUBESPRING_BULLET_DOUBLE)
    set(CUBESPRING_BULLET_MODULE bullet-float64)
  else()
    set(CUBESPRING_BULLET_MODULE bullet)
  endif()
  pkg_check_modules(BULLET QUIET IMPORTED_TARGET GLOBAL ${CUBESPRING_BULLET_MODULE})
  cubespring_require(BULLET_FOUND "Bullet (${CUBESPRING_BULLET_MODULE})" "libbullet-dev"
    "CUBESPRING_WITH_BULLET=ON (cubespring::bullet)")
endif()

if(CUBESPRING_WITH_OSMESA)
  pkg_check_modules(OSMESA QUIET IMPORTED_TARGET GLOBAL osmesa)
  cubespring_require(OSMESA_FOUND "OSMesa" "libosmesa6-dev" "CUBESPRING_WITH_OSMESA=ON (cubespring::render)")
  find_package(PNG QUIET)
  cubespring_require(PNG_FOUND "libpng" "libpng-dev" "CUBESPRING_WITH_OSMESA=ON (PNG frames)")
endif()

if(CUBESPRING_WITH_ASSIMP AND CUBESPRING_WITH_BULLET)
  find_package(nlohmann_json 3 QUIET)
  cubespring_require(nlohmann_json_FOUND "nlohmann_json" "nlohmann-json3-dev" "cubespring::scene (scene files)")
endif()

if(CUBESPRING_BUILD_APPS)
  if(NOT CUBESPRING_WITH_ASSIMP)
    message(FATAL_ERROR "cubespring: the command-line tool loads mesh files (voxelize): "
      "set CUBESPRING_WITH_ASSIMP=ON, or CUBESPRING_BUILD_APPS=OFF")
  endif()
  find_package(nlohmann_json 3 QUIET)
  cubespring_require(nlohmann_json_FOUND "nlohmann_json" "nlohmann-json3-dev" "CUBESPRING_BUILD_APPS=ON (JSON output)")
  find_package(CLI11 QUIET)
  cubespring_require(CLI11_FOUND "CLI11" "libcli11-dev" "CUBESPRING_BUILD_APPS=ON (argument parsing)")
endif()

if(CUBESPRING_BUILD_TESTS)
  find_package(GTest QUIET)
  cubespring_require(GTest_FOUND "GoogleTest" "libgtest-dev" "CUBESPRING_BUILD_TESTS=ON")
endif()
