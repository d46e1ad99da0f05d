# SPDX-License-Identifier: MIT
# Helpers for render.cmake and window.cmake (after cli_common.cmake).
include_guard(GLOBAL)

if(NOT DEFINED IMAGE_CHECK OR IMAGE_CHECK STREQUAL "")
  message(FATAL_ERROR "-DIMAGE_CHECK=... is required")
endif()

# expect_image(<file> CHECK...): image_check (image_check.cpp) on a file of
# WORK_DIR holds, e.g. expect_image(out.gif --frames 11 --size 640 240 --loop).
function(expect_image file)
  execute_process(
    COMMAND "${IMAGE_CHECK}" "${WORK_DIR}/${file}" ${ARGN}
    RESULT_VARIABLE check_rc
    OUTPUT_VARIABLE check_out
    ERROR_VARIABLE check_err)
  if(NOT check_rc STREQUAL "0")
    list(JOIN ARGN " " checks)
    fail("image_check ${file} ${checks} failed (${check_rc}):\n${check_out}${check_err}")
  endif()
endfunction()

# files_in(<var>): the files and folders under WORK_DIR (relative paths,
# hidden ones included), sorted.
function(files_in var)
  file(GLOB_RECURSE found LIST_DIRECTORIES true RELATIVE "${WORK_DIR}" "${WORK_DIR}/*")
  list(SORT found)
  set(${var} "${found}" PARENT_SCOPE)
endfunction()

# expect_files(<path>...): exactly these files and folders are in WORK_DIR.
function(expect_files)
  files_in(found)
  set(expected ${ARGN})
  list(SORT expected)
  if(NOT "${found}" STREQUAL "${expected}")
    fail("WORK_DIR holds [${found}], expected [${expected}]")
  endif()
endfunction()

# expect_mode(<file> <octal>): the file's permission bits (stat -c %a).
function(expect_mode file mode)
  execute_process(COMMAND stat -c %a "${WORK_DIR}/${file}" OUTPUT_VARIABLE found
                  OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT found STREQUAL "${mode}")
    fail("${file} has mode ${found}, expected ${mode}")
  endif()
endfunction()

# expect_out(<text>...): stdout of the last run holds each text.
function(expect_out)
  foreach(text IN LISTS ARGN)
    string(FIND "${out}" "${text}" at)
    if(at EQUAL -1)
      fail("expected stdout to contain: ${text}")
    endif()
  endforeach()
endfunction()
