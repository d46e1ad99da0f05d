#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""docs/PERFORMANCE.md's tables from calder-bench's Markdown output(s), one
set of sections (scripts/performance calls it).

    performance_page.py NATIVE.md [--avx2 AVX2.md] [--scaling SCALING.md]

NATIVE.md's sections in order; in each, AVX2.md's rows of the table of the
same section and place at its largest thread count are appended to the
native table, "(AVX2)" in their first cell (the peers' rows, which no kernel
choice changes, are left out, and the scaling rows; AVX2.md itself holds
every row), with the floors' notes; SCALING.md's tables (a larger machine's scaling
section, at 1, 4, 16, ... threads) go under the scaling section, its
machine in the machine section.
Writes the Markdown to standard output."""
import argparse
import re
import sys

PEERS = re.compile(r"^\| (learner|Box2D|floor: plain)")


def sections(text):
    """[(title, [lines])] of the '## ' sections; title None for what comes first."""
    out = [(None, [])]
    for line in text.splitlines():
        m = re.match(r"^#{2,3} (.*)$", line)
        if m:
            out.append((m.group(1), []))
        else:
            out[-1][1].append(line)
    return out


def blocks(lines):
    """A section's tables (lists of rows) and other lines, in order."""
    out = []
    for line in lines:
        kind = "table" if line.startswith("|") else "text"
        if out and out[-1][0] == kind and (kind == "table" or line.strip()):
            out[-1][1].append(line)
        elif line.strip() or kind == "table":
            out.append((kind, [line]))
    return out


def marked(row, label):
    cells = row.split("|")
    cells[1] = f" {cells[1].strip()} ({label}) "
    return "|".join(cells)


def label_of(note):
    return note[2:].split(":", 1)[0]


def at_most_threads(rows):
    """A table's data rows at its largest thread count (all, without a threads column)."""
    header = [c.strip() for c in rows[0].strip("|").split("|")]
    data = rows[2:]
    if "threads" not in header:
        return data
    k = header.index("threads")
    threads = lambda r: r.strip("|").split("|")[k].strip()
    counts = [int(threads(r)) for r in data if threads(r).isdigit()]
    return [r for r in data if counts and threads(r) == str(max(counts))]


def every_fourfold(rows):
    """A table with its rows at 1, 4, 16, ... threads and the largest count."""
    header = [c.strip() for c in rows[0].strip("|").split("|")]
    if "threads" not in header:
        return rows
    k = header.index("threads")
    threads = lambda r: r.strip("|").split("|")[k].strip()
    counts = [int(threads(r)) for r in rows[2:] if threads(r).isdigit()]
    keep = {str(t) for t in counts if (t & (t - 1)) == 0 and (t.bit_length() - 1) % 2 == 0}
    keep.add(str(max(counts)))
    return rows[:2] + [r for r in rows[2:] if threads(r) in keep]


def merge(native, other, label, rows_of=at_most_threads):
    """native's blocks with other's rows appended to the table in the same
    place (rows_of picks them; the peers' left out, labelled), and its
    floors' notes (their figures are the kernels' own)."""
    theirs = [ls for kind, ls in blocks(other) if kind == "table"]
    labels = {label_of(l) for kind, ls in blocks(native) if kind == "text" for l in ls
              if l.startswith("- ")}
    out, t = [], 0
    for kind, ls in blocks(native):
        if kind == "table":
            rows = list(ls)
            if t < len(theirs):
                rows += [marked(r, label) for r in rows_of(theirs[t]) if not PEERS.match(r)]
            t += 1
            out += rows + [""]
        else:
            out += ls + [""]
    out += [f"- {label}: {l[2:]}" for kind, ls in blocks(other) if kind == "text" for l in ls
            if l.startswith("- ") and label_of(l) in ("floor", "ceiling")]
    return out + [""]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("native")
    parser.add_argument("--avx2")
    parser.add_argument("--scaling")
    args = parser.parse_args()
    native = sections(open(args.native).read())
    avx2 = dict(sections(open(args.avx2).read())) if args.avx2 else {}
    scaling = dict(sections(open(args.scaling).read())) if args.scaling else {}
    cpu = next((l[len("- CPU: "):] for l in scaling.get("Machine", []) if l.startswith("- CPU: ")), "")
    kernels = next((l[len("- kernels: "):] for l in avx2.get("Machine", [])
                    if l.startswith("- kernels: ")), "avx2")
    out = []
    for title, lines in native:
        if title is None:
            continue
        out += [f"## {title}", ""]
        if title == "Machine":
            out += [l for l in lines if l.strip()]
            if args.avx2:
                out.append(f"- AVX2 rows: the same machine and run settings, a CALDER_PORTABLE=ON "
                           f"build with kernels {kernels}")
            if cpu:
                out.append(f"- larger machine (its scaling rows): {cpu}; "
                           + "; ".join(l[2:] for l in scaling["Machine"]
                                       if l.startswith(("- threads:", "- date:", "- others:"))))
            out.append("")
            continue
        merged = title in avx2 and not title.startswith("scaling")  # AVX2.md has those rows
        body = merge(lines, avx2[title], "AVX2") if merged else \
            [l for kind, ls in blocks(lines) for l in ls + [""]]
        if title.startswith("scaling") and title in scaling:
            body += [f"On the larger machine ({cpu}), at 1, 4 and 16 threads "
                     f"({args.scaling} holds every count):", ""]
            body += [l for kind, ls in blocks(scaling[title]) if kind == "table"
                     for l in every_fourfold(ls) + [""]]
        out += body
    text = "\n".join(out)
    sys.stdout.write(re.sub(r"\n{3,}", "\n\n", text).strip("\n") + "\n")


if __name__ == "__main__":
    main()
