#!/usr/bin/env python3
"""Noisy copies of the evaluation shapes: the same meshes with Gaussian noise on the vertex
positions, and the same ground truth, for measuring how the detector (and its peer) hold up
on messy input.

Every vertex of every `NAME.off` under DATA/DATASET gets independent normal noise of standard
deviation `sigma · √area` on each coordinate (`area` the mesh's surface area, so the noise
means the same on every shape whatever its units); the connectivity and `NAME.sym.txt` are
copied as they are. The noise is drawn from one generator seeded with `--seed`, shape after
shape in sorted order, so a copy is reproducible.

    python3 bench/noisy_copies.py OUT [--data DIR] [--sigma 0.002] [--seed 7]
                                      [--datasets tosca,faust,shrec16_kids,kids_hires]

Then, as for the clean data (docs/accuracy.md, "Session 30"):

    python3 bench/pyfm_peer.py --data OUT --cache OUT.pyfm
    ./target/release/intrinsym-eval --data OUT --peer OUT.pyfm --tsv noisy.tsv

For scale: at sigma = 0.002 the noise is about 14% of the mean edge length of the 5k FAUST
meshes (their edges are 0.014 · √area long), 11% of TOSCA's and 47% of the 60k KIDS poses'.
Evaluation tooling only: never in the product's runtime path.
"""
import argparse
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from hierarchy import area, read_off, shapes_with_truth  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out")
    ap.add_argument("--data", default=os.path.join(here, "..", "..", "shared", "data"))
    ap.add_argument("--sigma", type=float, default=0.002, help="noise per coordinate, fraction of sqrt(area)")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--datasets", default="tosca,faust,shrec16_kids,kids_hires")
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)
    for ds, path, truth in shapes_with_truth(args.data, args.datasets.split(","), args.out):
        v, faces = read_off(path)
        v = v + rng.normal(0.0, args.sigma * np.sqrt(area(v, faces)), v.shape)
        name = os.path.basename(path)
        with open(os.path.join(args.out, ds, name), "w") as f:
            f.write(f"OFF\n{len(v)} {len(faces)} 0\n")
            f.write("\n".join("%.9g %.9g %.9g" % tuple(p) for p in v))
            f.write("\n")
            f.write("\n".join("3 %d %d %d" % tuple(t) for t in faces))
            f.write("\n")
        shutil.copy(truth, os.path.join(args.out, ds, os.path.basename(truth)))
        print(f"{ds}/{name}: {len(v)} vertices")


if __name__ == "__main__":
    main()
