"""Reading Google Benchmark JSON results (scripts/bench.sh writes one file per suite under
bench/results/<stamp>/), shared by bench-compare.py and bench-report.py.

A benchmark's time is the median of its repetitions: the `median` aggregate when the run
has one (--benchmark_repetitions=N), else the median of its iteration rows.
"""
import json
import os
import re
import statistics
import sys

TO_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}


def result_files(path):
    """A JSON file, or every *.json in a results directory (sorted)."""
    if os.path.isdir(path):
        files = sorted(os.path.join(path, f) for f in os.listdir(path) if f.endswith(".json"))
        if not files:
            sys.exit(f"no *.json results in '{path}'")
        return files
    return [path]


def load(path):
    """{run name: {"real_ns", "cpu_ns", "counters", "suite"}} plus the first file's context."""
    results, context = {}, None
    for file in result_files(path):
        try:
            with open(file) as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            sys.exit(f"cannot read '{file}': {e}")
        context = context or data.get("context", {})
        suite = os.path.splitext(os.path.basename(file))[0]
        rows = {}
        for b in data.get("benchmarks", []):
            if b.get("error_occurred"):
                continue
            name = b.get("run_name", b["name"])
            entry = rows.setdefault(name, {"median": None, "iterations": []})
            if b.get("run_type") == "aggregate":
                if b.get("aggregate_name") == "median":
                    entry["median"] = b
            else:
                entry["iterations"].append(b)
        for name, entry in rows.items():
            chosen = [entry["median"]] if entry["median"] else entry["iterations"]
            if not chosen:
                continue
            unit = TO_NS[chosen[0].get("time_unit", "ns")]
            counters = {}
            for key, value in chosen[0].items():
                if key.endswith("_per_second") or (isinstance(value, float) and key not in
                                                   ("real_time", "cpu_time")):
                    counters[key] = statistics.median(c.get(key, value) for c in chosen)
            results[name] = {
                "suite": suite,
                "real_ns": statistics.median(c["real_time"] for c in chosen) * unit,
                "cpu_ns": statistics.median(c["cpu_time"] for c in chosen) * unit,
                "counters": counters,
            }
    return results, context or {}


def parse_name(name):
    """'BM_Frame/triangles:1048576/threads:2/real_time' -> ('BM_Frame', {'triangles': 1048576,
    'threads': 2}); unnamed arguments become arg0, arg1, ..."""
    parts = name.split("/")
    family, args = parts[0], {}
    for i, part in enumerate(parts[1:]):
        if part in ("real_time", "process_time", "manual_time") or part.startswith(
                ("repeats:", "min_time:", "iterations:")):
            continue
        key, _, value = part.rpartition(":")
        key = key or f"arg{i}"
        if re.fullmatch(r"-?\d+(\.\d+)?", value):
            args[key] = float(value) if "." in value else int(value)
        else:
            args[key] = value
    return family, args


def format_ns(ns):
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("us", 1e3)):
        if ns >= scale:
            return f"{ns / scale:.3g} {unit}"
    return f"{ns:.3g} ns"
