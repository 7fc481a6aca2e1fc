#!/usr/bin/env python3
"""Writes a benchmark workload as PREFIX.obj + PREFIX.cam (issue 3's CAM.txt), so that
`tessera raster` and `tessera-llvmpipe` render identical work without committed data.
(The single sphere and the MSOC fill-rate triangles come from `tessera testmesh`, the
meshes of bench_raster; this script adds the two workloads it lacks.)

  gen-workload.py grid     --triangles N --pixels S [--size WxH] --out PREFIX
      Screen-aligned grid of S x S px quads (2 triangles each, shared vertices on pixel
      corners, so diagonals pass through pixel centres: a fill-rule test), filling the screen
      in layers from back to front until N triangles.
  gen-workload.py spheres  --triangles N [--seed K] --out PREFIX
      A field of parametric spheres (n = (cos 2pi u sin pi v, sin 2pi u sin pi v,
      cos pi v), p = c + R n; 16 x 32 grid = 1024 triangles each) with normals and uv, for
      --shade phong. N = 1048576 gives the "1M-triangle Phong" workload.

Deterministic: the same arguments give the same bytes (Python's Mersenne Twister is stable
across versions for random()). Coordinates are written with 9 significant digits, enough
for float32 to read back exactly what was computed.
"""
import argparse
import math
import os
import random
import sys

# Camera for the screen-space workloads: at distance d in front of the eye, fovy 90 deg,
# pixel (px, py) (top-down, corners at integers) is world (x_ndc*aspect*d, y_ndc*d, 1 - d).
SCREEN_CAMERA = "eye 0 0 1\nlookat 0 0 0\nup 0 1 0\nfovy_deg 90\nnear 0.5\nfar 20\n"


def parse_size(text):
    try:
        w, h = (int(v) for v in text.lower().split("x"))
        if w > 0 and h > 0:
            return w, h
    except ValueError:
        pass
    raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT, got '{text}'")


def unproject(px, py, d, w, h):
    x_ndc = 2.0 * px / w - 1.0
    y_ndc = 1.0 - 2.0 * py / h
    return (x_ndc * (w / h) * d, y_ndc * d, 1.0 - d)


def fmt(v):
    return "%.9g" % v


class Obj:
    """Accumulates an OBJ in memory; every vertex carries a normal and a uv (same index)."""

    def __init__(self):
        self.lines = []
        self.vertices = 0
        self.triangles = 0

    def vertex(self, p, n, uv):
        self.lines.append("v %s %s %s\nvn %s %s %s\nvt %s %s\n" % (
            fmt(p[0]), fmt(p[1]), fmt(p[2]), fmt(n[0]), fmt(n[1]), fmt(n[2]),
            fmt(uv[0]), fmt(uv[1])))
        self.vertices += 1
        return self.vertices  # OBJ indices start at 1

    def triangle(self, a, b, c):
        self.lines.append("f %d/%d/%d %d/%d/%d %d/%d/%d\n" % (a, a, a, b, b, b, c, c, c))
        self.triangles += 1


def layer_depth(i, layers):
    """Back to front: the first layer is the farthest."""
    return 9.0 - 8.0 * (i + 0.5) / layers


def grid(args, obj):
    w, h = args.size
    s = args.pixels
    cols, rows = max(1, w // s), max(1, h // s)
    per_layer = 2 * cols * rows
    layers = -(-args.triangles // per_layer)
    for layer in range(layers):
        d = layer_depth(layer, layers)
        first = obj.vertices + 1
        for j in range(rows + 1):
            for i in range(cols + 1):
                obj.vertex(unproject(i * s, j * s, d, w, h), (0, 0, 1), (i / cols, j / rows))
        for j in range(rows):
            for i in range(cols):
                if obj.triangles + 2 > args.triangles:
                    return
                a = first + j * (cols + 1) + i
                b, c, e = a + 1, a + cols + 1, a + cols + 2
                # counter-clockwise on screen with y up: (a, c, b) and (b, c, e)
                obj.triangle(a, c, b)
                obj.triangle(b, c, e)


def spheres(args, obj):
    nv, nu = 16, 32  # 2 * 16 * 32 = 1024 triangles per sphere
    count = max(1, round(args.triangles / (2 * nu * nv)))
    cols = max(1, round(math.sqrt(count * 16 / 9)))
    rows = -(-count // cols)
    rng = random.Random(args.seed)
    for k in range(count):
        cx = (k % cols) - (cols - 1) / 2
        cy = (k // cols) - (rows - 1) / 2
        cz = rng.uniform(-0.3, 0.3)
        r = rng.uniform(0.35, 0.6)
        first = obj.vertex  # local alias for speed
        base = obj.vertices + 1
        for j in range(nv + 1):
            v = j / nv
            sv, cv = math.sin(math.pi * v), math.cos(math.pi * v)
            for i in range(nu + 1):
                u = i / nu
                n = (math.cos(2 * math.pi * u) * sv, math.sin(2 * math.pi * u) * sv, cv)
                first((cx + r * n[0], cy + r * n[1], cz + r * n[2]), n, (u, v))
        for j in range(nv):
            for i in range(nu):
                a = base + j * (nu + 1) + i
                b, c, e = a + 1, a + nu + 1, a + nu + 2
                # outward-facing (counter-clockwise seen from outside)
                obj.triangle(a, b, e)
                obj.triangle(a, e, c)
    distance = (rows / 2 + 1) / math.tan(math.radians(30))
    return ("eye 0 0 %s\nlookat 0 0 0\nup 0 1 0\nfovy_deg 60\nnear %s\nfar %s\n"
            % (fmt(distance), fmt(distance / 4), fmt(distance * 2)))


def write_atomically(path, text):
    tmp = path + ".tmp%d" % os.getpid()
    with open(tmp, "w") as f:
        f.write(text)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("kind", choices=["grid", "spheres"])
    parser.add_argument("--triangles", type=int, required=True)
    parser.add_argument("--pixels", type=int, default=10, help="triangle leg in pixels")
    parser.add_argument("--size", type=parse_size, default=(1920, 1080))
    parser.add_argument("--seed", type=int, default=1, help="spheres: radii and depths")
    parser.add_argument("--out", required=True, help="writes OUT.obj and OUT.cam")
    args = parser.parse_args()
    if args.triangles <= 0 or args.pixels <= 0:
        parser.error("--triangles and --pixels must be positive")
    obj = Obj()
    camera = {"grid": grid, "spheres": spheres}[args.kind](args, obj)
    header = "# tessera workload: %s\n" % " ".join(sys.argv[1:])
    write_atomically(args.out + ".obj", header + "".join(obj.lines))
    write_atomically(args.out + ".cam", camera or SCREEN_CAMERA)
    print("%s.obj: %d triangles, %d vertices" % (args.out, obj.triangles, obj.vertices))


if __name__ == "__main__":
    main()
