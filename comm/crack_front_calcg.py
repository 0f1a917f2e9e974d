"""Writes comm/crack_front_calcg.mail (for comm/crack_front_calcg.comm).

Half of a centre-cracked plate (crack 2a = 2, width 2b = 20, height
2h = 20) extruded over a thickness 0.2 in z: x in [0, 10], y in [-10, 10],
the crack on y = 0 for x < 1, its front the line x = 1, y = 0 (5 nodes,
4 SEG2). HEXA8 cells graded towards the front (0.05 there); the nodes of
the crack (y = 0, x < 1) are doubled, the lower cells holding the copies.

Run: python3 comm/crack_front_calcg.py > comm/crack_front_calcg.mail
"""

XL = [0.0, 0.25, 0.5, 0.65, 0.75, 0.85, 0.9, 0.95]
XTIP = 1.0
XR = [1.05, 1.1, 1.15, 1.25, 1.35, 1.5, 1.75, 2.0, 2.5, 3.0, 4.0, 5.5, 7.5, 10.0]
XS = XL + [XTIP] + XR
YP = [0.05, 0.1, 0.15, 0.25, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.5, 6.5, 10.0]
YS = [-y for y in reversed(YP)] + [0.0] + YP
ZS = [0.0, 0.05, 0.1, 0.15, 0.2]
ITIP = len(XL)
J0 = len(YP)

nodes = {}
coords = []


def node(key, x, y, z):
    nodes[key] = len(coords) + 1
    coords.append((x, y, z))


for k, z in enumerate(ZS):
    for j, y in enumerate(YS):
        for i, x in enumerate(XS):
            node((i, j, k, 0), x, y, z)
    for i in range(ITIP):
        node((i, J0, k, 1), XS[i], 0.0, ZS[k])


def n(i, j, k, lower=False):
    """The node (i, j, k); on the crack, the lower cells' copy."""
    if lower and j == J0 and i < ITIP:
        return nodes[(i, j, k, 1)]
    return nodes[(i, j, k, 0)]


hexa = []
for k in range(len(ZS) - 1):
    for j in range(len(YS) - 1):
        lower = j + 1 == J0
        for i in range(len(XS) - 1):
            c = [
                n(i, j, k),
                n(i + 1, j, k),
                n(i + 1, j + 1, k, lower),
                n(i, j + 1, k, lower),
            ]
            c += [
                n(i, j, k + 1),
                n(i + 1, j, k + 1),
                n(i + 1, j + 1, k + 1, lower),
                n(i, j + 1, k + 1, lower),
            ]
            hexa.append(c)

quads = {"TOP": [], "BOT": [], "LIP_SUP": [], "LIP_INF": []}
for k in range(len(ZS) - 1):
    for i in range(len(XS) - 1):
        jt = len(YS) - 1
        quads["TOP"].append([n(i, jt, k), n(i, jt, k + 1), n(i + 1, jt, k + 1), n(i + 1, jt, k)])
        quads["BOT"].append([n(i, 0, k), n(i + 1, 0, k), n(i + 1, 0, k + 1), n(i, 0, k + 1)])
        if i < ITIP:
            quads["LIP_SUP"].append(
                [n(i, J0, k), n(i + 1, J0, k), n(i + 1, J0, k + 1), n(i, J0, k + 1)]
            )
            quads["LIP_INF"].append(
                [
                    n(i, J0, k, True),
                    n(i, J0, k + 1, True),
                    n(i + 1, J0, k + 1, True),
                    n(i + 1, J0, k, True),
                ]
            )
segs = [[n(ITIP, J0, k), n(ITIP, J0, k + 1)] for k in range(len(ZS) - 1)]

out = []
out.append("TITRE")
out.append(
    "half of a centre-cracked plate extruded in z (crack 2a = 2, width 2b = 20, height 2h = 20, thickness 0.2),"
)
out.append(
    "HEXA8 graded towards the front (x = 1, y = 0, 0 <= z <= 0.2, 5 nodes); both lips meshed; written by comm/crack_front_calcg.py"
)
out.append("FINSF")
out.append("%")
out.append("COOR_3D")
for idx, (x, y, z) in enumerate(coords):
    out.append(f"N{idx + 1} {x!r} {y!r} {z!r}")
out.append("FINSF")
out.append("%")
out.append("HEXA8")
for idx, c in enumerate(hexa):
    out.append(f"H{idx + 1} " + " ".join(f"N{v}" for v in c))
out.append("FINSF")
out.append("%")
out.append("QUAD4")
names = {}
q = 0
for g, faces in quads.items():
    names[g] = []
    for c in faces:
        q += 1
        names[g].append(f"Q{q}")
        out.append(f"Q{q} " + " ".join(f"N{v}" for v in c))
out.append("FINSF")
out.append("%")
out.append("SEG2")
for idx, c in enumerate(segs):
    out.append(f"S{idx + 1} N{c[0]} N{c[1]}")
out.append("FINSF")
out.append("%")


def group(kind, name, members):
    out.append(kind)
    out.append(name)
    for s in range(0, len(members), 8):
        out.append(" ".join(members[s : s + 8]))
    out.append("FINSF")
    out.append("%")


group("GROUP_MA", "VOL", [f"H{i + 1}" for i in range(len(hexa))])
for g in quads:
    group("GROUP_MA", g, names[g])
group("GROUP_MA", "FRONT", [f"S{i + 1}" for i in range(len(segs))])
left = [f"N{v}" for key, v in nodes.items() if key[0] == 0]
group("GROUP_NO", "LEFT", left)
group("GROUP_NO", "ORIG", [f"N{n(ITIP, J0, 0)}"])
group("GROUP_NO", "EXTR", [f"N{n(ITIP, J0, len(ZS) - 1)}"])
group("GROUP_NO", "C", [f"N{n(len(XS) - 1, J0, 0)}"])
out.append("FIN")
print("\n".join(out))
