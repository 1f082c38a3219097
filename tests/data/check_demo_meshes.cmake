# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Runs the demo mesh generator into WORK_DIR and compares every file with the committed DATA_DIR.
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${GENERATOR} ${WORK_DIR} RESULT_VARIABLE result OUTPUT_QUIET)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "make_demo_meshes failed (${result})")
endif()
foreach(name liver.obj liver.mtl probe.obj probe.mtl)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/${name} ${DATA_DIR}/${name}
                  RESULT_VARIABLE different)
  if(different)
    message(FATAL_ERROR "data/${name} differs from what data/generator/make_demo_meshes writes: "
      "regenerate it (see data/generator/CMakeLists.txt)")
  endif()
endforeach()
