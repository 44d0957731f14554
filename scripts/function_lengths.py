#!/usr/bin/env python3
"""Lists the longest function bodies in C++ sources (a brace-matching scan, not a parser).

    python3 scripts/function_lengths.py [--top N] DIR...

A function body is a `{` whose preceding text (since the last `;`, `{` or `}`) ends with a
parameter list `)` plus optional qualifiers, and is not a control statement. Lines of the
body are counted from the line after `{` to the line of the matching `}`, exclusive.
Comments and string literals are blanked before matching.
"""
import re
import sys
from pathlib import Path

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else)\s*(\(.*\))?\s*$", re.S)
SIGNATURE = re.compile(
    r"([~\w:<>]+)\s*\((?:[^()]|\([^()]*\))*\)\s*(const|noexcept|override|final|mutable|->\s*[\w:<>,\s*&]+|\s)*$", re.S)


def blank(text):
    out = []
    i, n = 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i)); i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j])); i = j
        elif c == '"' or c == "'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(c + " " * (j - i - 1) + c if j < n else text[i:]); i = j + 1
        else:
            out.append(c); i += 1
    return "".join(out)


def functions(path):
    text = blank(path.read_text(errors="replace"))
    stack, results, start = [], [], 0
    for i, c in enumerate(text):
        if c == "{":
            head = text[start:i]
            name = None
            m = SIGNATURE.search(head.strip())
            if m and not CONTROL.search(head.strip()) and "=" not in head.split("(")[0][-3:]:
                name = m.group(1)
            stack.append((name, i))
            start = i + 1
        elif c == "}":
            if stack:
                name, j = stack.pop()
                if name and not any(s[0] for s in stack):
                    first = text.count("\n", 0, j) + 1
                    last = text.count("\n", 0, i) + 1
                    results.append((last - first - 1, f"{path}:{first}", name))
            start = i + 1
        elif c == ";":
            start = i + 1
    return results


def main(argv):
    top = 10
    if len(argv) > 1 and argv[0] == "--top":
        top, argv = int(argv[1]), argv[2:]
    rows = []
    for d in argv or ["."]:
        for p in sorted(Path(d).rglob("*")):
            if p.suffix in (".cpp", ".hpp") and "tests" not in p.parts and "build" not in p.parts[0]:
                rows += functions(p)
    rows.sort(key=lambda r: -r[0])
    for lines, where, name in rows[:top]:
        print(f"{lines:5d}  {name:40s} {where}")


if __name__ == "__main__":
    main(sys.argv[1:])
