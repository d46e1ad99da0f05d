# SPDX-License-Identifier: MIT
# `calder window`, one case per ctest (window.<CASE>, label window).
#
#   no_display, bad_display, bad_input   exit 2 with one line, no display needed
#   dummy, dummy_scripted                SDL's dummy video driver: no display needed
#   xvfb_drag, xvfb_keys                 a real X server (xvfb-run) driven by xdotool
#                                        (window_xvfb.sh); where they are missing the
#                                        test is skipped, except in CI (CI set), where
#                                        it fails: scripts/setup installs them
#
#   cmake -DCALDER=<exe> -DIMAGE_CHECK=<exe> -DCASE=<name> -DWORK_DIR=<dir>
#         -DSCRIPT_DIR=<tests/cli> -P window.cmake
cmake_minimum_required(VERSION 3.25)
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/image_common.cmake")

# window_run(ENV <VAR=value | --unset=VAR>... ARGS <arg>...): calder in WORK_DIR
# with that environment; sets rc, out, err (as calder_run).
function(window_run)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "" "ENV;ARGS")
  list(JOIN arg_ARGS " " shown_args)
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -E env ${arg_ENV} "${CALDER}" ${arg_ARGS}
    WORKING_DIRECTORY "${WORK_DIR}"
    INPUT_FILE /dev/null
    RESULT_VARIABLE result
    OUTPUT_VARIABLE stdout
    ERROR_VARIABLE stderr
    TIMEOUT 120)
  set(rc "${result}" PARENT_SCOPE)
  set(out "${stdout}" PARENT_SCOPE)
  set(err "${stderr}" PARENT_SCOPE)
  set(shown "${arg_ENV} calder ${shown_args}" PARENT_SCOPE)
endfunction()

set(no_display --unset=DISPLAY --unset=WAYLAND_DISPLAY --unset=SDL_VIDEODRIVER)
set(dummy --unset=DISPLAY --unset=WAYLAND_DISPLAY SDL_VIDEODRIVER=dummy)

# state_value(<var> <regex with one group>): the group of the first line of
# `out` (a --print-state) that matches.
function(state_value var regex)
  if(NOT out MATCHES "(^|\n)${regex}\n")
    fail("no line matching '${regex}' in the state")
  endif()
  set(${var} "${CMAKE_MATCH_2}" PARENT_SCOPE)
endfunction()

# expect_near(<what> <value> <expected> <tolerance>)
function(expect_near what value expected tolerance)
  math(EXPR low "${expected} - ${tolerance}")
  math(EXPR high "${expected} + ${tolerance}")
  if(NOT value GREATER_EQUAL low OR NOT value LESS_EQUAL high)
    fail("${what} is ${value}, expected ${expected} +- ${tolerance}")
  endif()
endfunction()

# require_x(): xvfb-run, xauth and xdotool (scripts/setup installs them; the
# test fails without them rather than skip).
macro(require_x)
  find_program(XVFB_RUN xvfb-run)
  find_program(XDOTOOL xdotool)
  find_program(XAUTH xauth)
  if(NOT XVFB_RUN OR NOT XDOTOOL OR NOT XAUTH)
    message(FATAL_ERROR "xvfb-run, xauth and xdotool are needed (scripts/setup installs them)")
  endif()
endmacro()

# xvfb(<scenario> [args]): window_xvfb.sh in a fresh X server; its log on failure.
function(xvfb)
  list(JOIN ARGN " " shown_args)
  execute_process(
    COMMAND timeout 150 "${XVFB_RUN}" -a -s "-screen 0 1024x768x24" bash
            "${SCRIPT_DIR}/window_xvfb.sh" "${CALDER}" ${ARGN}
    WORKING_DIRECTORY "${WORK_DIR}"
    INPUT_FILE /dev/null
    RESULT_VARIABLE result
    OUTPUT_VARIABLE xvfb_out
    ERROR_VARIABLE xvfb_err)
  foreach(name IN ITEMS log state stderr status)
    set(${name} "")
    if(EXISTS "${WORK_DIR}/${name}.txt")
      file(READ "${WORK_DIR}/${name}.txt" ${name})
    endif()
  endforeach()
  string(STRIP "${status}" status)
  set(rc "${status}" PARENT_SCOPE)
  set(out "${state}" PARENT_SCOPE)
  set(err "${stderr}" PARENT_SCOPE)
  set(shown "xvfb-run window_xvfb.sh ${shown_args}\n--- log:\n${log}" PARENT_SCOPE)
  set(log "${log}" PARENT_SCOPE)
  if(NOT result STREQUAL "0")
    set(rc "${status}")
    set(out "${state}")
    set(err "${stderr}")
    set(shown "xvfb-run window_xvfb.sh ${shown_args}\n--- log:\n${log}")
    fail("xvfb-run exited with ${result}:\n${xvfb_out}${xvfb_err}")
  endif()
endfunction()

if(CASE STREQUAL "no_display")
  window_run(ENV ${no_display} ARGS window example-2.1)
  expect_error(2 MATCHES "^calder: no display: ")
  expect_files()
elseif(CASE STREQUAL "bad_display")
  # A display that isn't there: SDL can't start its video.
  window_run(ENV --unset=WAYLAND_DISPLAY DISPLAY=:4321 SDL_VIDEODRIVER=x11 ARGS window example-2.1)
  expect_error(2 MATCHES "^calder: no display: ")
  expect_files()
elseif(CASE STREQUAL "bad_input")
  # Checked before the display is needed.
  window_run(ENV ${no_display} ARGS window nosuchscene)
  expect_error(2 CONTAINS "unknown scene 'nosuchscene'")
  foreach(scale IN ITEMS 0 9 x)
    window_run(ENV ${no_display} ARGS window example-2.1 --scale ${scale})
    expect_error(2 CONTAINS "--scale" "'${scale}'")
  endforeach()
  foreach(speed IN ITEMS 0 0.1 9 x)
    window_run(ENV ${no_display} ARGS window example-2.1 --speed ${speed})
    expect_error(2 CONTAINS "--speed" "'${speed}'" "0.125 to 8")
  endforeach()
  window_run(ENV ${no_display} ARGS window example-2.1 --exit-after-seconds 0)
  expect_error(2 CONTAINS "--exit-after-seconds" "'0'")
  window_run(ENV ${no_display} ARGS window example-2.1 --screenshot nodir/shot.png)
  expect_error(2 CONTAINS "nodir/shot.png" "does not exist")
  window_run(ENV ${no_display} ARGS window example-2.1 --frames -1)
  expect_error(2 CONTAINS "--frames" "'-1'")
  expect_files()
  # The screenshot may not overwrite an input (the output policy).
  file(WRITE "${WORK_DIR}/st.csv" "x,y,vx,vy,mass\n1,2,0,0,1\n")
  window_run(ENV ${no_display} ARGS window example-2.8 --state st.csv --screenshot st.csv)
  expect_error(2 CONTAINS "--screenshot 'st.csv': is --state 'st.csv'")
  expect_files(st.csv)
elseif(CASE STREQUAL "help")
  calder_run(window --help)
  expect_success()
  foreach(text IN ITEMS --scale --speed --frames --seed --screenshot --exit-after-seconds
                        --print-state --forces "space pause" "q quit")
    string(FIND "${out}" "${text}" at)
    if(at EQUAL -1)
      fail("calder window --help does not mention ${text}")
    endif()
  endforeach()
elseif(CASE STREQUAL "dummy")
  # SDL's dummy video driver: a window nobody sees, the whole loop all the same.
  window_run(ENV ${dummy} ARGS window example-2.1 --frames 30 --screenshot shot.png --print-state
             --quiet)
  expect_success()
  # 30 steps of gravity 0.1: y = 30 + 0.1 * (1 + ... + 30) = 76.5.
  state_value(frame "frame ([0-9]+)")
  if(NOT frame STREQUAL "30")
    fail("expected frame 30")
  endif()
  state_value(y "body 0 320 ([^ ]+) radius 24")
  expect_near("body 0's y" "${y}" 76 1)
  if(NOT out MATCHES "\nstate_hash [0-9a-f]+\n$")
    fail("expected the state hash last")
  endif()
  expect_image(shot.png --size 640 240 --gray 320 76.5 191 2 --dark-near 320 76.5 26 60
               --gray 320 20 255 0)
  expect_mode(shot.png 644)
  # Without --quiet the keys are printed on stderr once the window is open.
  window_run(ENV ${dummy} ARGS window example-2.1 --frames 1 --scale 0.5 --screenshot half.png)
  if(NOT rc STREQUAL "0" OR NOT err MATCHES "^calder window example-2.1: keys: [^\n]+\n$")
    fail("expected exit 0 and the keys on stderr")
  endif()
  expect_image(half.png --size 320 120)
elseif(CASE STREQUAL "dummy_scripted")
  # With --mouse-pressed the window replays the script: the same state as `calder run`.
  window_run(ENV ${dummy} ARGS window example-2.1 --frames 120 --mouse-pressed 20-90 --print-state
             --quiet --speed 8)
  expect_success()
  state_value(window_hash "state_hash ([0-9a-f]+)")
  calder_run(run example-2.1 --frames 120 --mouse-pressed 20-90)
  expect_success()
  if(NOT out MATCHES "state hash +([0-9a-f]+)")
    fail("no state hash in the summary")
  endif()
  if(NOT CMAKE_MATCH_1 STREQUAL window_hash)
    fail("calder window's state hash ${window_hash} differs from calder run's ${CMAKE_MATCH_1}")
  endif()
elseif(CASE STREQUAL "xvfb_drag")
  require_x()
  # Example 2.7 at scale 1.5: xdotool drags the attractor from (320, 120) to
  # (200, 80) (canvas pixels; window pixels 480, 180 to 300, 120).
  xvfb(drag 1.5)
  expect_success()
  state_value(frame "frame ([0-9]+)")
  if(NOT frame STREQUAL "600")
    fail("expected frame 600 (the window stops after --frames 600)")
  endif()
  if(NOT out MATCHES "\nattractor 0 ([^ ]+) ([^ ]+) mass 20\n")
    fail("no attractor in the state")
  endif()
  set(ax "${CMAKE_MATCH_1}")
  set(ay "${CMAKE_MATCH_2}")
  expect_near("the attractor's x" "${ax}" 200 2)
  expect_near("the attractor's y" "${ay}" 80 2)
  # The screenshot: 960 x 360; the attractor drawn where it was dragged,
  # fill(175, 200) over white = 192.25, and a 4 px black stroke at radius 20.
  expect_image(out.png --size 960 360 --scale 1.5 --gray-near ${ax} ${ay} 10 192 3
               --dark-near ${ax} ${ay} 21 60)
  # Each body inside the canvas shows its black stroke around its position.
  string(REGEX MATCHALL "body [0-9]+ [^ ]+ [^ ]+ radius [^\n]+" bodies "${out}")
  set(checked 0)
  foreach(body IN LISTS bodies)
    string(REGEX MATCH "body ([0-9]+) ([^ ]+) ([^ ]+) radius (.+)" _ "${body}")
    set(x "${CMAKE_MATCH_2}")
    set(y "${CMAKE_MATCH_3}")
    set(r "${CMAKE_MATCH_4}")
    if(x GREATER_EQUAL 0 AND x LESS_EQUAL 640 AND y GREATER_EQUAL 0 AND y LESS_EQUAL 240)
      expect_image(out.png --scale 1.5 --pad 2 --dark-near ${x} ${y} ${r} 60)
      math(EXPR checked "${checked} + 1")
    endif()
  endforeach()
  if(checked EQUAL 0)
    fail("no body inside the canvas to check")
  endif()
  message(STATUS "attractor at (${ax}, ${ay}); ${checked} bodies seen in the screenshot")
elseif(CASE STREQUAL "xvfb_keys")
  require_x()
  string(TIMESTAMP started "%s" UTC)
  xvfb(keys)
  string(TIMESTAMP ended "%s" UTC)
  expect_success()
  math(EXPR seconds "${ended} - ${started}")
  if(seconds GREATER 45)
    fail("q did not quit: the run took ${seconds} s (--exit-after-seconds 60)")
  endif()
  # s: a PNG, named and printed
  if(NOT out MATCHES "(^|\n)saved (calder-example-2\\.1-[0-9][0-9][0-9][0-9][0-9][0-9]\\.png)\n")
    fail("s: expected 'saved calder-example-2.1-NNNNNN.png'")
  endif()
  expect_image("${CMAKE_MATCH_2}" --size 640 240)
  # g ... g: a GIF recorded, looping
  if(NOT out MATCHES
     "(^|\n)recording (calder-example-2\\.1-[0-9]+-[0-9]+\\.gif) \\(g stops\\)\n")
    fail("g: expected 'recording calder-example-2.1-TIME.gif'")
  endif()
  set(gif "${CMAKE_MATCH_2}")
  string(REPLACE "." "\\." gif_regex "${gif}")
  if(NOT out MATCHES "\nsaved ${gif_regex} \\([0-9]+ frames\\)\n")
    fail("g: expected 'saved ${gif} (N frames)'")
  endif()
  expect_image("${gif}" --size 640 240 --loop)
  # The title showed the state: paused (and where) after space, one frame
  # further after each ., speed x2 after +; q quit with the state at the pause
  # plus two steps.
  if(NOT log MATCHES "key space; title: calder: example-2\\.1 \\[paused at frame ([0-9]+), recording")
    fail("space: the title does not say paused")
  endif()
  set(paused_at "${CMAKE_MATCH_1}")
  math(EXPR stepped "${paused_at} + 2")
  if(NOT log MATCHES "key period; title: calder: example-2\\.1 \\[paused at frame ${stepped},")
    fail(". . : expected the title to say frame ${stepped}")
  endif()
  if(NOT log MATCHES "key plus; title: calder: example-2\\.1 \\[paused at frame ${stepped}, speed x2\\]")
    fail("+: the title does not say speed x2")
  endif()
  state_value(frame "frame ([0-9]+)")
  if(NOT frame STREQUAL "${stepped}")
    fail("expected the state at frame ${stepped}")
  endif()
  # k (paused at that frame): a snapshot, named and printed, that the
  # command goes on from with the window's state.
  state_value(window_hash "state_hash ([0-9a-f]+)")
  if(NOT out MATCHES "(^|\n)saved (calder-example-2\\.1-${stepped}\\.snap)\n")
    fail("k: expected 'saved calder-example-2.1-${stepped}.snap'")
  endif()
  calder_run(run "${CMAKE_MATCH_2}" --frames ${stepped})
  expect_success()
  if(NOT out MATCHES "state hash +${window_hash}\n")
    fail("k: the snapshot does not hold the window's state ${window_hash}")
  endif()
  # f: the forces are drawn, with their legend at the top left.
  expect_image(out.png --size 640 240 --colored-near 40 30 40)
else()
  message(FATAL_ERROR "unknown CASE '${CASE}'")
endif()
