#!/usr/bin/env python3
"""Runs the counting benchmark built with counting compiled in and compiled out, interleaved in one
run, and prints the frame time of each variant and its ratio to the compiled-out build.

usage: benchmarks/counting_overhead.py BUILD_DIR [REPETITIONS]
"""
import json
import os
import subprocess
import sys


def run(binary, bench_filter, repetitions):
    out = subprocess.run(
        [binary, f"--benchmark_filter={bench_filter}", f"--benchmark_repetitions={repetitions}",
         "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
        check=True, capture_output=True, text=True).stdout
    rows = json.loads(out)["benchmarks"]
    return next(r for r in rows if r.get("aggregate_name") == "median")


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    build = sys.argv[1]
    reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    binary_in = os.path.join(build, "benchmarks/scenegraph/bench_counting")
    binary_out = os.path.join(build, "benchmarks/scenegraph/bench_counting_compiled_out")
    for b in (binary_in, binary_out):
        if not os.path.exists(b):
            sys.exit(f"counting_overhead: {b} is missing: build the benchmarks first")
    variants = [
        ("compiled out", binary_out, "CountingOff"),
        ("compiled in, switched off", binary_in, "CountingOff"),
        ("compiled in, switched on", binary_in, "CountingOn"),
    ]
    results = {name: run(binary, f, reps) for name, binary, f in variants}
    base = results["compiled out"]["real_time"]
    print(f"one traditional frame, 2000 figures, median of {reps} repetitions")
    print(f"{'counting':28} {'ms/frame':>10} {'vs compiled out':>16}")
    for name, _, _ in variants:
        t = results[name]["real_time"]
        print(f"{name:28} {t:10.3f} {t / base:15.3f}x")


if __name__ == "__main__":
    main()
