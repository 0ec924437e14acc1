#!/usr/bin/env python3
"""Module-level dependency cycles inside each Rust crate of the workspace (ARCHITECTURE.md:
"inside a crate no module imports one that imports it back"); exits 1 when it finds one.

Run from anywhere: `python3 xtask/scripts/module_cycles.py [-v]`.

Heuristics (read-only, no cargo):
  * Files are mapped to module paths by walking `mod x;` declarations from
    lib.rs/main.rs (x.rs, x/mod.rs, #[path] honoured).  Files never reached via
    a `mod` declaration are ignored.  Inline `mod x { ... }` blocks are modules.
  * Everything under `#[cfg(test)]` (items, inline `mod tests {}`, `mod x;`
    file modules, and their sub-trees), files named tests.rs and files under a
    `tests/` directory are excluded.  Comments (incl. doc comments, so
    intra-doc links), string and char literals are stripped.
  * Edges come from: `use` trees (module level and inside fns), and paths in
    code that start with `crate::`, `self::`, `super::`, `$crate::`, or with the
    name of a child module (2018+ uniform paths, e.g. `child::f()` in a parent,
    `pub use child::X`).
  * A path is resolved to the longest existing module prefix; the next segment
    is an item name which is then followed through that module's `use`
    imports / glob imports (so `super::Item` where the parent only re-exports
    Item from a sibling becomes an edge to the sibling, `crate::Error` where
    lib.rs does `pub use error::Error` becomes an edge to `error`).  Only items
    *defined* in a module (fn/struct/enum/trait/type/const/static/union/
    macro_rules) make an edge to that module.
  * Glob imports `use P::*`: each identifier of the file that names an item
    defined (or imported) in P gives an edge to where that item lives.
  * `mod` declarations themselves are not edges.
"""
import os
import re
import sys
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CRATES = [
    ('spline-core', 'crates/spline-core/src', 'lib.rs'),
    ('spline-geom', 'crates/spline-geom/src', 'lib.rs'),
    ('spline-fit', 'crates/spline-fit/src', 'lib.rs'),
    ('spline-algebra', 'crates/spline-algebra/src', 'lib.rs'),
    ('spline-shape', 'crates/spline-shape/src', 'lib.rs'),
    ('spline-io', 'crates/spline-io/src', 'lib.rs'),
    ('spline-cli', 'crates/spline-cli/src', 'main.rs'),
    ('spline-studio', 'crates/spline-studio/src', 'lib.rs'),
    ('spline-testing', 'crates/spline-testing/src', 'lib.rs'),
    ('spline (root facade)', 'src', 'lib.rs'),
    ('xtask', 'xtask/src', 'main.rs'),
    ('python (pyo3)', 'python/src', 'lib.rs'),
]

ITEM_KW = {'fn', 'struct', 'enum', 'trait', 'type', 'const', 'static', 'union'}


# ---------------------------------------------------------------- tokenizer
def tokenize(src):
    toks = []  # (kind, text, line)
    i, n, line = 0, len(src), 1
    while i < n:
        c = src[i]
        if c == '\n':
            line += 1; i += 1; continue
        if c.isspace():
            i += 1; continue
        if src.startswith('//', i):
            j = src.find('\n', i)
            i = n if j < 0 else j
            continue
        if src.startswith('/*', i):
            depth, j = 1, i + 2
            while j < n and depth:
                if src.startswith('/*', j):
                    depth += 1; j += 2
                elif src.startswith('*/', j):
                    depth -= 1; j += 2
                else:
                    if src[j] == '\n':
                        line += 1
                    j += 1
            i = j; continue
        m = re.match(r'(?:b|c)?r(#*)"', src[i:i + 10])
        if m and (i == 0 or not (src[i - 1].isalnum() or src[i - 1] == '_')):
            hashes = m.group(1)
            end = '"' + hashes
            j = src.find(end, i + m.end())
            j = n if j < 0 else j + len(end)
            line += src.count('\n', i, j)
            toks.append(('lit', '""', line)); i = j; continue
        if c == '"' or (c in 'bc' and i + 1 < n and src[i + 1] == '"' and not (i > 0 and (src[i-1].isalnum() or src[i-1] == '_'))):
            j = i + (1 if c == '"' else 2)
            while j < n and src[j] != '"':
                if src[j] == '\\':
                    j += 1
                j += 1
            j += 1
            line += src.count('\n', i, j)
            toks.append(('lit', '""', line)); i = j; continue
        if c == "'" or (c == 'b' and i + 1 < n and src[i + 1] == "'"):
            k = i + (1 if c == "'" else 2)
            # char literal?  'x'  '\n'  '\u{..}'
            m2 = re.match(r"(\\u\{[0-9a-fA-F_]*\}|\\x[0-9a-fA-F]{2}|\\.|[^\\'])'", src[k:k + 12])
            if m2:
                toks.append(('lit', "''", line)); i = k + m2.end(); continue
            if c == "'":
                m3 = re.match(r"'[A-Za-z_][A-Za-z0-9_]*", src[i:])
                toks.append(('life', m3.group(0) if m3 else "'", line))
                i += m3.end() if m3 else 1; continue
        if c.isalpha() or c == '_':
            m = re.match(r'(?:r#)?[A-Za-z_][A-Za-z0-9_]*', src[i:])
            w = m.group(0)
            if w.startswith('r#'):
                w = w[2:]
            toks.append(('id', w, line)); i += m.end(); continue
        if c.isdigit():
            m = re.match(r'[0-9][0-9A-Za-z_]*(\.[0-9][0-9A-Za-z_]*)?', src[i:])
            toks.append(('lit', m.group(0), line)); i += m.end(); continue
        if src.startswith('::', i):
            toks.append(('p', '::', line)); i += 2; continue
        toks.append(('p', c, line)); i += 1
    return toks


# ---------------------------------------------------------------- model
class Module:
    def __init__(self, path, file, parent):
        self.path = path            # tuple of names; () = crate root
        self.file = file
        self.parent = parent
        self.children = {}          # name -> Module
        self.defs = {}              # item name -> line
        self.imports = {}           # name -> (abs-ish path list, base module, line, is_pub)
        self.globs = []             # (path list, base module, line)
        self.refs = []              # (path list, base module path, line, kind, file)
        self.idents = set()         # identifiers used in (non-test) code of the file part
        self.macros = set()         # macro_rules! names defined here
        self.invocations = []       # (name, line, file) of bare `name!(...)` invocations

    def name(self):
        return 'crate' + ''.join('::' + p for p in self.path)


def match_close(toks, i):
    """toks[i] is an opening bracket; return index of its matching close."""
    pairs = {'{': '}', '(': ')', '[': ']'}
    stack = [pairs[toks[i][1]]]
    j = i + 1
    while j < len(toks) and stack:
        t = toks[j][1] if toks[j][0] == 'p' else None
        if t in pairs:
            stack.append(pairs[t])
        elif t in (')', ']', '}') and t == stack[-1]:
            stack.pop()
        j += 1
    return j - 1


def item_end(toks, i):
    """Given the first token of an item/statement, return index of its last token."""
    j = i
    kw = None
    while j < len(toks):
        k, t, _ = toks[j]
        if k == 'id' and kw is None and t in ('fn', 'struct', 'enum', 'trait', 'impl', 'mod', 'union', 'use',
                                               'const', 'static', 'let', 'type', 'macro_rules', 'extern'):
            kw = t
        if k == 'p' and t == '#' and j + 1 < len(toks) and toks[j + 1][1] in ('[', '!'):
            # nested attribute
            b = j + 1 if toks[j + 1][1] == '[' else j + 2
            j = match_close(toks, b) + 1
            continue
        if k == 'p' and t == ';':
            return j
        if k == 'p' and t in '([':
            j = match_close(toks, j) + 1
            continue
        if k == 'p' and t == '{':
            e = match_close(toks, j)
            if kw in ('const', 'static', 'let', 'use', 'type'):
                j = e + 1
                continue
            # block-like item ends at the brace (optionally followed by ;)
            if e + 1 < len(toks) and toks[e + 1][1] == ';':
                return e + 1
            return e
        if k == 'p' and t in (',', '}') and kw is None:
            return j - 1
        j += 1
    return len(toks) - 1


def is_cfg_test(attr_toks):
    txt = ' '.join(t[1] for t in attr_toks)
    if not re.match(r'^cfg \(', txt):
        return False
    # crude: cfg(test) / cfg(all(test, ..)) / cfg(any(test ...)) but not cfg(not(test))
    if re.search(r'not \( test', txt):
        return False
    return re.search(r'\btest\b', txt) is not None


def parse_use_tree(toks, i, prefix, out, line):
    """Parse a use tree starting at toks[i]; append (path, alias, line) to out. Returns index after tree."""
    path = list(prefix)
    while i < len(toks):
        k, t, ln = toks[i]
        if k == 'p' and t == '{':
            e = match_close(toks, i)
            j = i + 1
            while j < e:
                j = parse_use_tree(toks, j, path, out, ln)
                if j < e and toks[j][1] == ',':
                    j += 1
            return e + 1
        if k == 'p' and t == '*':
            out.append((path + ['*'], None, ln))
            return i + 1
        if k == 'p' and t == '::':
            i += 1
            continue
        if k == 'p' and t == '$':
            i += 1
            continue
        if k == 'id':
            if t == 'as':
                alias = toks[i + 1][1]
                out.append((path, alias, ln))
                return i + 2
            path.append(t)
            i += 1
            # leaf?
            if i >= len(toks) or toks[i][1] in (',', '}', ';'):
                if t == 'self':
                    out.append((path[:-1], path[-2] if len(path) > 1 else None, ln))
                else:
                    out.append((path, None, ln))
                return i
            continue
        return i + 1
    return i


class Crate:
    def __init__(self, label, srcdir, rootfile):
        self.label = label
        self.srcdir = os.path.join(ROOT, srcdir)
        self.modules = {}
        self.excluded = []
        self.root = self.load_file(os.path.join(self.srcdir, rootfile), (), None, is_root=True)

    def rel(self, f):
        return os.path.relpath(f, ROOT)

    # --------------------------------------------------------------- loading
    def load_file(self, fname, path, parent, is_root=False):
        mod = Module(path, fname, parent)
        self.modules[path] = mod
        with open(fname, encoding='utf-8') as fh:
            src = fh.read()
        toks = tokenize(src)
        # directory for child modules
        base = os.path.basename(fname)
        d = os.path.dirname(fname)
        if is_root or base == 'mod.rs':
            childdir = d
        else:
            childdir = os.path.join(d, base[:-3])
        self.scan(toks, 0, len(toks), mod, childdir, fname)
        return mod

    def scan(self, toks, i, end, mod, childdir, fname, depth_in_item=False):
        """Scan tokens [i, end) belonging to module `mod` (module-level if not depth_in_item)."""
        pending_test = False
        pending_path = None
        while i < end:
            k, t, ln = toks[i]
            # attributes
            if k == 'p' and t == '#' and i + 1 < end and toks[i + 1][1] in ('[', '!'):
                inner = toks[i + 1][1] == '!'
                b = i + 2 if inner else i + 1
                e = match_close(toks, b)
                attr = toks[b + 1:e]
                if is_cfg_test(attr):
                    if inner:
                        self.excluded.append(f'{self.rel(fname)} (#![cfg(test)])')
                        return
                    pending_test = True
                if attr and attr[0][1] == 'path' and len(attr) >= 3:
                    pending_path = None  # literal stripped; handled specially below
                    pending_path = '__PATH__'
                i = e + 1
                continue
            if pending_test:
                e = item_end(toks, i)
                # record excluded modules for the report
                seg = toks[i:e + 1]
                for q in range(len(seg) - 1):
                    if seg[q][1] == 'mod' and seg[q + 1][0] == 'id':
                        self.excluded.append(f'{self.rel(fname)}:{seg[q][2]} mod {seg[q+1][1]} (cfg(test))')
                        break
                pending_test = False
                pending_path = None
                i = e + 1
                continue
            # module declarations
            if k == 'id' and t == 'mod' and i + 1 < end and toks[i + 1][0] == 'id' and (i == 0 or toks[i - 1][1] != '::'):
                name = toks[i + 1][1]
                if i + 2 < end and toks[i + 2][1] == ';':
                    if pending_path:
                        # #[path] modules: only the test-only one exists in this tree; skip
                        self.excluded.append(f'{self.rel(fname)}:{ln} mod {name} (#[path], not followed)')
                    else:
                        cand = [os.path.join(childdir, name + '.rs'), os.path.join(childdir, name, 'mod.rs')]
                        f = next((c for c in cand if os.path.exists(c)), None)
                        if f is None:
                            print(f'warning: {fname}:{ln} mod {name} file not found', file=sys.stderr)
                        elif name == 'tests' or '/tests/' in f:
                            self.excluded.append(f'{self.rel(f)} (tests file)')
                        else:
                            child = self.load_file(f, mod.path + (name,), mod)
                            mod.children[name] = child
                    pending_path = None
                    i += 3
                    continue
                if i + 2 < end and toks[i + 2][1] == '{':
                    e = match_close(toks, i + 2)
                    if name == 'tests':
                        self.excluded.append(f'{self.rel(fname)}:{ln} inline mod tests')
                    else:
                        child = Module(mod.path + (name,), fname, mod)
                        self.modules[child.path] = child
                        mod.children[name] = child
                        self.scan(toks, i + 3, e, child, os.path.join(childdir, name), fname)
                    i = e + 1
                    continue
            pending_path = None
            # item definitions (module level only)
            if not depth_in_item and k == 'id':
                prev = toks[i - 1][1] if i > 0 else None
                if t in ITEM_KW and i + 1 < end and toks[i + 1][0] == 'id' and prev != '::':
                    nm = toks[i + 1][1]
                    if not (t == 'const' and nm == 'fn') and not (t == 'static' and nm == 'mut') and not (t == 'type' and prev == 'impl'):
                        mod.defs.setdefault(nm, ln)
                    elif t == 'const' and nm == 'fn' and i + 2 < end:
                        mod.defs.setdefault(toks[i + 2][1], ln)
                    elif t == 'static' and nm == 'mut' and i + 2 < end:
                        mod.defs.setdefault(toks[i + 2][1], ln)
                if t == 'macro_rules' and i + 2 < end and toks[i + 1][1] == '!':
                    mod.defs.setdefault(toks[i + 2][1], ln)
                    mod.macros.add(toks[i + 2][1])
            # use declarations
            if k == 'id' and t == 'use' and (i == 0 or toks[i - 1][1] not in ('::',)):
                is_pub = i > 0 and toks[i - 1][1] in ('pub', ')')
                out = []
                j = parse_use_tree(toks, i + 1, [], out, ln)
                module_level = not depth_in_item
                for path, alias, l2 in out:
                    if not path:
                        continue
                    if path[-1] == '*':
                        if module_level:
                            mod.globs.append((path[:-1], mod.path, l2))
                        mod.refs.append((path[:-1], mod.path, l2, 'use-glob', fname))
                        continue
                    nm = alias or path[-1]
                    if module_level and nm != '_':
                        mod.imports[nm] = (path, mod.path, l2, is_pub)
                    mod.refs.append((path, mod.path, l2, 'pub use' if is_pub else 'use', fname))
                while j < end and toks[j][1] != ';':
                    j += 1
                i = j + 1
                continue
            # impl / fn / trait bodies: scan inside with depth_in_item
            if k == 'p' and t == '{':
                e = match_close(toks, i)
                self.scan(toks, i + 1, e, mod, childdir, fname, depth_in_item=True)
                i = e + 1
                continue
            # code paths
            if k == 'id':
                mod.idents.add(t)
                if (t != 'macro_rules' and i + 2 < end and toks[i + 1][1] == '!'
                        and toks[i + 2][1] in '([{' and (i == 0 or toks[i - 1][1] != '::')):
                    mod.invocations.append((t, ln, fname))
                prev = toks[i - 1][1] if i > 0 else None
                if prev != '::' and i + 1 < end and toks[i + 1][1] == '::':
                    anchored = t in ('crate', 'self', 'super') or (prev == '$' and t == 'crate')
                    path = [t]
                    j = i + 1
                    while j + 1 < end and toks[j][1] == '::' and toks[j + 1][0] == 'id':
                        path.append(toks[j + 1][1]); j += 2
                    mod.refs.append((path, mod.path, ln, 'path' if anchored else 'bare-path', fname))
                    i = j
                    continue
            i += 1

    # --------------------------------------------------------------- resolution
    def mod_at(self, path):
        return self.modules.get(tuple(path))

    def start(self, path, base):
        """Turn a possibly relative path into (module, remaining segments) or None for external."""
        if not path:
            return None
        cur = self.modules[base]
        segs = list(path)
        if segs[0] in ('crate', '$crate'):
            return self.root, segs[1:]
        if segs[0] == 'self':
            return cur, segs[1:]
        if segs[0] == 'super':
            while segs and segs[0] == 'super':
                cur = cur.parent if cur.parent else cur
                segs = segs[1:]
            return cur, segs
        # uniform path: name in scope of `cur`
        if segs[0] in cur.children or segs[0] in cur.imports or segs[0] in cur.defs:
            return cur, segs
        return None

    def resolve(self, path, base, seen=None):
        """Return (target module, item or None, chain) ; None if external."""
        if seen is None:
            seen = set()
        st = self.start(path, base)
        if st is None:
            return None
        cur, segs = st
        chain = []
        while segs:
            s = segs[0]
            if s in cur.children:
                cur = cur.children[s]; segs = segs[1:]; continue
            if s in cur.defs:
                return cur, s, chain
            if s in cur.imports and (cur.path, s) not in seen:
                seen.add((cur.path, s))
                ipath, ibase, iline, _ = cur.imports[s]
                r = self.resolve(ipath, ibase, seen)
                if r is None:
                    return None  # re-export of an external item
                tgt, item, ch = r
                chain = chain + [f'{cur.name()} imports {s} ({self.rel(cur.file)}:{iline})'] + ch
                if item is None:
                    cur = tgt; segs = segs[1:]; continue
                return tgt, item, chain
            # glob imports of cur
            for gpath, gbase, gline in cur.globs:
                r = self.resolve(list(gpath) + [s], gbase, seen)
                if r is not None and (r[1] is not None or len(segs) > 1 or True):
                    tgt, item, ch = r
                    if tgt is not None and (item is not None and item in tgt.defs or item is None):
                        chain = chain + [f'{cur.name()} glob-imports {"::".join(gpath)}::* ({self.rel(cur.file)}:{gline})'] + ch
                        if item is None:
                            cur = tgt; segs = segs[1:]; break
                        return tgt, item, chain
            else:
                # unknown name in cur (enum variant, macro, assoc item...) -> attribute to cur
                return cur, s, chain
            continue
        return cur, None, chain

    def edges(self):
        E = defaultdict(list)   # (a, b) -> list of (file:line, text, chain)
        for mod in self.modules.values():
            for path, base, line, kind, fname in mod.refs:
                if kind == 'bare-path':
                    m = self.modules[base]
                    if not (path[0] in m.children or (path[0] in m.imports)):
                        continue
                    if path[0] in m.imports and path[0] not in m.children:
                        continue  # use already counted
                if kind == 'use-glob':
                    st = self.resolve(path, base)
                    if st is None:
                        continue
                    tgt, item, chain = st
                    if item is not None:
                        # glob over an enum etc: edge to the module defining it
                        if tgt is not mod:
                            E[(mod.path, tgt.path)].append((f'{self.rel(fname)}:{line}', 'use ' + '::'.join(path) + '::*', chain))
                        continue
                    # which names of tgt does this file use?
                    names = set(tgt.defs) | set(tgt.imports) | set(tgt.children)
                    used = sorted(n for n in names & mod.idents)
                    for n in used:
                        r = self.resolve(list(path) + [n], base)
                        if r is None:
                            continue
                        t2, it2, ch2 = r
                        if t2 is not mod:
                            E[(mod.path, t2.path)].append((f'{self.rel(fname)}:{line}', 'use ' + '::'.join(path) + f'::* (uses {n})', ch2))
                    continue
                r = self.resolve(path, base)
                if r is None:
                    continue
                tgt, item, chain = r
                if tgt is mod:
                    continue
                # a path to a module that is an ancestor with no item: e.g. `use super::x` where x is a module -> handled;
                # path ending at an ancestor module itself (`use super::super`) -> no item -> skip
                if item is None and tgt.path == mod.path[:len(tgt.path)]:
                    continue
                E[(mod.path, tgt.path)].append((f'{self.rel(fname)}:{line}', kind + ' ' + '::'.join(path), chain))
        # textual-scope macros: `name!(..)` resolves to the nearest enclosing module
        # (itself or an ancestor) that defines `macro_rules! name`
        for mod in self.modules.values():
            for name, line, fname in mod.invocations:
                m = mod
                while m is not None and name not in m.macros:
                    m = m.parent
                if m is not None and m is not mod:
                    E[(mod.path, m.path)].append((f'{self.rel(fname)}:{line}', f'macro {name}! (textual scope)', []))
        return E


def tarjan(nodes, adj):
    index, low, onstack, stack, res = {}, {}, set(), [], []
    counter = [0]
    sys.setrecursionlimit(10000)

    def strong(v):
        index[v] = low[v] = counter[0]; counter[0] += 1
        stack.append(v); onstack.add(v)
        for w in adj.get(v, ()):
            if w not in index:
                strong(w); low[v] = min(low[v], low[w])
            elif w in onstack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop(); onstack.discard(w); comp.append(w)
                if w == v:
                    break
            res.append(comp)
    for v in nodes:
        if v not in index:
            strong(v)
    return res


def mname(p):
    return 'crate' + ''.join('::' + x for x in p)


def main():
    verbose = '-v' in sys.argv
    out = []
    for label, srcdir, rootfile in CRATES:
        c = Crate(label, srcdir, rootfile)
        E = c.edges()
        adj = defaultdict(set)
        for (a, b) in E:
            adj[a].add(b)
        comps = [sorted(x) for x in tarjan(list(c.modules), adj) if len(x) > 1]
        # the same without textual-macro edges, and without the hub (shortest path) of each SCC
        adj_nomacro = defaultdict(set)
        for (a, b), ev in E.items():
            if any(not txt.startswith('macro ') for _, txt, _ in ev):
                adj_nomacro[a].add(b)
        nomacro = [set(x) for x in tarjan(list(c.modules), adj_nomacro) if len(x) > 1]
        out.append(f'## {label}  ({len(c.modules)} modules, {len(E)} module edges)')
        if c.excluded and verbose:
            out.append('excluded: ' + '; '.join(c.excluded))
        if not comps:
            out.append('no cycles')
        for comp in comps:
            s = set(comp)
            hub = min(comp, key=len)
            rest = [p for p in comp if p != hub]
            adj_rest = {a: {b for b in adj[a] if b in rest} for a in rest}
            inner = [sorted(x) for x in tarjan(rest, adj_rest) if len(x) > 1]
            tags = []
            if not any(s <= x for x in nomacro):
                tags.append('ONLY through textual macro_rules! edges')
            tags.append('hub ' + mname(hub) + ('; without the hub: ' + ' | '.join(', '.join(mname(p) for p in x) for x in inner) if inner else '; acyclic without the hub'))
            out.append('CYCLE: ' + ', '.join(mname(p) for p in comp) + '   [' + '; '.join(tags) + ']')
            for (a, b), ev in sorted(E.items()):
                if a in s and b in s:
                    out.append(f'  {mname(a)} -> {mname(b)}')
                    for loc, txt, chain in ev:
                        out.append(f'      {loc}: {txt}' + (('   [via ' + ' -> '.join(chain) + ']') if chain else ''))
        if verbose:
            for (a, b), ev in sorted(E.items()):
                out.append(f'  edge {mname(a)} -> {mname(b)}: ' + ', '.join(loc for loc, _, _ in ev[:4]))
        out.append('')
    print('\n'.join(out))
    return any(line.startswith('CYCLE') for line in out)


if __name__ == '__main__':
    sys.exit(1 if main() else 0)
