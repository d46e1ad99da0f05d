#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every place in calder's code that opens a file for writing is in the
output module (src/output/): a writer anywhere else goes around the output
policy (src/output/output.hpp).

    writers_check.py REPO_ROOT        lists what it finds; exit 1 on one outside

It looks for what opens, creates or replaces a path: fopen, std::ofstream
and std::fstream, open/openat/creat with O_WRONLY, O_RDWR or O_CREAT, the
mkstemp and mkdtemp family, rename and renameat, cairo_surface_write_to_png
(the path form), giflib's EGifOpenFileName, and Python's open() for writing.
Comments and C++ string literals are skipped, so that prose about them is
not counted. With --self-test it checks that it finds each kind.
"""

import re
import sys
from pathlib import Path

# The product's code: the libraries, the command, the Python module, the
# page's bindings, the benchmarks.
ROOTS = ("src", "include", "apps", "python/src", "python/calder", "web", "bench")
SUFFIXES = {".cpp", ".hpp", ".h", ".cc", ".py"}
MODULE = "src/output/"
# A sink that is no file: the benchmark of CSV rows writes to /dev/null.
ALLOWED = {("bench/bench_run.cpp", 'std::ofstream null_out("/dev/null", std::ios::binary);')}

CPP_PATTERNS = [
    r"\bfopen\s*\(",
    r"\bfreopen\s*\(",
    r"(?<![iw])\bofstream\b",
    r"(?<![io])\bfstream\b",
    r"\b(?:open|openat|open64)\s*\([^;]*\bO_(?:WRONLY|RDWR|CREAT)\b",
    r"\bcreat\s*\(",
    r"\bmk(?:o?s?temps?|dtemp)\s*\(",
    r"\brename(?:at2?)?\s*\(",
    r"\bcairo_surface_write_to_png\s*\(",
    r"\bEGifOpenFileName\s*\(",
]
PY_PATTERNS = [
    r"\bopen\s*\([^)]*,\s*(?:mode\s*=\s*)?['\"][^'\"]*[wax+][^'\"]*['\"]",
    r"\.write_(?:bytes|text)\s*\(",
    r"\bos\.(?:rename|replace)\s*\(",
]


def strip_cpp(line: str, in_comment: bool):
    """The code of a C++ line without comments and string literals."""
    out, i = [], 0
    while i < len(line):
        if in_comment:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_comment = end + 2, False
        elif line.startswith("//", i):
            break
        elif line.startswith("/*", i):
            in_comment, i = True, i + 2
        elif line[i] == '"':
            j = i + 1
            while j < len(line) and line[j] != '"':
                j += 2 if line[j] == "\\" else 1
            out.append('""')
            i = j + 1
        else:
            out.append(line[i])
            i += 1
    return "".join(out), in_comment


def strip_py(line: str, in_doc: bool):
    """The code of a Python line without comments and docstrings."""
    stripped = line.strip()
    if in_doc:
        return "", '"""' not in stripped
    if stripped.startswith('"""'):
        return "", not (stripped.count('"""') >= 2 and len(stripped) > 3)
    return line.split("#", 1)[0], False


def writers(path: Path, text: str):
    """(line number, line) of each place in `text` that opens a file for writing."""
    python = path.suffix == ".py"
    patterns = [re.compile(p) for p in (PY_PATTERNS if python else CPP_PATTERNS)]
    found, state = [], False
    for number, line in enumerate(text.splitlines(), 1):
        code, state = (strip_py if python else strip_cpp)(line, state)
        if not python and code.lstrip().startswith("#"):
            continue  # a preprocessor line (#include <fstream>)
        if any(p.search(code) for p in patterns):
            found.append((number, line.strip()))
    return found


def self_test() -> int:
    cpp = Path("x.cpp")
    cases = [
        'FILE* f = fopen("a", "w");', 'std::ofstream out(path);', "int fd = ::open(p, O_WRONLY);",
        "fd = openat(d, n, O_RDWR | O_CREAT, 0644);", "mkstemp(buf);", "::mkdtemp(t);",
        "std::rename(a, b);", "cairo_surface_write_to_png(s, path);", "EGifOpenFileName(p, 0, &e);",
    ]
    quiet = ['std::ifstream in(path);', '// std::ofstream in a comment', 'x = "fopen(";',
             "open(p, O_RDONLY);", "EGifOpenFileHandle(fd, &e);"]
    bad = [c for c in cases if not writers(cpp, c)] + [q for q in quiet if writers(cpp, q)]
    py = Path("x.py")
    if not writers(py, 'with open(p, "w") as f:') or writers(py, 'with open(p, "rb") as f:'):
        bad.append("python open")
    for b in bad:
        print(f"writers_check self-test: wrong about: {b}")
    return 1 if bad else 0


def main() -> int:
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = Path(sys.argv[1]).resolve()
    outside = 0
    for base in ROOTS:
        for path in sorted((root / base).rglob("*")):
            if path.suffix not in SUFFIXES or not path.is_file():
                continue
            rel = path.relative_to(root).as_posix()
            for number, line in writers(path, path.read_text(encoding="utf-8", errors="replace")):
                inside = rel.startswith(MODULE)
                allowed = (rel, line) in ALLOWED
                print(f"{'ok     ' if inside or allowed else 'OUTSIDE'} {rel}:{number}: {line}")
                outside += 0 if inside or allowed else 1
    if outside:
        print(f"writers_check: {outside} place(s) open files for writing outside {MODULE}: "
              "write through src/output/output.hpp")
    return 1 if outside else 0


if __name__ == "__main__":
    sys.exit(main())
