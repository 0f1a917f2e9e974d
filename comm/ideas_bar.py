"""Writes comm/ideas_bar.unv, the I-DEAS universal file of comm/ideas_bar.comm
(written for the aster project): a bar [0, 2] x [0, 1] x [0, 1] of two HEXA20
(descriptor 116), its end face x = 2 as a QUAD8 (descriptor 95), the edge
y = z = 0, x in [0, 1] as a SEG3 (descriptor 22, with its beam record), in
I-DEAS node order (inistb's permutations inverted); node labels 10 + 3 k
in lattice order, element labels 5, 9, 20, 21; groups in dataset 2467."""

import itertools

pts = []
for i, j, k in itertools.product(range(5), range(3), range(3)):
    if (i % 2) + (j % 2) + (k % 2) <= 1:
        pts.append((i, j, k))
label = {p: 10 + 3 * n for n, p in enumerate(pts)}


def node(x2, y2, z2):
    """The label of the lattice point at twice the coordinates."""
    return label[(x2, y2, z2)]


def hexa20(x0):
    """code_aster's HEXA20 of [x0, x0 + 1] x [0, 1] x [0, 1] (half steps)."""
    a = 2 * x0
    c = [(a, 0, 0), (a + 2, 0, 0), (a + 2, 2, 0), (a, 2, 0),
         (a, 0, 2), (a + 2, 0, 2), (a + 2, 2, 2), (a, 2, 2)]
    edges = [(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 5), (2, 6), (3, 7),
             (4, 5), (5, 6), (6, 7), (7, 4)]
    mids = [tuple((c[p][d] + c[q][d]) // 2 for d in range(3)) for p, q in edges]
    return [node(*p) for p in c + mids]


def ideas_order(aster, permut):
    """I-DEAS node i is code_aster node permut[i]."""
    return [aster[p - 1] for p in permut]


H20 = [1, 9, 2, 10, 3, 11, 4, 12, 13, 14, 15, 16, 5, 17, 6, 18, 7, 19, 8, 20]
Q8 = [1, 5, 2, 6, 3, 7, 4, 8]
S3 = [1, 3, 2]

quad8 = [node(4, 0, 0), node(4, 2, 0), node(4, 2, 2), node(4, 0, 2),
         node(4, 1, 0), node(4, 2, 1), node(4, 1, 2), node(4, 0, 1)]
seg3 = [node(0, 0, 0), node(2, 0, 0), node(1, 0, 0)]

out = []
w = out.append
w("    -1\n   151\nideas_bar: two HEXA20 in series\nwritten for the aster project\n"
  "I-DEAS universal file\n    -1\n")
# Units: millimetres declared; code_aster does not apply them.
w("    -1\n   164\n         2  mm (milli-newton)            2\n"
  "  1.00000000000000000D+03  1.00000000000000000D+03  1.00000000000000000D+00\n"
  "  2.73149999999999980D+02\n    -1\n")
w("    -1\n  2420\n         1\nPart1\n         1         0         8\nCS1\n")
for row in ("   1.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00",
            "   0.0000000000000000D+00   1.0000000000000000D+00   0.0000000000000000D+00",
            "   0.0000000000000000D+00   0.0000000000000000D+00   1.0000000000000000D+00",
            "   0.0000000000000000D+00   0.0000000000000000D+00   0.0000000000000000D+00"):
    w(row + "\n")
w("    -1\n    -1\n  2411\n")
for p in pts:
    w("%10d%10d%10d%10d\n" % (label[p], 1, 1, 11))
    w("".join("%25.16E" % (v / 2.0) for v in p).replace("E", "D") + "\n")
w("    -1\n    -1\n  2412\n")


def element(lab, desc, nodes, beam=False):
    w("%10d%10d%10d%10d%10d%10d\n" % (lab, desc, 1, 1, 7, len(nodes)))
    if beam:
        w("%10d%10d%10d\n" % (0, 1, 1))
    for k in range(0, len(nodes), 8):
        w("".join("%10d" % n for n in nodes[k:k + 8]) + "\n")


element(5, 116, ideas_order(hexa20(0), H20))
element(9, 116, ideas_order(hexa20(1), H20))
element(20, 95, ideas_order(quad8, Q8))
element(21, 22, ideas_order(seg3, S3), beam=True)
w("    -1\n    -1\n  2467\n")


def group(number, name, entities):
    w("%10d%10d%10d%10d%10d%10d%10d%10d\n" % (number, 0, 0, 0, 0, 0, 0, len(entities)))
    w(name + "\n")
    for k in range(0, len(entities), 2):
        w("".join("%10d%10d%10d%10d" % (t, n, 0, 0) for t, n in entities[k:k + 2]) + "\n")


def nodes_at(test):
    return [(7, label[p]) for p in pts if test(p)]


group(1, "LEFTSIDE_NODES", nodes_at(lambda p: p[0] == 0))
group(2, "BOTTOM", nodes_at(lambda p: p[1] == 0))
group(3, "BACK", nodes_at(lambda p: p[2] == 0))
group(4, "MID.PLANE", nodes_at(lambda p: p[0] == 2))
group(5, "END", [(8, 20)] + nodes_at(lambda p: p[0] == 4))
group(6, "SOFT", [(8, 5)])
group(7, "PERMANENT GROUP 7", [(8, 9)])
group(8, "EDGE", [(8, 21)])
w("    -1\n")
open("ideas_bar.unv", "w").write("".join(out))
