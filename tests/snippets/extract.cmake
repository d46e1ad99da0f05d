# SPDX-License-Identifier: MIT
# Extracts the ```cpp snippets of a Markdown file into C++ sources.
#
# calder_extract_snippets(<markdown> <out_dir> <prefix> <sources_var> <runnable_var>)
#
# Every ```cpp ... ``` block of <markdown> becomes <out_dir>/<prefix>_<n>.cpp
# (n counts from 1 in the order of the file) and is listed in <sources_var>;
# those that are whole programs are also listed in <runnable_var>.
#
# The convention (docs/API.md, "Code in these pages"):
#   - a snippet that defines `int main(` is a whole program, compiled as it
#     is and run;
#   - any other snippet is a fragment, compiled (not run) as the body of a
#     function, after `#include` of every public calder header (calder.hpp,
#     render.hpp, scene_file.hpp, nbody.hpp, bulk.hpp), <iostream>,
#     <string>, and `using namespace calder;`;
#   - an HTML comment on the line just before the fence,
#     `<!-- snippet: DECLARATIONS -->`, gives the names a fragment assumes
#     (`Vec2 w{1, 2}; double t = 0;`): they are declared first in the function.
include_guard(GLOBAL)

function(calder_extract_snippets markdown out_dir prefix sources_var runnable_var)
  file(READ "${markdown}" text)
  file(MAKE_DIRECTORY "${out_dir}")
  set(sources)
  set(runnable)
  set(count 0)
  set(fence "```cpp\n")
  while(TRUE)
    string(FIND "${text}" "${fence}" start)
    if(start EQUAL -1)
      break()
    endif()
    # The line before the fence: a context comment or not.
    string(SUBSTRING "${text}" 0 ${start} before)
    set(context "")
    if(before MATCHES "<!-- snippet: ([^\n]*) -->\n$")
      set(context "${CMAKE_MATCH_1}")
    endif()
    string(LENGTH "${fence}" fence_length)
    math(EXPR body_start "${start} + ${fence_length}")
    string(SUBSTRING "${text}" ${body_start} -1 text)
    string(FIND "${text}" "```" end)
    if(end EQUAL -1)
      message(FATAL_ERROR "${markdown}: a ```cpp block is not closed")
    endif()
    string(SUBSTRING "${text}" 0 ${end} code)
    string(SUBSTRING "${text}" ${end} -1 text)
    string(SUBSTRING "${text}" 3 -1 text)

    math(EXPR count "${count} + 1")
    set(source "${out_dir}/${prefix}_${count}.cpp")
    if(code MATCHES "int main\\(")
      set(program "// Extracted from ${markdown}, snippet ${count}: a whole program.\n${code}")
      list(APPEND runnable "${prefix}_${count}")
    else()
      # Quoted pieces only: an unquoted expansion would split at the code's semicolons.
      string(
        CONCAT program
          "// Extracted from ${markdown}, snippet ${count}: a fragment.\n"
          "#include <calder/calder.hpp>\n#include <calder/bulk.hpp>\n"
          "#include <calder/nbody.hpp>\n#include <calder/render.hpp>\n"
          "#include <calder/scene_file.hpp>\n#include <iostream>\n#include <string>\n"
          "using namespace calder;\n"
          "[[maybe_unused]] static void snippet() {\n${context}\n${code}}\n"
          "int main() { return 0; }\n")
    endif()
    # Rewrite only on change, so that a reconfigure does not rebuild them all.
    set(old "")
    if(EXISTS "${source}")
      file(READ "${source}" old)
    endif()
    if(NOT old STREQUAL program)
      file(WRITE "${source}" "${program}")
    endif()
    list(APPEND sources "${source}")
  endwhile()
  set(${sources_var} "${sources}" PARENT_SCOPE)
  set(${runnable_var} "${runnable}" PARENT_SCOPE)
endfunction()
