"""Writes comm/prepvarc_plates.mail: three square plates of side 1 m,
written for the aster project, for comm/prepvarc_plates.comm (temperatures
through the thickness, CREA_RESU/PREP_VARC). Each is a 2 x 2 grid of nodes
Pk_i_j (i, j = 0..2):
- PA: 4 QUAD4 in the plane z = 0, x, y in [0, 1]; A00 the corner (0, 0),
  A20 (1, 0), A02 (0, 1), A22 (1, 1).
- PB: 8 TRIA3 in the plane x = 2 (y, z in [0, 1], normal +x); BORD_B its
  boundary nodes, BC its centre.
- PC: 4 QUAD4 in the plane z = 0, x in [4, 5], y in [0, 1]; BORD_C its
  boundary nodes, CC its centre.
Every cell and node is also a group of its own name.
Usage: python3 comm/prepvarc_plates.py > comm/prepvarc_plates.mail
"""

print("% Three square plates for comm/prepvarc_plates.comm (comm/prepvarc_plates.py),")
print("% written for the aster project: PA 4 QUAD4 (z = 0), PB 8 TRIA3 (x = 2),")
print("% PC 4 QUAD4 (z = 0, x in [4, 5]).")
print("TITRE\n plates heated through their thickness\nFINSF")


def coord(k, i, j):
    a, b = i / 2, j / 2
    if k == "A":
        return (a, b, 0.0)
    if k == "B":
        return (2.0, a, b)
    return (4.0 + a, b, 0.0)


print("COOR_3D")
for k in "ABC":
    for j in range(3):
        for i in range(3):
            x, y, z = coord(k, i, j)
            print(f"  {k}{i}{j}  {x:.6f}  {y:.6f}  {z:.6f}")
print("FINSF")
groups = {}
print("QUAD4")
for k in "AC":
    for j in range(2):
        for i in range(2):
            n = f"M{k}{i}{j}"
            groups.setdefault("P" + k, []).append(n)
            print(f"  {n}  {k}{i}{j} {k}{i + 1}{j} {k}{i + 1}{j + 1} {k}{i}{j + 1}")
print("FINSF")
print("TRIA3")
for j in range(2):
    for i in range(2):
        a, b, c, d = f"B{i}{j}", f"B{i + 1}{j}", f"B{i + 1}{j + 1}", f"B{i}{j + 1}"
        for t, nodes in enumerate(((a, b, c), (a, c, d))):
            n = f"MB{i}{j}{t}"
            groups.setdefault("PB", []).append(n)
            print(f"  {n}  {' '.join(nodes)}")
print("FINSF")
for g, cells in groups.items():
    print(f"GROUP_MA NOM={g}\n  {' '.join(cells)}\nFINSF")
for k in "BC":
    border = [f"{k}{i}{j}" for j in range(3) for i in range(3) if (i, j) != (1, 1)]
    print(f"GROUP_NO NOM=BORD_{k}\n  {' '.join(border)}\nFINSF")
    print(f"GROUP_NO NOM={k}C\n  {k}11\nFINSF")
# One group per cell and per node (TEST_RESU names them by group).
for cells in groups.values():
    for c in cells:
        print(f"GROUP_MA NOM={c}\n  {c}\nFINSF")
for k in "ABC":
    for j in range(3):
        for i in range(3):
            print(f"GROUP_NO NOM={k}{i}{j}\n  {k}{i}{j}\nFINSF")
print("FIN")
