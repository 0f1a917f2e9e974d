#!/usr/bin/env python3
"""Writes comm/cattaneo.mail: the frictional Hertz (Cattaneo-Mindlin) scene.

Plane strain. Upper body UP: x in [-L, L], bottom y = x^2 / (2 R) (the
parabolic profile Hertz's theory gives a cylinder of radius R), top y = H.
Lower body LOW: [-L, L] x [-H, 0] (the flat). Both bodies meshed with QUAD4,
uniform cells of size h over |x| <= XF (the contact zone, a ~ 1) growing
geometrically outside, and rows growing from h at the interface to H.

Groups (cells): UP, LOW, ESCL (bottom of UP, slave), MAIT (top of LOW,
master), TOP (top of UP), BOT (bottom of LOW). Usage:
    python3 comm/cattaneo_mesh.py [h] > comm/cattaneo.mail
"""
import sys

R, L, H, XF = 50.0, 10.0, 10.0, 1.5


def graded(start, length, h, ratio=1.15):
    """Sizes growing from h by `ratio`, scaled to fill `length` exactly."""
    sizes, total = [], 0.0
    s = h
    while total + s < length:
        sizes.append(s)
        total += s
        s *= ratio
    scale = length / total if total > 0 else 1.0
    pos, out = start, [start]
    for s in sizes:
        pos += s * scale
        out.append(pos)
    out[-1] = start + length
    return out


def columns(h):
    n = max(1, round(2 * XF / h))
    fine = [-XF + 2 * XF * i / n for i in range(n + 1)]
    right = graded(XF, L - XF, 2 * XF / n)
    left = [-x for x in reversed(right)]
    return left[:-1] + fine + right[1:]


def main():
    h = float(sys.argv[1]) if len(sys.argv) > 1 else 0.05
    xs = columns(h)
    rows = graded(0.0, H, h, ratio=1.2)  # 0 .. H, fine at 0
    nodes, cells, groups = [], [], {k: [] for k in ("UP", "LOW", "ESCL", "MAIT", "TOP", "BOT")}
    nx, ny = len(xs), len(rows)

    def body(coord, flip):
        base = len(nodes)
        for j in range(ny):
            for i in range(nx):
                nodes.append(coord(xs[i], rows[j]))
        idx = lambda i, j: base + j * nx + i + 1
        quads = []
        for j in range(ny - 1):
            for i in range(nx - 1):
                q = [idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)]
                if flip:  # rows go downward: keep counter-clockwise order
                    q = [q[0], q[3], q[2], q[1]]
                quads.append(q)
        near = [(idx(i, 0), idx(i + 1, 0)) for i in range(nx - 1)]
        far = [(idx(i + 1, ny - 1), idx(i, ny - 1)) for i in range(nx - 1)]
        return quads, near, far

    up_q, up_near, up_far = body(lambda x, s: (x, x * x / (2 * R) + s * (1 - x * x / (2 * R) / H)), False)
    lo_q, lo_near, lo_far = body(lambda x, s: (x, -s), True)
    out = ["TITRE", "Cattaneo-Mindlin scene, h = %g (comm/cattaneo_mesh.py)" % h, "FINSF", "%", "COOR_2D"]
    out += ["N%d %.17g %.17g" % (k + 1, x, y) for k, (x, y) in enumerate(nodes)]
    out += ["FINSF", "%"]
    m = 0

    def emit(kind, conn, group):
        nonlocal m
        out.append(kind)
        for c in conn:
            m += 1
            out.append("M%d " % m + " ".join("N%d" % n for n in c))
            groups[group].append(m)
        out.extend(["FINSF", "%"])

    emit("QUAD4", up_q, "UP")
    emit("QUAD4", lo_q, "LOW")
    emit("SEG2", up_near, "ESCL")
    # the lower body's near row, oriented so its outward normal points up
    emit("SEG2", [(b, a) for a, b in lo_near], "MAIT")
    emit("SEG2", up_far, "TOP")
    emit("SEG2", [(b, a) for a, b in lo_far], "BOT")
    for name, members in groups.items():
        out.append("GROUP_MA NOM=%s" % name)
        for k in range(0, len(members), 8):
            out.append(" ".join("M%d" % c for c in members[k:k + 8]))
        out.extend(["FINSF", "%"])
    out.append("FIN")
    print("\n".join(out))


main()
