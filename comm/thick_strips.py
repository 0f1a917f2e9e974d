"""Writes comm/thick_strips.mail: five cantilever strips of plate facets,
written for the aster project (metres). Each strip is x in [0, 1], width
0.1 along y, in the plane z = 0: S1 (10 QUAD4) at y in [0, 0.1], S2 (80
cells along x, each cut in two TRIA3) at y in [1, 1.1], S3 (10 QUAD4) at
y in [2, 2.1], S4 (20 TRIA3) at y in [3, 3.1], S5 (10 QUAD4) at y in
[4, 4.1]. CLk: the
clamped end (x = 0) of strip k, TIPk: its free end (x = 1), Ak: its tip
node at the lower y, Ok: its clamped node at the lower y, Mk: its first
cell (at the clamp). Usage: python3 comm/thick_strips.py > comm/thick_strips.mail
"""

NX = {1: 10, 2: 80, 3: 10, 4: 10, 5: 10}
print("% Five cantilever strips of plate facets (comm/thick_strips.py),")
print("% written for the aster project: S1, S3, S5 10 QUAD4, S2 160 TRIA3, S4 20 TRIA3,")
print("% x in [0, 1], width 0.1, in the plane z = 0, strip k at y = k - 1.")
print("TITRE\n thick plate strips\nFINSF")
print("COOR_3D")
for k in range(1, 6):
    for j in range(2):
        for i in range(NX[k] + 1):
            print(f"  S{k}_{j}_{i}  {i / NX[k]:.6f}  {k - 1 + 0.1 * j:.6f}  0.0")
print("FINSF")
cells = {}
for k in (1, 3, 5):
    print("QUAD4")
    names = []
    for i in range(NX[k]):
        n = f"Q{k}_{i + 1}"
        names.append(n)
        print(f"  {n}  S{k}_0_{i} S{k}_0_{i + 1} S{k}_1_{i + 1} S{k}_1_{i}")
    print("FINSF")
    cells[k] = names
for k in (2, 4):
    print("TRIA3")
    names = []
    for i in range(NX[k]):
        a, b, c, d = f"S{k}_0_{i}", f"S{k}_0_{i + 1}", f"S{k}_1_{i + 1}", f"S{k}_1_{i}"
        names += [f"T{k}_{2 * i + 1}", f"T{k}_{2 * i + 2}"]
        print(f"  T{k}_{2 * i + 1}  {a} {b} {c}")
        print(f"  T{k}_{2 * i + 2}  {a} {c} {d}")
    print("FINSF")
    cells[k] = names
for k in range(1, 6):
    print(f"GROUP_MA NOM=S{k}\n  " + " ".join(cells[k]) + "\nFINSF")
    print(f"GROUP_NO NOM=CL{k}\n  S{k}_0_0 S{k}_1_0\nFINSF")
    print(f"GROUP_NO NOM=TIP{k}\n  S{k}_0_{NX[k]} S{k}_1_{NX[k]}\nFINSF")
    print(f"GROUP_NO NOM=A{k}\n  S{k}_0_{NX[k]}\nFINSF")
    print(f"GROUP_NO NOM=O{k}\n  S{k}_0_0\nFINSF")
    print(f"GROUP_MA NOM=M{k}\n  {cells[k][0]}\nFINSF")
print("FIN")
