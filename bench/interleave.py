#!/usr/bin/env python3
"""Compare the speed of intrinsym builds on TOSCA, interleaved (this machine's speed drifts).

    python3 bench/interleave.py ROUNDS BIN [BIN ...]
    python3 bench/interleave.py 4 /tmp/old/intrinsym target/release/intrinsym

Every round runs every TOSCA shape of ../shared/data with each binary in turn
(`intrinsym detect SHAPE --json`), so drift hits all builds alike. Per binary and shape the
fastest round is kept (by `timings.total`), then the mean over the shapes is printed, total
and per stage. A `BIN` may be a script (for instance `taskset -c 0 BIN "$@"` for one core).
"""
import glob
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "shared", "data", "tosca")


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rounds, bins = int(sys.argv[1]), sys.argv[2:]
    shapes = sorted(glob.glob(os.path.join(DATA, "*.off")))
    if not shapes:
        sys.exit(f"no shapes in {DATA}")
    best = {b: {} for b in bins}
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out.json")
        for _ in range(rounds):
            for shape in shapes:
                for b in bins:
                    subprocess.run([b, "detect", shape, "--json", out], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
                    with open(out) as f:
                        t = json.load(f)["timings"]
                    if shape not in best[b] or t["total"] < best[b][shape]["total"]:
                        best[b][shape] = t
    for b in bins:
        mean = lambda key: sum(best[b][s][key] for s in shapes) / len(shapes)
        stages = [k for k in best[b][shapes[0]] if k != "total" and mean(k) >= 0.0005]
        print(f"{b}: total {mean('total'):.3f} s  " + "  ".join(f"{k} {mean(k):.3f}" for k in stages))


if __name__ == "__main__":
    main()
