#!/usr/bin/env python3
"""Prints the import cycles between the modules of one crate: for each crate's src/, an edge
from a top-level module to every module it names as crate::X (tests cut off); strongly
connected components of more than one module are cycles. No output: none.
Usage: python3 scripts/module-cycles.py [REPO_ROOT]"""
import os, re, sys, glob
root = sys.argv[1] if len(sys.argv) > 1 else '.'
for crate in sorted(glob.glob(os.path.join(root, 'crates/*/src'))):
    mods = {}
    for f in glob.glob(os.path.join(crate, '**/*.rs'), recursive=True):
        rel = os.path.relpath(f, crate)
        top = rel.split(os.sep)[0].removesuffix('.rs')
        if top in ('lib', 'main'):
            continue
        text = re.sub(r'//[^\n]*', '', open(f).read())
        # cut test modules
        text = text.split('#[cfg(test)]')[0]
        refs = set(re.findall(r'crate::(\w+)', text))
        # use crate::{a, b::c}
        for grp in re.findall(r'crate::\{([^}]*)\}', text):
            refs |= set(re.findall(r'(?:^|,)\s*(\w+)', grp))
        mods.setdefault(top, set()).update(r for r in refs if r != top)
    names = set(mods)
    g = {m: {r for r in mods[m] if r in names} for m in mods}
    index, low, stack, on, out, i = {}, {}, [], set(), [], [0]
    def sc(v):
        index[v] = low[v] = i[0]; i[0] += 1; stack.append(v); on.add(v)
        for w in g[v]:
            if w not in index: sc(w); low[v] = min(low[v], low[w])
            elif w in on: low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); on.discard(w); comp.append(w)
                if w == v: break
            if len(comp) > 1: out.append(comp)
    for v in g:
        if v not in index: sc(v)
    for comp in out:
        print(os.path.basename(os.path.dirname(crate)), sorted(comp))
