# SPDX-License-Identifier: MIT
# calder_cli_cases(<script> <var>): the case names of a CLI test script (one
# ctest each), read from its `CASE STREQUAL "<name>"` lines (a .cmake script)
# or its `  <name>)` lines (a .sh script's case), so that a case is named once,
# in its script. A case whose line ends in `# scene file` is left
# out when the command reads no scene files (CALDER_APP_HAS_SCENE_FILE off); one
# marked `# registered apart` is registered by other code. A new case in the
# script reconfigures the build.
include_guard(GLOBAL)

function(calder_cli_cases script var)
  if(script MATCHES "\\.sh$")
    set(pattern "^  ([A-Za-z0-9_]+)\\)")
  else()
    set(pattern "CASE STREQUAL \"([A-Za-z0-9_]+)\"")
  endif()
  file(STRINGS "${script}" lines REGEX "${pattern}")
  set(cases)
  foreach(line IN LISTS lines)
    string(REGEX MATCH "${pattern}" match "${line}")
    set(name "${CMAKE_MATCH_1}")  # before the MATCHES below reset CMAKE_MATCH_1
    if(line MATCHES "# registered apart$"
       OR (line MATCHES "# scene file$" AND NOT CALDER_APP_HAS_SCENE_FILE))
      continue()
    endif()
    list(APPEND cases "${name}")
  endforeach()
  if(NOT cases)
    message(FATAL_ERROR "calder: no test cases found in ${script}")
  endif()
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${script}")
  set(${var}
      ${cases}
      PARENT_SCOPE)
endfunction()
