#!/usr/bin/env python3
"""Turns one benchmark run (bench/results/<stamp>/: Google Benchmark JSON per suite, written by
scripts/bench.sh, plus peer.jsonl from scripts/peer.sh) into markdown tables and PNG plots.

  bench-report.py [RESULTS_DIR]      (default: the newest directory under bench/results/)

Writes RESULTS_DIR/report.md (tables, ready for BENCHMARKS.md) and RESULTS_DIR/plots/*.png
through gnuplot (Debian gnuplot-nox; without it, tables only). Every figure and the report
name the machine (machine.txt), the command and the date.

Plots follow the benchmarks' argument names (Google Benchmark ArgNames, shown in the
benchmark name as key:value): `triangles` (or `ktris`, `mtris`), `height` (or `width`,
`pixels`), `lights`, `threads`; see AXES.
  time_vs_triangles.png  time_vs_resolution.png  time_vs_lights.png
  raster_vs_embree.png   (families whose name contains "Embree" against the others, by triangles)
  speedup_vs_threads.png (T(1 thread) / T(n threads) per configuration, with the ideal line)
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
from collections import defaultdict

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bench_results  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def newest_results():
    base = os.path.join(ROOT, "bench", "results")
    runs = sorted(d for d in os.listdir(base) if os.path.isdir(os.path.join(base, d))) \
        if os.path.isdir(base) else []
    if not runs:
        sys.exit("bench-report: no results under bench/results/ (run `make bench` first)")
    return os.path.join(base, runs[-1])


def machine_facts(directory, context):
    facts = {"cpu": context.get("host_name", "unknown machine"), "date": context.get("date", ""),
             "command": "scripts/bench.sh", "text": ""}
    path = os.path.join(directory, "machine.txt")
    if os.path.exists(path):
        with open(path) as f:
            facts["text"] = f.read().strip()
        for line in facts["text"].splitlines():
            key, _, value = line.partition(": ")
            if key in ("cpu", "date", "command"):
                facts[key] = value
    return facts


# Each plot axis and the argument names that mean it, with the factor to its unit.
AXES = {
    "triangles": (("triangles", 1), ("ktris", 1000), ("mtris", 1000000)),
    "resolution": (("height", 1), ("width", 1), ("pixels", 1)),
    "lights": (("lights", 1),),
    "threads": (("threads", 1),),
}


def series_by(results, axis, family_filter=lambda family: True):
    """{label: [(x, ms)]} for every benchmark with an argument meaning `axis`; the label is
    the family plus the other arguments, so each line is one configuration."""
    series = defaultdict(list)
    for name, r in results.items():
        family, args = bench_results.parse_name(name)
        key = next(((k, f) for k, f in AXES[axis] if k in args), None)
        if key is None or not family_filter(family):
            continue
        rest = ",".join(f"{k}={v}" for k, v in args.items() if k != key[0])
        label = family + (f" ({rest})" if rest else "")
        series[label].append((args[key[0]] * key[1], r["real_ns"] / 1e6))
    return {k: sorted(v) for k, v in series.items() if len(v) > 1}


def gnuplot(path, facts, xlabel, ylabel, series, logx=False, logy=False, ideal=False):
    lines = [
        "set terminal pngcairo size 1100,700 font 'sans,10'",
        f"set output '{path}'",
        "set title \"%s\\n%s, %s\" noenhanced" % (facts["cpu"], facts["command"], facts["date"]),
        f"set xlabel '{xlabel}'", f"set ylabel '{ylabel}'",
        "set key outside right top noenhanced", "set grid",
    ]
    if logx:
        lines.append("set logscale x")
    if logy:
        lines.append("set logscale y")
    plots = []
    for i, (label, points) in enumerate(sorted(series.items())):
        lines.append(f"$d{i} << EOD")
        lines += [f"{x} {y}" for x, y in points]
        lines.append("EOD")
        plots.append(f"$d{i} using 1:2 with linespoints title '{label}'")
    if ideal:
        plots.append("x with lines dashtype 2 lc rgb 'gray' title 'ideal'")
    lines.append("plot " + ", ".join(plots))
    subprocess.run(["gnuplot"], input="\n".join(lines), text=True, check=True)


def speedups(results):
    by_threads = series_by(results, "threads")
    out = {}
    for label, points in by_threads.items():
        one = dict(points).get(1)
        if one:
            out[label] = [(t, one / ms) for t, ms in points]
    return out


def peer_tables(directory):
    path = os.path.join(directory, "peer.jsonl")
    if not os.path.exists(path):
        return []
    rows = [json.loads(line) for line in open(path) if line.strip()]
    md = []

    # One table per kind of figure: wall time per frame, and CPU time per frame.
    def comparison(kind, heading, unit, suffix):
        chosen = [r for r in rows if r["kind"] == kind]
        if not chosen:
            return
        md.extend([heading, "",
                   f"| workload | size | shade | threads | tessera {unit} | llvmpipe {unit} | llvmpipe / tessera |",
                   "|---|---|---|---:|---:|---:|---:|"])
        for r in chosen:
            t, l = r["tessera" + suffix], r["llvmpipe" + suffix]
            ratio = "%.2f" % (l / t) if t else "-"
            md.append(f"| {r['workload']} | {r['size']} | {r['shade']} | {r['threads']} | "
                      f"{t if t is not None else '-'} | {l} | {ratio} |")
        md.append("")

    comparison("time", "### Peer: tessera raster vs Mesa llvmpipe (same workload, same threads)", "ms", "_ms")
    comparison("cpu", "CPU time per frame (all threads; steadier than wall time on a shared machine):",
               "CPU ms", "_cpu_ms")
    ids = [r for r in rows if r["kind"] == "ids"]
    if ids:
        md += ["| workload | size | pixels whose triangle id differs |", "|---|---|---:|"]
        md += [f"| {r['workload']} | {r['size']} | {r['differing_pixels']} |" for r in ids]
        md.append("")
    memory = [r for r in rows if r["kind"] == "memory"]
    if memory:
        md += ["| renderer | workload | size | peak RSS MiB | frame MiB (vs 64x64) |",
               "|---|---|---|---:|---:|"]
        md += [f"| {r['renderer']} | {r['workload']} | {r['size']} | "
               f"{r['peak_rss_kib'] / 1024:.1f} | {r['frame_kib'] / 1024:.1f} |" for r in memory]
        md.append("")
    return md


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("results", nargs="?", help="bench/results/<stamp> (default: newest)")
    args = parser.parse_args()
    directory = args.results or newest_results()
    has_json = any(f.endswith(".json") for f in os.listdir(directory))
    results, context = bench_results.load(directory) if has_json else ({}, {})
    facts = machine_facts(directory, context)

    md = [f"## Benchmarks: {os.path.basename(os.path.normpath(directory))}", "",
          f"Machine: {facts['cpu']}  ", f"Command: `{facts['command']}`  ",
          f"Date: {facts['date']}", ""]
    if facts["text"]:
        md += ["```", facts["text"], "```", ""]
    by_suite = defaultdict(list)
    for name, r in results.items():
        by_suite[r["suite"]].append((name, r))
    for suite in sorted(by_suite):
        md += [f"### {suite}", "", "| benchmark | real time (median) | CPU time | counters |",
               "|---|---:|---:|---|"]
        for name, r in sorted(by_suite[suite]):
            counters = ", ".join(f"{k}={v:.4g}" for k, v in sorted(r["counters"].items()))
            md.append(f"| {name} | {bench_results.format_ns(r['real_ns'])} | "
                      f"{bench_results.format_ns(r['cpu_ns'])} | {counters} |")
        md.append("")
    scaling = speedups(results)
    if scaling:
        md += ["### Thread scaling", "",
               "| configuration | threads | speed-up vs 1 thread | efficiency per core |",
               "|---|---:|---:|---:|"]
        for label, points in sorted(scaling.items()):
            md += [f"| {label} | {t} | {x:.2f} | {x / t:.2f} |" for t, x in points if t > 1]
        md.append("")
    md += peer_tables(directory)

    plots = {
        "time_vs_triangles": ("triangles", series_by(results, "triangles"), True, True, False),
        "time_vs_resolution": ("image height (px)", series_by(results, "resolution"), True,
                               True, False),
        "time_vs_lights": ("lights", series_by(results, "lights"), False, False, False),
        "speedup_vs_threads": ("threads", speedups(results), False, False, True),
    }
    if any("embree" in bench_results.parse_name(n)[0].lower() for n in results):
        # the two renderers at the most threads measured, so the crossover is the best of each
        most = max((bench_results.parse_name(n)[1].get("threads", 0) for n in results),
                   default=0)
        at_most = {n: r for n, r in results.items()
                   if bench_results.parse_name(n)[1].get("threads", most) == most}
        plots["raster_vs_embree"] = ("triangles", series_by(at_most, "triangles"), True, True,
                                     False)
    if shutil.which("gnuplot"):
        os.makedirs(os.path.join(directory, "plots"), exist_ok=True)
        made = []
        for name, (xlabel, series, logx, logy, ideal) in plots.items():
            if not series:
                continue
            ylabel = "speed-up vs 1 thread" if ideal else "real time per frame (ms, median)"
            gnuplot(os.path.join(directory, "plots", name + ".png"), facts, xlabel, ylabel,
                    series, logx, logy, ideal)
            made.append(name)
        if made:
            md += ["### Plots", ""] + [f"![{n}](plots/{n}.png)" for n in made] + [""]
    else:
        md += ["(gnuplot not installed: no plots; install the Debian package gnuplot-nox)", ""]

    report = os.path.join(directory, "report.md")
    tmp = report + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(md))
    os.replace(tmp, report)
    print(f"bench-report: {report}")


if __name__ == "__main__":
    main()
