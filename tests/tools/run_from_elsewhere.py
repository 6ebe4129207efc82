#!/usr/bin/python3
"""Runs an executable from a fresh temporary folder (not the build tree, not the sources): first with --help, which
must succeed, list options and name only default paths that exist, then with the given arguments (a small run on its
defaults), which must succeed and print at least N lines matching a pattern (and, with --file, write a file in the
working folder with at least N lines matching another). Exit 0 when all hold, 1 with the reason otherwise.

Data that a clone may lack (the ../shared/data folder beside the sources): a default under an --optional folder may
be absent when that folder is; with --needs FOLDER, the run is skipped (exit 77, CTest's SKIP_RETURN_CODE) with a
message naming FOLDER when it is absent.

Usage: run_from_elsewhere.py EXECUTABLE --expect REGEX [--count N] [--file NAME REGEX N] [--optional FOLDER]
                             [--needs FOLDER] -- ARG..."""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SKIP = 77  # CTest's SKIP_RETURN_CODE for these tests


def run(args, cwd):
    result = subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=1200)
    return result.returncode, result.stdout, result.stderr


def matching(text, pattern):
    return sum(1 for line in text.splitlines() if re.search(pattern, line))


def absent_optional(path, optional):
    """True when path lies in one of the optional folders and that folder is absent (its default is then unused)."""
    for root in optional:
        root = os.path.abspath(root)
        inside = os.path.commonpath([root, os.path.abspath(path)]) == root
        if inside and not os.path.isdir(root):
            return True
    return False


def check(options, folder):
    """The reasons the executable fails when run in folder (none when it passes)."""
    problems = []
    status, out, err = run([options.executable, "--help"], folder)
    if status != 0:
        return ["--help exited with %d: %s" % (status, err.strip())]
    if matching(out, r"^\s+(-\w \[ )?--[a-z]") < 2:
        problems.append("--help lists fewer than two options:\n" + out)
    for path in re.findall(r"\(default:\s+(/[^)\s]+)\)", out):
        if not os.path.exists(path) and not absent_optional(path, options.optional):
            problems.append("--help names a default that does not exist: " + path)
    status, out, err = run([options.executable] + options.args, folder)
    if status != 0:
        return problems + ["%s exited with %d:\n%s%s" % (" ".join(options.args), status, out, err)]
    found = matching(out, options.expect)
    if found < options.count:
        problems.append("%d line(s) match '%s', expected at least %d:\n%s" % (found, options.expect, options.count,
                                                                                out))
    if options.file:
        name, pattern, count = options.file[0], options.file[1], int(options.file[2])
        path = os.path.join(folder, name)
        if not os.path.exists(path):
            problems.append("%s was not written in the working folder" % name)
        else:
            with open(path, encoding="utf-8") as text:
                found = matching(text.read(), pattern)
            if found < count:
                problems.append("%d line(s) of %s match '%s', expected at least %d" % (found, name, pattern, count))
    return problems


def main():
    parser = argparse.ArgumentParser(usage=__doc__)
    parser.add_argument("executable")
    parser.add_argument("--expect", required=True, help="pattern of the lines the run must print")
    parser.add_argument("--count", type=int, default=1, help="at least this many such lines")
    parser.add_argument("--file", nargs=3, metavar=("NAME", "REGEX", "N"), help="a file the run must write")
    parser.add_argument("--optional", action="append", default=[], metavar="FOLDER",
                        help="a folder a clone may lack: defaults under it may be absent when it is")
    parser.add_argument("--needs", action="append", default=[], metavar="FOLDER",
                        help="a folder the run needs: skipped (exit %d) when absent" % SKIP)
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    options = parser.parse_args(argv[:split])
    options.args = argv[split + 1:]
    options.executable = os.path.abspath(options.executable)
    missing = [folder for folder in options.needs if not os.path.isdir(folder)]
    if missing:
        print("%s: skipped: %s is not a folder (the data this run needs)" % (os.path.basename(options.executable),
                                                                            ", ".join(missing)))
        return SKIP
    with tempfile.TemporaryDirectory(prefix="meshgap-elsewhere-") as folder:
        problems = check(options, folder)
    for problem in problems:
        print(os.path.basename(options.executable) + ": " + problem)
    if not problems:
        print(os.path.basename(options.executable) + ": --help and a small run work from " + folder)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
