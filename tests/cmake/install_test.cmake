# Install test: installs calder from a build tree into a scratch prefix, then
# configures, builds and runs tests/consumer against that prefix with
# find_package(calder CONFIG REQUIRED).
#
#   cmake -DCALDER_BUILD_DIR=<build> -DCONSUMER_SOURCE_DIR=<tests/consumer>
#         -DWORK_DIR=<build>/install-test -DCXX_COMPILER=<c++> -DGENERATOR=<gen>
#         [-DMAKE_PROGRAM=<ninja>] [-DCONFIG=<Release>] [-DCXX_FLAGS=<flags>]
#         -P install_test.cmake
cmake_minimum_required(VERSION 3.25)

foreach(var IN ITEMS CALDER_BUILD_DIR CONSUMER_SOURCE_DIR WORK_DIR CXX_COMPILER GENERATOR)
  if(NOT DEFINED ${var} OR "${${var}}" STREQUAL "")
    message(FATAL_ERROR "install_test.cmake: -D${var}=... is required")
  endif()
endforeach()

set(prefix "${WORK_DIR}/prefix")
set(consumer_build "${WORK_DIR}/build")
# Start from nothing, so that a stale install cannot hide a broken one.
file(REMOVE_RECURSE "${prefix}" "${consumer_build}")

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
endfunction()

set(config_args)
if(DEFINED CONFIG AND NOT CONFIG STREQUAL "")
  set(config_args --config "${CONFIG}")
endif()

# (a) install
run_step("cmake --install ${CALDER_BUILD_DIR} --prefix ${prefix}"
         "${CMAKE_COMMAND}" --install "${CALDER_BUILD_DIR}" --prefix "${prefix}" ${config_args})
if(NOT EXISTS "${prefix}/include/calder")
  message(FATAL_ERROR "install test: ${prefix}/include/calder was not installed")
endif()

# (b) configure the consumer against the prefix, with the same toolchain
set(configure_args
    -S "${CONSUMER_SOURCE_DIR}"
    -B "${consumer_build}"
    -G "${GENERATOR}"
    "-DCMAKE_PREFIX_PATH=${prefix}"
    "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}"
    "-DCMAKE_CXX_FLAGS=${CXX_FLAGS}"
    # Only the installed package may satisfy find_package, not a user or
    # system package registry entry.
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF
    -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(DEFINED MAKE_PROGRAM AND NOT MAKE_PROGRAM STREQUAL "")
  list(APPEND configure_args "-DCMAKE_MAKE_PROGRAM=${MAKE_PROGRAM}")
endif()
if(DEFINED CONFIG AND NOT CONFIG STREQUAL "")
  list(APPEND configure_args "-DCMAKE_BUILD_TYPE=${CONFIG}")
endif()
run_step("configure tests/consumer with find_package(calder)" "${CMAKE_COMMAND}"
         ${configure_args})

# (c) build it
run_step("build tests/consumer" "${CMAKE_COMMAND}" --build "${consumer_build}" ${config_args})

# (d) run it (single-config generators put it in the build folder,
#     multi-config ones in a per-configuration subfolder)
set(consumer_exe "${consumer_build}/calder_consumer${CMAKE_EXECUTABLE_SUFFIX}")
if(NOT EXISTS "${consumer_exe}" AND DEFINED CONFIG)
  set(consumer_exe "${consumer_build}/${CONFIG}/calder_consumer${CMAKE_EXECUTABLE_SUFFIX}")
endif()
if(NOT EXISTS "${consumer_exe}")
  message(FATAL_ERROR "install test: the consumer was built but ${consumer_exe} is missing")
endif()
run_step("run the consumer" "${consumer_exe}")
