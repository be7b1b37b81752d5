#!/usr/bin/python3
"""Write a Gmsh (format 2.2) file of the block of the coarse block_sliding_3d
tests: [-0.05, 0.05] x [0, 0.01] x [-0.05, 0.05], 2 x 1 x 2 hexahedra.

An independent construction of the mesh that block_sliding_3d builds with
GridGenerator::subdivided_hyper_rectangle (same vertices, own numbering and
Gmsh's node order), so that reading it through deal.II's GridIn must give
the built-in mesh's results. The quadrilaterals of the lower face y = 0 get
the physical tag 2 (the contact boundary id); the rest of the boundary is
untagged (id 0).

usage: make_block_msh.py > block_2x1x2.msh
"""
NX, NY, NZ = 2, 1, 2
X0, X1, Y0, Y1, Z0, Z1 = -0.05, 0.05, 0.0, 0.01, -0.05, 0.05


def node(i, j, k):
    """1-based Gmsh number of the vertex (i, j, k), numbered z-fastest."""
    return 1 + k + (NZ + 1) * (j + (NY + 1) * i)


def coordinate(i, j, k):
    return (X0 + (X1 - X0) * i / NX, Y0 + (Y1 - Y0) * j / NY,
            Z0 + (Z1 - Z0) * k / NZ)


nodes = [(node(i, j, k), coordinate(i, j, k))
         for i in range(NX + 1) for j in range(NY + 1) for k in range(NZ + 1)]
elements = []
# Lower face y = 0: quadrilaterals (type 3) with physical tag 2.
for i in range(NX):
    for k in range(NZ):
        elements.append((3, 2, [node(i, 0, k), node(i + 1, 0, k),
                                node(i + 1, 0, k + 1), node(i, 0, k + 1)]))
# Hexahedra (type 5), Gmsh's order: the face z = z_k counter-clockwise
# seen from +z, then the face z = z_k+1.
for i in range(NX):
    for j in range(NY):
        for k in range(NZ):
            elements.append((5, 1, [node(i, j, k), node(i + 1, j, k),
                                    node(i + 1, j + 1, k), node(i, j + 1, k),
                                    node(i, j, k + 1), node(i + 1, j, k + 1),
                                    node(i + 1, j + 1, k + 1),
                                    node(i, j + 1, k + 1)]))

print("$MeshFormat\n2.2 0 8\n$EndMeshFormat")
print(f"$Nodes\n{len(nodes)}")
for number, (x, y, z) in sorted(nodes):
    print(f"{number} {x:.17g} {y:.17g} {z:.17g}")
print(f"$EndNodes\n$Elements\n{len(elements)}")
for n, (kind, tag, vertices) in enumerate(elements, start=1):
    print(f"{n} {kind} 2 {tag} {tag} " + " ".join(map(str, vertices)))
print("$EndElements")
