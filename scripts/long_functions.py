#!/usr/bin/python3
"""List C++, JavaScript and Python functions with their line counts (issue 53).

The dashboard's JavaScript modules (src/ros/dashboard_web/*.js) are scanned
the same way as C++: a `function name(...) {` reads like a C++ definition
(arrow functions count as part of the function around them).

Python (files under scripts/ ending .py, and extensionless ones whose first
line is a python3 shebang, e.g. scripts/rocking_report) is read with the
`ast` module: a `def` counts end_lineno - lineno + 1 lines (decorators not
included); nested defs are listed on their own and also count in the
function around them.

C++ and JavaScript: a brace-matching scan, not a parser: comments, strings and
character literals are blanked first, then every top-level-ish `{` whose preceding
text ends in `)` (optionally followed by const/noexcept/override/-> type/
a constructor's initialiser list) opens a function body.  Lambdas and
control blocks inside a body are counted as part of that body, which is
what a reader sees.  Good enough to find the long ones; not exact.

    scripts/long_functions.py [--min N] [paths...]   (default: src/ scripts/, N=80)
"""
import argparse
import ast
import os
import re
import sys

CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof",
           "decltype", "alignof", "static_assert", "noexcept"}


def blank_comments_and_strings(text):
    """Replace comments and literals by spaces, keeping newlines, so that
    braces inside them do not count and line numbers stay right."""
    out = []
    i, n = 0, len(text)
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
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c == 'R' and text.startswith('R"', i):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            if m:
                end = text.find(")" + m.group(1) + '"', i)
                end = n if end < 0 else end + len(m.group(1)) + 2
                out.append(re.sub(r"[^\n]", " ", text[i:end]))
                i = end
            else:
                out.append(c)
                i += 1
        elif c in "\"'":
            # A digit separator (1'000) is not a literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and \
                    i + 1 < n and text[i + 1].isalnum() and \
                    re.match(r"[0-9a-fA-F]", text[i - 1]):
                out.append(" ")
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j + 1, n)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        else:
            out.append(c)
            i += 1
    return "".join(out)


def function_name(head):
    """The name before the parameter list of `head` (text before `{`),
    or None when the block is not a function definition."""
    head = head.rstrip()
    # Strip trailing qualifiers and a constructor's initialiser list.
    head = re.sub(r"\s*->\s*[\w:<>,\s\*&]+$", "", head)
    while True:
        stripped = re.sub(r"\s*\b(const|noexcept|override|final|mutable)\s*$",
                          "", head)
        if stripped == head:
            break
        head = stripped
    # Initialiser list: find a ':' at depth 0 following a ')'.
    depth = 0
    for k in range(len(head) - 1, -1, -1):
        ch = head[k]
        if ch in ")]}":
            depth += 1
        elif ch in "([{":
            depth -= 1
        elif ch == ":" and depth == 0:
            before = head[:k].rstrip()
            if before.endswith(")") and not head[k - 1] == ":" and \
                    not (k + 1 < len(head) and head[k + 1] == ":"):
                head = before
                break
        elif ch in ";}" and depth == 0:
            break
    if not head.endswith(")"):
        return None
    depth = 0
    for k in range(len(head) - 1, -1, -1):
        if head[k] == ")":
            depth += 1
        elif head[k] == "(":
            depth -= 1
            if depth == 0:
                m = re.search(r"([~\w:]+(?:<[^<>()]*>)?|operator\s*\S+)\s*$",
                              head[:k])
                if not m:
                    return None
                name = m.group(1)
                if name.split("::")[-1] in CONTROL or name == "]":
                    return None
                # A lambda's `](...)`, or `= [..](...)`.
                if head[:k].rstrip().endswith("]"):
                    return None
                return name
    return None


def scan(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        text = blank_comments_and_strings(f.read())
    found = []
    depth = 0
    start = 0          # where the current statement's text began
    open_fn = None     # (name, line, depth) of the function being read
    line = 1
    for i, ch in enumerate(text):
        if ch == "\n":
            line += 1
        elif ch == "{":
            if open_fn is None:
                name = function_name(text[start:i])
                if name:
                    open_fn = (name, line, depth)
            depth += 1
            start = i + 1
        elif ch == "}":
            depth -= 1
            if open_fn and depth == open_fn[2]:
                found.append((open_fn[0], open_fn[1], line - open_fn[1] + 1))
                open_fn = None
            start = i + 1
        elif ch == ";":
            start = i + 1
    return found


def is_python(path):
    """A .py file, or an extensionless one whose first line is a python3 shebang."""
    if path.endswith(".py"):
        return True
    if os.path.splitext(os.path.basename(path))[1]:
        return False
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            first = f.readline()
    except OSError:
        return False
    return first.startswith("#!") and "python3" in first


def scan_python(path):
    """(name, first line, line count) of every def in a Python file."""
    with open(path, encoding="utf-8", errors="replace") as f:
        tree = ast.parse(f.read(), filename=path)
    return [(node.name, node.lineno, node.end_lineno - node.lineno + 1)
            for node in ast.walk(tree)
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))]


def source_files(root):
    """The C++/JS and Python files under root (or root itself, a file)."""
    if os.path.isfile(root):
        return [root]
    return [os.path.join(d, f) for d, _, fs in os.walk(root) for f in fs
            if f.endswith((".cpp", ".hpp", ".h", ".cc", ".js"))
            or is_python(os.path.join(d, f))]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--min", type=int, default=80,
                    help="report functions of at least this many lines")
    ap.add_argument("paths", nargs="*", default=["src", "scripts"])
    args = ap.parse_args()
    rows = []
    for root in args.paths:
        for path in sorted(source_files(root)):
            found = scan_python(path) if is_python(path) else scan(path)
            for name, first, count in found:
                if count >= args.min:
                    rows.append((count, path, first, name))
    for count, path, first, name in sorted(rows, reverse=True):
        print(f"{count:5d}  {path}:{first}  {name}")
    print(f"{len(rows)} functions of {args.min} lines or more", file=sys.stderr)


if __name__ == "__main__":
    main()
