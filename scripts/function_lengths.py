#!/usr/bin/env python3
"""Lists the functions longer than a bound (none over 120 lines outside tests/).

    scripts/function_lengths.py [--max-lines 120] [--report-only] [--root .] [folder ...]

Scans the .h/.cc files under each folder (default: every source folder but tests/, recursively)
and prints one line per function over the bound, "path:line: Name N lines", longest first. Exits 1
if any is over, 0 otherwise; --report-only always exits 0.

A function is a definition at namespace scope in clang-formatted code (Google style): its
signature starts at column 0, its body ends at the next line starting with "}" at column 0. Its
length counts every line from the first line of its signature (template line included) to that
closing brace. Member functions defined inside a class body and lambdas are counted as part of
what contains them, not on their own.
"""
import argparse
import os
import re
import sys

_NOT_FUNCTIONS = re.compile(r"^(namespace|class|struct|enum|union|extern)\b")


def _code(line):
    """The line without a trailing // comment (good enough for signatures and braces)."""
    return line.split("//", 1)[0].rstrip()


def long_functions(path, max_lines):
    """[(first line number, name, length)] of the functions in `path` over max_lines."""
    with open(path, encoding="utf-8", errors="replace") as f:
        lines = f.read().split("\n")
    found = []
    statement_start = None  # first line of the namespace-scope statement being read
    skip_until_close = False  # inside a class/struct/enum body (closed by "};" at column 0)
    inside = None  # (start, name) of the function whose body is being read
    for number, line in enumerate(lines):
        code = _code(line)
        if inside is not None:
            if line.startswith("}"):
                start, name = inside
                length = number - start + 1
                if length > max_lines:
                    found.append((start + 1, name, length))
                inside = None
            continue
        if skip_until_close:
            if line.startswith("}"):
                skip_until_close = False
            continue
        stripped = code.strip()
        if not stripped or stripped.startswith("#") or line.startswith("}"):
            statement_start = None
            continue
        if statement_start is None:
            if line[0].isspace():
                continue  # a continuation of something that is not a definition
            statement_start = number
        if code.endswith(";"):
            statement_start = None
            continue
        if not code.endswith("{"):
            continue
        statement = " ".join(l.strip() for l in lines[statement_start:number + 1])
        head = re.sub(r"^template\s*<[^>]*>\s*", "", statement)
        if _NOT_FUNCTIONS.match(head):
            # Namespaces and extern blocks hold definitions; class bodies are skipped whole.
            skip_until_close = not head.startswith(("namespace", "extern"))
            statement_start = None
            continue
        if "(" in head and "=" not in head.split("(", 1)[0]:
            name = head.split("(", 1)[0].split()[-1] if head.split("(", 1)[0].split() else "?"
            inside = (statement_start, name)
        else:
            skip_until_close = True  # an initialiser such as "const T kTable[] = {"
        statement_start = None
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("folders", nargs="*", default=["apps", "examples", "frontend", "fuzz", "io", "python", "render", "sfm"])
    parser.add_argument("--root", default=".")
    parser.add_argument("--max-lines", type=int, default=120)
    parser.add_argument("--report-only", action="store_true")
    args = parser.parse_args()
    over = []
    for folder in args.folders:
        top = os.path.join(args.root, folder)
        if not os.path.isdir(top):
            print(f"function_lengths: no folder {top}", file=sys.stderr)
            return 2
        for directory, _, files in sorted(os.walk(top)):
            for file in sorted(files):
                if file.endswith((".h", ".cc")):
                    path = os.path.join(directory, file)
                    for line, name, length in long_functions(path, args.max_lines):
                        over.append((length, os.path.relpath(path, args.root), line, name))
    over.sort(key=lambda item: (-item[0], item[1], item[2]))
    for length, path, line, name in over:
        print(f"{path}:{line}: {name} {length} lines")
    folders = ", ".join(args.folders)
    print(f"{len(over)} function(s) over {args.max_lines} lines in {folders}")
    return 1 if over and not args.report_only else 0


if __name__ == "__main__":
    sys.exit(main())
