# SPDX-License-Identifier: MIT
# Runs `calder run` on the built-in scene of a p5.js reference and compares the
# trajectory with trajectory_diff. Everything comes from the reference's
# scenario.json, so a new reference folder needs no edit here:
#
#   scene     the folder's name: example_2_1_forces -> example-2.1,
#             exercise_2_16 -> exercise-2.16 (<kind>_<chapter>_<number>[_...])
#   --seed    seed.randomSeed (1 when absent)
#   --frames  frames
#   --mouse-pressed A-B   for each [A, B] of input.mouseIsPressed_frames
#   --state   with USE_STATE=ON: a CSV made from bodies[] (position, velocity,
#             mass, and radius when every body has one)
#
#   cmake -DCALDER=<exe> -DTRAJECTORY_DIFF=<exe> -DREFERENCE_DIR=<folder>
#         -DWORK_DIR=<dir> [-DUSE_STATE=ON] [-DTOLERANCE=1e-9] -P reference.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS CALDER TRAJECTORY_DIFF REFERENCE_DIR WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "reference.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED TOLERANCE OR "${TOLERANCE}" STREQUAL "")
  set(TOLERANCE 1e-9)
endif()

set(scenario_file "${REFERENCE_DIR}/scenario.json")
set(reference "${REFERENCE_DIR}/trajectory.csv")
foreach(file IN ITEMS "${scenario_file}" "${reference}")
  if(NOT EXISTS "${file}")
    message(FATAL_ERROR "missing ${file}")
  endif()
endforeach()
file(READ "${scenario_file}" scenario)

# The scene: example_2_1_forces -> example-2.1.
get_filename_component(folder "${REFERENCE_DIR}" NAME)
if(NOT folder MATCHES "^(example|exercise)_([0-9]+)_([0-9]+)")
  message(FATAL_ERROR "${folder}: can't tell the scene from the folder's name "
                      "(expected example_<chapter>_<number>_... or exercise_<chapter>_<number>)")
endif()
set(scene "${CMAKE_MATCH_1}-${CMAKE_MATCH_2}.${CMAKE_MATCH_3}")

string(JSON frames ERROR_VARIABLE err GET "${scenario}" frames)
if(err)
  message(FATAL_ERROR "${scenario_file}: no frames: ${err}")
endif()
string(JSON seed ERROR_VARIABLE err GET "${scenario}" seed randomSeed)
if(err)
  set(seed 1)
endif()

set(args run "${scene}" --seed "${seed}" --frames "${frames}")

# Scripted presses.
string(JSON ranges ERROR_VARIABLE err GET "${scenario}" input mouseIsPressed_frames)
if(NOT err)
  string(JSON count LENGTH "${ranges}")
  if(count GREATER 0)
    math(EXPR last "${count} - 1")
    foreach(i RANGE ${last})
      string(JSON first GET "${ranges}" ${i} 0)
      string(JSON final GET "${ranges}" ${i} 1)
      list(APPEND args --mouse-pressed "${first}-${final}")
    endforeach()
  endif()
endif()

file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

# The bodies after setup, as a --state CSV. CMake prints JSON numbers with 17
# significant digits, which read back to the same doubles.
if(USE_STATE)
  string(JSON bodies GET "${scenario}" bodies)
  string(JSON count LENGTH "${bodies}")
  set(with_radius ON)
  set(rows "")
  if(count GREATER 0)
    math(EXPR last "${count} - 1")
    foreach(i RANGE ${last})
      string(JSON radius ERROR_VARIABLE err GET "${bodies}" ${i} radius)
      if(err)
        set(with_radius OFF)
      endif()
    endforeach()
    foreach(i RANGE ${last})
      string(JSON x GET "${bodies}" ${i} position 0)
      string(JSON y GET "${bodies}" ${i} position 1)
      string(JSON vx GET "${bodies}" ${i} velocity 0)
      string(JSON vy GET "${bodies}" ${i} velocity 1)
      string(JSON mass GET "${bodies}" ${i} mass)
      set(row "${x},${y},${vx},${vy},${mass}")
      if(with_radius)
        string(JSON radius GET "${bodies}" ${i} radius)
        string(APPEND row ",${radius}")
      endif()
      string(APPEND rows "${row}\n")
    endforeach()
  endif()
  set(header "x,y,vx,vy,mass")
  if(with_radius)
    string(APPEND header ",radius")
  endif()
  file(WRITE "${WORK_DIR}/state.csv" "${header}\n${rows}")
  list(APPEND args --state "${WORK_DIR}/state.csv")
endif()

set(output "${WORK_DIR}/trajectory.csv")
list(APPEND args --trajectory "${output}")
list(JOIN args " " shown)
message(STATUS "calder ${shown}")
execute_process(
  COMMAND "${CALDER}" ${args}
  INPUT_FILE /dev/null
  RESULT_VARIABLE result
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "calder ${shown}\nfailed (${result}): ${out}${err}")
endif()

execute_process(
  COMMAND "${TRAJECTORY_DIFF}" "${reference}" "${output}" --tolerance "${TOLERANCE}"
  RESULT_VARIABLE diff_result
  OUTPUT_VARIABLE diff_output
  ERROR_VARIABLE diff_output)
string(STRIP "${diff_output}" diff_output)
if(NOT diff_result STREQUAL "0")
  message(FATAL_ERROR "calder ${shown}\ndiffers from the p5.js reference (exit ${diff_result}):\n"
                      "  ${diff_output}\n  reference: ${reference}\n  candidate: ${output}")
endif()

# Nothing but the inputs and the trajectory is left behind (no temporaries).
file(GLOB left RELATIVE "${WORK_DIR}" "${WORK_DIR}/*" "${WORK_DIR}/.*")
list(REMOVE_ITEM left trajectory.csv state.csv)
if(left)
  message(FATAL_ERROR "files left behind in ${WORK_DIR}: ${left}")
endif()
message(STATUS "${diff_output}")
