# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -P install_test.cmake
# Installs the build into a fresh prefix, builds the consumer project against it and runs it.
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE result OUTPUT_QUIET)
if(result)
  message(FATAL_ERROR "cmake --install failed")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${WORK_DIR}/build" -G Ninja
                        "-DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix" RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "configuring the consumer against the installed package failed")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK_DIR}/build" RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "building the consumer failed")
endif()
execute_process(COMMAND "${WORK_DIR}/build/consumer" RESULT_VARIABLE result)
if(result)
  message(FATAL_ERROR "the consumer failed")
endif()
# the optional parts' consumers, where cubespring was built with those parts
foreach(consumer plugin_consumer scene_consumer scene_world_consumer)
  if(EXISTS "${WORK_DIR}/build/${consumer}")
    execute_process(COMMAND "${WORK_DIR}/build/${consumer}" WORKING_DIRECTORY "${WORK_DIR}/build" RESULT_VARIABLE result)
    if(result)
      message(FATAL_ERROR "${consumer} failed")
    endif()
  endif()
endforeach()
