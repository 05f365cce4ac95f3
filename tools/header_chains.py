#!/usr/bin/env python3
"""Groups flange's public headers into include chains for the self-containment
check (tests/CMakeLists.txt, tests/layers/header.cmake).

A chain A1, A2, ..., Ak is a list of headers in which every header includes,
directly or not, the one before it. Compiled as one unit (`-include A1
-include A2 ...`, nothing before A1), it checks each of them as if it were
compiled on its own: a header fails on its own only where some header H of
its include closure uses a name declared in none of H's own includes, and
the headers before H in the chain are all in H's closure, so they declare
nothing H's closure does not. The check needs the include lists to be exact:
a header with a flange include inside #if/#ifdef is not chained (its own test).

A minimum chain cover (Dilworth, by bipartite matching over the closure) turns
113 compilations into about a third as many, each as long as its last header's.

  tools/header_chains.py --root include  flange/a.hpp flange/b.hpp ...
prints one chain per line, headers separated by ';' (a CMake list);
  tools/header_chains.py --root include --check flange/a.hpp,flange/b.hpp
exits with 1 and says why if the headers no longer form a chain (an include
removed since CMake grouped them): the test then fails and asks for a
re-configure rather than check less than it says.
"""
import argparse
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s+"(flange/[^"]+)"')
CONDITIONAL_OPEN = re.compile(r'^\s*#\s*if')
CONDITIONAL_CLOSE = re.compile(r'^\s*#\s*endif')


def direct_includes(root: Path, header: str):
    """The flange headers `header` includes, and whether one of them is inside a conditional."""
    depth, found, conditional = 0, [], False
    for line in (root / header).read_text(encoding="utf-8").splitlines():
        if CONDITIONAL_OPEN.match(line):
            depth += 1
        elif CONDITIONAL_CLOSE.match(line):
            depth -= 1
        m = INCLUDE.match(line)
        if m:
            found.append(m.group(1))
            conditional |= depth > 0
    return found, conditional


def closures(root: Path, headers):
    direct, conditional = {}, set()

    def visit(h):
        if h in direct:
            return
        inc, cond = direct_includes(root, h)
        direct[h] = inc
        if cond:
            conditional.add(h)
        for i in inc:
            visit(i)

    for h in headers:
        visit(h)
    closure = {}

    def close(h):
        if h not in closure:
            closure[h] = set()
            for i in direct[h]:
                closure[h] |= {i} | close(i)
        return closure[h]

    for h in direct:
        close(h)
    # A header whose closure holds a conditionally including one is not exact either.
    inexact = {h for h in direct if h in conditional or closure[h] & conditional}
    return closure, inexact


def chain_cover(headers, closure):
    """A minimum cover of `headers` by chains (each header in its successor's closure)."""
    succ_of = {}   # matched: a -> b (a comes right before b)
    pred_of = {}

    def augment(a, seen):
        for b in headers:
            if a in closure[b] and b not in seen:
                seen.add(b)
                if b not in pred_of or augment(pred_of[b], seen):
                    succ_of[a], pred_of[b] = b, a
                    return True
        return False

    for a in headers:
        augment(a, set())
    chains = []
    for h in headers:
        if h in pred_of:
            continue
        chain = [h]
        while chain[-1] in succ_of:
            chain.append(succ_of[chain[-1]])
        chains.append(chain)
    return chains


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--root", required=True, type=Path, help="the include directory")
    ap.add_argument("--check", help="a chain, comma-separated: is it still one?")
    ap.add_argument("headers", nargs="*", help="headers relative to the root, e.g. flange/math/types.hpp")
    args = ap.parse_args()
    if args.check:
        chain = args.check.split(",")
        closure, inexact = closures(args.root, chain)
        for a, b in zip(chain, chain[1:]):
            if a not in closure[b] or b in inexact:
                print(f"{b} no longer includes {a} exactly: re-run cmake to group the headers anew")
                return 1
        return 0
    headers = sorted(set(args.headers))
    closure, inexact = closures(args.root, headers)
    chained = [h for h in headers if h not in inexact]
    chains = chain_cover(chained, closure) + [[h] for h in headers if h in inexact]
    for c in chains:
        print(";".join(c))
    return 0


if __name__ == "__main__":
    sys.exit(main())
