#!/usr/bin/env python3
"""Turns the C++ snippets of README.md and docs/*.md into translation units
that the build compiles (tests/CMakeLists.txt, target doc_snippets), so that
a snippet that no longer compiles breaks the build.

    tools/doc_snippets.py --out DIR --context DIR [--without mpi,tbb] FILE.md...

prints the generated .cpp files, one a line.

Every ```cpp block is compiled. The blocks of one document form programs in
reading order: a block continues the program of the block before it (it may
use what that one declared), unless an HTML comment on the line just above
its fence says otherwise:

    <!-- snippet: new -->               starts a new program
    <!-- snippet: context NAME -->      first puts tests/snippets/NAME.inc
                                        (declarations the prose assumes, such
                                        as a scene `top`; it may include the
                                        example scenes, <flange/models/...>,
                                        nothing else) before it
    <!-- snippet: file-scope -->        the block is namespace-scope code
    <!-- snippet: global-scope -->      the block is code of the global namespace (a macro such as
                                        BOOST_HANA_ADAPT_STRUCT that must be there)
                                        (a struct, a template), not statements

(several, comma-separated). A program sees only the #include lines the
document shows up to its last block, and the using-directives and namespace
aliases of the programs before it (a reader who has read that far has seen
them); the rest of its blocks run, in order, inside one function.
"""
import argparse
import os
import re
import sys

FENCE = re.compile(r"^(\s*)```(\w*)\s*$")
DIRECTIVE = re.compile(r"^\s*<!--\s*snippet:\s*(.*?)\s*-->\s*$")
USING = re.compile(r"^(using namespace [\w:]+|namespace \w+ = [\w:]+);")
NEEDS = {"flange/ensemble/mpi.hpp": "mpi", "flange/ensemble/tbb.hpp": "tbb"}


def blocks(path):
    """(first line number, directive list, code lines) for each ```cpp block."""
    lines = open(path, encoding="utf-8").read().split("\n")
    i = 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        indent, lang = m.group(1), m.group(2)
        directives = []
        d = DIRECTIVE.match(lines[i - 1]) if i > 0 else None
        if d:
            directives = [x.strip() for x in d.group(1).split(",") if x.strip()]
        j = i + 1
        while j < len(lines) and not re.match(r"^\s*```\s*$", lines[j]):
            j += 1
        if j == len(lines):
            sys.exit(f"{path}:{i + 1}: a ``` block that is never closed")
        code = [l[len(indent):] if l.startswith(indent) else l.lstrip() for l in lines[i + 1:j]]
        if lang == "cpp":
            yield i + 2, directives, code
        i = j + 1


def programs(path):
    """Groups a document's blocks into programs."""
    progs = []
    for first, directives, code in blocks(path):
        for d in directives:
            if not (d in ("new", "file-scope", "global-scope") or d.startswith("context ")):
                sys.exit(f"{path}:{first - 1}: unknown snippet directive '{d}' (new, context NAME, file-scope, "
                         "global-scope)")
        if not progs or "new" in directives:
            progs.append([])
        progs[-1].append((first, directives, code))
    return progs


def unit(doc, earlier, prog, context_dir, context_name):
    """The translation unit of one program, after the document's earlier programs."""
    includes, global_scope, file_scope, body = [], [], [], []
    for first, directives, code in [b for p in earlier for b in p]:
        for k, line in enumerate(code):
            if line.lstrip().startswith("#include") or (USING.match(line) and "file-scope" not in directives):
                target = includes if line.lstrip().startswith("#include") else body
                target += [f'#line {first + k} "{doc}"', line.strip()]
    for first, directives, code in prog:
        for d in directives:
            if d.startswith("context "):
                name = d.split(None, 1)[1]
                ctx = open(os.path.join(context_dir, name + ".inc"), encoding="utf-8").read().split("\n")
                target = file_scope if "file-scope" in directives else body
                target.append(f'#line 1 "{context_name}/{name}.inc"')
                for line in ctx:
                    if line.startswith("#include"):
                        # only the example scenes it stands in for, never what the snippet must show
                        if not line.startswith("#include <flange/models/"):
                            sys.exit(f"{context_name}/{name}.inc: a context may include only <flange/models/...>")
                        includes.append(line)
                        line = ""
                    target.append(line)
        target = global_scope if "global-scope" in directives else file_scope if "file-scope" in directives else body
        target.append(f'#line {first} "{doc}"')
        for k, line in enumerate(code):
            if line.lstrip().startswith("#include"):
                includes.append(f'#line {first + k} "{doc}"')
                includes.append(line.strip())
                target.append("")  # keeps the #line numbering
            else:
                target.append(line)
    return "\n".join(
        ["// Generated by tools/doc_snippets.py from " + doc + ": edit the document, not this file."]
        + includes
        + global_scope
        + ["namespace doc_snippet {"]
        + file_scope
        + ["[[maybe_unused]] void run([[maybe_unused]] int argc, [[maybe_unused]] char** argv) {"]
        + body
        + ["}", "}  // namespace doc_snippet", ""]
    )


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", required=True)
    ap.add_argument("--context", required=True)
    ap.add_argument("--root", default=".")
    ap.add_argument("--without", default="")
    ap.add_argument("docs", nargs="+")
    a = ap.parse_args()
    without = {w for w in a.without.split(",") if w}
    os.makedirs(a.out, exist_ok=True)
    written = []
    for path in a.docs:
        doc = os.path.relpath(path, a.root)
        progs = programs(path)
        for k, prog in enumerate(progs, 1):
            text = unit(doc, progs[:k - 1], prog, a.context, os.path.relpath(a.context, a.root))
            lacking = {lib for h, lib in NEEDS.items() if f"<{h}>" in text and lib in without}
            if lacking:
                print(f"doc_snippets: {doc} program {k} left out: it needs {', '.join(sorted(lacking))}",
                      file=sys.stderr)
                continue
            name = re.sub(r"[^A-Za-z0-9]+", "_", doc) + f"_{k}.cpp"
            out = os.path.join(a.out, name)
            if not os.path.exists(out) or open(out, encoding="utf-8").read() != text:
                open(out, "w", encoding="utf-8").write(text)
            written.append(out)
    print("\n".join(written))


if __name__ == "__main__":
    main()
