# SPDX-License-Identifier: MIT
# bench/rebound_compare.sh without REBOUND at hand, one case per ctest
# (bench.rebound_compare.<CASE>): it fails at once with one line, before
# building anything. The comparison itself needs REBOUND (fetched from the
# network or REBOUND_SRC), so CI does not run it.
#
#   cmake -DCALDER=<bench/rebound_compare.sh> -DCASE=<name> -DWORK_DIR=<dir> -P rebound_compare.cmake
cmake_minimum_required(VERSION 3.25)
set(PROGRAM_NAME rebound_compare)  # its errors start "rebound_compare: "
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# Nothing to be had: no REBOUND_SRC, and a URL that cannot answer (as a
# machine without network).
set(ENV{REBOUND_SRC} "")
set(ENV{REBOUND_URL} "file://${WORK_DIR}/no-such-repository")
set(work --work "${WORK_DIR}/work")

if(CASE STREQUAL "no_network")
  calder_run(${work})
  expect_error(1 CONTAINS "cannot fetch REBOUND 5.0.0" "no network?" "set REBOUND_SRC")
  if(EXISTS "${WORK_DIR}/work/rebound-5.0.0")
    fail("a failed clone left its folder behind")
  endif()
elseif(CASE STREQUAL "bad_source")
  set(ENV{REBOUND_SRC} "${WORK_DIR}/missing")
  calder_run(${work})
  expect_error(1 CONTAINS "REBOUND_SRC=${WORK_DIR}/missing"
               "neither a REBOUND source tree (src/rebound.h) nor a git directory holding 5.0.0")
elseif(CASE STREQUAL "bad_repetitions")
  calder_run(${work} --repetitions 0)
  expect_error(2 CONTAINS "--repetitions" "got '0'")
elseif(CASE STREQUAL "bad_argument")
  calder_run(${work} --fast)
  expect_error(2 CONTAINS "unknown argument '--fast'")
elseif(CASE STREQUAL "output_missing_directory")
  calder_run(${work} --output missing/rebound.md)
  expect_error(2 CONTAINS "missing/rebound.md")
  expect_no_output(missing/rebound.md)
else()
  message(FATAL_ERROR "unknown CASE ${CASE}")
endif()
