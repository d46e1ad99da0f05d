# SPDX-License-Identifier: MIT
# What `calder` writes when it succeeds, one case per ctest (cli.output.<CASE>).
#
#   cmake -DCALDER=<exe> -DCASE=<name> -DWORK_DIR=<dir> [-DJSON_CHECK=<exe>]
#         [-DSCENE_FILE=<path>] -P output.cmake
cmake_minimum_required(VERSION 3.25)
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# expect_same_file(<a> <b>): two files of WORK_DIR are byte for byte equal.
function(expect_same_file a b)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK_DIR}/${a}"
                          "${WORK_DIR}/${b}" RESULT_VARIABLE different)
  if(different)
    fail("${a} and ${b} differ")
  endif()
endfunction()

function(expect_different_file a b)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${WORK_DIR}/${a}"
                          "${WORK_DIR}/${b}" RESULT_VARIABLE different)
  if(NOT different)
    fail("${a} and ${b} are equal")
  endif()
endfunction()

# The example 2.1 world as a scene file, with the mouse held on frames 100..160.
set(windy_toml
    "name = \"windy\"
frames = 200
[boundary]
kind = \"bounce\"
edges = [\"left\", \"right\", \"bottom\"]
[[bodies]]
mass = 1
position = [320, 30]
[[fields]]
type = \"gravity\"
g = [0, 0.1]
[[fields]]
type = \"wind\"
force = [0.1, 0]
while_pressed = true
[input]
mouse_pressed = [[100, 160]]
")

if(CASE STREQUAL "help")
  foreach(args IN ITEMS "--help" "run;--help" "list;--help" "-h")
    calder_run(${args})
    expect_success()
    if(NOT out MATCHES "Usage:")
      fail("expected a usage text")
    endif()
  endforeach()
  calder_run(run --help)
  foreach(text IN ITEMS --frames --dt --seed --state --mouse-pressed --mouse --trajectory --format
                        REPLACE)
    string(FIND "${out}" "${text}" at)
    if(at EQUAL -1)
      fail("calder run --help does not mention ${text}")
    endif()
  endforeach()
elseif(CASE STREQUAL "version")
  calder_run(--version)
  expect_success()
  if(NOT out MATCHES "^calder [0-9]+\\.[0-9]+\\.[0-9]+\n$")
    fail("expected 'calder X.Y.Z'")
  endif()
elseif(CASE STREQUAL "list")
  # One line per built-in scene, the descriptions aligned in one column; the
  # chapter's examples are all there (the unit test checks the exact list).
  calder_run(list)
  expect_success()
  string(REGEX REPLACE "\n$" "" text "${out}")
  string(REPLACE ";" "," text "${text}")  # descriptions hold ';', CMake's list separator
  string(REPLACE "\n" ";" lines "${text}")
  set(column "")
  set(names)
  foreach(line IN LISTS lines)
    if(NOT line MATCHES "^([a-z0-9.-]+)(  +)[^ ]")
      fail("expected NAME, two or more spaces, a description: ${line}")
    endif()
    list(APPEND names "${CMAKE_MATCH_1}")
    string(LENGTH "${CMAKE_MATCH_1}${CMAKE_MATCH_2}" at)
    if(column STREQUAL "")
      set(column ${at})
    elseif(NOT column EQUAL at)
      fail("descriptions are not aligned (column ${at}, not ${column}): ${line}")
    endif()
  endforeach()
  foreach(scene IN ITEMS example-2.1 example-2.2 example-2.3 example-2.4 example-2.5 example-2.6
                         example-2.7 example-2.8 example-2.9 exercise-2.16)
    if(NOT scene IN_LIST names)
      fail("${scene} is not listed")
    endif()
  endforeach()
elseif(CASE STREQUAL "summary")
  calder_run(run example-2.8)
  expect_success()
  foreach(label IN ITEMS "scene +example-2.8" "frames +600" "bodies +2" "dt +1" "seed +0"
                         "kinetic energy +[-0-9.e]+" "potential energy +[-0-9.e]+"
                         "total energy +[-0-9.e]+" "momentum +\\([-0-9.e]+, [-0-9.e]+\\)"
                         "angular momentum +[-0-9.e]+" "state hash +[0-9a-f]+")
    if(NOT out MATCHES "(^|\n)${label}\n")
      fail("the summary lacks a line '${label}'")
    endif()
  endforeach()
  if(NOT out MATCHES "\nstate hash +[0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f][0-9a-f]\n")
    fail("the state hash is not 16 hex digits")
  endif()
  # Two equal bodies moving oppositely: zero momentum.
  if(NOT out MATCHES "\nmomentum +\\(0, 0\\)\n")
    fail("example 2.8 should have zero linear momentum")
  endif()
elseif(CASE STREQUAL "energy_warning")
  # Fixed-step RK4 on the Pythagorean problem: the first close approach (t
  # about 1.9) wrecks the energy. One warning names the frame; the exit
  # status stays 0 unless --fail-on-energy asks.
  calder_run(run pythagorean --integrator rk4 --dt 0.001 --frames 2500)
  if(NOT rc STREQUAL "0")
    fail("expected exit 0")
  endif()
  if(NOT err MATCHES "^calder: warning: relative energy error [-0-9.e]+ passed 1e-06 at frame 18[0-9][0-9] \\(t = 1\\.8[0-9]*\\)\n$")
    fail("expected one warning naming a frame of the first close approach")
  endif()
  if(NOT out MATCHES "\nenergy error +[-0-9.e]+ \\(relative, since frame 0\\)")
    fail("the summary should report the energy error")
  endif()
  calder_run(run pythagorean --integrator rk4 --dt 0.001 --frames 2500 --fail-on-energy)
  if(NOT rc STREQUAL "1" OR NOT err MATCHES "--fail-on-energy")
    fail("--fail-on-energy: expected exit 1 and the reason")
  endif()
  # The scene's own ias15: no warning, its steps and closest approach shown.
  calder_run(run pythagorean --energy-every 350)
  expect_success()
  foreach(label IN ITEMS "energy frame 350 t 35 total [-0-9.e]+ relative error [-0-9.e]+"
                         "energy frame 700 t 70 total [-0-9.e]+ relative error [-0-9.e]+"
                         "energy error +[-0-9.e]+ \\(relative, since frame 0\\)"
                         "internal steps +[0-9]+ \\([0-9]+ rejected, [0-9]+ force evaluations\\)"
                         "closest approach +0\\.01[0-9]+ at t = 15\\.8[0-9]*")
    if(NOT out MATCHES "(^|\n)${label}\n")
      fail("the output lacks a line '${label}'")
    endif()
  endforeach()
elseif(CASE STREQUAL "summary_hash")
  # Same run, same summary (and hash); another seed, another hash.
  calder_run(run example-2.7 --seed 7 --frames 300)
  expect_success()
  set(first "${out}")
  string(REGEX MATCH "state hash +([0-9a-f]+)" _ "${out}")
  set(hash "${CMAKE_MATCH_1}")
  calder_run(run example-2.7 --seed 7 --frames 300)
  expect_success()
  if(NOT out STREQUAL first)
    fail("two equal runs printed different summaries:\n${first}")
  endif()
  calder_run(run example-2.7 --seed 8 --frames 300)
  expect_success()
  string(REGEX MATCH "state hash +([0-9a-f]+)" _ "${out}")
  if(CMAKE_MATCH_1 STREQUAL hash)
    fail("seeds 7 and 8 gave the same state hash ${hash}")
  endif()
  if(NOT out MATCHES "\nseed +8\n")
    fail("the summary does not show --seed 8")
  endif()
elseif(CASE STREQUAL "trajectory_rows")
  # --trajectory FILE prints nothing and writes (frames + 1) * bodies rows.
  calder_run(run example-2.2 --mouse-pressed 100-160 --frames 250 --trajectory out.csv)
  expect_success()
  if(NOT out STREQUAL "")
    fail("--trajectory FILE printed something")
  endif()
  file(STRINGS "${WORK_DIR}/out.csv" rows)
  list(LENGTH rows count)
  if(NOT count EQUAL 503)  # header + 251 frames * 2 bodies
    fail("expected 503 lines in out.csv, got ${count}")
  endif()
elseif(CASE STREQUAL "json")
  # JSON holds the same numbers as CSV, bit for bit (a C++ check with nlohmann).
  calder_run(run example-2.7 --seed 3 --frames 120 --mouse-pressed 10-20 --mouse 100,100
             --trajectory out.csv)
  expect_success()
  calder_run(run example-2.7 --seed 3 --frames 120 --mouse-pressed 10-20 --mouse 100,100
             --trajectory out.json)
  expect_success()
  calder_run(run example-2.7 --seed 3 --frames 120 --mouse-pressed 10-20 --mouse 100,100
             --trajectory out.data --format json)
  expect_success()
  expect_same_file(out.json out.data)
  execute_process(
    COMMAND "${JSON_CHECK}" out.json out.csv --scene example-2.7 --frames 120 --bodies 10 --dt 1
            --seed 3
    WORKING_DIRECTORY "${WORK_DIR}"
    RESULT_VARIABLE rc
    OUTPUT_VARIABLE out
    ERROR_VARIABLE err)
  if(NOT rc STREQUAL "0")
    fail("cli_json_check failed")
  endif()
elseif(CASE STREQUAL "stdout")
  # '-' writes the trajectory to standard output, the same bytes as a file.
  calder_run(run example-2.4 --frames 50 --trajectory out.csv)
  expect_success()
  calder_run(run example-2.4 --frames 50 --trajectory -)
  expect_success()
  write(stdout.csv "${out}")
  expect_same_file(out.csv stdout.csv)
  calder_run(run example-2.4 --frames 50 --trajectory - --format json)
  expect_success()
  if(NOT out MATCHES "^\\{\"scene\": \"example-2.4\"" OR NOT out MATCHES "\n\\]\\}\n$")
    fail("expected a JSON document on stdout")
  endif()
elseif(CASE STREQUAL "frames_zero")
  calder_run(run example-2.2 --frames 0 --trajectory out.csv)
  expect_success()
  file(READ "${WORK_DIR}/out.csv" text)
  if(NOT text STREQUAL "frame,body,x,y,vx,vy\n0,0,200,30,0,0\n0,1,440,30,0,0\n")
    fail("unexpected trajectory for --frames 0:\n${text}")
  endif()
elseif(CASE STREQUAL "overwrite")
  # An existing file is replaced whole; nothing else is left in the folder.
  write(out.csv "old\n")
  calder_run(run example-2.1 --frames 3 --trajectory out.csv)
  expect_success()
  file(READ "${WORK_DIR}/out.csv" text)
  if(NOT text MATCHES "^frame,body,x,y,vx,vy\n0,0,320,30,0,0\n")
    fail("out.csv was not replaced:\n${text}")
  endif()
  file(GLOB left RELATIVE "${WORK_DIR}" "${WORK_DIR}/*" "${WORK_DIR}/.*")
  if(NOT left STREQUAL "out.csv")
    fail("expected only out.csv in the folder, got: ${left}")
  endif()
elseif(CASE STREQUAL "state")
  # --state replaces the bodies after setup: example 2.2's own bodies give the
  # same trajectory; other bodies a different one.
  write(same.csv "x,y,vx,vy,mass\n200,30,0,0,10\n440,30,0,0,2\n")
  write(other.csv "x,y,vx,vy,mass,radius\n100,50,1,0,3,5\n")
  calder_run(run example-2.2 --frames 100 --mouse-pressed 20-40 --trajectory a.csv)
  expect_success()
  calder_run(run example-2.2 --frames 100 --mouse-pressed 20-40 --state same.csv
             --trajectory b.csv)
  expect_success()
  expect_same_file(a.csv b.csv)
  calder_run(run example-2.2 --frames 10 --state other.csv)
  expect_success()
  if(NOT out MATCHES "\nbodies +1\n")
    fail("--state with one row should give one body")
  endif()
elseif(CASE STREQUAL "mouse_pressed_replaces") # scene file
  # A scene file's scripted presses, and --mouse-pressed replacing them.
  write(windy.toml "${windy_toml}")
  calder_run(run windy.toml --trajectory file.csv)
  expect_success()
  calder_run(run example-2.1 --frames 200 --mouse-pressed 100-160 --trajectory builtin.csv)
  expect_success()
  expect_same_file(file.csv builtin.csv)
  calder_run(run windy.toml --mouse-pressed none --trajectory none.csv)
  expect_success()
  calder_run(run example-2.1 --frames 200 --trajectory still.csv)
  expect_success()
  expect_same_file(none.csv still.csv)
  expect_different_file(none.csv file.csv)
  calder_run(run windy.toml --mouse-pressed 10-20 --mouse-pressed 30-31 --trajectory a.csv)
  expect_success()
  calder_run(run example-2.1 --frames 200 --mouse-pressed 10-20 --mouse-pressed 30-31
             --trajectory b.csv)
  expect_success()
  expect_same_file(a.csv b.csv)
elseif(CASE STREQUAL "scene_file_summary") # scene file
  write(windy.toml "${windy_toml}")
  calder_run(run windy.toml --frames 5 --seed 9 --dt 0.5)
  expect_success()
  foreach(label IN ITEMS "scene +windy" "frames +5" "bodies +1" "dt +0.5" "seed +9")
    if(NOT out MATCHES "(^|\n)${label}\n")
      fail("the summary lacks a line '${label}'")
    endif()
  endforeach()
elseif(CASE STREQUAL "scene_file") # registered apart
  # A scene file of scenes/ runs; when a built-in scene has its name, both give
  # the same trajectory, byte for byte.
  get_filename_component(name "${SCENE_FILE}" NAME_WLE)
  calder_run(run "${SCENE_FILE}" --frames 200 --seed 1 --trajectory file.csv)
  expect_success()
  calder_run(list)
  if(out MATCHES "(^|\n)${name} ")
    calder_run(run "${name}" --frames 200 --seed 1 --trajectory builtin.csv)
    expect_success()
    expect_same_file(file.csv builtin.csv)
  endif()
else()
  message(FATAL_ERROR "output.cmake: unknown CASE '${CASE}'")
endif()
