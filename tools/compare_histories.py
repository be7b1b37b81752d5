#!/usr/bin/env python3
"""Compare two history.csv files of the same scene (for example a serial
program's and contact_mpi's, or runs on 1 and 2 MPI ranks).

    compare_histories.py A/history.csv B/history.csv [--tolerance 1e-8]

The columns both files have are compared row by row, each against a scale
that says what the number means, so that round-off in a small number is
not read as a difference:

* momentum_* (and each body's, *_momentum_*): the largest |p| over the
  run (all these columns together),
  with --allowance added to the tolerance: the two runs' own impulse
  balance errors (|p(t) - p(0) - impulses| / max |p|, in their
  summary.json), which the round-off of K u (a body that slides far
  carries a large rigid displacement) makes of order 1e-8;
* kinetic_energy: against its largest value (elastic_energy is not
  compared: u.K u of a body that slides far is a difference of large
  numbers, whose round-off, eps |u| |K| |u|, reaches 1e-8 of the kinetic
  energy on the sliding blocks);
* force_* (and each body's, *_force_*): accumulated over the steps (sum
  of force times h, the contact impulse), against the largest accumulated
  |impulse|: a step in which a body stops carries the momentum's
  round-off divided by h;
* normal_force: itself, against its largest value;
* active_contacts: exactly.

--rename OLD=NEW (repeatable) renames the columns of A that start with OLD
(for example bar_1_=body_1_: the serial bars' names against
contact_mpi's body_1_ and body_2_).

Prints one line per quantity and exits with 1 if one differs by more than
the tolerance."""
import argparse
import csv
import sys


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"compare_histories: {path} has no rows")
    return rows


def column(rows, name):
    return [float(r[name]) for r in rows]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--tolerance", type=float, default=1e-8)
    ap.add_argument("--allowance", type=float, default=0.,
                    help="added to the tolerance of the momentum")
    ap.add_argument("--rename", action="append", default=[],
                    help="OLD=NEW: rename A's columns that start with OLD")
    args = ap.parse_args()
    a, b = read(args.a), read(args.b)
    for rule in args.rename:
        old, _, new = rule.partition("=")
        a = [{(new + k[len(old):] if k.startswith(old) else k): v
              for k, v in r.items()} for r in a]
    if len(a) != len(b):
        print(f"different numbers of rows: {len(a)} and {len(b)}")
        return 1
    common = [c for c in a[0] if c in b[0]]
    ta, tb = column(a, "time"), column(b, "time")
    if max(abs(x - y) for x, y in zip(ta, tb)) > 1e-12 * max(map(abs, ta)):
        print("the times of the rows differ")
        return 1
    checks = []  # (quantity, largest difference, scale)

    momentum = [c for c in common
                if c.startswith("momentum_") or "_momentum_" in c]
    if momentum:
        scale = max(sum(float(r[c]) ** 2 for c in momentum) ** 0.5 for r in a)
        diff = max(abs(float(r[c]) - float(s[c]))
                   for r, s in zip(a, b) for c in momentum)
        checks.append(("momentum", diff, scale, args.allowance))
    if "kinetic_energy" in common:
        ea, eb = column(a, "kinetic_energy"), column(b, "kinetic_energy")
        checks.append(("kinetic energy",
                       max(abs(x - y) for x, y in zip(ea, eb)),
                       max(map(abs, ea)), 0.))
    forces = [c for c in common if c.startswith("force_") or "_force_" in c]
    if forces:
        acc_a = {c: 0. for c in forces}
        acc_b = {c: 0. for c in forces}
        diff = scale = 0.
        for i in range(1, len(a)):
            h = ta[i] - ta[i - 1]
            for c in forces:
                acc_a[c] += h * float(a[i][c])
                acc_b[c] += h * float(b[i][c])
                diff = max(diff, abs(acc_a[c] - acc_b[c]))
            scale = max(scale, sum(v * v for v in acc_a.values()) ** 0.5)
        checks.append(("accumulated contact impulse", diff, scale, 0.))
    if "normal_force" in common:
        na, nb = column(a, "normal_force"), column(b, "normal_force")
        checks.append(("normal force", max(abs(x - y) for x, y in zip(na, nb)),
                       max(map(abs, na)), 0.))
    ok = True
    for name, diff, scale, allowance in checks:
        rel = diff / scale if scale > 0 else diff
        bound = args.tolerance + allowance
        good = rel <= bound
        ok &= good
        print(f"{name}: largest difference {rel:.2e} of its scale "
              f"{scale:.4g}, bound {bound:.2e} ({'OK' if good else 'DIFFERENT'})")
    if "active_contacts" in common:
        same = column(a, "active_contacts") == column(b, "active_contacts")
        ok &= same
        print(f"active contacts: {'the same at every step' if same else 'DIFFERENT'}")
    print(f"{len(a)} rows, {'agree' if ok else 'differ'} to {args.tolerance:g}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
