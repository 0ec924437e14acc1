#!/usr/bin/env python3
"""Import cycles between the modules of the Python package python/python/spline (exits 1
when it finds one): `python3 xtask/scripts/python_import_cycles.py`.
Edges: `from . import x`, `from .x import Y`, `import spline.x`, `from spline import Y`,
including function-level (lazy) imports (marked).  `from . import Name` / `from spline import Name`
where Name is not a submodule is followed through __init__'s own imports to the defining module.
The native extension `_core` is a node (it cannot import back).  The .pyi stub is ignored."""
import ast, os, sys
from collections import defaultdict
PKG = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), 'python', 'python', 'spline')
PKGNAME = 'spline'
mods = {}
for f in sorted(os.listdir(PKG)):
    if f.endswith('.py'):
        mods['__init__' if f == '__init__.py' else f[:-3]] = os.path.join(PKG, f)
submods = set(mods) | {'_core'}
trees = {m: ast.parse(open(p).read(), p) for m, p in mods.items()}

def init_names():
    names = {}
    for node in trees['__init__'].body:
        if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
            for a in node.names:
                names[a.asname or a.name] = node.module.split('.')[0]
    return names
INIT = init_names()

def lazy(node, tree):
    # is node nested in a function?
    for fn in ast.walk(tree):
        if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
            for sub in ast.walk(fn):
                if sub is node:
                    return True
    return False

E = defaultdict(list)
for m, tree in trees.items():
    for node in ast.walk(tree):
        tgts = []
        if isinstance(node, ast.ImportFrom):
            if node.level == 1 or (node.level == 0 and node.module and node.module.split('.')[0] == PKGNAME):
                mod = node.module if node.level == 1 else '.'.join(node.module.split('.')[1:])
                if mod:
                    tgts.append(mod.split('.')[0])
                else:
                    for a in node.names:
                        if a.name in submods:
                            tgts.append(a.name)
                        else:
                            tgts.append(INIT.get(a.name, '__init__'))
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split('.')
                if parts[0] == PKGNAME:
                    tgts.append(parts[1] if len(parts) > 1 else '__init__')
        for t in tgts:
            if t != m:
                E[(m, t)].append((f'python/python/spline/{os.path.basename(mods[m])}:{node.lineno}', lazy(node, tree)))
adj = defaultdict(set)
for (a, b) in E:
    adj[a].add(b)
# SCC (tiny graph: use reachability)
nodes = sorted(submods)
reach = {n: set() for n in nodes}
for n in nodes:
    st = [n]
    while st:
        v = st.pop()
        for w in adj.get(v, ()):
            if w not in reach[n]:
                reach[n].add(w); st.append(w)
comps, seen = [], set()
for n in nodes:
    if n in seen: continue
    c = {n} | {w for w in reach[n] if n in reach[w]}
    seen |= c
    if len(c) > 1: comps.append(sorted(c))
for (a, b), ev in sorted(E.items()):
    print(f'edge {a} -> {b}: ' + ', '.join(l + (' (lazy)' if z else '') for l, z in ev))
print('CYCLES:', comps if comps else 'none')
sys.exit(1 if comps else 0)
