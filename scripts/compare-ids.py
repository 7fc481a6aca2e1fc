#!/usr/bin/env python3
"""Compares two triangle-id images (TSID, issue 3) pixel for pixel, or sample for sample.

  compare-ids.py A.id B.id [--max-fraction F] [--show N]

Prints one summary line:
  ids: 2073600 pixels, 12 differ (0.000579%): 3 covered only in A, 2 only in B, 7 by
  different triangles
then, with --show N, the first N differing pixels as "x y idA idB" (rows top to bottom).
Multisampled files (header "TSID W H S": S ids per pixel, a pixel's samples adjacent) are
compared sample for sample: the line counts samples ("ids: 921600 samples (4 per pixel), ...")
and the differing ones show as "x y s idA idB". Both files must have the same sample count.
Exits 1 when the fraction of differing pixels (samples) exceeds --max-fraction (default:
never), 2 on unreadable or mismatched files.
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
    words = data[:end].split(b" ") if end > 0 else []
    if len(words) not in (3, 4) or words[0] != b"TSID" or not all(w.isdigit() for w in words[1:]):
        sys.exit(f"compare-ids: '{path}' is not a TSID file (header 'TSID W H' or 'TSID W H S')")
    w, h = int(words[1]), int(words[2])
    samples = int(words[3]) if len(words) == 4 else 1
    if len(words) == 4 and samples not in (4, 8, 16):
        sys.exit(f"compare-ids: '{path}': {samples} is not a sample count (4, 8 or 16)")
    ids = array("I")
    ids.frombytes(data[end + 1:])
    if sys.byteorder != "little":
        ids.byteswap()
    if len(ids) != w * h * samples:
        sys.exit(f"compare-ids: '{path}': {len(ids)} ids for {w}x{h} pixels x {samples} samples")
    return w, h, samples, ids


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--max-fraction", type=float, default=None)
    parser.add_argument("--show", type=int, default=0)
    args = parser.parse_args()
    wa, ha, na, a = read_tsid(args.a)
    wb, hb, nb, b = read_tsid(args.b)
    if (wa, ha, na) != (wb, hb, nb):
        print(f"compare-ids: sizes differ: {wa}x{ha} x {na} samples vs {wb}x{hb} x {nb} samples",
              file=sys.stderr)
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
                    pixel = i // na
                    where = f"{pixel % wa} {pixel // wa}" + (f" {i % na}" if na > 1 else "")
                    shown.append(f"{where} {x if x != EMPTY else '-'} {y if y != EMPTY else '-'}")
    total = wa * ha * na
    unit = "pixels" if na == 1 else f"samples ({na} per pixel)"
    differ = only_a + only_b + other
    fraction = differ / total if total else 0.0
    print(f"ids: {total} {unit}, {differ} differ ({100 * fraction:.6f}%): {only_a} covered only "
          f"in A, {only_b} only in B, {other} by different triangles")
    for line in shown:
        print(line)
    if args.max_fraction is not None and fraction > args.max_fraction:
        sys.exit(1)


if __name__ == "__main__":
    main()
