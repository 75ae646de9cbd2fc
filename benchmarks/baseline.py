#!/usr/bin/env python3
"""The core's speed against its committed baseline (used by benchmarks/check-baseline).

Reads the JSON of bench_actor_processing and the CSV of bench_osg_peer, derives ratios that do not
depend on the machine's speed (actor / traditional processing measured side by side, the FMULT rate
relative to a scalar kernel timed in the same process, OpenSceneGraph / actor, the cost per posed
actor at 10k over 1M), prints them beside benchmarks/baseline.json, and exits 1 when one dropped by
more than the allowed share. --update rewrites the baseline (give the reason: it is recorded);
--results writes a results page (Markdown, stamped with date, commit and machine).
"""

import argparse
import csv
import datetime
import json
import os
import platform
import subprocess
import sys

ALLOWED_DROP = 0.15

# (key, what it says); every ratio is "higher is better". The town layout's FMULT rate is not
# guarded: its frame (a millisecond, mostly Reference Points of actors never seen) swings by more
# than the allowed drop from run to run against the yardstick; its speedups are guarded.
GUARDED = [
    ("speedup table2 1000", "traditional / actor processing, Table 2 proportions, 1k actors"),
    ("speedup table2 10000", "traditional / actor processing, Table 2 proportions, 10k actors"),
    ("speedup table2 100000", "traditional / actor processing, Table 2 proportions, 100k actors"),
    ("speedup town 1000", "traditional / actor processing, town layout, 1k actors"),
    ("speedup town 10000", "traditional / actor processing, town layout, 10k actors"),
    ("speedup town 100000", "traditional / actor processing, town layout, 100k actors"),
    ("speedup town 1000000", "traditional / actor processing, town layout, 1M actors"),
    ("fmult rate table2 10000", "actor processing's FMULT per us over the scalar kernel's, Table 2, 10k"),
    ("fmult rate table2 100000", "the same, Table 2, 100k"),
    ("fmult rate table2 1000000", "the same, Table 2, 1M"),
    ("linearity table2", "us per posed actor at 100k over the same at 1M (1: linear)"),
    ("osg / actor table2 10000", "OpenSceneGraph update+cull / actor processing, Table 2, 10k"),
]


def load_benchmark(path):
    """Rows of bench_actor_processing keyed by (layout, actors)."""
    rows = {}
    for b in json.load(open(path))["benchmarks"]:
        name = b["name"].split("/")
        layout = {"BM_Table2Proportions": "table2", "BM_TownSpread": "town"}[name[0]]
        rows[(layout, int(name[1]))] = b
    return rows


def ratios(rows, osg_csv):
    r = {}
    for (layout, actors), b in rows.items():
        if "speedup" in b:
            r[f"speedup {layout} {actors}"] = b["speedup"]
        r[f"fmult rate {layout} {actors}"] = b["actor_fmult_rate"]
    if ("table2", 100000) in rows and ("table2", 1000000) in rows:
        r["linearity table2"] = rows[("table2", 100000)]["actor_us_per_posed"] / rows[("table2", 1000000)]["actor_us_per_posed"]
    if osg_csv:
        for row in csv.DictReader(open(osg_csv)):
            r[f"osg / actor {row['scene']} {row['actors']}"] = float(row["osg_over_actor"])
    return r


def stamp():
    def git(*args):
        try:
            return subprocess.run(["git", *args], capture_output=True, text=True, check=True).stdout.strip()
        except (OSError, subprocess.CalledProcessError):
            return ""
    commit = git("rev-parse", "--short", "HEAD") or "unknown"
    if git("status", "--porcelain", "--untracked-files=no"):
        commit += " (with uncommitted changes)"
    cpu = platform.processor() or platform.machine()
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {"date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"), "commit": commit,
            "machine": f"{cpu}, {os.cpu_count()} cores, {platform.system()} {platform.release()}"}


def compare(baseline, now):
    """Table rows (key, baseline, now, change, verdict) and the keys that dropped too far."""
    table, dropped = [], []
    for key, _ in GUARDED:
        before, after = baseline["ratios"].get(key), now.get(key)
        if before is None or after is None:
            table.append((key, before, after, None, "not measured" if after is None else "new"))
            continue
        change = after / before - 1.0
        verdict = "DROP" if change < -ALLOWED_DROP else "ok"
        if verdict == "DROP":
            dropped.append(key)
        table.append((key, before, after, change, verdict))
    return table, dropped


def fmt(x, digits=3):
    return "-" if x is None else f"{x:.{digits}g}"


def print_table(table, baseline):
    print(f"baseline: {baseline['stamp']['commit']} of {baseline['stamp']['date']} on {baseline['stamp']['machine']}")
    print(f"  ({baseline['why']})")
    width = max(len(k) for k, *_ in table)
    print(f"{'ratio':<{width}}  {'baseline':>9}  {'now':>9}  {'change':>7}")
    for key, before, after, change, verdict in table:
        ch = "-" if change is None else f"{100 * change:+.1f}%"
        print(f"{key:<{width}}  {fmt(before):>9}  {fmt(after):>9}  {ch:>7}  {verdict}")


def results_page(path, rows, now, table, baseline, st):
    out = ["# Core speed: actor against traditional processing", "",
           f"Generated by `benchmarks/check-baseline` on {st['date']}, commit {st['commit']}, on {st['machine']}.",
           "Release build, one thread; each iteration runs one frame of each method on the same state, "
           "after four warm-up frames of each. Do not edit: run the script again.", "",
           "## Ratios guarded against the baseline", "",
           f"Baseline: commit {baseline['stamp']['commit']} of {baseline['stamp']['date']} ({baseline['why']}). "
           f"A drop of more than {int(100 * ALLOWED_DROP)} % fails the check.", "",
           "| ratio | what | baseline | now | change |", "|---|---|---:|---:|---:|"]
    what = dict(GUARDED)
    for key, before, after, change, verdict in table:
        ch = "-" if change is None else f"{100 * change:+.1f} %"
        out.append(f"| {key} | {what[key]} | {fmt(before)} | {fmt(after)} | {ch}{' **drop**' if verdict == 'DROP' else ''} |")
    out += ["", "## bench_actor_processing", "",
            "| layout | actors | posed | traditional ms | actor ms | speedup | actor us / posed | actor ns / actor | actor FMULT rate |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for (layout, actors), b in sorted(rows.items()):
        out.append(f"| {layout} | {actors:,} | {b['posed']:,.0f} | {fmt(b.get('traditional_ms'), 4)} | {fmt(b['actor_ms'], 4)} | "
                   f"{fmt(b.get('speedup'))} | {b['actor_us_per_posed']:.3f} | {b['actor_ns_per_actor']:.1f} | {b['actor_fmult_rate']:.3f} |")
    out += ["", "Actor processing by phase (ms):", "",
            "| layout | actors | Refpoints | CULL 1 | Sklsroots | CULL 2 | pose | CULL 3 | draw list |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for (layout, actors), b in sorted(rows.items()):
        phases = " | ".join(f"{b[k]:.3f}" for k in ("refpoint_ms", "cull1_ms", "sklsroot_ms", "cull2_ms", "pose_ms", "cull3_ms", "drawlist_ms"))
        out.append(f"| {layout} | {actors:,} | {phases} |")
    if "osg / actor table2 10000" in now:
        out += ["", f"OpenSceneGraph 3.6 update + cull over actor processing, Table 2 at 10k (bench_osg_peer): "
                    f"{now['osg / actor table2 10000']:.1f}."]
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(tmp, path)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("baseline")
    p.add_argument("benchmark_json")
    p.add_argument("--osg-csv")
    p.add_argument("--update", metavar="WHY", help="write these ratios as the new baseline, with the reason")
    p.add_argument("--results", metavar="PAGE", help="write the results page here")
    a = p.parse_args()
    rows = load_benchmark(a.benchmark_json)
    now = ratios(rows, a.osg_csv)
    st = stamp()
    if a.update:
        baseline = {"why": a.update, "stamp": st, "ratios": {k: now[k] for k, _ in GUARDED if k in now}}
        tmp = a.baseline + ".tmp"
        with open(tmp, "w") as f:
            json.dump(baseline, f, indent=2)
            f.write("\n")
        os.replace(tmp, a.baseline)
        print(f"check-baseline: {a.baseline} rewritten ({a.update})")
    try:
        baseline = json.load(open(a.baseline))
    except FileNotFoundError:
        sys.exit(f"check-baseline: no baseline at {a.baseline}: run with --update WHY to record one")
    table, dropped = compare(baseline, now)
    print_table(table, baseline)
    if a.results:
        results_page(a.results, rows, now, table, baseline, st)
        print(f"check-baseline: results written to {a.results}")
    if dropped:
        print(f"check-baseline: FAILED: {', '.join(dropped)} dropped more than {int(100 * ALLOWED_DROP)} % below the baseline")
        return 1
    print("check-baseline: every ratio within the allowed drop of its baseline")
    return 0


if __name__ == "__main__":
    sys.exit(main())
