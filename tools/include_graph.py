#!/usr/bin/env python3
"""Print the include graph of src/ by folder and the arrows that point back up.

A unit is a header/source pair (x.hpp + x.cpp); an arrow A -> B means a file of unit A includes
"B.hpp" (quoted, relative to src/). Inside one folder the units must form a graph without cycles:
an arrow is printed as pointing back up when its two units are in one strongly connected
component, i.e. each reaches the other. Between folders the same is done on the folder graph.

Usage: python3 tools/include_graph.py [--src src] [--edges] [--check]
  --edges  also print every folder -> folder arrow with its count
  --check  exit 1 when any arrow points back up (inside a folder or between folders)
"""
import argparse
import collections
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def units(src):
    """{unit: set of included units} for every .hpp/.cpp under src, units relative to src."""
    graph = collections.defaultdict(set)
    for root, _, files in os.walk(src):
        for name in files:
            stem, ext = os.path.splitext(name)
            if ext not in ('.hpp', '.cpp'):
                continue
            path = os.path.join(root, name)
            unit = os.path.relpath(os.path.join(root, stem), src)
            graph[unit]
            with open(path, encoding='utf-8') as f:
                for inc in INCLUDE.findall(f.read()):
                    target = os.path.splitext(inc)[0]
                    if target != unit and os.path.exists(os.path.join(src, inc)):
                        graph[unit].add(target)
    return graph


def strongly_connected(nodes, edges):
    """Tarjan's algorithm, iterative: {node: component id}."""
    index, low, comp, stack, on = {}, {}, {}, [], set()
    counter = [0]
    for start in sorted(nodes):
        if start in index:
            continue
        work = [(start, iter(sorted(edges.get(start, ()))))]
        index[start] = low[start] = counter[0]; counter[0] += 1
        stack.append(start); on.add(start)
        while work:
            node, it = work[-1]
            advanced = False
            for nxt in it:
                if nxt not in nodes:
                    continue
                if nxt not in index:
                    index[nxt] = low[nxt] = counter[0]; counter[0] += 1
                    stack.append(nxt); on.add(nxt)
                    work.append((nxt, iter(sorted(edges.get(nxt, ())))))
                    advanced = True
                    break
                if nxt in on:
                    low[node] = min(low[node], index[nxt])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                while True:
                    top = stack.pop(); on.discard(top)
                    comp[top] = node
                    if top == node:
                        break
    return comp


def back_arrows(nodes, edges):
    comp = strongly_connected(nodes, edges)
    return sorted((a, b) for a in nodes for b in edges.get(a, ())
                  if b in nodes and comp[a] == comp[b])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--src', default=os.path.join(os.path.dirname(__file__), '..', 'src'))
    parser.add_argument('--edges', action='store_true')
    parser.add_argument('--check', action='store_true')
    args = parser.parse_args()
    graph = units(args.src)

    folders = collections.defaultdict(set)
    for unit in graph:
        folders[os.path.dirname(unit)].add(unit)
    total = 0
    print('arrows pointing back up inside each folder (units in one cycle):')
    for folder in sorted(folders):
        nodes = folders[folder]
        back = back_arrows(nodes, graph)
        total += len(back)
        print(f'  {folder}/ ({len(nodes)} units): {len(back)}')
        for a, b in back:
            print(f'    {os.path.basename(a)} -> {os.path.basename(b)}')

    fedges = collections.defaultdict(collections.Counter)
    for unit, deps in graph.items():
        for dep in deps:
            fa, fb = os.path.dirname(unit), os.path.dirname(dep)
            if fa != fb:
                fedges[fa][fb] += 1
    fback = back_arrows(set(folders), {k: set(v) for k, v in fedges.items()})
    print(f'arrows pointing back up between folders: {len(fback)}')
    for a, b in fback:
        print(f'  {a}/ -> {b}/ ({fedges[a][b]} includes)')
    if args.edges:
        print('folder -> folder arrows (count of unit arrows):')
        for fa in sorted(fedges):
            for fb in sorted(fedges[fa]):
                print(f'  {fa}/ -> {fb}/ {fedges[fa][fb]}')
    total += len(fback)
    return 1 if args.check and total else 0


if __name__ == '__main__':
    sys.exit(main())
