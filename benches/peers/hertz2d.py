#!/usr/bin/env python3
"""The 2D Hertz problem for aster and CalculiX, on one mesh.

A half cylinder (radius R, plane strain) pressed on an elastic block, modelled
by symmetry (x >= 0): the quarter disk centred at (0, R + GAP) between its bottom
point (0, 0) and its horizontal radius (the loaded line y = R), and the block
[0, L] x [-L, 0]. Both bodies are refined towards the contact point. The top
line moves down by DELTA, the block's bottom is fixed, x = 0 is a symmetry
line; frictionless contact, one increment, linear elasticity.

    hertz2d.py OUTDIR --n N

writes OUTDIR/hertz2d.mail (code_aster's ASTER text mesh), OUTDIR/hertz2d.comm
(aster's command file, frictionless continuous contact) and OUTDIR/hertz2d.inp
(CalculiX: the same nodes and cells, CPE4/CPE3, node-to-surface contact with a
stiff linear pressure-overclosure law). N scales the mesh: about 36 N^2 nodes.

Reference (Hertz, two identical elastic cylinders' limit: a cylinder on a half
space): p0 = sqrt(F E* / (pi R)), with F the force per unit length on the full
cylinder (twice the symmetric model's) and 1/E* = 2 (1 - nu^2) / E. The block
is finite, so F (for a given DELTA) is the codes' own; p0 is then compared.
"""

import argparse
import math
import os

R = 50.0
L = 200.0
E = 2.0e5
NU = 0.3
DELTA = 0.05
# The cylinder starts this far above the block: CalculiX's expansion of plane
# elements into volumes fails ("nonpositive jacobian") when a node of one body
# coincides with a node of the other, as the bottom point does without it.
GAP = 1.0e-3
# CalculiX's contact: a linear pressure-overclosure law this stiff (N/mm^3):
# 1e8 leaves a penetration of 1e-5 mm at p0 (0.02 % of DELTA) and converges in
# one increment; PRESSURE-OVERCLOSURE=HARD needs ~30 increments with cutbacks
# here (21 s against 2 s at N = 8) for the same force.
CCX_K = 1.0e8


def geometric(total, n, h0):
    """n + 1 abscissae from 0 to `total`, the first step h0, each next one q
    times the last (q found by bisection; uniform when h0 >= total / n)."""
    if h0 * n >= total:
        return [total * i / n for i in range(n + 1)]
    lo, hi = 1.0, 2.0
    while h0 * (hi**n - 1) / (hi - 1) < total:
        hi *= 2
    for _ in range(200):
        q = 0.5 * (lo + hi)
        if h0 * (q**n - 1) / (q - 1) < total:
            lo = q
        else:
            hi = q
    q = 0.5 * (lo + hi)
    xs = [h0 * (q**i - 1) / (q - 1) for i in range(n + 1)]
    xs[-1] = total
    return xs


def mesh(n):
    nodes = []  # (x, y)
    cells = []  # (kind, [node indices], group)
    groups_no = {"SYM": [], "TOP": [], "BOT": []}
    groups_ma = {"ARC": [], "BTOP": []}

    def node(x, y):
        nodes.append((x, y))
        return len(nodes) - 1

    # The contact half-width is about 1 mm: the first cells are H0 / n wide.
    h0 = 0.8 / n
    # Block: nx x ny QUAD4, refined geometrically towards (0, 0).
    nx = ny = 4 * n
    xs = geometric(L, nx, h0)
    ys = [-y for y in geometric(L, ny, h0)]
    bid = [[node(x, y) for x in xs] for y in ys]
    for j in range(ny):
        for i in range(nx):
            # counter-clockwise: (i, j+1) is below (i, j)
            a, b, c, d = bid[j + 1][i], bid[j + 1][i + 1], bid[j][i + 1], bid[j][i]
            cells.append(("QUAD4", [a, b, c, d], "BLOCK"))
    for i in range(nx):
        cells.append(("SEG2", [bid[0][i], bid[0][i + 1]], "BTOP"))
    groups_no["SYM"] += [bid[j][0] for j in range(ny + 1)]
    groups_no["BOT"] += bid[ny]

    # Cylinder: rings refined towards r = R, angles towards the contact point.
    nr, nt = 4 * n, 5 * n
    centre = node(0.0, R + GAP)
    depths = geometric(R, nr, h0)  # from the surface inwards
    rs = [R - depths[nr - k] for k in range(1, nr + 1)]
    phis = [s / R for s in geometric(0.5 * math.pi * R, nt, h0)]
    cid = [[node(r * math.sin(f), GAP + R - r * math.cos(f)) for f in phis] for r in rs]
    for t in range(nt):
        cells.append(("TRIA3", [centre, cid[0][t], cid[0][t + 1]], "CYL"))
    for k in range(nr - 1):
        for t in range(nt):
            a, b, c, d = cid[k][t], cid[k + 1][t], cid[k + 1][t + 1], cid[k][t + 1]
            cells.append(("QUAD4", [a, b, c, d], "CYL"))
    # The arc's part that can touch: the first third of the quarter.
    for t in range(nt):
        if phis[t + 1] <= math.pi / 6 + 1e-12:
            cells.append(("SEG2", [cid[nr - 1][t + 1], cid[nr - 1][t]], "ARC"))
    groups_no["SYM"] += [centre] + [cid[k][0] for k in range(nr)]
    groups_no["TOP"] += [centre] + [cid[k][nt] for k in range(nr)]
    groups_no["P0"] = [cid[nr - 1][0]]
    return nodes, cells, groups_no


def write_mail(path, nodes, cells, groups_no):
    with open(path, "w") as f:
        f.write("TITRE\nhertz2d.py\nFINSF\n%\nCOOR_2D\n")
        for i, (x, y) in enumerate(nodes):
            f.write(f"N{i + 1} {x!r} {y!r}\n")
        f.write("FINSF\n%\n")
        for kind in ("QUAD4", "TRIA3", "SEG2"):
            f.write(f"{kind}\n")
            for k, (kk, conn, _) in enumerate(cells):
                if kk == kind:
                    f.write(f"M{k + 1} " + " ".join(f"N{c + 1}" for c in conn) + "\n")
            f.write("FINSF\n%\n")
        by_group = {}
        for k, (_, _, g) in enumerate(cells):
            by_group.setdefault(g, []).append(k)
        for g, ks in by_group.items():
            f.write(f"GROUP_MA\n{g}\n" + "\n".join(f"M{k + 1}" for k in ks) + "\nFINSF\n%\n")
        for g, ns in groups_no.items():
            f.write(f"GROUP_NO\n{g}\n" + "\n".join(f"N{c + 1}" for c in ns) + "\nFINSF\n%\n")
        f.write("FIN\n")


COMM = """\
# 2D Hertz (benches/peers/hertz2d.py): the same mesh as hertz2d.inp.
DEBUT()
MA = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
MA = DEFI_GROUP(reuse=MA, MAILLAGE=MA, CREA_GROUP_NO=_F(GROUP_MA="ARC", NOM="ARCN"))
MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU=("ARC", "BTOP")))
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="D_PLAN"))
MAT = DEFI_MATERIAU(ELAS=_F(E={E!r}, NU={NU!r}))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CL = AFFE_CHAR_MECA(
    MODELE=MO,
    DDL_IMPO=(_F(GROUP_NO="SYM", DX=0.0), _F(GROUP_NO="BOT", DY=0.0), _F(GROUP_NO="TOP", DY=-{DELTA!r})),
)
CONT = DEFI_CONTACT(
    MODELE=MO, FORMULATION="CONTINUE", ALGO_RESO_GEOM="NEWTON",
    ZONE=_F(GROUP_MA_MAIT="BTOP", GROUP_MA_ESCL="ARC"),
)
LI = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
RAMPE = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 1.0, 1.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CL, FONC_MULT=RAMPE), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LI),
    NEWTON=_F(REAC_ITER=1), CONVERGENCE=_F(RESI_GLOB_RELA=1e-8, ITER_GLOB_MAXI=50),
)
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, FORCE="REAC_NODA")
F = POST_RELEVE_T(ACTION=_F(INTITULE="F", OPERATION="EXTRACTION", RESULTAT=RES, NOM_CHAM="REAC_NODA",
                            GROUP_NO="TOP", RESULTANTE="DY", INST=1.0))
P = POST_RELEVE_T(ACTION=_F(INTITULE="P0", OPERATION="EXTRACTION", RESULTAT=RES, NOM_CHAM="DEPL",
                            GROUP_NO="ARCN", NOM_CMP="LAGS_C", INST=1.0))
IMPR_TABLE(TABLE=F, UNITE=8)
IMPR_TABLE(TABLE=P, UNITE=8)
FIN()
"""


def write_comm(path):
    with open(path, "w") as f:
        f.write(COMM.format(E=E, NU=NU, DELTA=DELTA))


def write_inp(path, nodes, cells, groups_no):
    with open(path, "w") as f:
        f.write("** 2D Hertz (benches/peers/hertz2d.py): the same mesh as hertz2d.mail\n*NODE, NSET=NALL\n")
        for i, (x, y) in enumerate(nodes):
            f.write(f"{i + 1}, {x!r}, {y!r}, 0.0\n")
        for kind, ccx in (("QUAD4", "CPE4"), ("TRIA3", "CPE3")):
            for body in ("BLOCK", "CYL"):
                rows = [(k, conn) for k, (kk, conn, g) in enumerate(cells) if kk == kind and g == body]
                if rows:
                    f.write(f"*ELEMENT, TYPE={ccx}, ELSET={body}\n")
                    for k, conn in rows:
                        f.write(f"{k + 1}, " + ", ".join(str(c + 1) for c in conn) + "\n")
        for g, ns in groups_no.items():
            f.write(f"*NSET, NSET={g}\n")
            for c in ns:
                f.write(f"{c + 1},\n")
        # Slave: the arc's nodes; master: the block's top faces (face S3 of
        # CPE4 a b c d is c-d, the top edge as written above).
        arc = sorted({c for kk, conn, g in cells if g == "ARC" for c in conn})
        f.write("*NSET, NSET=ARCN\n" + "".join(f"{c + 1},\n" for c in arc))
        f.write("*SURFACE, NAME=SLAVE, TYPE=NODE\nARCN\n")
        top = [k for k, (kk, conn, g) in enumerate(cells) if g == "BLOCK" and kk == "QUAD4"
               and all(abs(nodes[c][1]) < 1e-12 for c in (conn[2], conn[3]))]
        f.write("*SURFACE, NAME=MASTER\n" + "".join(f"{k + 1}, S3\n" for k in top))
        f.write(
            "*MATERIAL, NAME=STEEL\n*ELASTIC\n{E!r}, {NU!r}\n"
            "*SOLID SECTION, ELSET=BLOCK, MATERIAL=STEEL\n1.\n"
            "*SOLID SECTION, ELSET=CYL, MATERIAL=STEEL\n1.\n"
            "*SURFACE INTERACTION, NAME=SI\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n{K!r}\n"
            "*CONTACT PAIR, INTERACTION=SI, TYPE=NODE TO SURFACE\nSLAVE, MASTER\n"
            "*BOUNDARY\nSYM, 1, 1, 0.0\nBOT, 2, 2, 0.0\nTOP, 2, 2, -{DELTA!r}\n"
            "*STEP, NLGEOM=NO\n*STATIC\n1., 1.\n"
            "*NODE PRINT, NSET=TOP, TOTALS=ONLY\nRF\n"
            "*CONTACT PRINT\nCSTR\n"
            "*END STEP\n".format(E=E, NU=NU, DELTA=DELTA, K=CCX_K)
        )


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--n", type=int, default=8)
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    nodes, cells, groups_no = mesh(a.n)
    write_mail(os.path.join(a.outdir, "hertz2d.mail"), nodes, cells, groups_no)
    write_comm(os.path.join(a.outdir, "hertz2d.comm"))
    write_inp(os.path.join(a.outdir, "hertz2d.inp"), nodes, cells, groups_no)
    print(f"{len(nodes)} nodes, {2 * len(nodes)} unknowns, {len(cells)} cells")


if __name__ == "__main__":
    main()
