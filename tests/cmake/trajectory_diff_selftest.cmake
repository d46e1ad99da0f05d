# SPDX-License-Identifier: MIT
# Checks trajectory_diff's verdicts and exit codes on small hand-written files.
#
#   cmake -DTRAJECTORY_DIFF=<exe> -DWORK_DIR=<scratch folder> -P trajectory_diff_selftest.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS TRAJECTORY_DIFF WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "trajectory_diff_selftest.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

set(header "frame,body,x,y,vx,vy")
set(ref_rows "0,0,320,30,0,0\n0,1,1000000,-5,0.5,0\n1,0,320,30.1,0,0.1\n1,1,1000000.5,-5,0.5,0\n")
file(WRITE "${WORK_DIR}/ref.csv" "${header}\n${ref_rows}")

# write_candidate(<name> <content>)
function(write_candidate name content)
  file(WRITE "${WORK_DIR}/${name}.csv" "${content}")
endfunction()

# expect(<description> <exit code> <output regex> <args...>)
function(expect description code regex)
  execute_process(
    COMMAND "${TRAJECTORY_DIFF}" ${ARGN}
    WORKING_DIRECTORY "${WORK_DIR}"
    RESULT_VARIABLE result
    OUTPUT_VARIABLE output
    ERROR_VARIABLE output)
  string(STRIP "${output}" output)
  if(NOT result STREQUAL "${code}" OR NOT output MATCHES "${regex}")
    message(SEND_ERROR "${description}: expected exit ${code} and output matching '${regex}', "
                       "got exit ${result}: ${output}")
  else()
    message(STATUS "${description}: ${output}")
  endif()
endfunction()

write_candidate(same "${header}\n${ref_rows}")
expect("identical" 0 "^OK: 4 rows, max error 0 at frame 0 body 0$" ref.csv same.csv)

write_candidate(crlf "${header}\r\n0,0,320,30,0,0\r\n0,1,1000000,-5,0.5,0\r\n1,0,320,30.1,0,0.1\r\n1,1,1000000.5,-5,0.5,0\r\n\r\n")
expect("CRLF and a trailing blank line" 0 "^OK: 4 rows" ref.csv crlf.csv)

# 1e-4 off at magnitude 1e6 is 1e-10 relative: inside 1e-9.
write_candidate(relative "${header}\n0,0,320,30,0,0\n0,1,1000000.0001,-5,0.5,0\n1,0,320,30.1,0,0.1\n1,1,1000000.5,-5,0.5,0\n")
expect("relative error above magnitude 1" 0 "^OK: 4 rows, max error [0-9.e-]+ at frame 0 body 1$"
       ref.csv relative.csv)

write_candidate(off "${header}\n0,0,320,30,0,0\n0,1,1000000,-5,0.5,0\n1,0,320,30.1,0,0.1000001\n1,1,1000000.5,-5,0.5,0\n")
expect("value off by 1e-7" 1
       "^FAIL: first frame 1 body 0 column vy: reference 0.1 candidate 0.1000001 \\(error [0-9.e-]+\\)$"
       ref.csv off.csv)
expect("value off by 1e-7, --tolerance 1e-6" 0 "^OK: 4 rows, max error [0-9.e-]+ at frame 1 body 0$"
       ref.csv off.csv --tolerance 1e-6)
expect("--tolerance=" 0 "^OK:" ref.csv off.csv --tolerance=1e-6)

write_candidate(nan "${header}\n0,0,320,30,0,0\n0,1,1000000,-5,0.5,0\n1,0,nan,30.1,0,0.1\n1,1,1000000.5,-5,0.5,0\n")
expect("NaN" 1 "^FAIL: first frame 1 body 0 column x: reference 320 candidate nan" ref.csv nan.csv)

write_candidate(short "${header}\n0,0,320,30,0,0\n0,1,1000000,-5,0.5,0\n")
expect("fewer rows" 1 "^FAIL: row count differs: reference 4 candidate 2" ref.csv short.csv)

write_candidate(keys "${header}\n0,0,320,30,0,0\n0,2,1000000,-5,0.5,0\n1,0,320,30.1,0,0.1\n1,1,1000000.5,-5,0.5,0\n")
expect("other key" 1 "^FAIL: row 2 .*reference frame 0 body 1, candidate frame 0 body 2" ref.csv keys.csv)

write_candidate(header "frame,body,x,y\n${ref_rows}")
expect("other header" 1 "^FAIL: header differs" ref.csv header.csv)

write_candidate(malformed "${header}\n0,0,320,30,0,0\n0,1,1000000,-5,0.5\n")
expect("five fields" 2 "^trajectory_diff: malformed.csv:3: malformed row" ref.csv malformed.csv)
write_candidate(text "${header}\n0,0,320,30,0,0\n0,1,1000000,-5,0.5,zero\n")
expect("a word" 2 "^trajectory_diff: text.csv:3: malformed row, column vy" ref.csv text.csv)
write_candidate(extra "${header}\n0,0,320,30,0,0,7\n")
expect("seven fields" 2 "^trajectory_diff: extra.csv:2: malformed row" ref.csv extra.csv)
write_candidate(empty "")
expect("empty file" 2 "^trajectory_diff: empty.csv:1: empty file" ref.csv empty.csv)
expect("missing file" 2 "^trajectory_diff: cannot read missing.csv" ref.csv missing.csv)
expect("no candidate" 2 "^usage: trajectory_diff" ref.csv)
expect("bad tolerance" 2 "^trajectory_diff: --tolerance must be" ref.csv same.csv --tolerance -1)
