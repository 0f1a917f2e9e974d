"""Writes the meshes of the project's PESANTEUR, FORCE_ARETE and
LIAISON_OBLIQUE scenes (written for the aster project):

- gravity_column.mail: a 1 x 1 x 10 column of 5 HEXA8 along z, its base
  BASE and top TOP (QUAD4), the top face's 4 edges TOPEDGES (SEG2), the
  nodes A (0, 0, 0), B (1, 0, 0), MID (0, 0, 4), TIP (0, 0, 10).
- gravity_strip.mail: a 1 x 10 strip of 5 QUAD4 along y, its base BASE
  (SEG2), the nodes A (0, 0), B (1, 0), MID (0, 4), TIP (0, 10).
- edge_strip.mail: a 10 x 1 strip of 5 QUAD4 in the plane z = 0 (x along
  the strip), its free end END (one SEG2 at x = 10), the clamped nodes
  CLAMP (x = 0), the tip node TIP (10, 0, 0).
- oblique_block.mail: a 2 x 1 block of 2 x 2 QUAD4 in its own frame
  (t, n), turned by 30 degrees: x = t cos30 - n sin30, y = t sin30 +
  n cos30; its base BASE (n = 0) and top TOP (n = 1) as SEG2, the nodes
  A (t, n) = (0, 0), B (2, 0), C (2, 1).

python3 comm/loads_more_meshes.py (from the repository root).
"""
import math


def write(path, title, dim, nodes, cells, groups_ma, groups_no):
    out = ["TITRE", f" {title}", "FINSF", f"COOR_{dim}D"]
    for name, xyz in nodes:
        out.append(f"  {name} " + " ".join(f"{v:.15g}" for v in xyz))
    out.append("FINSF")
    for ty in dict.fromkeys(ty for _, ty, _ in cells):
        out.append(ty)
        for name, t, conn in cells:
            if t == ty:
                out.append(f"  {name} " + " ".join(conn))
        out.append("FINSF")
    for g, names in groups_ma.items():
        out += [f"GROUP_MA NOM={g}", "  " + " ".join(names), "FINSF"]
    for g, names in groups_no.items():
        out += [f"GROUP_NO NOM={g}", "  " + " ".join(names), "FINSF"]
    out.append("FIN")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def column():
    nz, h = 5, 2.0
    nodes, cells = [], []
    corner = [(0, 0), (1, 0), (1, 1), (0, 1)]
    n = lambda k, c: f"N{k}_{c}"
    for k in range(nz + 1):
        for c, (x, y) in enumerate(corner):
            nodes.append((n(k, c), (x, y, k * h)))
    for k in range(nz):
        conn = [n(k, c) for c in range(4)] + [n(k + 1, c) for c in range(4)]
        cells.append((f"H{k + 1}", "HEXA8", conn))
    cells.append(("BASE1", "QUAD4", [n(0, c) for c in (0, 3, 2, 1)]))
    cells.append(("TOP1", "QUAD4", [n(nz, c) for c in range(4)]))
    for c in range(4):
        cells.append((f"E{c + 1}", "SEG2", [n(nz, c), n(nz, (c + 1) % 4)]))
    write(
        "comm/gravity_column.mail",
        "a 1 x 1 x 10 column of HEXA8 (loads_more_meshes.py)",
        3,
        nodes,
        cells,
        {
            "COL": [f"H{k + 1}" for k in range(nz)],
            "BASE": ["BASE1"],
            "TOP": ["TOP1"],
            "TOPEDGES": [f"E{c + 1}" for c in range(4)],
        },
        {"A": [n(0, 0)], "B": [n(0, 1)], "MID": [n(2, 0)], "TIP": [n(nz, 0)]},
    )


def strip2d():
    ny, h = 5, 2.0
    n = lambda k, c: f"N{k}_{c}"
    nodes = [(n(k, c), (float(c), k * h)) for k in range(ny + 1) for c in range(2)]
    cells = [
        (f"Q{k + 1}", "QUAD4", [n(k, 0), n(k, 1), n(k + 1, 1), n(k + 1, 0)])
        for k in range(ny)
    ]
    cells.append(("S1", "SEG2", [n(0, 0), n(0, 1)]))
    write(
        "comm/gravity_strip.mail",
        "a 1 x 10 strip of QUAD4 (loads_more_meshes.py)",
        2,
        nodes,
        cells,
        {"STRIP": [f"Q{k + 1}" for k in range(ny)], "BASE": ["S1"]},
        {"A": [n(0, 0)], "B": [n(0, 1)], "MID": [n(2, 0)], "TIP": [n(ny, 0)]},
    )


def edge_strip():
    nx, h = 5, 2.0
    n = lambda i, j: f"N{i}_{j}"
    nodes = [(n(i, j), (i * h, float(j), 0.0)) for j in range(2) for i in range(nx + 1)]
    cells = [
        (f"Q{i + 1}", "QUAD4", [n(i, 0), n(i + 1, 0), n(i + 1, 1), n(i, 1)])
        for i in range(nx)
    ]
    cells.append(("S1", "SEG2", [n(nx, 0), n(nx, 1)]))
    write(
        "comm/edge_strip.mail",
        "a 10 x 1 strip of QUAD4 shells (loads_more_meshes.py)",
        3,
        nodes,
        cells,
        {"STRIP": [f"Q{i + 1}" for i in range(nx)], "END": ["S1"]},
        {"CLAMP": [n(0, 0), n(0, 1)], "TIP": [n(nx, 0)]},
    )


def oblique_block():
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    n = lambda i, j: f"N{i}_{j}"
    nodes = []
    for j in range(3):
        for i in range(3):
            t, nn = i * 1.0, j * 0.5
            nodes.append((n(i, j), (t * c - nn * s, t * s + nn * c)))
    cells = [
        (f"Q{i + 1}{j + 1}", "QUAD4", [n(i, j), n(i + 1, j), n(i + 1, j + 1), n(i, j + 1)])
        for j in range(2)
        for i in range(2)
    ]
    cells += [(f"B{i + 1}", "SEG2", [n(i, 0), n(i + 1, 0)]) for i in range(2)]
    cells += [(f"T{i + 1}", "SEG2", [n(i + 1, 2), n(i, 2)]) for i in range(2)]
    write(
        "comm/oblique_block.mail",
        "a 2 x 1 block of QUAD4 turned by 30 degrees (loads_more_meshes.py)",
        2,
        nodes,
        cells,
        {
            "BLOCK": [f"Q{i + 1}{j + 1}" for j in range(2) for i in range(2)],
            "BASE": ["B1", "B2"],
            "TOP": ["T1", "T2"],
        },
        {"A": [n(0, 0)], "B": [n(2, 0)], "C": [n(2, 2)]},
    )


column()
strip2d()
edge_strip()
oblique_block()
