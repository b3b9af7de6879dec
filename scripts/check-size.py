#!/usr/bin/env python3
"""Prints the files over 400 lines and the functions over 80 lines (house style).

Usage: scripts/check-size.py [--strict] [PATH ...]   (default: src include apps python tests benchmarks fuzz scripts)

C++ functions are found by their braces in clang-formatted code: a `{` at namespace or class
scope whose header holds a parameter list opens a function; its length runs from the first line
of that header (template line included) to the closing brace. Python functions come from `ast`.
Exit code 0, or 1 with --strict when anything is over its limit.
"""

import ast
import re
import sys
from pathlib import Path

FILE_LIMIT = 400
FUNCTION_LIMIT = 80
DEFAULT_ROOTS = ["src", "include", "apps", "python", "tests", "benchmarks", "fuzz", "scripts"]
CPP_SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}

_STRIP = re.compile(r'R"([^(]*)\((?:.|\n)*?\)\1"|"(?:\\.|[^"\\\n])*"|\'(?:\\.|[^\'\\\n])*\'|//[^\n]*|/\*(?:.|\n)*?\*/')


def _blank(match: re.Match) -> str:
    """The match with every character but newlines replaced by a space (keeps line numbers)."""
    return re.sub(r"[^\n]", " ", match.group(0))


def _is_function_header(header: str) -> bool:
    text = " ".join(header.split())
    if not text or "(" not in text:
        return False
    if re.match(r"(template\s*<.*>\s*)?(namespace|struct|class|enum|union|extern)\b", text):
        return False
    # An initialiser (`= [](...) {`, `= Foo{`) or a control statement is not a function.
    head = text.split("(", 1)[0]
    if "=" in head or re.search(r"\b(if|for|while|switch|return|do|else)\s*$", head):
        return False
    return True


def cpp_functions(path: Path):
    """Yields (name, first_line, line_count) for each function defined at namespace or class scope."""
    code = _STRIP.sub(_blank, path.read_text(encoding="utf-8", errors="replace"))
    code = re.sub(r"^[ \t]*#.*$", "", code, flags=re.M)  # preprocessor lines
    scopes = []  # per open brace: "scope" (namespace/class/extern) or "body"
    header_start = 0
    for i, ch in enumerate(code):
        if ch == "{":
            header = code[header_start:i]
            in_scope = all(kind[0] == "scope" for kind in scopes)
            if in_scope and _is_function_header(header):
                offset = len(header) - len(header.lstrip())
                start = code.count("\n", 0, header_start + offset) + 1
                name = header.split("(", 1)[0].split()[-1] if header.split("(", 1)[0].split() else "?"
                scopes.append(("body", start, name))
            elif in_scope and re.match(r"\s*(template\s*<.*>\s*)?(namespace|struct|class|union|extern)\b", header, re.S):
                scopes.append(("scope",))
            else:
                scopes.append(("other",))
            header_start = i + 1
        elif ch == "}":
            if scopes:
                kind = scopes.pop()
                if kind[0] == "body":
                    end = code.count("\n", 0, i) + 1
                    yield kind[2], kind[1], end - kind[1] + 1
            header_start = i + 1
        elif ch == ";" and all(kind[0] == "scope" for kind in scopes):
            header_start = i + 1
        elif ch == ":" and all(kind[0] == "scope" for kind in scopes):
            # `public:` and friends end a header; `::` and constructor initialisers do not matter
            # here because they sit inside a function's header, not before it.
            if re.search(r"\b(public|private|protected)\s*$", code[header_start:i]):
                header_start = i + 1


def python_functions(path: Path):
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = min([node.lineno] + [d.lineno for d in node.decorator_list])
            yield node.name, first, node.end_lineno - first + 1


def main(argv):
    strict = "--strict" in argv
    roots = [a for a in argv if a != "--strict"] or DEFAULT_ROOTS
    files = []
    for root in roots:
        p = Path(root)
        files += [p] if p.is_file() else sorted(q for q in p.rglob("*") if q.is_file())
    long_files, long_functions = [], []
    for f in files:
        if f.suffix not in CPP_SUFFIXES | {".py"} or "/generated/" in str(f):
            continue
        lines = f.read_text(encoding="utf-8", errors="replace").count("\n")
        if lines > FILE_LIMIT:
            long_files.append((lines, f))
        functions = python_functions(f) if f.suffix == ".py" else cpp_functions(f)
        for name, first, count in functions:
            if count > FUNCTION_LIMIT:
                long_functions.append((count, f, first, name))
    for lines, f in sorted(long_files, reverse=True):
        print(f"{f}: {lines} lines (limit {FILE_LIMIT})")
    for count, f, first, name in sorted(long_functions, reverse=True):
        print(f"{f}:{first}: {name}: {count} lines (limit {FUNCTION_LIMIT})")
    print(f"check-size: {len(long_files)} files over {FILE_LIMIT} lines, "
          f"{len(long_functions)} functions over {FUNCTION_LIMIT} lines")
    return 1 if strict and (long_files or long_functions) else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
