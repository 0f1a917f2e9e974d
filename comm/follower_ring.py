#!/usr/bin/env python3
"""Writes comm/follower_ring.mail: a quarter of a thick ring for the
follower-pressure scene (comm/follower_ring.comm).

Plane strain, inner radius A = 1, outer radius B = 2, angle 0 to 90 deg;
NR x NT QUAD8 cells, the middle nodes on the exact circles and radii.
Groups (cells): RING (the quadrangles), INNER (the SEG3 edges on r = A);
(nodes): X0 (on x = 0), Y0 (on y = 0), OUTER (on r = B), PA (r = A, y = 0), PB (r = B,
y = 0), PC (r = A, x = 0). Usage:
    python3 comm/follower_ring.py > comm/follower_ring.mail
"""
import math

A, B, NR, NT = 1.0, 2.0, 8, 12


def main():
    # Node grid (2 NR + 1) x (2 NT + 1) in (r, theta); the centre of each
    # cell is not used by QUAD8.
    names, coords = {}, []
    for j in range(2 * NT + 1):
        for i in range(2 * NR + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            r = A + (B - A) * i / (2 * NR)
            t = 0.5 * math.pi * j / (2 * NT)
            x, y = r * math.cos(t), r * math.sin(t)
            if j == 2 * NT:
                x = 0.0
            if j == 0:
                y = 0.0
            names[(i, j)] = f"N{i}_{j}"
            coords.append((names[(i, j)], x, y))
    out = [
        "% A quarter of a thick ring (A = 1, B = 2), QUAD8, written for the aster",
        "% project by comm/follower_ring.py (see there for the groups).",
        "TITRE",
        " quarter ring",
        "FINSF",
        "COOR_2D",
    ]
    out += [f"  {n}  {x:.15f}  {y:.15f}" for n, x, y in coords]
    out.append("FINSF")
    out.append("QUAD8")
    cells = []
    for j in range(NT):
        for i in range(NR):
            i0, j0 = 2 * i, 2 * j
            corners = [(i0, j0), (i0 + 2, j0), (i0 + 2, j0 + 2), (i0, j0 + 2)]
            mids = [(i0 + 1, j0), (i0 + 2, j0 + 1), (i0 + 1, j0 + 2), (i0, j0 + 1)]
            name = f"Q{i}_{j}"
            cells.append(name)
            out.append(f"  {name} " + " ".join(names[k] for k in corners + mids))
    out.append("FINSF")
    out.append("SEG3")
    inner = []
    for j in range(NT):
        # Ordered with decreasing theta: the segment's own normal then
        # points out of the ring; aster and ORIE_PEAU orient it anyway.
        name = f"S{j}"
        inner.append(name)
        out.append(f"  {name} {names[(0, 2 * j + 2)]} {names[(0, 2 * j)]} {names[(0, 2 * j + 1)]}")
    out.append("FINSF")

    def group(kind, name, members):
        out.append(kind)
        out.append(f"  {name}")
        for k in range(0, len(members), 8):
            out.append("  " + " ".join(members[k:k + 8]))
        out.append("FINSF")

    group("GROUP_MA", "RING", cells)
    group("GROUP_MA", "INNER", inner)
    group("GROUP_NO", "X0", [names[(i, 2 * NT)] for i in range(2 * NR + 1)])
    group("GROUP_NO", "Y0", [names[(i, 0)] for i in range(2 * NR + 1)])
    group("GROUP_NO", "OUTER", [names[(2 * NR, j)] for j in range(2 * NT + 1)])
    group("GROUP_NO", "PA", [names[(0, 0)]])
    group("GROUP_NO", "PB", [names[(2 * NR, 0)]])
    group("GROUP_NO", "PC", [names[(0, 2 * NT)]])
    out.append("FIN")
    print("\n".join(out))


main()
