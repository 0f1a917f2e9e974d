"""Meshes of comm/beam_sections.comm (written for the aster project).

- beam_section_rect.mail: a 0.1 x 0.05 m rectangle, 20 x 10 QUAD4, corner
  at the origin; BORD (its border, SEG2, counter-clockwise), P1 (a corner).
- beam_section_tube.mail: a circular tube of mean radius 0.1 m and wall
  0.01 m centred at the origin, 2 x 48 QUAD8; LEXT, LINT (the outer and
  inner borders, SEG3), P1 (a node of the outer border).

Run: python3 comm/beam_sections_mesh.py (writes both files beside it).
"""

import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def write(path, title, nodes, cells, groups_ma, groups_no):
    with open(path, "w") as f:
        f.write(f"% {title} (written for the aster project; comm/beam_sections_mesh.py)\n")
        f.write("TITRE\n " + title + "\nFINSF\nCOOR_2D\n")
        for i, (x, y) in enumerate(nodes):
            f.write(f"  N{i + 1} {x:.15e} {y:.15e}\n")
        f.write("FINSF\n")
        by_type = {}
        for name, ty, conn in cells:
            by_type.setdefault(ty, []).append((name, conn))
        for ty, cs in by_type.items():
            f.write(ty + "\n")
            for name, conn in cs:
                f.write(f"  {name} " + " ".join(f"N{n + 1}" for n in conn) + "\n")
            f.write("FINSF\n")
        for g, members in groups_ma.items():
            f.write("GROUP_MA\n" + g + "\n  " + " ".join(members) + "\nFINSF\n")
        for g, members in groups_no.items():
            f.write("GROUP_NO\n" + g + "\n  " + " ".join(f"N{n + 1}" for n in members) + "\nFINSF\n")
        f.write("FIN\n")


def rectangle():
    b, h, nx, ny = 0.1, 0.05, 20, 10
    nodes = [(b * i / nx, h * j / ny) for j in range(ny + 1) for i in range(nx + 1)]
    nid = lambda i, j: j * (nx + 1) + i
    cells = []
    for j in range(ny):
        for i in range(nx):
            conn = [nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)]
            cells.append((f"Q{len(cells) + 1}", "QUAD4", conn))
    loop = [(i, 0) for i in range(nx)] + [(nx, j) for j in range(ny)]
    loop += [(i, ny) for i in range(nx, 0, -1)] + [(0, j) for j in range(ny, 0, -1)]
    bord = []
    for k, (i, j) in enumerate(loop):
        a, c = loop[k], loop[(k + 1) % len(loop)]
        name = f"S{len(bord) + 1}"
        cells.append((name, "SEG2", [nid(*a), nid(*c)]))
        bord.append(name)
    write(os.path.join(HERE, "beam_section_rect.mail"), "rectangle 0.1 x 0.05",
          nodes, cells, {"BORD": bord}, {"P1": [nid(0, 0)]})


def tube():
    rm, t, nr, nt = 0.1, 0.01, 2, 48
    ri = rm - t / 2
    # Rings of corner nodes at 2*nr+1 radii (corners and mid-side radii).
    radii = [ri + t * k / (2 * nr) for k in range(2 * nr + 1)]
    nodes, index = [], {}
    for k, r in enumerate(radii):
        for m in range(2 * nt):
            if k % 2 == 1 and m % 2 == 1:
                continue  # QUAD8: no centre node
            a = 2 * math.pi * m / (2 * nt)
            index[(k, m)] = len(nodes)
            nodes.append((r * math.cos(a), r * math.sin(a)))
    at = lambda k, m: index[(k, m % (2 * nt))]
    cells = []
    for l in range(nr):
        for s in range(nt):
            k0, k1, k2 = 2 * l, 2 * l + 1, 2 * l + 2
            m0, m1, m2 = 2 * s, 2 * s + 1, 2 * s + 2
            conn = [at(k0, m0), at(k2, m0), at(k2, m2), at(k0, m2),
                    at(k1, m0), at(k2, m1), at(k1, m2), at(k0, m1)]
            cells.append((f"Q{len(cells) + 1}", "QUAD8", conn))
    lext, lint = [], []
    kx = 2 * nr
    for s in range(nt):
        name = f"E{s + 1}"
        cells.append((name, "SEG3", [at(kx, 2 * s), at(kx, 2 * s + 2), at(kx, 2 * s + 1)]))
        lext.append(name)
    for s in range(nt):
        name = f"I{s + 1}"
        # Clockwise: the hole's border seen from the section.
        cells.append((name, "SEG3", [at(0, 2 * s + 2), at(0, 2 * s), at(0, 2 * s + 1)]))
        lint.append(name)
    write(os.path.join(HERE, "beam_section_tube.mail"), "tube r=0.1 t=0.01",
          nodes, cells, {"LEXT": lext, "LINT": lint}, {"P1": [at(kx, 0)]})


rectangle()
tube()
