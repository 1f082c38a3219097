# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
include(GNUInstallDirs)

# cubespring_add_library(PART [OUTPUT_NAME NAME] [INCLUDE_DIR DIR] SOURCES ...): the library
# cubespring_PART of one part of the tree (docs/architecture.md), known to users as
# cubespring::PART, with the project's warnings. Its public headers are in INCLUDE_DIR (default:
# the part's include/ folder), installed to include/; the caller links what the part needs.
function(cubespring_add_library part)
  cmake_parse_arguments(ARG "" "OUTPUT_NAME;INCLUDE_DIR" "SOURCES" ${ARGN})
  set(target cubespring_${part})
  if(NOT ARG_OUTPUT_NAME)
    set(ARG_OUTPUT_NAME ${target})
  endif()
  if(NOT ARG_INCLUDE_DIR)
    set(ARG_INCLUDE_DIR ${CMAKE_CURRENT_SOURCE_DIR}/include)
  endif()
  add_library(${target} ${ARG_SOURCES})
  add_library(cubespring::${part} ALIAS ${target})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${ARG_OUTPUT_NAME} EXPORT_NAME ${part})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${ARG_INCLUDE_DIR}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  cubespring_set_warnings(${target})
endfunction()
