#!/usr/bin/env python3
"""Compares two triangle-id images (TSID, issue 3) pixel for pixel.

  compare-ids.py A.id B.id [--max-fraction F] [--show N]

Prints one summary line:
  ids: 2073600 pixels, 12 differ (0.000579%): 3 covered only in A, 2 only in B, 7 by
  different triangles
then, with --show N, the first N differing pixels as "x y idA idB" (rows top to bottom).
Exits 1 when the fraction of differing pixels exceeds --max-fraction (default: never),
2 on unreadable or mismatched files.
"""
import argparse
import sys
from array import array

EMPTY = 0xFFFFFFFF


def read_tsid(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError as e:
        sys.exit(f"compare-ids: cannot read '{path}': {e.strerror}")
    end = data.find(b"\n")
    words = data[:end].split() if end > 0 else []
    if len(words) != 3 or words[0] != b"TSID":
        sys.exit(f"compare-ids: '{path}' is not a TSID file (header 'TSID W H')")
    w, h = int(words[1]), int(words[2])
    ids = array("I")
    ids.frombytes(data[end + 1:])
    if sys.byteorder != "little":
        ids.byteswap()
    if len(ids) != w * h:
        sys.exit(f"compare-ids: '{path}': {len(ids)} ids for {w}x{h} pixels")
    return w, h, ids


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--max-fraction", type=float, default=None)
    parser.add_argument("--show", type=int, default=0)
    args = parser.parse_args()
    wa, ha, a = read_tsid(args.a)
    wb, hb, b = read_tsid(args.b)
    if (wa, ha) != (wb, hb):
        print(f"compare-ids: sizes differ: {wa}x{ha} vs {wb}x{hb}", file=sys.stderr)
        sys.exit(2)
    only_a = only_b = other = 0
    shown = []
    if a != b:  # the common case (identical) costs one C-level comparison
        for i, (x, y) in enumerate(zip(a, b)):
            if x != y:
                if y == EMPTY:
                    only_a += 1
                elif x == EMPTY:
                    only_b += 1
                else:
                    other += 1
                if len(shown) < args.show:
                    shown.append(f"{i % wa} {i // wa} {x if x != EMPTY else '-'} "
                                 f"{y if y != EMPTY else '-'}")
    total = wa * ha
    differ = only_a + only_b + other
    fraction = differ / total if total else 0.0
    print(f"ids: {total} pixels, {differ} differ ({100 * fraction:.6f}%): {only_a} covered only "
          f"in A, {only_b} only in B, {other} by different triangles")
    for line in shown:
        print(line)
    if args.max_fraction is not None and fraction > args.max_fraction:
        sys.exit(1)


if __name__ == "__main__":
    main()
