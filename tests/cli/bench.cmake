# SPDX-License-Identifier: MIT
# calder-bench (bench/), one case per ctest (cli.bench.<CASE>): --quick runs the
# whole comparison at tiny sizes and prints every table; bad flags and output
# paths fail at once, with one line.
#
#   cmake -DCALDER=<calder-bench> -DCASE=<name> -DWORK_DIR=<dir> -P bench.cmake
cmake_minimum_required(VERSION 3.25)
set(PROGRAM_NAME calder-bench)  # its errors start "calder-bench: "
include("${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake")

# expect_contains(<text> <piece>...): each piece occurs in text.
function(expect_contains text)
  foreach(piece IN LISTS ARGN)
    string(FIND "${text}" "${piece}" at)
    if(at EQUAL -1)
      fail("expected the output to contain: ${piece}")
    endif()
  endforeach()
endfunction()

# The header, each section's table header and the targets.
set(pieces
    "CPU"
    "kernels"
    "compiler"
    "pairs/s"
    "vs learner"
    "of FMA floor"
    "body-steps/s"
    "vs Box2D"
    "steps/s"
    "RMS error"
    "max error"
    "target"
    "not measured (--quick)")

if(CASE STREQUAL "quick_text")
  calder_run(--quick)
  if(NOT rc EQUAL 0)
    fail("expected exit 0")
  endif()
  expect_contains("${out}" ${pieces} "== targets")
elseif(CASE STREQUAL "quick_markdown")
  calder_run(--quick --format markdown --output perf.md)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "")
    fail("expected exit 0 and nothing on stdout")
  endif()
  file(READ "${WORK_DIR}/perf.md" md)
  expect_contains("${md}" ${pieces} "## Machine" "## targets" "| what | N |" "|---|--:|")
  expect_no_output(.perf.md.tmp)
elseif(CASE STREQUAL "only")
  calder_run(--quick --only bulk)
  if(NOT rc EQUAL 0)
    fail("expected exit 0")
  endif()
  expect_contains("${out}" "body-steps/s" "vs Box2D")
  string(FIND "${out}" "vs learner" at)
  if(NOT at EQUAL -1)
    fail("--only bulk printed the n-body table")
  endif()
elseif(CASE STREQUAL "scaling")
  # More threads than cores: the work columns still come from the counters.
  calder_run(--quick --only scaling --threads 1,2,3)
  if(NOT rc EQUAL 0)
    fail("expected exit 0")
  endif()
  expect_contains("${out}" "scaling with the thread count" "speedup" "efficiency"
                  "work imbalance" "Barnes-Hut, float64" "rain (calder::bulk), book"
                  "the scaling table ran 1, 2, 3 thread(s)" "ceiling: FMA peak"
                  "top of the tree (serial)" "subtrees placed (serial)")
elseif(CASE STREQUAL "bad_threads")
  calder_run(--quick --only scaling --threads 1,0)
  expect_error(2 CONTAINS "--threads" "1,0")
elseif(CASE STREQUAL "bad_format")
  calder_run(--quick --format xml)
  expect_error(2 CONTAINS "--format" "xml")
elseif(CASE STREQUAL "bad_only")
  calder_run(--quick --only nbody,gpu)
  expect_error(2 CONTAINS "--only" "nbody,gpu")
elseif(CASE STREQUAL "bad_min_time")
  calder_run(--quick --min-time 0)
  expect_error(2 CONTAINS "--min-time")
elseif(CASE STREQUAL "output_missing_directory")
  calder_run(--quick --output missing/perf.md)
  expect_error(2 CONTAINS "missing/perf.md")
  expect_no_output(missing/perf.md)
else()
  message(FATAL_ERROR "unknown case '${CASE}'")
endif()
