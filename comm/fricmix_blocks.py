# Generates comm/fricmix_blocks.mail: a base block and two upper blocks, PENTA6
# (each hexahedral column split in two prisms), TRIA3 contact faces.
nodes = []
cells = {"PENTA6": [], "TRIA3": []}
groups = {}

def node(x, y, z):
    nodes.append((x, y, z))
    return len(nodes)

def block(x0, x1, y0, y1, z0, z1, nx, ny, name, bottom, top):
    grid = {}
    for k, z in enumerate((z0, z1)):
        for j in range(ny + 1):
            for i in range(nx + 1):
                grid[i, j, k] = node(x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny, z)
    vol, bot, tp = [], [], []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = (i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)
            # alternate the diagonal so the triangles are not all alike
            tris = [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
            for t in tris:
                lo = [grid[p[0], p[1], 0] for p in t]
                hi = [grid[p[0], p[1], 1] for p in t]
                cells["PENTA6"].append(lo + hi)
                vol.append(len(cells["PENTA6"]))
                # bottom face: outward normal -z (clockwise from above)
                cells["TRIA3"].append([lo[0], lo[2], lo[1]])
                bot.append(("T", len(cells["TRIA3"])))
                cells["TRIA3"].append(hi)
                tp.append(("T", len(cells["TRIA3"])))
    groups[name] = [("P", v) for v in vol]
    groups[bottom] = bot
    groups[top] = tp

block(0.0, 2.5, 0.0, 1.0, -0.5, 0.0, 5, 3, "BASE", "BASEB", "BASET")
block(0.0, 1.0, 0.0, 1.0, 0.0, 0.5, 2, 2, "BLA", "BLAB", "BLAT")
block(1.5, 2.5, 0.0, 1.0, 0.0, 0.5, 3, 2, "BLB", "BLBB", "BLBT")

npenta = len(cells["PENTA6"])
def cname(kind, i):
    return f"M{i}" if kind == "P" else f"M{npenta + i}"

out = ["TITRE", "A base and two blocks of PENTA6 (TRIA3 faces at z = 0), aster project (fricmix)", "FINSF", "%", "COOR_3D"]
for i, (x, y, z) in enumerate(nodes, 1):
    out.append(f"N{i} {x!r} {y!r} {z!r}")
out += ["FINSF", "%", "PENTA6"]
for i, c in enumerate(cells["PENTA6"], 1):
    out.append(f"M{i} " + " ".join(f"N{n}" for n in c))
out += ["FINSF", "%", "TRIA3"]
for i, c in enumerate(cells["TRIA3"], 1):
    out.append(f"M{npenta + i} " + " ".join(f"N{n}" for n in c))
out += ["FINSF", "%"]
for g, members in groups.items():
    out.append(f"GROUP_MA NOM={g}")
    out += [cname(k, i) for k, i in members]
    out += ["FINSF", "%"]
def find(x, y, z):
    for i, p in reversed(list(enumerate(nodes, 1))):
        if abs(p[0] - x) < 1e-12 and abs(p[1] - y) < 1e-12 and abs(p[2] - z) < 1e-12:
            return i
    raise SystemExit("no node")
for g, p in (("PA", (0.5, 0.5, 0.0)), ("PA1", (0.0, 0.0, 0.0)), ("PB", (1.5 + 1.0 / 3.0, 0.5, 0.0))):
    out += [f"GROUP_NO NOM={g}", f"N{find(*p)}", "FINSF", "%"]
out.append("FIN")
open(__file__.replace(".py", ".mail"), "w").write("\n".join(out) + "\n")
print(len(nodes), npenta, len(cells["TRIA3"]))
