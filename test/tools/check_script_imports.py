#!/usr/bin/python3
"""check_script_imports: no import circle among the package's Python scripts (issue 53).

    check_script_imports.py [DIR]          (default: the scripts/ beside test/)

Reads every DIR/*.py and every extensionless file in DIR whose first line names python (rocking_report,
rocking_catalogue) with Python's ast, so nothing is imported or run. An edge A -> B is an import of a
module B that is one of these scripts, wherever it stands (a lazy import inside a function closes a
circle just the same at run time). Exit 0 and one line when there is no circle; exit 1 and one line per
circle (its modules in import order) otherwise; 2 on a file that does not parse.
"""
import ast
import os
import sys


def script_modules(directory):
    """{module name: path} of the Python scripts in directory."""
    modules = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if not os.path.isfile(path):
            continue
        if name.endswith(".py"):
            modules[name[:-3]] = path
        elif "." not in name:
            # an extensionless script is Python only if its #! line says so (run_*.sh etc. have a suffix)
            with open(path, "rb") as f:
                first = f.readline()
            if first.startswith(b"#!") and b"python" in first:
                modules[name] = path
    return modules


def imported_names(path):
    """Every top-level module name imported anywhere in the file (also inside functions)."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), filename=path)
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names.update(alias.name.split(".")[0] for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names


def circles(graph):
    """The strongly connected components of more than one module (or a module importing itself),
    each as a list starting at its first module by name, in import order along one cycle (Tarjan)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1 or v in graph[v]:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return sorted(found)


def main(argv):
    directory = argv[1] if len(argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts")
    modules = script_modules(directory)
    try:
        graph = {m: imported_names(p) & modules.keys() for m, p in modules.items()}
    except SyntaxError as e:
        print(f"check_script_imports: {e.filename}:{e.lineno}: {e.msg}", file=sys.stderr)
        return 2
    found = circles(graph)
    for component in found:
        # the modules of a circle and who imports whom inside it, so the fix is clear from the line
        edges = ", ".join(f"{a} -> {b}" for a in component for b in sorted(graph[a]) if b in component)
        print(f"check_script_imports: import circle: {' '.join(component)} ({edges})")
    if found:
        return 1
    print(f"check_script_imports: {len(modules)} scripts in {os.path.normpath(directory)}, no import circle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
