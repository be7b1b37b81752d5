#!/usr/bin/python3
"""Write a Gmsh (format 2.2) file of the oblique plate's mesh: nx x ny Q1
cells of a plate of width W whose vertical sides have height H and whose
lower side is an arc of radius R (bulging downwards, through the lower
corners), its lowest point at (0, Y0).

An independent construction of the mesh that
impactfe::Geometry::plate_with_round_side builds (same vertex positions,
own numbering): the grid of the unit-height rectangle [-W/2, W/2] x [0, 1],
each column mapped from the arc y_b(x) = R - sqrt(R^2 - x^2) to the top
y_b(W/2) + H. The segments of the round side get the physical tag 2 (the
plate's contact boundary id); the rest of the boundary is untagged (id 0).

usage: make_plate_msh.py NX NY W H R Y0 > file.msh
(parameter_files/oblique_plate_10x8.msh is `10 8 0.08 0.04 0.101 0`, the
mesh of oblique_plate.prm, for contact_mpi's oblique_plate_mpi.prm)
"""
import math
import sys

if len(sys.argv) != 7:
    sys.exit(__doc__)
NX, NY = int(sys.argv[1]), int(sys.argv[2])
W, H, R, Y0 = (float(a) for a in sys.argv[3:7])
half = 0.5 * W
top = R - math.sqrt(R * R - half * half) + H


def vertex(i, j):
    x = -half + W * i / NX
    eta = j / NY
    y_b = R - math.sqrt(R * R - x * x)
    return x, Y0 + y_b + eta * (top - y_b)


def number(i, j):
    return j * (NX + 1) + i + 1


print("$MeshFormat\n2.2 0 8\n$EndMeshFormat")
print("$Nodes\n%d" % ((NX + 1) * (NY + 1)))
for j in range(NY + 1):
    for i in range(NX + 1):
        x, y = vertex(i, j)
        print("%d %.17g %.17g 0" % (number(i, j), x, y))
print("$EndNodes")
print("$Elements\n%d" % (NX + NX * NY))
n = 0
for i in range(NX):  # the round side, tag 2
    n += 1
    print("%d 1 2 2 2 %d %d" % (n, number(i, 0), number(i + 1, 0)))
for j in range(NY):
    for i in range(NX):  # counter-clockwise
        n += 1
        print("%d 3 2 0 1 %d %d %d %d" % (n, number(i, j), number(i + 1, j),
                                          number(i + 1, j + 1),
                                          number(i, j + 1)))
print("$EndElements")
