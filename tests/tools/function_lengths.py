#!/usr/bin/python3
"""Reports the C++ functions (and Allman-style lambdas) longer than a limit, longest first.

Usage: function_lengths.py [--max N] [--fail] [--exclude FILE...] FILE_OR_FOLDER...
(default: --max 80; --fail: exit 1 if any; --exclude: files not looked at, each matched as the end of a path)

A heuristic for code in meshgap's style (.clang-format: Allman braces): a body is a line holding only "{" whose previous
code line has a "(" and is not a control statement; it ends at the "}" with the same indentation."""
import argparse
import os
import re
import sys

CONTROL = re.compile(r"^\s*(if|for|while|switch|catch|else|do|try|namespace|struct|class|enum|union)\b")


def is_comment(line):
    text = line.strip()
    return text.startswith(("//", "/*", "*")) or text.endswith("*/")


def bodies(path):
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    for i, line in enumerate(lines):
        if line.strip() != "{":
            continue
        j = i - 1
        while j >= 0 and (not lines[j].strip() or is_comment(lines[j])):
            j -= 1
        head = lines[j] if j >= 0 else ""
        # The signature may span lines: look back to the line that opens it.
        k = j
        while k > 0 and "(" not in head and lines[k - 1].strip() and not is_comment(lines[k - 1]) and \
                not lines[k - 1].strip().endswith((";", "}", "{")):
            k -= 1
            head = lines[k] + head
        if "(" not in head or CONTROL.match(lines[k]) or head.rstrip().endswith(";"):
            continue
        indent = len(line) - len(line.lstrip())
        for end in range(i + 1, len(lines)):
            if lines[end].strip().startswith("}") and len(lines[end]) - len(lines[end].lstrip()) == indent:
                yield (end - k + 1, k + 1, lines[k].strip()[:90])
                break


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max", type=int, default=80)
    parser.add_argument("--fail", action="store_true")
    parser.add_argument("--exclude", nargs="*", default=[])
    parser.add_argument("paths", nargs="+")
    args = parser.parse_args()
    found = []
    for root in args.paths:
        files = [root] if os.path.isfile(root) else \
            [os.path.join(d, f) for d, _, fs in os.walk(root) for f in fs if f.endswith((".cpp", ".h"))]
        for path in sorted(files):
            if any(path.replace(os.sep, "/").endswith(e) for e in args.exclude):
                continue
            found += [(n, path, line, head) for n, line, head in bodies(path) if n > args.max]
    for n, path, line, head in sorted(found, reverse=True):
        print(f"{n:5d} lines  {path}:{line}  {head}")
    print(f"{len(found)} function(s) longer than {args.max} lines")
    return 1 if args.fail and found else 0


if __name__ == "__main__":
    sys.exit(main())
