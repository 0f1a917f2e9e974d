#!/usr/bin/env python3
"""A 3D elastic contact problem for aster at a chosen size (HEXA8).

A quarter model (x >= 0, y >= 0, symmetry planes x = 0 and y = 0): a base
block [0, L] x [0, L] x [-L, 0] and, above it, an indenter block
[0, L/2] x [0, L/2] x [GAP, GAP + L/2] whose bottom face is the paraboloid
z = GAP + (x^2 + y^2) / (2 R) (a Hertz-like sphere of radius R near the
contact point), blended linearly to the flat top. Both blocks are refined
geometrically towards the contact point (0, 0, 0) in the three directions.
The indenter's top moves down by DELTA, the base's bottom is fixed;
frictionless discrete contact, one increment, linear elasticity.

    hertz3d.py OUTDIR --n N

writes OUTDIR/hertz3d.mail (code_aster's ASTER text mesh) and
OUTDIR/hertz3d.comm (aster's command file). The base has 4N cells along each
edge, the indenter 2N: about 72 N^3 nodes, 216 N^3 unknowns (N = 4: 15k,
N = 8: 115k, N = 12: 380k, N = 16: 900k). The mesh is deterministic (no
randomness, fixed formatting), so two runs give the same files.

`cargo run --profile ci -p aster-fem --example fill3d -- OUTDIR/hertz3d.mail`
prints the Cholesky factor's size under each ordering for the stiffness
matrix of this mesh (benches/peers/fill3d.sh adds METIS's).
"""

import argparse
import os

R = 50.0
L = 100.0
E = 2.0e5
NU = 0.3
DELTA = 0.05
GAP = 1.0e-3


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
    nodes = []  # (x, y, z)
    cells = []  # (kind, [node indices], group)
    groups_no = {"SYMX": [], "SYMY": [], "BOT": [], "TOP": []}
    h0 = 1.6 / n  # the contact radius is about 1.6 mm

    def node(p):
        nodes.append(p)
        return len(nodes) - 1

    def block(m, size, zs, zmap, group, face_z):
        """m^3 HEXA8 on the grid xs = ys = geometric(size, m, h0) and the
        given z levels; zmap(x, y, z) moves a node; the cells' faces at level
        index face_z become QUAD4 of group + 'S'."""
        xs = geometric(size, m, h0)
        ids = [[[node((x, y, zmap(x, y, z))) for x in xs] for y in xs] for z in zs]
        for k in range(m):
            for j in range(m):
                for i in range(m):
                    a = ids[k][j][i], ids[k][j][i + 1], ids[k][j + 1][i + 1], ids[k][j + 1][i]
                    b = ids[k + 1][j][i], ids[k + 1][j][i + 1], ids[k + 1][j + 1][i + 1], ids[k + 1][j + 1][i]
                    cells.append(("HEXA8", list(a) + list(b), group))
        k = face_z
        for j in range(m):
            for i in range(m):
                f = [ids[k][j][i], ids[k][j][i + 1], ids[k][j + 1][i + 1], ids[k][j + 1][i]]
                cells.append(("QUAD4", f, group + "S"))
        for k in range(len(zs)):
            for j in range(m + 1):
                groups_no["SYMX"].append(ids[k][j][0])
                groups_no["SYMY"].append(ids[k][0][j])
        return ids

    m = 4 * n
    zs = [-z for z in reversed(geometric(L, m, h0))]
    base = block(m, L, zs, lambda x, y, z: z, "BASE", m)
    groups_no["BOT"] += [v for row in base[0] for v in row]
    mi = 2 * n
    h = 0.5 * L
    zi = geometric(h, mi, h0)

    def lift(x, y, z):
        bottom = GAP + (x * x + y * y) / (2 * R)
        return bottom + z * (GAP + h - bottom) / h

    ind = block(mi, h, zi, lift, "IND", 0)
    groups_no["TOP"] += [v for row in ind[mi] for v in row]
    groups_no["P0"] = [ind[0][0][0]]
    return nodes, cells, groups_no


def write_mail(path, nodes, cells, groups_no):
    with open(path, "w") as f:
        f.write("TITRE\nhertz3d.py\nFINSF\n%\nCOOR_3D\n")
        for i, (x, y, z) in enumerate(nodes):
            f.write(f"N{i + 1} {x!r} {y!r} {z!r}\n")
        f.write("FINSF\n%\n")
        for kind in ("HEXA8", "QUAD4"):
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
            ns = sorted(set(ns))
            f.write(f"GROUP_NO\n{g}\n" + "\n".join(f"N{c + 1}" for c in ns) + "\nFINSF\n%\n")
        f.write("FIN\n")


COMM = """\
# 3D Hertz-like indentation (benches/peers/hertz3d.py).
DEBUT()
MA = LIRE_MAILLAGE(FORMAT="ASTER", UNITE=20)
MA = MODI_MAILLAGE(reuse=MA, MAILLAGE=MA, ORIE_PEAU=_F(GROUP_MA_PEAU=("INDS", "BASES")))
MO = AFFE_MODELE(MAILLAGE=MA, AFFE=_F(TOUT="OUI", PHENOMENE="MECANIQUE", MODELISATION="3D"))
MAT = DEFI_MATERIAU(ELAS=_F(E={E!r}, NU={NU!r}))
CM = AFFE_MATERIAU(MAILLAGE=MA, AFFE=_F(TOUT="OUI", MATER=MAT))
CL = AFFE_CHAR_MECA(
    MODELE=MO,
    DDL_IMPO=(_F(GROUP_NO="SYMX", DX=0.0), _F(GROUP_NO="SYMY", DY=0.0),
              _F(GROUP_NO="BOT", DZ=0.0), _F(GROUP_NO="TOP", DZ=-{DELTA!r})),
)
CONT = DEFI_CONTACT(
    MODELE=MO, FORMULATION="DISCRETE",
    ZONE=_F(GROUP_MA_MAIT="BASES", GROUP_MA_ESCL="INDS"),
)
LI = DEFI_LIST_REEL(DEBUT=0.0, INTERVALLE=_F(JUSQU_A=1.0, NOMBRE=1))
RAMPE = DEFI_FONCTION(NOM_PARA="INST", VALE=(0.0, 0.0, 1.0, 1.0))
RES = STAT_NON_LINE(
    MODELE=MO, CHAM_MATER=CM, EXCIT=_F(CHARGE=CL, FONC_MULT=RAMPE), CONTACT=CONT,
    COMPORTEMENT=_F(RELATION="ELAS"), INCREMENT=_F(LIST_INST=LI),
    CONVERGENCE=_F(RESI_GLOB_RELA=1e-8, ITER_GLOB_MAXI=50),
)
RES = CALC_CHAMP(reuse=RES, RESULTAT=RES, FORCE="REAC_NODA")
F = POST_RELEVE_T(ACTION=_F(INTITULE="F", OPERATION="EXTRACTION", RESULTAT=RES, NOM_CHAM="REAC_NODA",
                            GROUP_NO="TOP", RESULTANTE="DZ", INST=1.0))
IMPR_TABLE(TABLE=F, UNITE=8)
FIN()
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir")
    ap.add_argument("--n", type=int, default=4)
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    nodes, cells, groups_no = mesh(a.n)
    write_mail(os.path.join(a.outdir, "hertz3d.mail"), nodes, cells, groups_no)
    with open(os.path.join(a.outdir, "hertz3d.comm"), "w") as f:
        f.write(COMM.format(E=E, NU=NU, DELTA=DELTA))
    print(f"{len(nodes)} nodes, {3 * len(nodes)} unknowns, {len(cells)} cells")


if __name__ == "__main__":
    main()
