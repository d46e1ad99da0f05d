# SPDX-License-Identifier: MIT
# Compile options for calder's own targets (library, examples, tests, tools).
#
# calder_target_defaults(<target>) gives a target calder's warnings and
# -ffp-contract=off (neither is handed on to consumers) and, when
# CALDER_SANITIZE is set, the sanitizers.
include_guard(GLOBAL)

set(CALDER_WARNING_FLAGS
    -Wall
    -Wextra
    -Wpedantic
    -Wshadow
    -Wconversion
    -Wsign-conversion
    -Wold-style-cast
    -Wnon-virtual-dtor
    -Woverloaded-virtual)

function(calder_target_defaults target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "^(GNU|Clang|AppleClang)$")
    # No fused multiply-add contraction: p5.js (JavaScript) rounds after every
    # multiplication and addition, and GCC (fast) and Clang (on) contract a*b+c
    # into one fma by default wherever the target has FMA, which changes the
    # last bits and lets trajectories drift from the reference. Kernels that
    # want contraction say so after this (their options come later and win).
    target_compile_options(${target} PRIVATE ${CALDER_WARNING_FLAGS} -ffp-contract=off)
    if(CALDER_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE -Werror)
    endif()
  elseif(MSVC)
    target_compile_options(${target} PRIVATE /W4 /permissive-)
    if(CALDER_WARNINGS_AS_ERRORS)
      target_compile_options(${target} PRIVATE /WX)
    endif()
  endif()

  if(CALDER_SANITIZE)
    set(sanitize_flags -fsanitize=${CALDER_SANITIZE} -fno-omit-frame-pointer
                       -fno-sanitize-recover=all)
    target_compile_options(${target} PRIVATE ${sanitize_flags})
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "STATIC_LIBRARY" OR type STREQUAL "SHARED_LIBRARY")
      # Whoever links an instrumented library needs the sanitizer runtimes,
      # installed consumers included: PUBLIC link options.
      target_link_options(${target} PUBLIC ${sanitize_flags})
    else()
      target_link_options(${target} PRIVATE ${sanitize_flags})
    endif()
  endif()
endfunction()
