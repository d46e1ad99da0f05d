# SPDX-License-Identifier: MIT
# Runs a draw-it-yourself example under SDL's dummy video driver for FRAMES
# frames, then checks its screenshot (a 24-bit BMP) against the bodies it
# printed ("body X Y R" and "attractor X Y R" lines, pixels):
#   - the centre of every body that no later-drawn circle covers has the
#     body fill (127, 127, 127);
#   - every point of a 20-pixel grid farther than R + 4 from every circle is
#     the white background;
#   - the screenshot is 640 x 240.
#
#   cmake -DEXAMPLE=<exe> -DFRAMES=<n> -DWORK_DIR=<dir> -P check_screenshot.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS EXAMPLE FRAMES WORK_DIR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "check_screenshot.cmake: -D${var}=... is required")
  endif()
endforeach()
file(MAKE_DIRECTORY "${WORK_DIR}")
set(bmp "${WORK_DIR}/screenshot.bmp")
file(REMOVE "${bmp}")
set(ENV{SDL_VIDEODRIVER} dummy)
execute_process(
  COMMAND "${EXAMPLE}" --frames "${FRAMES}" --screenshot "${bmp}"
  INPUT_FILE /dev/null
  OUTPUT_VARIABLE printed
  ERROR_VARIABLE errors
  RESULT_VARIABLE result)
if(NOT result STREQUAL "0" OR NOT EXISTS "${bmp}")
  message(FATAL_ERROR "example failed (${result}): ${errors}")
endif()

# A little-endian unsigned integer of `size` bytes at `offset`.
function(read_le offset size out)
  file(READ "${bmp}" hex OFFSET ${offset} LIMIT ${size} HEX)
  set(value 0)
  math(EXPR last "${size} - 1")
  foreach(i RANGE ${last} 0 -1)
    math(EXPR at "${i} * 2")
    string(SUBSTRING "${hex}" ${at} 2 byte)
    math(EXPR value "${value} * 256 + 0x${byte}")
  endforeach()
  set(${out} ${value} PARENT_SCOPE)
endfunction()

read_le(10 4 data_offset)
read_le(18 4 width)
read_le(22 4 height)
read_le(28 2 bits)
if(NOT width EQUAL 640 OR NOT height EQUAL 240 OR NOT bits EQUAL 24)
  message(FATAL_ERROR "screenshot is ${width} x ${height} x ${bits} bits, not 640 x 240 x 24")
endif()
math(EXPR row_bytes "((${width} * 3 + 3) / 4) * 4")

# The pixel at (x, y), top-left origin, as "R G B".
function(pixel x y out)
  math(EXPR offset "${data_offset} + (${height} - 1 - ${y}) * ${row_bytes} + ${x} * 3")
  file(READ "${bmp}" hex OFFSET ${offset} LIMIT 3 HEX)
  string(SUBSTRING "${hex}" 0 2 b)
  string(SUBSTRING "${hex}" 2 2 g)
  string(SUBSTRING "${hex}" 4 2 r)
  math(EXPR r "0x${r}")
  math(EXPR g "0x${g}")
  math(EXPR b "0x${b}")
  set(${out} "${r} ${g} ${b}" PARENT_SCOPE)
endfunction()

# Circles in drawing order: "X;Y;R" each.
string(REPLACE "\n" ";" lines "${printed}")
set(circles)
set(kinds)
foreach(line IN LISTS lines)
  if(line MATCHES "^(body|attractor) (-?[0-9]+) (-?[0-9]+) ([0-9]+)$")
    list(APPEND circles "${CMAKE_MATCH_2}:${CMAKE_MATCH_3}:${CMAKE_MATCH_4}")
    list(APPEND kinds "${CMAKE_MATCH_1}")
  endif()
endforeach()
list(LENGTH circles count)
if(count LESS 2)
  message(FATAL_ERROR "the example printed no bodies:\n${printed}")
endif()

# Body centres on the canvas and not covered by a later circle (with 3 px
# to spare for rounding and outlines).
math(EXPR last "${count} - 1")
set(centres_checked 0)
foreach(i RANGE 0 ${last})
  list(GET kinds ${i} kind)
  list(GET circles ${i} circle)
  string(REPLACE ":" ";" circle "${circle}")
  list(GET circle 0 x)
  list(GET circle 1 y)
  list(GET circle 2 r)
  if(NOT kind STREQUAL "body" OR x LESS 0 OR y LESS 0 OR x GREATER 639 OR y GREATER 239
     OR r LESS 4)
    continue()
  endif()
  set(covered OFF)
  math(EXPR next "${i} + 1")
  if(next LESS_EQUAL last)
    foreach(j RANGE ${next} ${last})
      list(GET circles ${j} other)
      string(REPLACE ":" ";" other "${other}")
      list(GET other 0 ox)
      list(GET other 1 oy)
      list(GET other 2 orr)
      math(EXPR d2 "(${x} - ${ox}) * (${x} - ${ox}) + (${y} - ${oy}) * (${y} - ${oy})")
      math(EXPR reach "(${orr} + 3) * (${orr} + 3)")
      if(d2 LESS_EQUAL reach)
        set(covered ON)
      endif()
    endforeach()
  endif()
  if(covered)
    continue()
  endif()
  pixel(${x} ${y} rgb)
  if(NOT rgb STREQUAL "127 127 127")
    message(FATAL_ERROR "body at (${x}, ${y}) radius ${r}: its centre is ${rgb}, not 127 127 127")
  endif()
  math(EXPR centres_checked "${centres_checked} + 1")
endforeach()
if(centres_checked EQUAL 0)
  message(FATAL_ERROR "no body centre could be checked (all covered or off the canvas)")
endif()

# The background, away from every circle.
set(background_checked 0)
foreach(y RANGE 10 230 20)
  foreach(x RANGE 10 630 20)
    set(near OFF)
    foreach(circle IN LISTS circles)
      string(REPLACE ":" ";" circle "${circle}")
      list(GET circle 0 cx)
      list(GET circle 1 cy)
      list(GET circle 2 r)
      math(EXPR d2 "(${x} - ${cx}) * (${x} - ${cx}) + (${y} - ${cy}) * (${y} - ${cy})")
      math(EXPR reach "(${r} + 4) * (${r} + 4)")
      if(d2 LESS_EQUAL reach)
        set(near ON)
        break()
      endif()
    endforeach()
    if(near)
      continue()
    endif()
    pixel(${x} ${y} rgb)
    if(NOT rgb STREQUAL "255 255 255")
      message(FATAL_ERROR "background at (${x}, ${y}) is ${rgb}, not white")
    endif()
    math(EXPR background_checked "${background_checked} + 1")
  endforeach()
endforeach()
message(STATUS "${centres_checked} body centres and ${background_checked} background points match")
