# SPDX-License-Identifier: MIT
# Runs an example and compares its stdout with a p5.js reference trajectory.
#
#   cmake -DEXAMPLE=<exe> -DTRAJECTORY_DIFF=<exe> -DREFERENCE=<csv> -DOUTPUT=<csv>
#         [-DTOLERANCE=1e-9] [-DEXAMPLE_ARGS=a|b|...] -P run_and_compare.cmake
#
# The example runs with EXAMPLE_ARGS ('|'-separated); its stdout goes to OUTPUT, its stderr
# passes through. Fails (non-zero exit) when the example fails or when
# trajectory_diff reports a mismatch or an unreadable file.
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS EXAMPLE TRAJECTORY_DIFF REFERENCE OUTPUT)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "run_and_compare.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED TOLERANCE OR "${TOLERANCE}" STREQUAL "")
  set(TOLERANCE 1e-9)
endif()
if(NOT EXISTS "${REFERENCE}")
  message(FATAL_ERROR "reference trajectory not found: ${REFERENCE}")
endif()

get_filename_component(output_dir "${OUTPUT}" DIRECTORY)
file(MAKE_DIRECTORY "${output_dir}")
file(REMOVE "${OUTPUT}")

# Examples take no input: give them an empty stdin so none can wait on one.
set(stdin_args)
if(UNIX)
  set(stdin_args INPUT_FILE /dev/null)
endif()
string(REPLACE "|" ";" example_args "${EXAMPLE_ARGS}")
execute_process(
  COMMAND "${EXAMPLE}" ${example_args} ${stdin_args}
  OUTPUT_FILE "${OUTPUT}"
  RESULT_VARIABLE example_result)
if(NOT example_result STREQUAL "0")
  message(FATAL_ERROR "example failed (${example_result}): ${EXAMPLE}\n"
                      "its output so far is in ${OUTPUT}")
endif()

execute_process(
  COMMAND "${TRAJECTORY_DIFF}" "${REFERENCE}" "${OUTPUT}" --tolerance "${TOLERANCE}"
  RESULT_VARIABLE diff_result
  OUTPUT_VARIABLE diff_output
  ERROR_VARIABLE diff_output)
string(STRIP "${diff_output}" diff_output)
if(NOT diff_result STREQUAL "0")
  message(FATAL_ERROR "trajectory differs from the p5.js reference (exit ${diff_result}):\n"
                      "  ${diff_output}\n"
                      "  reference: ${REFERENCE}\n"
                      "  candidate: ${OUTPUT}")
endif()
message(STATUS "${diff_output}")
