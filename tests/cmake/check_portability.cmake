# SPDX-License-Identifier: MIT
# Fails when the core library (include/calder, src) uses what Emscripten
# 3.1.6's libc++ 13 lacks: a browser build must reuse the core unchanged.
# Usage: cmake -DROOT=<source dir> -P check_portability.cmake
file(GLOB_RECURSE files "${ROOT}/include/calder/*.hpp" "${ROOT}/src/*.cpp" "${ROOT}/src/*.hpp")
set(forbidden
    "std::ranges" "std::views" "<ranges>" "std::format" "<format>" "std::bit_cast" "<bit>"
    "<source_location>" "std::source_location" "<numbers>" "std::numbers" "<execution>")
set(problems "")
foreach(file IN LISTS files)
  file(STRINGS "${file}" lines)
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    string(REGEX REPLACE "//.*$" "" code "${line}")  # comments may name them
    foreach(token IN LISTS forbidden)
      string(FIND "${code}" "${token}" at)
      if(NOT at EQUAL -1)
        file(RELATIVE_PATH rel "${ROOT}" "${file}")
        string(APPEND problems "${rel}:${number}: uses ${token}, which Emscripten's libc++ 13 lacks\n")
      endif()
    endforeach()
  endforeach()
endforeach()
if(problems)
  message(FATAL_ERROR "${problems}")
endif()
list(LENGTH files count)
message(STATUS "portability: ${count} core files use only what libc++ 13 supports")
