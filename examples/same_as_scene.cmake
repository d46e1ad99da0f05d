# SPDX-License-Identifier: MIT
# Runs an example and `calder run <scene>` with the same seed and checks that
# their trajectories are the same to the last bit.
#
#   cmake -DEXAMPLE=<exe> -DCALDER=<exe> -DTRAJECTORY_DIFF=<exe> -DSCENE=<name>
#         -DSEED=<n> -DFRAMES=<n> -DWORK_DIR=<dir> -P same_as_scene.cmake
#
# The example runs headless: --seed <n> --frames <n> --trajectory <csv>.
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS EXAMPLE CALDER TRAJECTORY_DIFF SCENE SEED FRAMES WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "same_as_scene.cmake: -D${var}=... is required")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK_DIR}")
set(example_csv "${WORK_DIR}/example-seed-${SEED}.csv")
set(scene_csv "${WORK_DIR}/scene-seed-${SEED}.csv")
file(REMOVE "${example_csv}" "${scene_csv}")

execute_process(
  COMMAND "${EXAMPLE}" --seed "${SEED}" --frames "${FRAMES}" --trajectory "${example_csv}"
  INPUT_FILE /dev/null
  RESULT_VARIABLE result)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "example failed (${result}): ${EXAMPLE}")
endif()
execute_process(
  COMMAND "${CALDER}" run "${SCENE}" --seed "${SEED}" --frames "${FRAMES}" --trajectory
          "${scene_csv}"
  INPUT_FILE /dev/null
  RESULT_VARIABLE result)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "calder run ${SCENE} failed (${result})")
endif()
execute_process(
  COMMAND "${TRAJECTORY_DIFF}" "${scene_csv}" "${example_csv}" --tolerance 0
  RESULT_VARIABLE result
  OUTPUT_VARIABLE diff_output
  ERROR_VARIABLE diff_output)
string(STRIP "${diff_output}" diff_output)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "the example's trajectory is not the scene's (seed ${SEED}):\n"
                      "  ${diff_output}\n  scene: ${scene_csv}\n  example: ${example_csv}")
endif()
message(STATUS "seed ${SEED}: ${diff_output}")
