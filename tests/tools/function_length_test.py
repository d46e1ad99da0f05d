#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The scanner of lint.function_length (function_length.py) on made-up sources
whose long functions are known (lint.function_length_self_test)."""
import pathlib
import sys
import tempfile
import unittest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import function_length  # noqa: E402


def body(lines):
    """A function body of exactly `lines` lines as clang-tidy counts them (the
    line breaks between its braces)."""
    return "{\n" + "  ++n;\n" * (lines - 1) + "}\n"


class FunctionLength(unittest.TestCase):
    def scan(self, source, max_lines=80):
        with tempfile.TemporaryDirectory() as folder:
            path = pathlib.Path(folder) / "sample.cpp"
            path.write_text(source)
            return [(name, lines) for _, name, lines in function_length.long_functions(path, max_lines)]

    def test_the_limit_itself_passes_one_more_fails(self):
        source = "int at_limit(int n) " + body(80) + "int over(int n) " + body(81)
        self.assertEqual(self.scan(source), [("over", 81)])

    def test_tables_of_data_are_not_functions(self):
        table = "constexpr std::array<int, 200> kTable = {\n" + "    1,\n" * 200 + "};\n"
        nested = "const std::vector<Row> kRows{\n" + "    {1, f(2)},\n" * 200 + "};\n"
        self.assertEqual(self.scan(table + nested), [])

    def test_members_namespaces_and_constructors_are_measured(self):
        source = ("namespace calder {\nnamespace {\nstruct Walker : Base {\n"
                  "  void walk(int n) const noexcept " + body(90) + "};\n}  // namespace\n"
                  "Tree::Tree(int n) : size_(n), nodes_{n, 0}, more_{} " + body(85) + "}\n")
        self.assertEqual(self.scan(source), [("walk", 90), ("Tree::Tree", 85)])

    def test_braces_in_strings_and_comments_do_not_count(self):
        source = ('int quoted(int n) {\n  const char* s = "}}}";  // }\n  /* } */ char c = \'}\';\n'
                  '  auto r = R"(})";\n' + "  ++n;\n" * 90 + "}\nint after(int n) " + body(81))
        self.assertEqual(self.scan(source), [("quoted", 94), ("after", 81)])

    def test_an_enum_is_not_a_function(self):
        source = "enum class Kind {\n" + "  k,\n" * 100 + "};\n"
        self.assertEqual(self.scan(source), [])


if __name__ == "__main__":
    unittest.main()
