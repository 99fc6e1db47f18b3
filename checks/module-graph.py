#!/usr/bin/env python3
"""The module graph of the core crate: which module of src/ uses which, read from the
`crate::` and `super::` paths in its code (comments and unit tests left out, and files
of unit-test code only, `#![cfg(test)]`; an item
re-exported at the crate root counts as a use of its module). Prints the graph and exits
with 1 if it has a cycle, between top-level modules or between files of one folder; if a
module uses one of a later layer than its own (the layers of src/lib.rs's "Layout"); or if
the f64 reference uses the kernels' code (`brdf`, `float`, `fixed`, `runs`, `real`).

Usage: python3 checks/module-graph.py [src]"""
import re, sys, pathlib
root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else 'src')
def module_of(p):
    rel = p.relative_to(root).with_suffix('')
    parts = rel.parts
    if parts[-1] == 'mod': parts = parts[:-1]
    return '::'.join(parts) if parts != ('lib',) else 'lib'
# items re-exported at the crate root (`pub use module::{A, B}`) count as uses of `module`
reexport = {}
lib = (root / 'lib.rs').read_text()
for mm in re.finditer(r'pub use (\w+)::(?:\{([^}]*)\}|(\w+));', lib):
    for item in re.findall(r'\w+', mm.group(2) or mm.group(3)):
        reexport[item] = mm.group(1)
edges = {}
for p in root.rglob('*.rs'):
    m = module_of(p)
    if m == 'lib': continue
    text = p.read_text()
    # a file of unit-test code only (`#![cfg(test)]`) is left out like the unit tests
    if re.search(r'^#!\[cfg\(test\)\]', text, re.M): continue
    # drop the unit tests and comments
    text = text.split('#[cfg(test)]')[0]
    code = '\n'.join(l.split('//')[0] for l in text.splitlines())
    deps = set()
    for mm in re.finditer(r'crate::(\w+)', code):
        deps.add(reexport.get(mm.group(1), mm.group(1)))
    # use crate::{a, b}
    for mm in re.finditer(r'crate::\{([^}]*)\}', code):
        for d in re.findall(r'(\w+)', mm.group(1)): deps.add(reexport.get(d, d))
    # sibling modules via super:: inside a folder: float::x -> float::y is intra-folder
    top = m.split('::')[0]
    sib = set()
    for mm in re.finditer(r'super::(\w+)', code):
        sib.add(top + '::' + mm.group(1))
    is_module = lambda d: (root / (d + '.rs')).exists() or (root / d).is_dir()
    edges.setdefault(m, set()).update({d for d in deps if d != top and is_module(d)})
    edges[m].update(sib - {m})
# the top-level graph (one node per module or folder); `edges` keeps the file graph
top_edges = {}
for m, ds in edges.items():
    t = m.split('::')[0]
    for d in ds:
        dt = d.split('::')[0]
        if dt != t: top_edges.setdefault(t, set()).add(dt)
        else: top_edges.setdefault(t, set())
def find_cycle(g):
    color = {}
    def dfs(u, stack):
        color[u] = 1; stack.append(u)
        for v in sorted(g.get(u, ())):
            if color.get(v) == 1: return stack[stack.index(v):] + [v]
            if not color.get(v):
                c = dfs(v, stack)
                if c: return c
        color[u] = 2; stack.pop(); return None
    for u in sorted(g):
        if not color.get(u):
            c = dfs(u, [])
            if c: return c
    return None
# The layers of src/lib.rs's "Layout": each module uses only its own layer and earlier ones.
LAYERS = [
    {'real', 'vec3', 'encoding', 'pixel'},
    {'scene'},
    {'brdf'},
    {'render', 'runs'},
    {'float', 'fixed'},
    {'eg', 'damage'},
    {'presets', 'reference'},
]
layer_of = {m: i for i, layer in enumerate(LAYERS) for m in layer}
# The reference is independent of the kernels: none of their code, formulas or numbers.
KERNELS = {'brdf', 'float', 'fixed', 'runs', 'real'}
ok = True
for t in sorted(top_edges):
    if t not in layer_of:
        print(f'module {t} is in no layer of src/lib.rs\'s Layout'); ok = False
        continue
    for d in sorted(top_edges[t]):
        if d in layer_of and layer_of[d] > layer_of[t]:
            print(f'layer order: {t} (layer {layer_of[t] + 1}) uses {d} (layer {layer_of[d] + 1})'); ok = False
for d in sorted(top_edges.get('reference', set()) & KERNELS):
    print(f'the reference uses the kernels\' module {d}'); ok = False
for name, g in (('modules', top_edges), ('files', edges)):
    c = find_cycle(g)
    if c:
        print(f'cycle among {name}: ' + ' -> '.join(c)); ok = False
for t in sorted(top_edges):
    print(f'{t:10} -> {", ".join(sorted(top_edges[t])) or "-"}')
sys.exit(0 if ok else 1)
