#!/usr/bin/python3
"""Write a Gmsh (format 2.2) file of the O-grid disc used by the coarse
cylinder tests: radius 10, centre (0, 10), 4 x 4 core cells, 3 rings.

An independent construction of the mesh that impactfe::Geometry::disc
builds (same vertex positions, own numbering), so that reading the file
through deal.II's GridIn must reproduce the built-in mesh's results.
The segments of the lower half of the circle get the physical tag 1 (the
contact boundary id); the rest of the boundary is untagged (id 0).

usage: make_disc_msh.py > disc_4x3.msh
       make_disc_msh.py --format 4.1 > disc_4x3_gmsh41.msh
       make_disc_msh.py --format 4.0 > disc_4x3_gmsh40.msh
       make_disc_msh.py N_CORE N_RINGS CENTRE_HEIGHT > file.msh
(the second form: the paper's cylinder, 12 9 11.5, is
parameter_files/cylinder_12x9.msh, the mesh of cylinder_impact.prm with its
initial gap of 1.5, for contact_mpi's cylinder_impact_mpi.prm)
--format 4.1 writes Gmsh's current format instead: entity blocks, the
physical tag on a curve entity of $Entities (mesh_from_file_gmsh41.prm).
--format 4.0 writes the format of Gmsh 4.0 (2018): the same entities
(other tags), but no tag ranges in the section headers, block headers of
"entity tag, dimension" (4.1: dimension first) and each node's tag on its
coordinates' line (mesh_from_file_gmsh40.prm).
"""
import math
import sys

R, CX, CY, N, M = 10.0, 0.0, 10.0, 4, 3
FORMAT = "2.2"
if sys.argv[1:2] == ["--format"]:
    if sys.argv[2:3] not in (["2.2"], ["4.1"], ["4.0"]):
        sys.exit("--format takes 2.2, 4.0 or 4.1\n\n" + __doc__)
    FORMAT = sys.argv[2]
    del sys.argv[1:3]
if len(sys.argv) == 4:
    N, M, CY = int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3])
elif len(sys.argv) != 1:
    sys.exit(__doc__)
A = 0.37 * R

points = {}  # (kind, a, b) -> (x, y)
for j in range(N + 1):
    for i in range(N + 1):
        points[("core", i, j)] = (-A + 2 * A * i / N, -A + 2 * A * j / N)


def square_key(k):
    if k < N:
        return ("core", N, k)
    if k < 2 * N:
        return ("core", N - (k - N), N)
    if k < 3 * N:
        return ("core", 0, N - (k - 2 * N))
    return ("core", k - 3 * N, 0)


def ring_key(level, k):
    k %= 4 * N
    return square_key(k) if level == 0 else ("ring", level, k)


for level in range(1, M + 1):
    s = level / M
    for k in range(4 * N):
        angle = -math.pi / 4 + (math.pi / 2) * k / N
        sx, sy = points[square_key(k)]
        points[("ring", level, k)] = ((1 - s) * sx + s * R * math.cos(angle),
                                      (1 - s) * sy + s * R * math.sin(angle))

keys = list(points)
number = {key: n + 1 for n, key in enumerate(keys)}

quads = []
for j in range(N):
    for i in range(N):
        # counter-clockwise
        quads.append([("core", i, j), ("core", i + 1, j),
                      ("core", i + 1, j + 1), ("core", i, j + 1)])
for level in range(M):
    for k in range(4 * N):
        quads.append([ring_key(level, k), ring_key(level + 1, k),
                      ring_key(level + 1, k + 1), ring_key(level, k + 1)])

lines = []
for k in range(4 * N):
    a, b = ring_key(M, k), ring_key(M, k + 1)
    if 0.5 * (points[a][1] + points[b][1]) < 0.0:  # below the centre
        lines.append((a, b))

if FORMAT == "2.2":
    print("$MeshFormat\n2.2 0 8\n$EndMeshFormat")
    print("$Nodes\n%d" % len(keys))
    for key in keys:
        x, y = points[key]
        print("%d %.17g %.17g 0" % (number[key], x + CX, y + CY))
    print("$EndNodes")
    print("$Elements\n%d" % (len(lines) + len(quads)))
    n = 0
    for a, b in lines:
        n += 1
        print("%d 1 2 1 1 %d %d" % (n, number[a], number[b]))
    for q in quads:
        n += 1
        print("%d 3 2 0 2 %s" % (n, " ".join(str(number[v]) for v in q)))
    print("$EndElements")
else:
    # One curve entity (physical tag 1: the lower half's segments) and one
    # surface entity (no physical tag) with all the nodes. Format 4.1: tags
    # 1 and 2, tag ranges in the section headers, block headers "dimension
    # tag", the node tags before the coordinates. Format 4.0: tags 5 and 7,
    # so that its block headers "tag dimension" differ from 4.1's order, no
    # tag ranges, each node's tag on its coordinates' line.
    four_one = FORMAT == "4.1"
    curve, surface = (1, 2) if four_one else (5, 7)

    def block(dim, tag, n_items, kind):
        first, second = (dim, tag) if four_one else (tag, dim)
        return "%d %d %d %d" % (first, second, kind, n_items)

    print("$MeshFormat\n%s 0 8\n$EndMeshFormat" % ("4.1" if four_one else "4"))
    print("$Entities\n0 1 1 0")
    box = "%.17g %.17g 0 %.17g %.17g 0" % (CX - R, CY - R, CX + R, CY + R)
    print("%d %s 1 1 0" % (curve, box))
    print("%d %s 0 0" % (surface, box))
    print("$EndEntities")
    ranges = " 1 %d" % len(keys) if four_one else ""
    print("$Nodes\n1 %d%s" % (len(keys), ranges))
    print(block(2, surface, len(keys), 0))
    if four_one:
        for key in keys:
            print(number[key])
    for key in keys:
        x, y = points[key]
        tag = "" if four_one else "%d " % number[key]
        print("%s%.17g %.17g 0" % (tag, x + CX, y + CY))
    print("$EndNodes")
    n_elements = len(lines) + len(quads)
    ranges = " 1 %d" % n_elements if four_one else ""
    print("$Elements\n2 %d%s" % (n_elements, ranges))
    print(block(1, curve, len(lines), 1))
    n = 0
    for a, b in lines:
        n += 1
        print("%d %d %d" % (n, number[a], number[b]))
    print(block(2, surface, len(quads), 3))
    for q in quads:
        n += 1
        print("%d %s" % (n, " ".join(str(number[v]) for v in q)))
    print("$EndElements")
