# SPDX-FileCopyrightText: 2026 cubespring authors
# SPDX-License-Identifier: MIT
# Warnings are set per target, never through CMAKE_CXX_FLAGS.
function(cubespring_set_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
      -Wno-sign-conversion -Wno-unknown-pragmas -ffp-contract=off)
    if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
      # `#pragma omp simd` is a hint for gcc's vectoriser; clang declining one is no fault
      target_compile_options(${target} PRIVATE -Wno-pass-failed)
    endif()
    if(CUBESPRING_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  endif()
endfunction()
