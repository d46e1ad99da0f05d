# SPDX-License-Identifier: MIT
# bench/barnes_hut_ab.sh's refusals, one case per ctest
# (bench.barnes_hut_ab.<CASE>): each fails at once with one line, before
# checking anything out or building. The A/B itself takes minutes of an idle
# machine, so CI does not run it.
#
#   cmake -DCALDER=<bench/barnes_hut_ab.sh> -DCASE=<name> -DWORK_DIR=<dir> -P barnes_hut_ab.cmake
cmake_minimum_required(VERSION 3.25)
set(PROGRAM_NAME barnes_hut_ab)  # its errors start "barnes_hut_ab: "
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

set(work --work "${WORK_DIR}/work")
if(CASE STREQUAL "no_revision")
  calder_run(${work})
  expect_error(2 CONTAINS "give BEFORE")
elseif(CASE STREQUAL "bad_revision")
  calder_run(${work} no-such-revision-here)
  expect_error(1 CONTAINS "'no-such-revision-here' is not a revision")
  if(EXISTS "${WORK_DIR}/work")
    fail("a refused revision left a work folder behind")
  endif()
elseif(CASE STREQUAL "bad_rounds")
  calder_run(${work} HEAD --rounds 0)
  expect_error(2 CONTAINS "--rounds" "got '0'")
elseif(CASE STREQUAL "bad_option")
  calder_run(${work} HEAD --fast)
  expect_error(2 CONTAINS "unknown option '--fast'")
else()
  message(FATAL_ERROR "unknown CASE ${CASE}")
endif()
