# SPDX-License-Identifier: MIT
# Fails when a C++ file of the project is not formatted by .clang-format.
# Usage: cmake -DROOT=<source dir> -DCLANG_FORMAT=<path> -P check_format.cmake
file(GLOB_RECURSE files "${ROOT}/include/*.hpp" "${ROOT}/src/*.cpp" "${ROOT}/src/*.hpp"
     "${ROOT}/tests/*.cpp" "${ROOT}/examples/*.cpp" "${ROOT}/apps/*.cpp" "${ROOT}/bench/*.cpp")
set(bad "")
foreach(file IN LISTS files)
  execute_process(COMMAND "${CLANG_FORMAT}" --dry-run --Werror "${file}" RESULT_VARIABLE rc
                  OUTPUT_QUIET ERROR_QUIET)
  if(NOT rc EQUAL 0)
    file(RELATIVE_PATH rel "${ROOT}" "${file}")
    string(APPEND bad "  ${rel}\n")
  endif()
endforeach()
if(bad)
  message(FATAL_ERROR "not formatted by .clang-format (run clang-format -i on them):\n${bad}")
endif()
