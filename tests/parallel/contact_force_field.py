#!/usr/bin/env python3
"""ctest driver of parallel/contact_force_field: contact_mpi on two ranks
with VTU output (three_materials.prm, Scene = bodies), then reads every
written .pvtu's pieces back and checks, at each output time,

* the cell field `body` holds the bodies 1, 2, 3;
* the nodal `contact_force` summed over each body's nodes equals that
  body's contact force in history.csv (body_b_force_x, _y) at that time,
  to 1e-5 of the largest (the VTU holds float32); the two sums are made
  by different code (DistributedContact::add_impulses() with the nodes'
  weights against the candidates' frames in body_impulses());
* over the run the force field is non-zero somewhere (so the check is not
  0 = 0), and equal and opposite across each interface (the bodies'
  sums add up to zero, no obstacle).

The VTU reader follows deal.II's zlib-compressed appended-inline format:
each DataArray is base64(header) + base64(zlib data), the header four
uint32 (1 block, its size, the last block's size, the compressed
size)."""
import base64
import csv
import os
import shlex
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import bodies_arguments, write_meshes  # noqa: E402
from serial_vs_mpi import run as run_logged  # noqa: E402


def decode(array):
    """The values of a deal.II DataArray (float32, int32, uint8...)."""
    text = "".join(array.text.split())
    header = base64.b64decode(text[:24])
    blocks, _, _, size = struct.unpack("<4I", header)
    assert blocks == 1, "one compressed block expected"
    data = zlib.decompress(base64.b64decode(text[24:]))
    kind = {"Float32": "f", "Float64": "d", "Int32": "i", "UInt32": "I",
            "UInt8": "B", "Int64": "q", "UInt64": "Q"}[array.get("type")]
    return struct.unpack(f"<{len(data) // struct.calcsize(kind)}{kind}",
                         data)


def read_piece(path):
    """Points, connectivity and the point arrays (deal.II writes cell data
    such as `body` as point data of each cell's own copies of its
    vertices)."""
    piece = ET.parse(path).getroot().find("UnstructuredGrid/Piece")
    arrays = {}
    for group in ("Points", "Cells", "PointData"):
        for array in piece.find(group).findall("DataArray"):
            name = array.get("Name", group)
            arrays[(group, name)] = (decode(array),
                                     int(array.get("NumberOfComponents",
                                                   "1")))
    return arrays


def body_forces(pvtu, dim):
    """Per body (1, 2, ...), the sum of contact_force over its distinct
    nodes (a node is written once per cell and per piece)."""
    directory = os.path.dirname(pvtu)
    root = ET.parse(pvtu).getroot()
    seen = set()
    sums = {}
    bodies = set()
    for piece in root.find("PUnstructuredGrid").findall("Piece"):
        a = read_piece(os.path.join(directory, piece.get("Source")))
        points, _ = a[("Points", "Points")]
        connectivity, _ = a[("Cells", "connectivity")]
        offsets, _ = a[("Cells", "offsets")]
        force, n_force = a[("PointData", "contact_force")]
        body, _ = a[("PointData", "body")]
        start = 0
        for end in offsets:
            for p in connectivity[start:end]:
                b = int(body[p])
                bodies.add(b)
                key = (b,) + tuple(points[3 * p:3 * p + 3])
                if key in seen:
                    continue
                seen.add(key)
                total = sums.setdefault(b, [0.] * dim)
                for d in range(dim):
                    total[d] += force[n_force * p + d]
            start = end
    return bodies, sums


def main():
    a = bodies_arguments(compare=False)
    os.makedirs(a.work)
    write_meshes(a.make_mesh, a.work,
                 {f"bar_{bar + 1}.msh": (2, 20, 4, (bar - 1) * 0.254, 0.254,
                                         0.0254) for bar in range(3)})
    text = open(a.prm).read().replace(
        "set VTU output             = false",
        "set VTU output             = true\n  set Output interval        = 4")
    assert "Output interval" in text
    with open(os.path.join(a.work, "run.prm"), "w") as out:
        out.write(text)
    run_logged(shlex.split(a.mpiexec) + [a.program, "run.prm"], a.work,
               "log")
    results = os.path.join(a.work, "results")
    rows = {float(r["time"]): r
            for r in csv.DictReader(open(os.path.join(results,
                                                      "history.csv")))}
    largest = max(abs(float(r[f"body_{b}_force_{x}"]))
                  for r in rows.values() for b in (1, 2, 3) for x in "xy")
    ok = largest > 0.
    worst = 0.
    n_files = 0
    for data_set in ET.parse(os.path.join(results, "solution.pvd")) \
            .getroot().iter("DataSet"):
        time = float(data_set.get("timestep"))
        bodies, sums = body_forces(os.path.join(results,
                                                data_set.get("file")), 2)
        if bodies != {1, 2, 3}:
            print(f"t = {time}: cell field body holds {sorted(bodies)}")
            ok = False
        row = min(rows.items(), key=lambda item: abs(item[0] - time))[1]
        for b in (1, 2, 3):
            for d, x in enumerate("xy"):
                worst = max(worst, abs(sums[b][d] -
                                       float(row[f"body_{b}_force_{x}"])))
        worst = max(worst, max(abs(sum(sums[b][d] for b in (1, 2, 3)))
                               for d in range(2)))
        n_files += 1
    print(f"{n_files} output times; cell field body holds 1, 2, 3: "
          f"{'OK' if ok else 'WRONG'}")
    within = worst <= 1e-5 * largest
    print(f"nodal contact_force summed per body against history.csv, and "
          f"the bodies' sum against 0: largest difference "
          f"{worst / largest:.1e} of the largest force, bound 1e-5 "
          f"({'OK' if within else 'WRONG'})")
    return 0 if ok and within and n_files > 10 else 1


if __name__ == "__main__":
    sys.exit(main())
