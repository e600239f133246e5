"""The pyFM peer of the accuracy evaluation (issue 14): off-the-shelf functional maps.

For every `NAME.off` with a `NAME.sym.txt` under DATA (default ../shared/data), computes the
orientation-reversing self-map of pyFM (`pyfmaps` 1.3.1) with the settings of issue 14:
WKS with 100 descriptors, k_process=200, fit(K=(30,30), w_descr=1, w_lap=1e-2, w_dcomm=1e-1,
w_orient=1, orient_reversing=True), zoomout_refine(nit=15, step=5), the map get_p2p of that.
Writes one image vertex per line to CACHE/NAME.map (default ~/.cache/intrinsym/pyfm); a shape
whose map is cached is skipped (the maps do not change). `intrinsym-eval --peer CACHE` scores
them with the same scorer as intrinsym's maps.

    python3 bench/pyfm_peer.py [--data DIR] [--cache DIR] [--only SUBSTRING]

Test tooling only: never in the product's runtime path.
"""
import argparse
import os
import sys
import time

import numpy as np
from pyFM.functional import FunctionalMapping
from pyFM.mesh import TriMesh


def read_off(path):
    with open(path) as f:
        tokens = f.read().split()
    assert tokens[0] == "OFF", path
    n, m = int(tokens[1]), int(tokens[2])
    i = 4
    v = np.array(tokens[i:i + 3 * n], dtype=float).reshape(n, 3)
    i += 3 * n
    faces = []
    for _ in range(m):
        c = int(tokens[i])
        faces.append([int(t) for t in tokens[i + 1:i + 1 + c]])
        i += 1 + c
    return v, np.array(faces, dtype=np.int64)


def self_map(vertices, faces):
    m1 = TriMesh(vertices, faces)
    m2 = TriMesh(vertices, faces)
    model = FunctionalMapping(m1, m2)
    model.preprocess(n_descr=100, descr_type="WKS", k_process=200, verbose=False)
    model.fit(K=(30, 30), w_descr=1, w_lap=1e-2, w_dcomm=1e-1, w_orient=1,
              orient_reversing=True, verbose=False)
    model.zoomout_refine(nit=15, step=5, verbose=False)
    return np.asarray(model.get_p2p(n_jobs=1))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "../../shared/data"))
    ap.add_argument("--cache", default=os.path.expanduser("~/.cache/intrinsym/pyfm"))
    ap.add_argument("--only", default="")
    args = ap.parse_args()
    os.makedirs(args.cache, exist_ok=True)
    shapes = []
    for root, _, files in os.walk(args.data):
        for f in files:
            if f.endswith(".sym.txt"):
                name = f[: -len(".sym.txt")]
                off = os.path.join(root, name + ".off")
                if os.path.exists(off) and args.only in name:
                    shapes.append((os.path.getsize(off), name, off))
    for _, name, off in sorted(shapes):
        out = os.path.join(args.cache, name + ".map")
        if os.path.exists(out):
            continue
        t = time.perf_counter()
        v, f = read_off(off)
        p2p = self_map(v, f)
        tmp = out + ".tmp"
        np.savetxt(tmp, p2p, fmt="%d")
        os.replace(tmp, out)
        print(f"{name}: {len(v)} vertices, {time.perf_counter() - t:.1f} s", flush=True)


if __name__ == "__main__":
    sys.exit(main())
