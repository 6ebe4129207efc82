#!/usr/bin/env python3
"""Reports the names that more than one test file declares in an anonymous namespace (or as a static at file scope).

The test files are compiled sixteen to a unit (tests/CMakeLists.txt, MESHGAP_TEST_UNITY_BUILD): two files that declare
the same name there either fail to compile together or, for functions of different parameters, quietly become
overloads, and a call in one file can take the other file's function. So every such name is unique across the test
files, overloads included. A heuristic for this codebase's style: comments, strings and character literals are
blanked, braces are counted, and at namespace scope each statement names what it declares (a function, a type, a
variable, an alias).
"""
import argparse
import collections
import pathlib
import re
import sys

TOKEN = re.compile(r"[A-Za-z_]\w*|::|->|[{}();=<>\[\],*&]|\S")
KEYWORDS = {"const", "constexpr", "static", "inline", "auto", "unsigned", "signed", "long", "short", "int", "double",
            "float", "bool", "char", "void", "std", "typename", "template", "noexcept", "override", "final",
            "operator", "return", "struct", "class", "enum", "union", "using", "typedef", "namespace", "extern",
            "volatile", "mutable", "thread_local", "explicit", "virtual", "friend"}


def blank(text):
    """The text with comments, string and character literals and preprocessor lines replaced by spaces (newlines
    kept)."""
    text = re.sub(r"(?m)^[ \t]*#.*$", lambda m: " " * len(m.group(0)), text)
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append("".join(ch if ch == "\n" else " " for ch in text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def declared(tokens):
    """The name one namespace-scope statement (tokens up to its ';' or first '{') declares, or None."""
    words = [t for t in tokens if re.match(r"[A-Za-z_]", t)]
    if not words or words[0] in ("namespace", "TEST", "TEST_F", "TEST_P", "INSTANTIATE_TEST_SUITE_P"):
        return None
    if words[0] == "using" and "=" not in tokens:
        return None  # a using-declaration or directive names another's entity: repeating it is harmless
    for keyword in ("struct", "class", "union", "enum"):
        if keyword in tokens and "(" not in tokens[:tokens.index(keyword)]:
            rest = [t for t in tokens[tokens.index(keyword) + 1:] if re.match(r"[A-Za-z_]", t)]
            rest = [t for t in rest if t not in ("class", "struct")]
            return rest[0] if rest else None
    cut = len(tokens)
    for stop in ("=", "("):
        if stop in tokens:
            cut = min(cut, tokens.index(stop))
    names = [t for t in tokens[:cut] if re.match(r"[A-Za-z_]\w*$", t) and t not in KEYWORDS]
    if not names or "operator" in tokens[:cut]:
        return None
    # Skip a template's parameter list: the name is the last identifier outside angle brackets.
    depth, last = 0, None
    for t in tokens[:cut]:
        if t == "<":
            depth += 1
        elif t == ">":
            depth = max(0, depth - 1)
        elif depth == 0 and re.match(r"[A-Za-z_]\w*$", t) and t not in KEYWORDS:
            last = t
    return last


def names_of(path):
    """The names a file declares in an anonymous namespace, and as statics at file scope."""
    tokens = TOKEN.findall(blank(path.read_text(encoding="utf-8", errors="replace")))
    found = set()
    # Scopes: ("file" | "anonymous" | "named" | "other"); a statement at namespace scope collects its tokens.
    scopes, statement, named, opened = ["file"], [], False, []
    for t in tokens:
        scope = scopes[-1]
        at_namespace = scope in ("file", "anonymous", "named")
        counts = scope == "anonymous" or (scope == "file" and "static" in statement)
        if t == "{":
            if at_namespace:
                if statement and statement[0] == "namespace":
                    scopes.append("anonymous" if len(statement) == 1 else "named")
                    opened.append("namespace")
                    statement, named = [], False
                    continue
                if counts and not named:
                    name = declared(statement)
                    if name:
                        found.add(name)
                    named = True
                # A function's body ends its statement; a type's or an initialiser's braces do not.
                is_function = "(" in statement and "=" not in statement and not any(
                    k in statement for k in ("struct", "class", "union", "enum"))
                opened.append("function" if is_function else "statement")
            else:
                opened.append("other")
            scopes.append("other")
        elif t == "}":
            if len(scopes) > 1:
                scopes.pop()
                kind = opened.pop() if opened else "other"
                if kind in ("namespace", "function"):
                    statement, named = [], False
        elif at_namespace:
            if t == ";":
                if counts and not named:
                    name = declared(statement)
                    if name:
                        found.add(name)
                statement, named = [], False
            else:
                statement.append(t)
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folders", nargs="+", help="folders searched for test files")
    parser.add_argument("--glob", default="*Test.cpp",
                        help="the test files' names (default: *Test.cpp, as tests/CMakeLists.txt globs them)")
    parser.add_argument("--fail", action="store_true", help="exit 1 when a name is in more than one file")
    args = parser.parse_args()
    files = sorted(p for folder in args.folders for p in pathlib.Path(folder).rglob(args.glob))
    where = collections.defaultdict(list)
    for path in files:
        for name in names_of(path):
            where[name].append(path)
    shared = {name: paths for name, paths in where.items() if len(paths) > 1}
    for name in sorted(shared):
        print(f"{name}: " + ", ".join(str(p) for p in shared[name]))
    print(f"{len(shared)} name(s) in more than one file, of {len(where)} in {len(files)} test file(s)")
    return 1 if args.fail and shared else 0


if __name__ == "__main__":
    sys.exit(main())
