#!/usr/bin/env python3
"""Runs the ```python blocks of a Markdown document as one program, in order
(each block continues the one before it), so that what docs/python.md and
the README show from Python stays true. Lines keep their numbers: an error
names the document's line. matplotlib draws off-screen (Agg); plt.show()
returns at once.

    build/python/python3 tools/doc_python.py docs/python.md
"""

import os
import re
import sys
import warnings


def program(path):
    lines = open(path, encoding="utf-8").read().split("\n")
    out, inside, blocks = [], False, 0
    for line in lines:
        if not inside and re.match(r"^```python\s*$", line):
            inside, blocks = True, blocks + 1
            out.append("")
        elif inside and line.startswith("```"):
            inside = False
            out.append("")
        else:
            out.append(line if inside else "")
    return "\n".join(out), blocks


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: doc_python.py <document.md>")
    path = sys.argv[1]
    source, blocks = program(path)
    if blocks == 0:
        sys.exit(f"{path}: no python blocks")
    os.environ.setdefault("MPLBACKEND", "Agg")
    warnings.filterwarnings("ignore", message=".*non-interactive.*")
    exec(compile(source, path, "exec"), {"__name__": "__doc_python__"})
    print(f"{path}: {blocks} python block(s) ran")


if __name__ == "__main__":
    main()
