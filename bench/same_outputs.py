#!/usr/bin/env python3
"""Check that two intrinsym builds detect the same symmetries on shared/data's shapes.

    python3 bench/same_outputs.py OLD_BIN NEW_BIN [DATASET ...]

Runs `intrinsym detect SHAPE --json` with both binaries on every shape of the named datasets
of ../shared/data (folder names: tosca, faust, shrec16_kids, kids_hires; by default tosca
and shrec16_kids; SHREC'16 kids with --allow-non-manifold) and compares the JSON `symmetries` (every map,
confidence, functional map, complexity, ...) exactly, on the keys both builds write (a field
added by the new build is not a difference). Prints one line per shape and exits
with status 1 when any differs. A speed change that should not change results must pass this
(and `intrinsym-eval --generated` must print the same table).
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data")


def symmetries(binary, shape, out):
    extra = ["--allow-non-manifold"] if "shrec16" in shape else []
    subprocess.run([binary, "detect", shape, "--json", out] + extra, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
    with open(out) as f:
        return json.load(f)["symmetries"]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    old, new = sys.argv[1:3]
    datasets = sys.argv[3:] or ["tosca", "shrec16_kids"]
    shapes = [s for d in datasets for s in sorted(glob.glob(os.path.join(DATA, d, "*.off")))]
    if not shapes:
        sys.exit(f"no shapes in {DATA}")
    different = 0
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.json")
        for shape in shapes:
            a, b = symmetries(old, shape, out), symmetries(new, shape, out)
            common = lambda x, y: [{k: v for k, v in s.items() if k in t} for s, t in zip(x, y)]
            same = len(a) == len(b) and common(a, b) == common(b, a)
            different += not same
            print(f"{os.path.basename(shape)}: {'same' if same else 'DIFFERENT'} ({len(a)} and {len(b)} symmetries)")
    print(f"{different} of {len(shapes)} shapes differ")
    sys.exit(1 if different else 0)


if __name__ == "__main__":
    main()
