#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Checks that the documents name only what exists, and that the command
lines they show work as written.

Reads README.md, docs/*.md, apps/README.md and python/README.md and checks:
- every `calder ...` command line (in sh blocks, and in inline code without
  placeholders) runs with exit 0, or with the code its comment states
  ("# exit 2"); one document's lines run in order in one scratch folder, as a
  reader following it would (a line may read what an earlier one wrote);
  `calder window` runs on SDL's dummy driver and may still be open after a
  few seconds. A line with placeholders (SCENE, FILE, N, ...) has its verb
  and each of its flags checked against `calder VERB --help` instead;
- every CMake component named (`COMPONENTS ...`, "the components are ...")
  is one calderConfig.cmake knows;
- every CMake option (`-DNAME=`, and `CALDER_*` names) is defined somewhere
  in the sources, and every `--target NAME` is a target of some CMakeLists;
- every file path named (in code spans and links) exists.

usage: docs_check.py SOURCE_DIR CALDER_EXE [--list]
Prints one line per problem, "N passed, N failed" at the end; exit 1 if any
check failed.
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile
from pathlib import Path

DOCS = ["README.md", "apps/README.md", "python/README.md"]
SOURCE_DIRS = ("include", "src", "apps", "scenes", "examples", "web", "python", "tests",
               "bench", "docs", "scripts", "cmake", ".ci")
# What a documented path may name without being in the repository: what a
# build or a run writes.
OUTPUT_PREFIXES = ("build", "~", "$", "/usr", "/tmp", "/dev", "/proc", "../shared", "shared/")
PLACEHOLDER = re.compile(r"(^|[\s=,:/])([A-Z][A-Z0-9_]*[A-Z0-9]|[A-Z])(?=$|[\s,.:/|\]])|<[^>]*>|\.\.\.|\||\*")
SECONDS_PER_COMMAND = 120


class Checks:
    def __init__(self):
        self.passed = 0
        self.failed = 0

    def ok(self):
        self.passed += 1

    def fail(self, where, message):
        self.failed += 1
        print(f"docs: {where}: {message}")


def documents(root):
    names = DOCS + sorted(str(p.relative_to(root)) for p in (root / "docs").glob("*.md"))
    return [root / n for n in names if (root / n).exists()]


def code_blocks(text):
    """Yields (line number, language, line) for each line inside a fenced block."""
    language = None
    for number, line in enumerate(text.splitlines(), 1):
        fence = re.match(r"^\s*```(\S*)", line)
        if fence:
            language = None if language is not None else fence.group(1)
            continue
        if language is not None:
            yield number, language, line


def paragraphs(text):
    """Yields (first line number, paragraph) for the prose outside fenced blocks."""
    in_block = False
    start, lines = 0, []
    for number, line in enumerate(text.splitlines() + [""], 1):
        if re.match(r"^\s*```", line):
            in_block = not in_block
        if in_block or not line.strip() or line.startswith("```"):
            if lines:
                yield start, "\n".join(lines)
            lines = []
            continue
        if not lines:
            start = number
        lines.append(line)


def inline_spans(text):
    """Yields (line number, span, exit code its paragraph states) for each inline code span."""
    for start, paragraph in paragraphs(text):
        stated = re.search(r"\bexits? (\d+)", paragraph)
        for match in re.finditer(r"`([^`]+)`", paragraph):
            number = start + paragraph.count("\n", 0, match.start())
            yield number, match.group(1), int(stated.group(1)) if stated else 0


def split_commands(line):
    """The `calder ...` commands of one shell line, with the exit code its comment states."""
    code, _, comment = line.partition(" #")
    expected = 0
    stated = re.search(r"\bexits? (\d+)", comment)
    if stated:
        expected = int(stated.group(1))
    commands = []
    for part in re.split(r"&&|;|\|\|", code):
        part = part.strip()
        if part.startswith("$ "):
            part = part[2:]
        if re.match(r"^calder(\s|$)", part):
            commands.append(part)
    return commands, expected


def has_operand(command):
    """Whether a command names something to work on besides its verb and flags."""
    words = shlex.split(command)[1:]
    if words and not words[0].startswith("-"):
        words = words[1:]  # the verb
    flags_with_values = 0
    for i, word in enumerate(words):
        if not word.startswith("-") and (i == 0 or not words[i - 1].startswith("-")):
            return True
        flags_with_values += word.startswith("-")
    return False


class Commands:
    def __init__(self, root, exe, checks):
        self.root = root
        self.exe = exe
        self.checks = checks
        self.helps = {}

    def help_of(self, verb):
        if verb not in self.helps:
            args = [self.exe, verb, "--help"] if verb else [self.exe, "--help"]
            result = subprocess.run(args, capture_output=True, text=True, timeout=60)
            self.helps[verb] = result.stdout + result.stderr if result.returncode == 0 else None
        return self.helps[verb]

    def check_template(self, where, command):
        """A command with placeholders: its verb and flags exist."""
        words = command.split()[1:]
        verb = words[0] if words and not words[0].startswith("-") and words[0] != "..." else ""
        text = self.help_of(verb)
        if text is None:
            self.checks.fail(where, f"`calder {verb}` is not a verb (in `{command}`)")
            return
        for flag in re.findall(r"(?<![\w-])--[a-z][a-z0-9-]*", command):
            if not re.search(re.escape(flag) + r"(?![a-z0-9-])", text):
                self.checks.fail(where, f"`calder {verb} --help` has no {flag} (in `{command}`)")
                return
        self.checks.ok()

    def run(self, where, command, expected, folder):
        args = shlex.split(command)
        args[0] = self.exe
        env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
        is_window = len(args) > 1 and args[1] == "window"
        try:
            result = subprocess.run(args, cwd=folder, env=env, capture_output=True, text=True,
                                    timeout=5 if is_window else SECONDS_PER_COMMAND)
        except subprocess.TimeoutExpired:
            if is_window:
                self.checks.ok()  # open and running, as it is meant to be
            else:
                self.checks.fail(where, f"`{command}` ran past {SECONDS_PER_COMMAND} s")
            return
        if result.returncode == expected:
            self.checks.ok()
        else:
            last = (result.stderr.strip().splitlines() or [""])[-1]
            self.checks.fail(where, f"`{command}` exited {result.returncode}, not {expected}: {last}")

    def check_document(self, path):
        text = path.read_text()
        name = path.relative_to(self.root)
        with tempfile.TemporaryDirectory(prefix="calder-docs-") as scratch:
            folder = Path(scratch)
            # The reader's working copy: the repository's files, their own outputs beside them.
            for entry in self.root.iterdir():
                if not entry.name.startswith(".") and not entry.name.startswith("build"):
                    (folder / entry.name).symlink_to(entry)
            for number, language, line in code_blocks(text):
                if language not in ("sh", "bash", "shell", "console", ""):
                    continue
                commands, expected = split_commands(line)
                for command in commands:
                    self.one(f"{name}:{number}", command, expected, folder)
            for number, span, stated in inline_spans(text):
                commands, expected = split_commands(span)
                expected = expected or stated
                for command in commands:
                    # Prose names a verb or a flag (`calder run --state`); a
                    # span with a scene or file in it is a command line.
                    if has_operand(command):
                        self.one(f"{name}:{number}", command, expected, folder)
                    else:
                        self.check_template(f"{name}:{number}", command)

    def one(self, where, command, expected, folder):
        if PLACEHOLDER.search(command[len("calder"):]):
            self.check_template(where, command)
        else:
            self.run(where, command, expected, folder)


def cmake_sources(root):
    files = [root / "CMakeLists.txt", *sorted((root / "cmake").glob("*"))]
    for folder in SOURCE_DIRS:
        files += sorted((root / folder).rglob("CMakeLists.txt"))
    return "\n".join(p.read_text() for p in files if p.is_file())


def known_components(root):
    config = (root / "cmake" / "calderConfig.cmake.in").read_text()
    listed = re.search(r"set\(_calder_known_components([^)]*)\)", config)
    if listed:
        return set(listed.group(1).split())
    return set(re.findall(r"calder_(\w+)Targets\.cmake", config)) | set(
        re.findall(r'"(\w+)"', config))


def check_cmake_names(root, docs, checks):
    cmake = cmake_sources(root)
    targets = set(re.findall(
        r"(?:add_executable|add_library|add_custom_target|pybind11_add_module)\(\s*([\w.-]+)", cmake))
    options = set(re.findall(r"option\(\s*(\w+)", cmake)) | set(
        re.findall(r"set\(\s*(\w+)\s[^)]*CACHE", cmake))
    code = "\n".join(p.read_text(errors="replace") for d in SOURCE_DIRS + ("",)
                     for p in ((root / d).rglob("*") if d else root.glob("*"))
                     if p.is_file() and p.suffix not in (".md", ".png", ".gif") and p.stat().st_size < 2_000_000)
    components = known_components(root)
    for path in docs:
        name = path.relative_to(root)
        text = path.read_text()
        for start, paragraph in paragraphs(text):
            sentence = re.search(r"components (?:are|is)\s+((?:`[a-z_]+`[,\s]*(?:and|or)?\s*)+)",
                                 paragraph)
            for component in re.findall(r"`([a-z_]+)`", sentence.group(1)) if sentence else []:
                where = f"{name}:{start + paragraph.count(chr(10), 0, sentence.start())}"
                (checks.ok() if component in components else
                 checks.fail(where, f"`{component}` is not a component of find_package(calder) "
                                    f"(they are {', '.join(sorted(components))})"))
        for number, line in enumerate(text.splitlines(), 1):
            where = f"{name}:{number}"
            for listed in re.findall(r"COMPONENTS((?:\s+[a-z_]+)+)", line):
                for component in listed.split():
                    (checks.ok() if component in components else
                     checks.fail(where, f"`{component}` is not a component of find_package(calder) "
                                        f"(they are {', '.join(sorted(components))})"))
            for option in re.findall(r"-D([A-Z][A-Z0-9_]+)=", line.replace("-DNAME=", "")):
                (checks.ok() if option in options or option.startswith("CMAKE_") else
                 checks.fail(where, f"-D{option} is not a CMake option of calder"))
            for option in set(re.findall(r"\bCALDER_[A-Z0-9_]+\b", line)) - {"CALDER_WITH_FOO"}:
                (checks.ok() if re.search(r"\b" + option + r"\b", code) else
                 checks.fail(where, f"{option} is named nowhere in the sources"))
            for target in re.findall(r"--target\s+([\w.-]+)", line):
                (checks.ok() if target in targets else
                 checks.fail(where, f"--target {target} is not a target of any CMakeLists.txt"))


def candidate_paths(line):
    for span in re.findall(r"`([^`]+)`", line):
        for word in span.split():
            yield word
    for link in re.findall(r"\]\(([^)#\s]+)", line):
        if not re.match(r"^[a-z]+:", link):
            yield link


def check_paths(root, docs, checks):
    cmake = cmake_sources(root)
    basenames = set()
    for folder, subfolders, names in os.walk(root):
        subfolders[:] = [d for d in subfolders
                         if not d.startswith((".", "build")) and d != "node_modules"]
        basenames.update(names)
    for path in docs:
        name = path.relative_to(root)
        for number, line in enumerate(path.read_text().splitlines(), 1):
            for word in candidate_paths(line):
                word = word.strip("'\",;:()").rstrip(".")
                if (PLACEHOLDER.search(word) or word.startswith(OUTPUT_PREFIXES) or "=" in word
                        or re.search(r"\bfoo\b", word)):  # the recipes' stand-in name
                    continue
                head = word.split("/")[0]
                is_path = "/" in word and (head in SOURCE_DIRS or (root / head).is_file())
                is_source = "/" not in word and re.search(r"\.(hpp|cpp|py|pyi|mjs|cmake)$", word)
                if not (is_path or is_source or word.endswith(".md") and "/" in word):
                    continue
                where = f"{name}:{number}"
                if is_source:
                    # calderConfig.cmake from its .in, calderTargets.cmake from install(EXPORT)
                    generated = word + ".in" in basenames or word.endswith(".cmake") and re.search(
                        r"\b" + re.escape(word[: -len(".cmake")]) + r"\b", cmake)
                    (checks.ok() if word in basenames or generated else
                     checks.fail(where, f"no file is named {word}"))
                    continue
                target = (path.parent / word) if (path.parent / word).exists() else root / word
                (checks.ok() if target.exists() else checks.fail(where, f"{word} does not exist"))


def main():
    if len(sys.argv) < 3:
        print(__doc__.strip().splitlines()[-4], file=sys.stderr)
        return 2
    root = Path(sys.argv[1]).resolve()
    exe = str(Path(sys.argv[2]).resolve())
    checks = Checks()
    docs = documents(root)
    check_cmake_names(root, docs, checks)
    check_paths(root, docs, checks)
    commands = Commands(root, exe, checks)
    for path in docs:
        commands.check_document(path)
    print(f"{checks.passed} passed, {checks.failed} failed")
    return 1 if checks.failed else 0


if __name__ == "__main__":
    sys.exit(main())
