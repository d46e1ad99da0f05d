# SPDX-License-Identifier: MIT
# Helpers for the CLI test scripts (included by bad_input.cmake and output.cmake).
include_guard(GLOBAL)

foreach(var IN ITEMS CALDER CASE WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "-D${var}=... is required")
  endif()
endforeach()

# A fresh working folder per case; calder runs inside it, so messages name
# files as given on the command line (bad.toml, state.csv, out.csv).
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# calder_run(ARGS...): runs calder in WORK_DIR; sets rc, out, err.
function(calder_run)
  list(JOIN ARGN " " shown)
  execute_process(
    COMMAND "${CALDER}" ${ARGN}
    WORKING_DIRECTORY "${WORK_DIR}"
    INPUT_FILE /dev/null
    RESULT_VARIABLE result
    OUTPUT_VARIABLE stdout
    ERROR_VARIABLE stderr)
  set(rc "${result}" PARENT_SCOPE)
  set(out "${stdout}" PARENT_SCOPE)
  set(err "${stderr}" PARENT_SCOPE)
  set(shown "calder ${shown}" PARENT_SCOPE)
endfunction()

function(fail what)
  message(FATAL_ERROR "${shown}\n${what}\n--- exit: ${rc}\n--- stdout:\n${out}\n--- stderr:\n${err}")
endfunction()

# write(<name> <text>): a file in WORK_DIR.
function(write name text)
  file(WRITE "${WORK_DIR}/${name}" "${text}")
endfunction()

# expect_error(<exit code> [CONTAINS text...] [MATCHES regex...]): the last run
# exited with that code, printed nothing on stdout and exactly one line on
# stderr, starting "calder: " and holding each text and regex.
function(expect_error code)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "CONTAINS;MATCHES")
  if(NOT rc STREQUAL "${code}")
    fail("expected exit ${code}")
  endif()
  if(NOT out STREQUAL "")
    fail("expected nothing on stdout")
  endif()
  if(NOT DEFINED PROGRAM_NAME)
    set(PROGRAM_NAME calder)  # the program whose errors these are
  endif()
  if(NOT err MATCHES "^${PROGRAM_NAME}: [^\n]+\n$")
    fail("expected exactly one line on stderr, starting with '${PROGRAM_NAME}: '")
  endif()
  foreach(text IN LISTS arg_CONTAINS)
    string(FIND "${err}" "${text}" at)
    if(at EQUAL -1)
      fail("expected stderr to contain: ${text}")
    endif()
  endforeach()
  foreach(regex IN LISTS arg_MATCHES)
    if(NOT err MATCHES "${regex}")
      fail("expected stderr to match: ${regex}")
    endif()
  endforeach()
endfunction()

# expect_no_output(<relative path>): neither the file nor a temporary of it
# (".NAME.tmp-XXXXXX") exists in its folder.
function(expect_no_output path)
  if(EXISTS "${WORK_DIR}/${path}")
    fail("${path} exists, but the run failed")
  endif()
  get_filename_component(dir "${WORK_DIR}/${path}" DIRECTORY)
  get_filename_component(name "${path}" NAME)
  file(GLOB temps "${dir}/.${name}.tmp-*")
  if(temps)
    fail("temporary files left behind: ${temps}")
  endif()
endfunction()

function(expect_success)
  if(NOT rc STREQUAL "0")
    fail("expected exit 0")
  endif()
  if(NOT err STREQUAL "")
    fail("expected nothing on stderr")
  endif()
endfunction()
