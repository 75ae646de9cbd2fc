#!/usr/bin/env python3
"""The shared step on one and two cores, as threads and as MPI ranks, in alternating rounds.

usage: ranks_sweep.py BENCH_RANKS [--actors 10000,100000] [--rounds 3] [--region-blocks 2]
                      [--warmup 20] [--steps 20] [--mpiexec mpiexec]

Runs bench_ranks plainly with 1 and 2 threads and under `mpiexec -np 2` with 1 thread each, round
after round (so that a drift of the machine's load falls on every configuration), and prints a
Markdown table of the median step times, the speed-ups and the scaling efficiency from 1 to 2
ranks (time on 1 rank / (2 x time on 2 ranks)), with what crossed between the ranks.
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
import tempfile


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("bench")
    p.add_argument("--actors", default="10000,100000")
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--region-blocks", default="2")
    p.add_argument("--warmup", default="20")
    p.add_argument("--steps", default="20")
    p.add_argument("--mpiexec", default="mpiexec")
    a = p.parse_args()
    configs = {"1 rank, 1 thread": ([], ["--threads", "1"]), "1 rank, 2 threads": ([], ["--threads", "2"]),
               "2 ranks, 1 thread each": ([a.mpiexec, "-np", "2", "--oversubscribe"], ["--threads", "1"])}
    rows = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.actors.split(","):
            for r in range(a.rounds):
                for name, (launcher, extra) in configs.items():
                    out = os.path.join(tmp, "rows.csv")
                    if os.path.exists(out):
                        os.remove(out)
                    cmd = [*launcher, a.bench, "--actors", n, "--region-blocks", a.region_blocks, "--warmup", a.warmup,
                           "--steps", a.steps, "--csv", out, *extra]
                    done = subprocess.run(cmd, capture_output=True, text=True)
                    if done.returncode != 0:
                        sys.exit(f"{' '.join(cmd)} failed ({done.returncode}):\n{done.stderr}")
                    row = list(csv.DictReader(open(out)))[0]
                    rows.setdefault((n, name), []).append(row)
                    print(f"ranks_sweep: {n} actors, {name}, round {r + 1}: {float(row['step_ms']):.1f} ms", file=sys.stderr)
    print("| actors | regions | configuration | step ms (median of %d) | all rounds | speed-up | efficiency | ghosts to the other rank | "
          "handed to it | border bytes | bytes per border agent | state bytes to rank 0 |" % a.rounds)
    print("|---:|---:|---|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for n in a.actors.split(","):
        base = statistics.median(float(r["step_ms"]) for r in rows[(n, "1 rank, 1 thread")])
        for name in configs:
            got = rows[(n, name)]
            ms = statistics.median(float(r["step_ms"]) for r in got)
            last = got[-1]
            cores = 2 if "2" in name else 1
            ghosts, handed = float(last["ghosts_to_ranks"]), float(last["handed_to_ranks"])
            border = float(last["border_bytes"])
            per = f"{border / (ghosts + handed):.0f}" if ghosts + handed > 0 else "-"
            rounds = " / ".join("%.0f" % float(r["step_ms"]) for r in got)
            print(f"| {n} | {last['regions']} | {name} | {ms:.1f} | {rounds} | "
                  f"{base / ms:.2f}x | {base / (cores * ms) * 100:.0f} % | {ghosts:.0f} | {handed:.1f} | {border:.0f} | {per} | "
                  f"{float(last['state_bytes']):.0f} |")


if __name__ == "__main__":
    main()
