#!/usr/bin/env python3
"""METIS's nested dissection (METIS_NodeND through pymetis) of a graph in
METIS's text format ("n m", then each vertex's 1-based neighbours), written as
the elimination order, one 0-based vertex per line.

    metis_order.py GRAPH ORDER

Exits 3 (with a message) when pymetis is not installed (`pip install
pymetis`): an optional reference, never needed to build or test aster.
"""

import sys
import time


def main():
    try:
        import pymetis
    except ImportError:
        print("metis_order: pymetis is not installed (pip install pymetis): skipped")
        sys.exit(3)
    graph, out = sys.argv[1], sys.argv[2]
    with open(graph) as f:
        n, _ = map(int, f.readline().split())
        xadj, adjncy = [0], []
        for _ in range(n):
            adjncy.extend(int(t) - 1 for t in f.readline().split())
            xadj.append(len(adjncy))
    t = time.time()
    perm, _iperm = pymetis.nested_dissection(pymetis.CSRAdjacency(xadj, adjncy))
    print(f"METIS_NodeND: {n} vertices in {time.time() - t:.2f} s")
    with open(out, "w") as f:
        f.write("".join(f"{v}\n" for v in perm))


if __name__ == "__main__":
    main()
