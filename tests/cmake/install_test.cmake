# SPDX-License-Identifier: MIT
# Install tests: get an installed calder into a scratch prefix, then configure,
# build and run tests/consumer against it with find_package(calder CONFIG).
#
#   cmake -DCONSUMER_SOURCE_DIR=<tests/consumer> -DWORK_DIR=<dir> -DCXX_COMPILER=<c++>
#         -DGENERATOR=<gen> [-DMAKE_PROGRAM=<ninja>] [-DCONFIG=<Release>]
#         <where calder comes from> [what to check] -P install_test.cmake
#
# Where calder comes from (one of):
#   -DCALDER_BUILD_DIR=<build>        cmake --install that build tree
#   -DCALDER_SOURCE_DIR=<src> -DCALDER_ARGS=<a|b>
#                                     configure (with CALDER_ARGS), build and install
#                                     a calder of its own in WORK_DIR/calder-build
#   -DCALDER_BUILD_DIR=<build> -DPACKAGE=DEB
#                                     cpack -G DEB in that build, then dpkg -x the
#                                     .deb into WORK_DIR/root (prefix root/usr)
# What to check:
#   -DCOMPONENTS=<a|b>       find_package(... COMPONENTS a b), a program per component
#   -DCONSUMER_ARGS=<a|b>    more arguments for the consumer's configure (e.g.
#                            -DCMAKE_DISABLE_FIND_PACKAGE_tomlplusplus=ON)
#   -DCONSUMER_ENV=<a|b>     environment for the consumer's configure (e.g. PKG_CONFIG_LIBDIR=)
#   -DEXPECT_CONFIGURE_ERROR=<a|b>
#                            the consumer's configure must fail and say a and b
#   -DCXX_FLAGS=<flags>      the consumer's CMAKE_CXX_FLAGS
#   -DBOOK_EXAMPLE=<.cpp> -DREFERENCE=<trajectory.csv> -DTRAJECTORY_DIFF=<exe>
#                            build the example in the consumer, its output must
#                            equal the p5.js reference bit for bit
#   -DPKG_CONFIG=<pkg-config> -DPC_MODULES=<a|b>
#                            also compile tests/consumer/<first component or main>.cpp
#                            with `pkg-config --cflags --libs` of those modules
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS CONSUMER_SOURCE_DIR WORK_DIR CXX_COMPILER GENERATOR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "install_test.cmake: -D${var}=... is required")
  endif()
endforeach()

# List arguments come with '|' between their items (a ';' would not survive
# ctest and add_test).
foreach(var IN ITEMS COMPONENTS CONSUMER_ARGS CONSUMER_ENV CALDER_ARGS PC_MODULES)
  string(REPLACE "|" ";" ${var} "${${var}}")
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")
# Start from nothing, so that a stale install cannot hide a broken one.
file(REMOVE_RECURSE "${prefix}" "${consumer_build}" "${WORK_DIR}/root")

# Runs one step; on failure prints what ran and its output, then stops.
function(run_step description)
  execute_process(
    COMMAND ${ARGN}
    RESULT_VARIABLE result
    OUTPUT_VARIABLE output
    ERROR_VARIABLE output)
  if(NOT result STREQUAL "0")
    string(REPLACE ";" " " command_line "${ARGN}")
    message(FATAL_ERROR "install test: ${description} failed (exit ${result})\n"
                        "command: ${command_line}\n${output}")
  endif()
  message(STATUS "install test: ${description}: ok")
  set(step_output "${output}" PARENT_SCOPE)
endfunction()

set(config_args)
if(DEFINED CONFIG AND NOT CONFIG STREQUAL "")
  set(config_args --config "${CONFIG}")
endif()
set(toolchain_args "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" -G "${GENERATOR}")
if(DEFINED MAKE_PROGRAM AND NOT MAKE_PROGRAM STREQUAL "")
  list(APPEND toolchain_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
if(DEFINED CONFIG AND NOT CONFIG STREQUAL "")
  list(APPEND toolchain_args "-DCMAKE_BUILD_TYPE=${CONFIG}")
endif()

# (a) an installed calder in ${prefix}
if(DEFINED PACKAGE AND PACKAGE STREQUAL "DEB")
  get_filename_component(cmake_bin "${CMAKE_COMMAND}" DIRECTORY)
  set(package_dir "${WORK_DIR}/package")
  file(REMOVE_RECURSE "${package_dir}")
  run_step("cpack -G DEB" "${cmake_bin}/cpack" -G DEB -B "${package_dir}" --config
           "${CALDER_BUILD_DIR}/CPackConfig.cmake")
  file(GLOB debs "${package_dir}/*.deb")
  list(LENGTH debs deb_count)
  if(NOT deb_count EQUAL 1)
    message(FATAL_ERROR "install test: expected one .deb in ${package_dir}, found: ${debs}")
  endif()
  run_step("dpkg-deb --info" dpkg-deb --info ${debs})
  message(STATUS "${step_output}")
  run_step("dpkg -x into ${WORK_DIR}/root" dpkg -x ${debs} "${WORK_DIR}/root")
  set(prefix "${WORK_DIR}/root/usr")
elseif(DEFINED CALDER_BUILD_DIR)
  run_step("cmake --install ${CALDER_BUILD_DIR} --prefix ${prefix}"
           "${CMAKE_COMMAND}" --install "${CALDER_BUILD_DIR}" --prefix "${prefix}" ${config_args})
elseif(DEFINED CALDER_SOURCE_DIR)
  set(calder_build "${WORK_DIR}/calder-build")
  file(REMOVE_RECURSE "${calder_build}")
  run_step("configure calder (${CALDER_ARGS})" "${CMAKE_COMMAND}" -S "${CALDER_SOURCE_DIR}" -B
           "${calder_build}" ${toolchain_args} "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}" ${CALDER_ARGS})
  run_step("build calder" "${CMAKE_COMMAND}" --build "${calder_build}" ${config_args})
  run_step("install calder" "${CMAKE_COMMAND}" --install "${calder_build}" --prefix "${prefix}"
           ${config_args})
else()
  message(FATAL_ERROR "install_test.cmake: -DCALDER_BUILD_DIR or -DCALDER_SOURCE_DIR is required")
endif()
if(NOT EXISTS "${prefix}/include/calder/calder.hpp")
  message(FATAL_ERROR "install test: ${prefix}/include/calder/calder.hpp was not installed")
endif()

# (b) configure the consumer against the prefix, with the same toolchain
list(JOIN COMPONENTS "," components_text)
set(configure_args
    -S "${CONSUMER_SOURCE_DIR}"
    -B "${consumer_build}"
    ${toolchain_args}
    "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    "-DCALDER_CONSUMER_COMPONENTS=${components_text}"
    # Only the installed package may satisfy find_package, not a user or
    # system package registry entry.
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
    ${CONSUMER_ARGS})
if(DEFINED BOOK_EXAMPLE)
  list(APPEND configure_args "-DCALDER_CONSUMER_BOOK_EXAMPLE=${BOOK_EXAMPLE}")
endif()
if(DEFINED EXPECT_CONFIGURE_ERROR)
  # The consumer's configure must fail, saying each of EXPECT_CONFIGURE_ERROR.
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -E env ${CONSUMER_ENV} "${CMAKE_COMMAND}" ${configure_args}
    RESULT_VARIABLE result
    OUTPUT_VARIABLE output
    ERROR_VARIABLE output)
  if(result STREQUAL "0")
    message(FATAL_ERROR "install test: the consumer's configure succeeded; expected it to fail")
  endif()
  string(REPLACE "|" ";" expected "${EXPECT_CONFIGURE_ERROR}")
  foreach(text IN LISTS expected)
    string(FIND "${output}" "${text}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "install test: expected the configure error to say '${text}':\n${output}")
    endif()
  endforeach()
  message(STATUS "install test: the consumer's configure failed as expected")
  return()
endif()
run_step("configure tests/consumer (components: ${COMPONENTS})" "${CMAKE_COMMAND}" -E env
         ${CONSUMER_ENV} "${CMAKE_COMMAND}" ${configure_args})

# (c) build it
run_step("build tests/consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_args})

# (d) run each program (single-config generators put them in the build folder,
#     multi-config ones in a per-configuration subfolder)
function(consumer_program name result_var)
  set(exe "${consumer_build}/${name}${CMAKE_EXECUTABLE_SUFFIX}")
  if(NOT EXISTS "${exe}" AND DEFINED CONFIG)
    set(exe "${consumer_build}/${CONFIG}/${name}${CMAKE_EXECUTABLE_SUFFIX}")
  endif()
  if(NOT EXISTS "${exe}")
    message(FATAL_ERROR "install test: the consumer was built but ${exe} is missing")
  endif()
  set(${result_var} "${exe}" PARENT_SCOPE)
endfunction()
set(programs calder_consumer)
foreach(component IN LISTS COMPONENTS)
  list(APPEND programs consumer_${component})
endforeach()
foreach(program IN LISTS programs)
  consumer_program(${program} exe)
  if(program STREQUAL "consumer_sketch")
    # The README's first sketch, headless: its GIF must be written.
    set(gif "${WORK_DIR}/first-sketch.gif")
    file(REMOVE "${gif}")
    run_step("run ${program} headless" "${exe}" --gif "${gif}" --frames 120 --quiet)
    if(NOT EXISTS "${gif}")
      message(FATAL_ERROR "install test: ${program} --gif wrote no ${gif}")
    endif()
    file(SIZE "${gif}" gif_size)
    message(STATUS "install test: the first sketch wrote ${gif} (${gif_size} bytes)")
  else()
    run_step("run ${program}" "${exe}")
  endif()
endforeach()

# (e) the book's example, compiled with the consumer's flags, against p5.js
if(DEFINED BOOK_EXAMPLE)
  consumer_program(book_example exe)
  set(output "${WORK_DIR}/book_example.csv")
  # The example is a sketch: headless, the reference run's mouse, the CSV on stdout.
  execute_process(COMMAND "${exe}" --mouse-pressed 100-160 --trajectory - --quiet
                  OUTPUT_FILE "${output}" RESULT_VARIABLE result)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "install test: book_example failed (${result})")
  endif()
  run_step("book_example (CXX_FLAGS '${CXX_FLAGS}') against ${REFERENCE}, bit for bit"
           "${TRAJECTORY_DIFF}" "${REFERENCE}" "${output}" --tolerance 0)
  message(STATUS "${step_output}")
endif()

# (f) pkg-config: the same program, compiled by hand with the .pc files' flags
if(PKG_CONFIG AND PC_MODULES)
  set(source "${CONSUMER_SOURCE_DIR}/main.cpp")
  if(COMPONENTS)
    list(GET COMPONENTS 0 first)
    set(source "${CONSUMER_SOURCE_DIR}/${first}.cpp")
  endif()
  file(GLOB_RECURSE pc_files "${prefix}/*/calder.pc")
  list(GET pc_files 0 pc_file)
  get_filename_component(pc_dir "${pc_file}" DIRECTORY)
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -E env "PKG_CONFIG_PATH=${pc_dir}" "${PKG_CONFIG}" --cflags --libs
            ${PC_MODULES}
    RESULT_VARIABLE result
    OUTPUT_VARIABLE pc_flags
    ERROR_VARIABLE pc_error
    OUTPUT_STRIP_TRAILING_WHITESPACE)
  if(NOT result STREQUAL "0")
    message(FATAL_ERROR "install test: pkg-config --cflags --libs ${PC_MODULES}: ${pc_error}")
  endif()
  separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
  set(pc_exe "${WORK_DIR}/pkg_config_consumer")
  separate_arguments(cxx_flags_list UNIX_COMMAND "${CXX_FLAGS}")
  run_step("compile ${source} with pkg-config ${PC_MODULES} (${pc_flags})" "${CXX_COMPILER}"
           -std=c++20 ${cxx_flags_list} "${source}" -o "${pc_exe}" ${pc_flags})
  get_filename_component(lib_dir "${pc_dir}" DIRECTORY)
  run_step("run the pkg-config consumer" "${CMAKE_COMMAND}" -E env "LD_LIBRARY_PATH=${lib_dir}"
           "${pc_exe}")
endif()
