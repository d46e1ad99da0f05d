# SPDX-License-Identifier: MIT
# Draws an example sketch headless and `calder render` of its scene, and checks
# that frames 1, 100 and 600 are the same pixels (every r, g, b and alpha).
#
#   cmake -DEXAMPLE=<exe> -DCALDER=<exe> -DIMAGE_CHECK=<exe> -DSCENE=<name>
#         -DWORK_DIR=<dir> [-DMOUSE_PRESSED=A-B] [-DSCALE=S] -P same_pixels.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS EXAMPLE CALDER IMAGE_CHECK SCENE WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "same_pixels.cmake: -D${var}=... is required")
  endif()
endforeach()
if(NOT DEFINED SCALE)
  set(SCALE 1)
endif()
set(sketch_dir "${WORK_DIR}/sketch")
set(render_dir "${WORK_DIR}/render")
file(REMOVE_RECURSE "${sketch_dir}" "${render_dir}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(sketch_args --png "${sketch_dir}" --frames 600 --scale "${SCALE}" --seed 1 --quiet)
set(render_args --png "${render_dir}" --frames 600 --scale "${SCALE}" --seed 1 --quiet)
if(DEFINED MOUSE_PRESSED AND NOT MOUSE_PRESSED STREQUAL "")
  list(APPEND sketch_args --mouse-pressed "${MOUSE_PRESSED}")
  list(APPEND render_args --mouse-pressed "${MOUSE_PRESSED}")
endif()
execute_process(COMMAND "${EXAMPLE}" ${sketch_args} INPUT_FILE /dev/null RESULT_VARIABLE result
                ERROR_VARIABLE error)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "the sketch failed (${result}): ${error}")
endif()
execute_process(COMMAND "${CALDER}" render "${SCENE}" ${render_args} INPUT_FILE /dev/null
                RESULT_VARIABLE result ERROR_VARIABLE error)
if(NOT result STREQUAL "0")
  message(FATAL_ERROR "calder render ${SCENE} failed (${result}): ${error}")
endif()
foreach(frame IN ITEMS 000001 000100 000600)
  set(a "${sketch_dir}/frame-${frame}.png")
  set(b "${render_dir}/frame-${frame}.png")
  execute_process(COMMAND "${IMAGE_CHECK}" "${a}" --equals "${b}" RESULT_VARIABLE result
                  OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "frame ${frame} of the sketch is not calder render's:\n${output}\n"
                        "  sketch: ${a}\n  render: ${b}")
  endif()
endforeach()
message(STATUS "${SCENE}: frames 1, 100 and 600 are calder render's, pixel for pixel")
