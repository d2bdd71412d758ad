#!/usr/bin/env python3
"""Figures of the code's structure: the largest source files in src/, the longest functions,
the include cycles among headers (a header that includes, directly or not, one that
includes it back), and the lines of code of the config mapping (the JSON reading and writing
of the options' tables, and the config's key-specific rules: MAPPING below).

  /usr/bin/python3 tools/code_figures.py [--top N] [--module pipeline]

Functions are found by their braces: a `{` that follows a `)` (with qualifiers such as const,
override, noexcept or an initializer list in between) at namespace or class level opens a
function body, its matching `}` closes it; lambdas inside a body count towards that body. The
length is from the line of the signature's start to the closing brace, inclusive. A heuristic,
good enough for this code base's style (clang-format, one definition per signature)."""
import argparse
import os
import re
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
SRC = os.path.join(ROOT, "src")


def sources():
    for d, _, files in os.walk(SRC):
        for f in sorted(files):
            if f.endswith((".cpp", ".hpp")):
                yield os.path.relpath(os.path.join(d, f), ROOT)


def strip(text):
    """Comments, strings and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = ")" + m.group(1) + '"'
            j = text.find(end, i) + len(end)
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def statement_before(text, i):
    """Start of the statement that the `{` at `i` ends: back to the previous ; { or } outside
    parentheses (a default argument `= {}` belongs to the signature)."""
    depth, j = 0, i - 1
    while j >= 0:
        c = text[j]
        if c == ")":
            depth += 1
        elif c == "(":
            depth -= 1
        elif depth <= 0 and c in ";{}":
            return j + 1
        j -= 1
    return 0


SIGNATURE = re.compile(r"\)\s*(const|override|final|noexcept|mutable|->\s*[\w:<>&*, ]+|\s|:[^;]*)*$")
# A brace initializer in a constructor's member initializer list: `) : a_{x}` or `, b_{y}`.
INIT_LIST_START = re.compile(r"\)\s*(const\s*|noexcept\s*)*:\s*[^;]*[\w>]\s*$")
NAME = re.compile(r"((?:[~\w]+::)*operator\s*(?:\(\s*\)|[^\s(]+)|[~\w:]+(?:<[^()<>]*>)?)\s*\(")


def functions(path):
    text = strip(open(os.path.join(ROOT, path)).read())
    lines = text.split("\n")
    line_of = []
    for k, line in enumerate(lines):
        line_of.extend([k + 1] * (len(line) + 1))
    found, stack = [], []
    # stack entries: (kind, start line, name); kind "fn", "init" (a constructor's brace
    # initializer, carrying the constructor's start and name) or "scope"
    ctor = None  # (end of the last closed "init" brace, start line, name)
    for m in re.finditer(r"[{}]", text):
        i = m.start()
        if text[i] == "{":
            inside_fn = any(k == "fn" for k, _, _ in stack)
            cut = statement_before(text, i)
            stmt = text[cut:i]
            start_pos = cut + (len(stmt) - len(stmt.lstrip()))
            if inside_fn:
                stack.append(("scope", 0, ""))
                continue
            if ctor and cut == ctor[0] and re.fullmatch(r"[\s,\w:<>()&*.\[\]+-]*", stmt):
                # after a brace initializer: another one, or the constructor's body
                kind = "init" if re.search(r"[\w>]\s*$", stmt) else "fn"
                stack.append((kind, ctor[1], ctor[2]))
                continue
            head = stmt.split("(")[0] + "("
            plausible = (not re.match(r"\s*(namespace|class|struct|enum|union)\b", stmt)
                         and not re.search(r"\b(if|for|while|switch|catch)\s*\(", head))
            name = NAME.search(stmt)
            name = (re.sub(r"\s+", "", name.group(1)) if name else "(lambda)" if "[" in stmt else "?")
            if plausible and INIT_LIST_START.search(stmt):
                stack.append(("init", line_of[start_pos], name))
            elif plausible and SIGNATURE.search(stmt):
                stack.append(("fn", line_of[start_pos], name))
            else:
                stack.append(("scope", 0, ""))
        else:
            if not stack:
                continue
            kind, start, name = stack.pop()
            ctor = (i + 1, start, name) if kind == "init" else None
            if kind == "fn":
                found.append((line_of[i] - start + 1, path, start, name))
    return found


# The config mapping: the generic reader/writer of the field tables and the config's own rules.
# Not counted: the tables (beside each options struct), the strict JSON parser (io/json_text.*),
# the words of messages (core/spelling.*) and the reference generator (config/reference.*).
MAPPING = ["src/io/options_json.hpp", "src/io/options_json.cpp",
           "src/config/config.hpp", "src/config/config.cpp"]


def code_lines(path):
    """Lines that hold code: neither blank nor only a comment."""
    return sum(1 for line in strip(open(os.path.join(ROOT, path)).read()).split("\n")
               if line.strip())


def include_graph():
    graph = {}
    for path in sources():
        if not path.endswith(".hpp"):
            continue
        rel = os.path.relpath(path, "src")
        graph[rel] = re.findall(r'^#include "([^"]+)"', open(os.path.join(ROOT, path)).read(), re.M)
    return graph


def reaches(graph, a, b, seen=None):
    seen = seen if seen is not None else set()
    for h in graph.get(a, []):
        if h == b:
            return True
        if h not in seen:
            seen.add(h)
            if reaches(graph, h, b, seen):
                return True
    return False


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--top", type=int, default=5)
    p.add_argument("--module", default="pipeline", help="module whose headers are checked")
    a = p.parse_args()
    files = sorted(((sum(1 for _ in open(os.path.join(ROOT, f))), f) for f in sources()),
                   reverse=True)
    print("largest source files in src/ (lines):")
    for n, f in files[: a.top]:
        print(f"  {n:5d}  {f}")
    fns = sorted((fn for f in sources() for fn in functions(f)), reverse=True)
    print("longest functions in src/ (lines, signature to closing brace):")
    for n, f, line, name in fns[: a.top]:
        print(f"  {n:5d}  {f}:{line}  {name}")
    counts = [(code_lines(f), f) for f in MAPPING]
    print(f"config mapping: {sum(n for n, _ in counts)} lines of code ("
          + ", ".join(f"{os.path.basename(f)} {n}" for n, f in counts) + ")")
    graph = include_graph()
    cycles = []
    for h in sorted(graph):
        if not h.startswith(a.module + "/"):
            continue
        for inc in graph[h]:
            if reaches(graph, inc, h):
                cycles.append((h, inc))
    print(f"{a.module}/ headers that include one that includes them back: "
          + (", ".join(f"{h} <-> {i}" for h, i in cycles) if cycles else "none"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
