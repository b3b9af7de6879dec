#!/usr/bin/env python3
"""Prints pkm's module graph as CMake has it, as a Markdown table.

Usage: scripts/module-graph.py BUILD_DIR [--check DOC | --update DOC]

BUILD_DIR/module-graph.txt is written at configure time (cmake/PkmModuleGraph.cmake). --check
compares the table with the block of DOC between the markers below and exits 1 when they differ
(test_module_graph runs it on docs/architecture.md); a row of OPTIONAL_ROWS that the build did
not configure is not compared. --update rewrites that block.
"""

import sys
from pathlib import Path

# Rows the documented table may hold although a build did not configure them: the Python module
# is built only where pybind11 is (and not in the sanitizer build); pkm-truth only where LinuxCNC's
# HAL headers and library are.
OPTIONAL_ROWS = ("| Python module |", "| program pkm-truth |")

BEGIN = "<!-- module-graph: printed by scripts/module-graph.py from CMake; do not edit -->"
END = "<!-- /module-graph -->"


def table(build_dir: Path) -> str:
    rows = ["| target | depends on (public: its users get them too) | private |", "|---|---|---|"]
    for line in (build_dir / "module-graph.txt").read_text(encoding="utf-8").splitlines():
        name, public, private = line.split("|")
        rows.append(f"| {name} | {public or '—'} | {private or '—'} |")
    return "\n".join(rows) + "\n"


def block_of(doc: str) -> tuple[int, int]:
    start = doc.find(BEGIN)
    end = doc.find(END)
    if start < 0 or end < start:
        raise SystemExit(f"module-graph: the markers {BEGIN!r} … {END!r} are missing")
    return start + len(BEGIN) + 1, end


def main(argv: list[str]) -> int:
    if len(argv) not in (1, 3) or (len(argv) == 3 and argv[1] not in ("--check", "--update")):
        print(__doc__, file=sys.stderr)
        return 2
    printed = table(Path(argv[0]))
    if len(argv) == 1:
        sys.stdout.write(printed)
        return 0
    doc_path = Path(argv[2])
    doc = doc_path.read_text(encoding="utf-8")
    start, end = block_of(doc)
    if argv[1] == "--update":
        doc_path.write_text(doc[:start] + printed + doc[end:], encoding="utf-8")
        return 0
    documented = [row for row in doc[start:end].splitlines()
                  if not (row.startswith(OPTIONAL_ROWS) and row not in printed.splitlines())]
    if documented != printed.splitlines():
        print(f"module-graph: {doc_path} does not show the graph CMake has; run "
              f"scripts/module-graph.py {argv[0]} --update {doc_path}. CMake has:\n{printed}",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
