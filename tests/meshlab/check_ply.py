"""Checks meshlabserver's output PLY: per-vertex quality in [0, 1], and that a vertex and its
mirror image carry the same colour (Correspondence colouring).

    check_ply.py OUT.ply              mirror pairs found by position (x -> -x): colours equal
    check_ply.py OUT.ply TRUTH.txt    posed mesh, true pairs `x sym_x` by index: colours within
                                      12 levels (a map within ~5% of the bounding box)
    check_ply.py OUT.ply --varied     the colours vary over the surface (a sphere's antipodal
                                      map once painted every vertex alike)
"""
import struct
import sys

SIZES = {"char": "b", "uchar": "B", "short": "h", "ushort": "H", "int": "i", "uint": "I", "float": "f", "double": "d",
         "int8": "b", "uint8": "B", "int16": "h", "uint16": "H", "int32": "i", "uint32": "I", "float32": "f", "float64": "d"}


def read_vertices(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    assert any("binary_little_endian" in l for l in header) or any("ascii" in l for l in header), header[:3]
    ascii_format = any(l.startswith("format ascii") for l in header)
    props, count, in_vertex = [], 0, False
    for line in header:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count, in_vertex = int(words[2]), True
        elif words and words[0] == "element":
            in_vertex = False
        elif in_vertex and words[:1] == ["property"]:
            props.append((words[-1], words[1]))
    names = [p[0] for p in props]
    rows = []
    if ascii_format:
        lines = data[end:].decode("ascii").split("\n")
        for i in range(count):
            values = lines[i].split()
            rows.append({n: float(v) for n, v in zip(names, values)})
    else:
        fmt = "<" + "".join(SIZES[t] for _, t in props)
        size = struct.calcsize(fmt)
        for i in range(count):
            rows.append(dict(zip(names, struct.unpack_from(fmt, data, end + i * size))))
    return rows


def check_truth(rows, truth_path):
    pairs = [tuple(map(int, l.split())) for l in open(truth_path) if l.strip()]
    close = sum(1 for a, b in pairs if max(abs(rows[a][c] - rows[b][c]) for c in ("red", "green", "blue")) <= 12)
    print("%d true mirror pairs, %d with colours within 12 levels (%.1f%%)" % (len(pairs), close, 100.0 * close / len(pairs)))
    assert close >= 0.85 * len(pairs), "mirror vertices do not share colours"


def main():
    rows = read_vertices(sys.argv[1])
    if sys.argv[2:] == ["--varied"]:
        colours = {(r["red"], r["green"], r["blue"]) for r in rows}
        spread = max(max(r[c] for r in rows) - min(r[c] for r in rows) for c in ("red", "green", "blue"))
        print("%d vertices, %d distinct colours, largest channel spread %d" % (len(rows), len(colours), spread))
        assert len(colours) >= 50 and spread >= 40, "the colouring says nothing about the map"
        return
    if len(sys.argv) > 2:
        assert all(0.0 <= r["quality"] <= 1.0 for r in rows), "quality outside [0, 1]"
        check_truth(rows, sys.argv[2])
        return
    n = len(rows)
    assert n > 0 and "quality" in rows[0] and "red" in rows[0], "no quality/colour in the PLY: %s" % list(rows[0])
    q = [r["quality"] for r in rows]
    assert all(0.0 <= x <= 1.0 for x in q), "quality outside [0, 1]"
    key = {(round(r["x"], 4), round(r["y"], 4), round(r["z"], 4)): i for i, r in enumerate(rows)}
    pairs = same = 0
    for r in rows:
        j = key.get((round(-r["x"], 4), round(r["y"], 4), round(r["z"], 4)))
        if j is None:
            continue
        pairs += 1
        s = rows[j]
        if (r["red"], r["green"], r["blue"]) == (s["red"], s["green"], s["blue"]):
            same += 1
    mean_q = sum(q) / n
    print("%d vertices, %d mirror pairs found by position, %d share their colour; mean quality %.3f" % (n, pairs, same, mean_q))
    assert pairs >= 0.95 * n, "mirror pairs not found"
    assert same >= 0.95 * pairs, "mirror vertices do not share colours"
    assert mean_q > 0.5, "confidence too low"


if __name__ == "__main__":
    main()
