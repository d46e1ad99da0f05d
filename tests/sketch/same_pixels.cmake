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

# Frame 1 from a run of one frame; frames 100 and 600 from a run of 600 that
# writes every 100th, each run into a folder of its own (a run replaces its
# folder's frames; render names its images by their order, the sketch by
# their frame).
set(mouse_args)
if(DEFINED MOUSE_PRESSED AND NOT MOUSE_PRESSED STREQUAL "")
  set(mouse_args --mouse-pressed "${MOUSE_PRESSED}")
endif()
function(draw_both frames every)
  set(common --frames ${frames} --every ${every} --scale "${SCALE}" --seed 1 --quiet ${mouse_args})
  execute_process(COMMAND "${EXAMPLE}" --png "${sketch_dir}/${frames}" ${common} INPUT_FILE /dev/null
                  RESULT_VARIABLE result ERROR_VARIABLE error)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "the sketch failed (${result}): ${error}")
  endif()
  execute_process(COMMAND "${CALDER}" render "${SCENE}" --png "${render_dir}/${frames}" ${common}
                  INPUT_FILE /dev/null RESULT_VARIABLE result ERROR_VARIABLE error)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "calder render ${SCENE} failed (${result}): ${error}")
  endif()
endfunction()
draw_both(1 1)
draw_both(600 100)
foreach(pair IN ITEMS "1/frame-000001|1/frame-000001" "600/frame-000100|600/frame-000001"
                      "600/frame-000600|600/frame-000006")
  string(REPLACE "|" ";" pair "${pair}")
  list(GET pair 0 frame)
  list(GET pair 1 rendered)
  set(a "${sketch_dir}/${frame}.png")
  set(b "${render_dir}/${rendered}.png")
  execute_process(COMMAND "${IMAGE_CHECK}" "${a}" --equals "${b}" RESULT_VARIABLE result
                  OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "frame ${frame} of the sketch is not calder render's:\n${output}\n"
                        "  sketch: ${a}\n  render: ${b}")
  endif()
endforeach()
message(STATUS "${SCENE}: frames 1, 100 and 600 are calder render's, pixel for pixel")
