#!/usr/bin/python3
"""Write a Gmsh (format 2.2) file of a bar: a box [X0, X0 + L] x [0, H]
(x [0, H] in 3D) of NX x NY (x NY) Q1 cells, with the boundary ids that
deal.II's GridGenerator::subdivided_hyper_rectangle(..., colorize = true)
gives: 0 at x = X0, 1 at x = X0 + L, 2 and 3 at y = 0 and H, 4 and 5 at
z = 0 and H. Faces with id 0 are not written (0 is the default id).

An independent construction of the bars that the serial programs
two_bars_2d and two_bars_3d build, for contact_mpi's Scene = two
bodies (same vertex positions, own numbering).

usage: make_bar_msh.py DIM NX NY X0 L H [Y0] > file.msh
(Y0, default 0, shifts the box to [Y0, Y0 + H] along y)
(parameter_files/two_bars_2d_bar_1.msh is `2 20 4 -0.254 0.254 0.0254`,
 two_bars_2d_bar_2.msh `2 20 4 0 0.254 0.0254`; the 3D files
 `3 20 2 -0.254 0.254 0.0254` and `3 20 2 0 0.254 0.0254`)
"""
import itertools
import sys

if len(sys.argv) not in (7, 8):
    sys.exit(__doc__)
DIM, NX, NY = (int(a) for a in sys.argv[1:4])
X0, L, H = (float(a) for a in sys.argv[4:7])
Y0 = float(sys.argv[7]) if len(sys.argv) == 8 else 0.
if DIM not in (2, 3):
    sys.exit("DIM must be 2 or 3")
NZ = NY if DIM == 3 else 0
counts = (NX, NY, NZ)[:DIM]


def coordinate(axis, i):
    if axis == 0:
        return X0 + L * i / NX
    if axis == 1:
        return Y0 + H * i / NY
    return H * i / NY


def number(index):
    n, stride = 0, 1
    for axis in range(DIM):
        n += index[axis] * stride
        stride *= counts[axis] + 1
    return n + 1


nodes = list(itertools.product(*(range(c + 1) for c in reversed(counts))))
print("$MeshFormat\n2.2 0 8\n$EndMeshFormat")
print("$Nodes\n%d" % len(nodes))
for reversed_index in nodes:
    index = tuple(reversed(reversed_index))
    x = [coordinate(a, index[a]) for a in range(DIM)] + [0.] * (3 - DIM)
    print("%d %.17g %.17g %.17g" % (number(index), *x))
print("$EndNodes")

# counter-clockwise corners of a quadrilateral, Gmsh's hexahedron order
square = [(0, 0), (1, 0), (1, 1), (0, 1)]
elements = []
cells = list(itertools.product(*(range(c) for c in reversed(counts))))
for reversed_cell in cells:
    cell = tuple(reversed(reversed_cell))
    if DIM == 2:
        corners = [(cell[0] + a, cell[1] + b) for a, b in square]
        elements.append((3, 1, corners))
    else:
        corners = [(cell[0] + a, cell[1] + b, cell[2] + c)
                   for c in (0, 1) for a, b in square]
        elements.append((5, 1, corners))
# boundary faces with ids 1..2*DIM-1: the side at the low (id 2 axis) or
# high (id 2 axis + 1) end of each axis, their corners in a cyclic order
for axis in range(DIM):
    others = [a for a in range(DIM) if a != axis]
    for high in (0, 1):
        tag = 2 * axis + high
        if tag == 0:
            continue
        fixed = counts[axis] if high else 0
        for face in itertools.product(*(range(counts[a]) for a in others)):
            corners = []
            offsets = [(0,), (1,)] if DIM == 2 else square
            for offset in offsets:
                index = [0] * DIM
                index[axis] = fixed
                for a, o, f in zip(others, offset, face):
                    index[a] = f + o
                corners.append(tuple(index))
            elements.append((1 if DIM == 2 else 3, tag, corners))
print("$Elements\n%d" % len(elements))
for n, (kind, tag, corners) in enumerate(elements, 1):
    print("%d %d 2 %d %d %s" % (n, kind, tag, tag,
                                " ".join(str(number(c)) for c in corners)))
print("$EndElements")
