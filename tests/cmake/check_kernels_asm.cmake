# SPDX-License-Identifier: MIT
# lint.bulk_kernels_asm: reads the machine code of calder::bulk's kernel
# objects (objdump) and checks what the source promises:
#   - the book kernels contain no contracted multiply-add (they must round
#     every operation as the plain loops do, or p5.js sketches drift): their
#     only fused instructions are quotient_by_mass's corrections, written
#     with intrinsics (src/bulk/kernels_impl.hpp), a vfmsub then a vfnmadd
#     each, so as many of one as of the other and no vfmadd or vfnmsub, which
#     a compiler contracting a * b + c would emit;
#   - on a target with AVX2 + FMA or AVX-512, the kernels are vectorised:
#     packed square roots and divisions on ymm/zmm registers, and the fast
#     kernels use packed fused multiply-adds.
# Arguments: -DOBJDUMP=... -DBOOK=<objects;...> -DFAST=<objects;...> -DWIDE=ON|OFF
foreach(var OBJDUMP BOOK FAST WIDE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "check_kernels_asm: ${var} not set")
  endif()
endforeach()

function(disassemble out objects)
  set(text "")
  foreach(object IN LISTS objects)
    execute_process(COMMAND ${OBJDUMP} -d --no-show-raw-insn ${object} OUTPUT_VARIABLE part
                    RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "check_kernels_asm: objdump failed on ${object}")
    endif()
    string(APPEND text "${part}")
  endforeach()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

disassemble(book "${BOOK}")
disassemble(fast "${FAST}")

if(book MATCHES "(vfmadd|vfnmsub|vfmaddsub|vfmsubadd)[0-9]*[ps][sd]")
  message(FATAL_ERROR "check_kernels_asm: the book kernels contain a fused multiply-add "
                      "(${CMAKE_MATCH_0}); they must be compiled with -ffp-contract=off")
endif()
string(REGEX MATCHALL "vfmsub[0-9]*[ps][sd]" book_fmsub "${book}")
string(REGEX MATCHALL "vfnmadd[0-9]*[ps][sd]" book_fnmadd "${book}")
list(LENGTH book_fmsub fmsub_count)
list(LENGTH book_fnmadd fnmadd_count)
if(NOT fmsub_count EQUAL fnmadd_count)
  message(FATAL_ERROR "check_kernels_asm: the book kernels have ${fmsub_count} vfmsub and "
                      "${fnmadd_count} vfnmadd: fused instructions other than quotient_by_mass's "
                      "pairs; they must be compiled with -ffp-contract=off")
endif()
if(WIDE)
  foreach(pattern "vsqrtpd[ \t]+%[yz]mm" "vdivpd[ \t]+%[yz]mm")
    if(NOT book MATCHES "${pattern}")
      message(FATAL_ERROR "check_kernels_asm: the book kernels have no '${pattern}': not vectorised")
    endif()
  endforeach()
  foreach(pattern "vsqrtpd[ \t]+%[yz]mm" "vsqrtps[ \t]+%[yz]mm" "vfmadd[0-9]+pd[ \t]+%[yz]mm"
                  "vfmadd[0-9]+ps[ \t]+%[yz]mm")
    if(NOT fast MATCHES "${pattern}")
      message(FATAL_ERROR "check_kernels_asm: the fast kernels have no '${pattern}'")
    endif()
  endforeach()
endif()
message(STATUS "check_kernels_asm: book kernels without FMA; vectorisation checked: ${WIDE}")
