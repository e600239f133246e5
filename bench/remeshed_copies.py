#!/usr/bin/env python3
"""Remeshed copies of the evaluation shapes: the same surfaces with a different triangulation,
and the ground truth carried over, for measuring how the detector (and its peer) depend on the
meshing they were tuned on.

Every `NAME.off` under DATA/DATASET is remeshed by MeshLab's isotropic explicit remeshing
(`pymeshlab`, `meshing_isotropic_explicit_remeshing`: edge splits, collapses, flips and
tangential relaxation towards one target edge length, `--iterations` rounds) with the target
length chosen so that the copy has about `--scale` times the original's vertex count
(a first pass at the original's mean edge length, then one correction of the length by the
square root of the count ratio). The remesher's vertices lie on the original surface, but
none is an original vertex, so the truth is carried over through the nearest original vertex:
for a copy's vertex `x` whose nearest original vertex `o` (within one original mean edge) has
a truth image `T(o)`, the truth image of `x` is the copy's vertex nearest `T(o)`'s position.
Both nearest-vertex steps are within half an edge of the exact point, so a carried pair is
off by up to about one edge (0.014·√area on 5k shapes, a quarter of the acc@0.05 radius):
the copies' figures are comparable between methods, not to the originals' to the point
(docs/accuracy.md, "Session 37").

    python3 bench/remeshed_copies.py OUT [--data DIR] [--datasets tosca,faust]
                                         [--scale 1.0] [--iterations 5] [--only NAME]

The copies are regular where the originals are not: edge lengths between the 5th and 95th
percentile vary by a factor of about 1.8 on a copy, 6.5 on TOSCA's cat0 (its density follows
the detail).

Then, as for the clean data:

    python3 bench/pyfm_peer.py --data OUT --cache OUT.pyfm
    ./target/release/intrinsym-eval --data OUT --peer OUT.pyfm --tsv remeshed.tsv

Evaluation tooling only (`pip install pymeshlab`; numpy, scipy): never in the product's
runtime path.
"""
import argparse
import os
import sys

import numpy as np
from scipy.spatial import cKDTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import read_off, shapes_with_truth, write_off  # noqa: E402


def mean_edge(v, f):
    e = np.concatenate([f[:, [0, 1]], f[:, [1, 2]], f[:, [2, 0]]])
    e = np.unique(np.sort(e, axis=1), axis=0)
    return np.linalg.norm(v[e[:, 0]] - v[e[:, 1]], axis=1).mean()


def remesh(v, f, length, iterations):
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.add_mesh(pymeshlab.Mesh(vertex_matrix=v, face_matrix=f))
    ms.meshing_isotropic_explicit_remeshing(iterations=iterations, targetlen=pymeshlab.PureValue(length))
    ms.meshing_remove_unreferenced_vertices()
    m = ms.current_mesh()
    return np.asarray(m.vertex_matrix(), float), np.asarray(m.face_matrix(), int)


def read_truth(path):
    pairs = []
    with open(path) as fh:
        for line in fh:
            t = line.split()
            if len(t) >= 2:
                pairs.append((int(t[0]), int(t[1])))
    return pairs


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--datasets", default="tosca,faust")
    ap.add_argument("--scale", type=float, default=1.0, help="vertex count of a copy over the original's")
    ap.add_argument("--iterations", type=int, default=5)
    ap.add_argument("--only", default="", help="only shapes whose name contains this")
    args = ap.parse_args()
    for ds, path, truth_path in shapes_with_truth(args.data, args.datasets.split(","), args.out):
        name = os.path.basename(path)[:-4]
        if args.only not in name:
            continue
        v, f = read_off(path)
        edge = mean_edge(v, f)
        # The remesher's length is not its mean edge: one correction by the count ratio.
        length = edge / np.sqrt(args.scale)
        rv, rf = remesh(v, f, length, args.iterations)
        length *= np.sqrt(len(rv) / (args.scale * len(v)))
        rv, rf = remesh(v, f, length, args.iterations)
        # Carry the truth over through the nearest original vertex.
        dist, nearest = cKDTree(v).query(rv)
        truth = dict(read_truth(truth_path))
        copy_tree = cKDTree(rv)
        pairs = []
        for x, (d, o) in enumerate(zip(dist, nearest)):
            if d <= edge and o in truth:
                pairs.append((x, int(copy_tree.query(v[truth[o]])[1])))
        write_off(os.path.join(args.out, ds, name + ".off"), rv, rf)
        with open(os.path.join(args.out, ds, name + ".sym.txt"), "w") as fh:
            fh.write("".join(f"{a} {b}\n" for a, b in pairs))
        print(f"{ds}/{name}: {len(v)} -> {len(rv)} vertices, mean edge {edge:.4g} -> {mean_edge(rv, rf):.4g}, "
              f"truth {len(truth)} -> {len(pairs)} pairs", flush=True)


if __name__ == "__main__":
    main()
