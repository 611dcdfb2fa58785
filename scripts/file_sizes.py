#!/usr/bin/env python3
"""Lists the workspace's Rust source files above a line limit (issue 18: no file above 600
lines, test modules aside), and the line total of `crates/cli/src/`. A file's size is its
lines before a `#[cfg(test)]` that opens a `mod tests`; files under `tests/`, `benches/`,
`examples/` and `fuzz/` are tests or tools and not counted. Exits 1 if any file is above the
limit. Usage: scripts/file_sizes.py [LIMIT]"""
import os
import sys

limit = int(sys.argv[1]) if len(sys.argv) > 1 else 600
skipped = {"tests", "benches", "examples", "fuzz", "target"}


def code_lines(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    for index, line in enumerate(lines):
        following = lines[index + 1].strip() if index + 1 < len(lines) else ""
        if line.strip() == "#[cfg(test)]" and following.startswith("mod tests"):
            return index
    return len(lines)


over = []
cli_total = 0
for folder, directories, names in os.walk("crates"):
    directories[:] = sorted(d for d in directories if d not in skipped)
    for name in sorted(names):
        if name.endswith(".rs"):
            path = os.path.join(folder, name)
            size = code_lines(path)
            if size > limit:
                over.append((size, path))
            if path.startswith(os.path.join("crates", "cli", "src")):
                cli_total += size
for size, path in sorted(over, reverse=True):
    print(f"{size:6} {path}")
print(f"{len(over)} file(s) above {limit} lines; crates/cli/src/ {cli_total} lines in all")
sys.exit(1 if over else 0)
