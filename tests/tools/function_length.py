#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Lists the C++ functions longer than a limit (the lint test lint.function_length).

    function_length.py [--max-lines N] PATH...

PATH is a file or a folder (its .cpp, .hpp and .h files). A function's length
is the line breaks between its opening and its closing brace, as clang-tidy's
readability-function-size counts them (LineThreshold). Tables of
data are not functions: a brace after `=` at namespace or class scope (an
initializer, `const std::array kTable = {...}`) is skipped, as are enums,
classes and namespaces themselves (their member functions are measured). Exit
status: 0 none too long, 1 some (one line each: file:line: name: N lines), 2
bad usage.

A small scanner rather than clang-tidy itself: clang-tidy parses every header
of every file (about 20 s for one command source on a busy 2-core machine, 10+
minutes for src/ and apps/), this reads the text in well under a second.
"""
import argparse
import pathlib
import re
import sys

SOURCE_SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}


def blank_out(text):
    """The text with comments, string and character literals replaced by
    spaces (line breaks kept), so that braces in them don't count."""
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == "R" and text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            open_paren = text.find("(", i + 2)
            delimiter = text[i + 2:open_paren]
            j = text.find(")" + delimiter + '"', open_paren)
            j = n if j < 0 else j + len(delimiter) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            if c == "'" and i > 0 and text[i - 1].isalnum():  # digit separator: 1'000
                out.append(c)
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(" " * (j - i))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def matching_brace(code, start):
    depth = 0
    for i in range(start, len(code)):
        if code[i] == "{":
            depth += 1
        elif code[i] == "}":
            depth -= 1
            if depth == 0:
                return i
    return len(code) - 1


def depth0_equals(head):
    """Whether head has an `=` outside parentheses (an initializer), not one
    of an operator's name or a comparison."""
    head = re.sub(r"operator\s*(==|!=|<=|>=|<=>|=|[-+*/%^&|<>]=|<<=|>>=|\(\)|\[\])", "operator", head)
    depth = 0
    for k, c in enumerate(head):
        if c in "([<":
            depth += 1 if c != "<" else 0
        elif c in ")]":
            depth -= 1
        elif c == "=" and depth == 0:
            before = head[k - 1] if k else ""
            after = head[k + 1] if k + 1 < len(head) else ""
            if before not in "=!<>" and after != "=":
                return True
    return False


def function_name(head):
    """The name before the first parameter list of a function's head."""
    head = re.sub(r"\s+", " ", head).strip()
    match = re.search(r"(operator\s*(?:\(\)|[^\s(]+)|[~\w:]+(?:<[^()]*>)?)\s*\(", head)
    return match.group(1) if match else head[-60:]


def long_functions(path, max_lines):
    text = path.read_text(encoding="utf-8", errors="replace")
    code = blank_out(text)
    line_of = [0] * (len(code) + 1)
    line = 1
    for k, c in enumerate(code):
        line_of[k] = line
        if c == "\n":
            line += 1
    found = []
    # Scopes that hold declarations: the file, namespaces, classes.
    i, head_start = 0, 0
    stack = []  # for each open brace at declaration scope: "scope" (namespace/class)
    while i < len(code):
        c = code[i]
        if c in ";":
            head_start = i + 1
        elif c == "}":
            if stack:
                stack.pop()
            head_start = i + 1
        elif c == "{":
            head = code[head_start:i]
            end = matching_brace(code, i)
            after = code[end + 1:].lstrip()[:1]
            if re.search(r"\b(namespace|extern)\b", head) or (
                    re.search(r"\b(class|struct|union)\b", head) and "(" not in head
                    and not re.search(r"\benum\b", head)):
                stack.append("scope")
                head_start = i + 1
                i += 1
                continue
            if ")" in head and not depth0_equals(head) and not re.search(r"\benum\b", head):
                if after in (",", "{") and re.search(r"\)\s*(noexcept\s*)?:[^:]", head):
                    i = end + 1  # a member initializer `name{...}`: still the head
                    continue
                lines = line_of[end] - line_of[i]
                if lines > max_lines:
                    found.append((line_of[i], function_name(head), lines))
            # A function body, a table of data or an enum: skip it whole.
            i = end + 1
            head_start = i
            continue
        i += 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-lines", type=int, default=80)
    parser.add_argument("paths", nargs="+", type=pathlib.Path)
    args = parser.parse_args()
    files = []
    for path in args.paths:
        if path.is_dir():
            files += sorted(p for p in path.rglob("*") if p.suffix in SOURCE_SUFFIXES)
        elif path.is_file():
            files.append(path)
        else:
            print(f"function_length.py: {path}: no such file or folder", file=sys.stderr)
            return 2
    too_long = 0
    for path in files:
        for line, name, lines in long_functions(path, args.max_lines):
            print(f"{path}:{line}: {name}: {lines} lines (over {args.max_lines})")
            too_long += 1
    print(f"{too_long} function(s) over {args.max_lines} lines in {len(files)} files")
    return 1 if too_long else 0


if __name__ == "__main__":
    sys.exit(main())
