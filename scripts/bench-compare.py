#!/usr/bin/env python3
"""Compares two Google Benchmark results, benchmark by benchmark.

  bench-compare.py OLD NEW [--cpu]

OLD and NEW are JSON files or bench/results/<stamp>/ directories (every suite in them).
Prints a markdown table: benchmark, old, new, ratio = new / old of the median real time
(--cpu: CPU time; real time is what matters for multi-threaded benchmarks), so below 1.00 is
faster. Benchmarks present on one side only are listed with a dash on the other.
Medians come from --benchmark_repetitions (aggregate rows); with one run they are that run.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_results  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("old")
    parser.add_argument("new")
    parser.add_argument("--cpu", action="store_true", help="compare CPU time, not real time")
    args = parser.parse_args()
    old, _ = bench_results.load(args.old)
    new, _ = bench_results.load(args.new)
    key = "cpu_ns" if args.cpu else "real_ns"
    print(f"old: {args.old}\nnew: {args.new}\n")
    print(f"| benchmark | old | new | ratio new/old |")
    print(f"|---|---:|---:|---:|")
    for name in sorted(set(old) | set(new), key=lambda n: (
            (old.get(n) or new.get(n))["suite"], n)):
        o, n = old.get(name), new.get(name)
        ratio = f"{n[key] / o[key]:.2f}" if o and n and o[key] > 0 else "-"
        print(f"| {name} | {bench_results.format_ns(o[key]) if o else '-'} | "
              f"{bench_results.format_ns(n[key]) if n else '-'} | {ratio} |")


if __name__ == "__main__":
    main()
