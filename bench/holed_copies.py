#!/usr/bin/env python3
"""Holed copies of the evaluation shapes: the same meshes with a few holes punched in them, as
a scan's occlusions leave them, and the ground truth restricted to what is left, for
measuring how the detector (and its peer) hold up on incomplete input.

Every `NAME.off` under DATA/DATASET loses every triangle with a corner within geodesic
distance `radius · √area` (Dijkstra on the edge graph) of one of `--holes` vertices drawn at
random; the vertices no triangle uses any more are dropped and the rest renumbered, and
`NAME.sym.txt` keeps the pairs whose two vertices are both left. The holes fall where they
fall: not mirrored, sometimes on one another, sometimes across a thin part (which the
detector then sees as a separate component). Drawn from one generator seeded with `--seed`,
shape after shape in sorted order, so a copy is reproducible.

    python3 bench/holed_copies.py OUT [--data DIR] [--radius 0.08] [--holes 3] [--seed 5]
                                      [--datasets tosca,faust]

Then, as for the clean data (docs/accuracy.md, "Session 31"):

    python3 bench/pyfm_peer.py --data OUT --cache OUT.pyfm
    ./target/release/intrinsym-eval --data OUT --peer OUT.pyfm --tsv holed.tsv

At radius 0.08 a hole's rim is about 0.5·√area long, inside `intrinsym::mesh::holes::MAX_LOOP`
(2.0) and above `MIN_LOOP` (0.4): the detector caps it; at radius 0.05 (rims about 0.3) the
holes stay open. Evaluation tooling only: never in the product's runtime path.
"""
import argparse
import os
import sys

import numpy as np
from scipy.sparse.csgraph import dijkstra

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import area, edge_graph, read_off, shapes_with_truth, write_off  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--radius", type=float, default=0.08, help="hole radius, fraction of sqrt(area)")
    ap.add_argument("--holes", type=int, default=3)
    ap.add_argument("--seed", type=int, default=5)
    ap.add_argument("--datasets", default="tosca,faust")
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    for ds, path, truth_path in shapes_with_truth(args.data, args.datasets.split(","), args.out):
        v, faces = read_off(path)
        centres = rng.choice(len(v), args.holes, replace=False)
        d = dijkstra(edge_graph(v, faces), directed=False, indices=centres).min(axis=0)
        gone = d < args.radius * np.sqrt(area(v, faces))
        faces = faces[~gone[faces].any(axis=1)]
        used = np.zeros(len(v), bool)
        used[faces.ravel()] = True
        new = np.cumsum(used) - 1
        truth = np.loadtxt(truth_path, dtype=int).reshape(-1, 2)
        truth = truth[used[truth[:, 0]] & used[truth[:, 1]]]
        name = os.path.basename(path)
        write_off(os.path.join(args.out, ds, name), v[used], new[faces])
        np.savetxt(os.path.join(args.out, ds, os.path.basename(truth_path)), new[truth], fmt="%d")
        print(f"{ds}/{name}: {used.sum()} of {len(v)} vertices left, {len(truth)} truth pairs")


if __name__ == "__main__":
    main()
