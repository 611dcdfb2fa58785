#!/usr/bin/env python3
"""Lists the dependency cycles between the top-level modules of a crate (issue 18): module A
depends on B when a file under A names `crate::B` (in a `use` or a path) or `super::B` from
A's root file. Prints each cycle (a strongly connected component of more than one module) and
exits 1 if there is any. Usage: scripts/module_cycles.py [crates/agripath/src]"""
import os
import re
import sys

root = sys.argv[1] if len(sys.argv) > 1 else "crates/agripath/src"
modules = {}
for entry in sorted(os.listdir(root)):
    path = os.path.join(root, entry)
    if entry.endswith(".rs") and entry not in ("lib.rs", "main.rs"):
        modules[entry[:-3]] = [path]
    elif os.path.isdir(path):
        files = []
        for folder, _, names in os.walk(path):
            files += [os.path.join(folder, name) for name in names if name.endswith(".rs")]
        modules[entry] = files

edges = {module: set() for module in modules}
reference = re.compile(r"\bcrate::([a-z_]+)")
for module, files in modules.items():
    for path in files:
        text = open(path, encoding="utf-8").read()
        # Tests may reach anywhere; only the library's own code counts.
        text = text.split("#[cfg(test)]")[0]
        for target in reference.findall(text):
            if target in modules and target != module:
                edges[module].add(target)

# Tarjan's strongly connected components.
index, low, on_stack, stack, components = {}, {}, set(), [], []
counter = [0]


def visit(node):
    index[node] = low[node] = counter[0]
    counter[0] += 1
    stack.append(node)
    on_stack.add(node)
    for target in sorted(edges[node]):
        if target not in index:
            visit(target)
            low[node] = min(low[node], low[target])
        elif target in on_stack:
            low[node] = min(low[node], index[target])
    if low[node] == index[node]:
        component = []
        while True:
            member = stack.pop()
            on_stack.discard(member)
            component.append(member)
            if member == node:
                break
        components.append(sorted(component))


sys.setrecursionlimit(10000)
for node in sorted(edges):
    if node not in index:
        visit(node)
cycles = [component for component in components if len(component) > 1]
for component in cycles:
    inner = {m: sorted(edges[m] & set(component)) for m in component}
    print("cycle:", ", ".join(f"{m} -> {'/'.join(t)}" for m, t in inner.items()))
print(f"{len(modules)} modules, {sum(len(t) for t in edges.values())} dependencies, {len(cycles)} cycle(s)")
sys.exit(1 if cycles else 0)
