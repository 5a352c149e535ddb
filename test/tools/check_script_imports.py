#!/usr/bin/python3
"""check_script_imports: no import circle among the package's Python scripts (issue 53).

    check_script_imports.py [DIR]          (default: the scripts/ beside test/)

Reads every DIR/*.py, every extensionless file in DIR whose first line names python (rocking_report,
rocking_catalogue) and every package DIR/P/ (an __init__.py: P and P.M for each P/M.py, e.g.
event_report.data) with Python's ast, so nothing is imported or run. An edge A -> B is an import of a
module B that is one of these, wherever it stands (a lazy import inside a function closes a circle just
the same at run time); `from .m import x` inside P is P.m, and importing P.M imports P (its __init__) too. Exit 0 and one line when there is no circle; exit 1 and one line per
circle (its modules in import order) otherwise; 2 on a file that does not parse.
"""
import ast
import os
import sys


def package_modules(directory, package):
    """{module name: path} of a package directory: the package itself (its __init__.py) and P.M per P/M.py."""
    modules = {package: os.path.join(directory, package, "__init__.py")}
    for name in sorted(os.listdir(os.path.join(directory, package))):
        if name.endswith(".py") and name != "__init__.py":
            modules[package + "." + name[:-3]] = os.path.join(directory, package, name)
    return modules


def script_modules(directory):
    """{module name: path} of the Python scripts and packages in directory."""
    modules = {}
    for name in sorted(os.listdir(directory)):
        path = os.path.join(directory, name)
        if os.path.isfile(os.path.join(path, "__init__.py")):
            modules.update(package_modules(directory, name))
            continue
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


def imported_names(path, package=None):
    """Every module name imported anywhere in the file (also inside functions), dotted in full, with each
    of its parents ("a.b.c" gives a, a.b, a.b.c: importing a submodule imports its packages). package: the
    package the file is in, for its relative imports."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), filename=path)
    dotted = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            dotted.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            # from a.b import c: c may be a submodule of a.b too
            dotted.update([node.module] + [node.module + "." + alias.name for alias in node.names])
        elif isinstance(node, ast.ImportFrom) and node.level == 1 and package:
            base = package + ("." + node.module if node.module else "")
            dotted.update([base] + [base + "." + alias.name for alias in node.names])
    names = set()
    for d in dotted:
        parts = d.split(".")
        names.update(".".join(parts[:k]) for k in range(1, len(parts) + 1))
    return names


def package_of(module, path):
    """The package a module's relative imports are relative to (None for a script)."""
    if os.path.basename(path) == "__init__.py":
        return module
    return module.rsplit(".", 1)[0] if "." in module else None


def module_edges(module, path, modules):
    """The modules of `modules` that `module` imports."""
    package = package_of(module, path)
    names = imported_names(path, package) & modules.keys()
    if package:
        # Its own package is already being imported when a package's module runs, and its __init__ may
        # import its modules (the usual re-exports): that is no circle.
        names.discard(package)
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
        graph = {m: module_edges(m, p, modules) for m, p in modules.items()}
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
    print(f"check_script_imports: {len(modules)} scripts and package modules in {os.path.normpath(directory)}, "
          "no import circle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
