#!/usr/bin/python3
"""Fails when an #include runs against meshgap's one-way flow (DESIGN.md):

    (top-level headers) -> mesh -> geometry -> distance -> scene -> robot -> ompl -> planners

A file may include its own part and the parts before it, never one after it. Usage: check_include_arrows.py REPO"""
import os
import re
import sys

ORDER = ["", "mesh", "geometry", "distance", "scene", "robot", "ompl", "planners"]
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')

# Known arrows against the flow, each with the reason it is still there. Keep this list short and shrinking.
ALLOWED = set()


def part_of_file(rel):
    """The part a repository file belongs to, or None for files outside the layered tree."""
    parts = rel.split("/")
    if parts[0] == "planners":
        return "planners"
    if parts[:2] == ["include", "meshgap"] or parts[0] == "src":
        rest = parts[2:] if parts[0] == "include" else parts[1:]
        return rest[0] if len(rest) > 1 and rest[0] in ORDER else ""
    return None


def part_of_include(name):
    """The part an include names, or None for a system or third-party header."""
    if name.startswith("meshgap/"):
        rest = name.split("/")[1:]
        return rest[0] if len(rest) > 1 and rest[0] in ORDER else ""
    if name.startswith("support/"):
        return "planners"
    return None


def arrows_against(repo):
    bad = []
    for top in ("include", "src", "planners"):
        for folder, _, files in os.walk(os.path.join(repo, top)):
            for f in sorted(files):
                if not f.endswith((".h", ".cpp", ".in")):
                    continue
                rel = os.path.relpath(os.path.join(folder, f), repo).replace(os.sep, "/")
                source = part_of_file(rel)
                if source is None:
                    continue
                with open(os.path.join(folder, f), encoding="utf-8") as text:
                    for number, line in enumerate(text, 1):
                        m = INCLUDE.match(line)
                        target = part_of_include(m.group(1)) if m else None
                        if target is not None and ORDER.index(target) > ORDER.index(source) and \
                                (rel, target) not in ALLOWED:
                            bad.append(f"{rel}:{number}: {source or 'top level'} includes {m.group(1)} ({target})")
    return bad


def main():
    if len(sys.argv) != 2 or not os.path.isdir(os.path.join(sys.argv[1], "src")):
        sys.exit("usage: check_include_arrows.py REPO (the folder holding src/ and include/)")
    bad = arrows_against(sys.argv[1])
    for line in bad:
        print(line)
    if bad:
        print(f"{len(bad)} include(s) run against mesh -> geometry -> distance -> scene -> robot -> ompl -> planners")
        return 1
    print("every include runs one way: mesh -> geometry -> distance -> scene -> robot -> ompl -> planners")
    return 0


if __name__ == "__main__":
    sys.exit(main())
