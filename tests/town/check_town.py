#!/usr/bin/env python3
"""End-to-end checks of throng-town, run by CTest.

usage: check_town.py TOWN_EXE MODE SCENES_DIR WORK_DIR
  determinism  same seed: identical stats.csv (timing columns aside) and identical frames,
               run twice with 1 thread, with 2 and 4, with DRAW overlapping the next frame, and
               drawn through OSMesa and through EGL (surfaceless)
  effects      a scene that declares no avoidance, gaze or flight never constructs or ticks them;
               declaring them turns them on; declared occlusion rests on some frames, testing nothing there
  window       with a display (the test runs under xvfb-run) a window opens and closes after --frames
  mpi          under $THRONG_MPIEXEC with 1, 2, 3 and 4 ranks, over TCP only, each rank in a working folder
               of its own, oversubscribed: the same stats.csv (timing and per-rank columns aside) and the
               same frames as the plain program, with walkers crossing between ranks; only rank 0 writes,
               every rank reports its peak memory and those that draw nothing hold less than rank 0; a
               rank reading another scene with other --actors, --seed and --frames stops the run, saying so,
               nothing written
  mpiPosing    --pose-on-ranks under $THRONG_MPIEXEC with 1, 2 and 3 ranks over TCP only, separate working
               folders: every rank poses the walkers it steps, rank 0 draws the plain program's frames and
               writes its stats.csv (timing, per-rank and the cell shortcut's work counts aside); every
               rank posed items; what it cannot do is refused, a rank without it stops the run
  mpiHang      under $THRONG_MPIEXEC with 2 ranks over TCP, rank 1 stopped mid-run: the run ends within the
               rank timeout with an error naming rank 1, never hangs
  signals      SIGINT and SIGTERM end a long run after the frame in progress: exit 130 / 143, one line
               saying so, stats.csv whole and summary.json "completed": false with the frames done; a
               second signal exits at once with whole lines only; a signal while building writes nothing
  fileLimit    a file-size limit (as a full disk would) mid-run: exit 3 naming stats.csv, the file ends
               at its last whole line and summary.json says why; a PNG over the limit is absent, whole
               or not at all, and no temporary file is left
  mpiKill      under $THRONG_MPIEXEC with 2 ranks over TCP, rank 1 killed (SIGKILL) mid-run: every process gone
               within the rank timeout plus 10 s, the message names rank 1, rank 0's stats.csv parses
  scale        50k and 100k actors: a progress line per phase of building (town, navigation mesh,
               actors, impostors), both frames done; prints the time to frame 1 and the peak memory
  memoryLimit  under an address-space limit (ulimit -v) a crowd larger than it is refused before
               anything is built, naming the limit and the crowd that fits; exit 2, nothing written
  budget       --frame-budget: stats.csv has the allocator's columns, every frame's settings are its
               rung's, over_budget agrees with app_cull_draw_ms, summary.json counts them; a budget
               nothing meets keeps the cheapest rung, one everything meets the most accurate, and the
               cheapest rung really draws more impostors and evaluates fewer nodes
  gpuCheck     benchmarks/gpu-check run with this throng-town, small: one CSV row per run with the
               context, step, APP+CULL, DRAW CPU and GPU and fps, the stamp with the EGL devices, the
               page made from them; a
               budget too small for any run skips them (exit 1); a bad option is refused (exit 2)
"""
import csv
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

# stats.csv columns that hold wall-clock times (their names end in _ms) differ from run to run; those
# of each rank's share of the step (rankN_...) exist only when the town is distributed over ranks.
def is_timing(column):
    return column.endswith("_ms") or re.match(r"rank\d+_", column) is not None


def run(exe, out, *args, launcher=()):
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [*launcher, exe, "--out", out, *args]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    return p


def stats_without_timing(out):
    with open(os.path.join(out, "stats.csv")) as f:
        rows = list(csv.DictReader(f))
    if not rows:
        sys.exit(f"{out}/stats.csv has no rows")
    return [{k: v for k, v in r.items() if not is_timing(k)} for r in rows]


def frames(out):
    folder = os.path.join(out, "frames")
    names = sorted(os.listdir(folder))
    if not names:
        sys.exit(f"{folder} holds no frame")
    return {n: open(os.path.join(folder, n), "rb").read() for n in names}


def first_difference(a, b):
    for i, (x, y) in enumerate(zip(a, b)):
        if x != y:
            keys = [k for k in x if x[k] != y.get(k)]
            return f"frame {i}: columns {keys}: {[x[k] for k in keys]} vs {[y[k] for k in keys]}"
    return f"{len(a)} rows vs {len(b)}"


def determinism(exe, scenes, work):
    common = ["--scene", os.path.join(scenes, "effects.json"), "--headless", "--frames", "90", "--every", "30",
              "--width", "320", "--height", "180", "--seed", "4"]
    # The same frames whatever the threads and whether DRAW overlaps the next frame's step and CULL.
    # And whether the frames are drawn through OSMesa or EGL's surfaceless platform (the same llvmpipe:
    # the PNGs are compared byte for byte).
    variants = {"one": ["--threads", "1", "--pipeline", "off", "--gl", "osmesa"], "again": ["--threads", "1", "--pipeline", "off"],
                "egl": ["--threads", "1", "--pipeline", "off", "--gl", "egl"],
                "two-threads": ["--threads", "2", "--pipeline", "off"], "four-threads": ["--threads", "4", "--pipeline", "off"],
                "pipelined": ["--threads", "1", "--pipeline", "on"], "pipelined-two-threads": ["--threads", "2", "--pipeline", "on"]}
    runs = {name: os.path.join(work, name) for name in variants}
    for name, args in variants.items():
        run(exe, runs[name], *common, *args)
    reference = stats_without_timing(runs["one"])
    reference_frames = frames(runs["one"])
    moved = {r["skeleton_nodes"] for r in reference}
    if len(moved) < 2:
        sys.exit("the scene does not change from frame to frame: the comparison would prove nothing")
    if not any(int(r["impostors"]) > 0 for r in reference):
        sys.exit("no actor was drawn as an impostor: the scene should exercise them")
    regions = json.load(open(os.path.join(runs["one"], "summary.json"))).get("regions", 0)
    if regions < 2:
        sys.exit(f"the walkers were stepped in {regions} region(s): the scene should exercise several")
    # Ghosts across borders are part of the state compared below (stats.csv's ghosts, handovers).
    if not any(int(r["ghosts"]) > 0 for r in reference):
        sys.exit("no walker was seen across a region border: the comparison would not cover ghosts")
    for name in list(variants)[1:]:
        other = stats_without_timing(runs[name])
        if other != reference:
            sys.exit(f"stats.csv of run '{name}' differs from the first run: {first_difference(reference, other)}")
        other_frames = frames(runs[name])
        if other_frames.keys() != reference_frames.keys():
            sys.exit(f"run '{name}' wrote frames {sorted(other_frames)} instead of {sorted(reference_frames)}")
        for n in reference_frames:
            if other_frames[n] != reference_frames[n]:
                sys.exit(f"frame {n} of run '{name}' differs from the first run")
    print(f"{len(variants)} runs agree (threads, pipeline, OSMesa and EGL): {len(reference)} rows of stats.csv, {len(reference_frames)} frames")
    # The same with ORCA keeping the walkers apart: the scene with its avoidance model switched (its
    # relative paths made absolute, since the copy lives in the work folder).
    scene = json.load(open(os.path.join(scenes, "effects.json")))

    def absolute(value):
        if isinstance(value, dict):
            return {k: absolute(v) for k, v in value.items()}
        if isinstance(value, list):
            return [absolute(v) for v in value]
        if isinstance(value, str) and value.startswith("../"):
            return os.path.normpath(os.path.join(scenes, value))
        return value

    scene = absolute(scene)
    scene["effects"]["avoidance"] = {"model": "orca"}
    orca_scene = os.path.join(work, "effects-orca.json")
    with open(orca_scene, "w") as f:
        json.dump(scene, f)
    orca_common = [a if a != os.path.join(scenes, "effects.json") else orca_scene for a in common]
    orca_runs = {name: os.path.join(work, "orca-" + name) for name in ("one", "two-threads")}
    run(exe, orca_runs["one"], *orca_common, "--threads", "1", "--pipeline", "off")
    run(exe, orca_runs["two-threads"], *orca_common, "--threads", "2", "--pipeline", "off")
    orca_reference = stats_without_timing(orca_runs["one"])
    if orca_reference == reference:
        sys.exit("the ORCA runs match DetourCrowd's: the avoidance model was not switched")
    other = stats_without_timing(orca_runs["two-threads"])
    if other != orca_reference:
        sys.exit(f"stats.csv with ORCA differs between 1 and 2 threads: {first_difference(orca_reference, other)}")
    if frames(orca_runs["two-threads"]) != frames(orca_runs["one"]):
        sys.exit("the frames with ORCA differ between 1 and 2 threads")
    print(f"ORCA: 1 and 2 threads agree: {len(orca_reference)} rows of stats.csv")


# Open MPI restricted to TCP, as between two hosts: the ob1 layer with TCP and self only (no shared
# memory, no UCX, which could bypass the BTLs), over the loopback interface, oversubscribed (the
# ranks may outnumber the cores).
TCP_ONLY = ["--oversubscribe", "--mca", "pml", "ob1", "--mca", "btl", "tcp,self", "--mca", "btl_tcp_if_include", "lo",
            "--mca", "oob_tcp_if_include", "lo"]


def start_ranks(exe, mpiexec, ranks, folder, args, rank_args=None):
    """`ranks` ranks of throng-town over TCP only, each in a working folder of its own (rank0, rank1, ...
    under `folder`), rank 0 writing to rank0/out; rank r's options are `rank_args[r]` when given.
    Returns the finished process."""
    if os.path.exists(folder):
        shutil.rmtree(folder)
    cmd = [mpiexec, *TCP_ONLY]
    for r in range(ranks):
        wdir = os.path.join(folder, f"rank{r}")
        os.makedirs(wdir)
        cmd += ([":"] if r else []) + ["-np", "1", "--wdir", wdir, exe, "--out", "out", *(rank_args[r] if rank_args else args)]
    return cmd, subprocess.run(cmd, capture_output=True, text=True, timeout=300)


def run_ranks(exe, mpiexec, ranks, folder, args):
    """start_ranks with the same options on every rank, which must succeed. Returns rank 0's output folder."""
    cmd, p = start_ranks(exe, mpiexec, ranks, folder, args)
    if p.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr}")
    # No rank but 0 writes anything: its working folder stays empty.
    for r in range(1, ranks):
        left = os.listdir(os.path.join(folder, f"rank{r}"))
        if left:
            sys.exit(f"{ranks} ranks: rank {r} wrote {left} into its working folder")
    return os.path.join(folder, "rank0", "out")


def mpi_launcher():
    """The MPI launcher CTest found."""
    mpiexec = os.environ.get("THRONG_MPIEXEC")
    if not mpiexec:
        sys.exit("THRONG_MPIEXEC names no MPI launcher")
    return mpiexec


def mpi_run_options(scenes):
    """The effects scene with 500 walkers in 16 regions, 80 frames: within them some walkers cross
    from one rank's regions to another's. The scene by its absolute path: each rank starts in a
    folder of its own."""
    return ["--scene", os.path.abspath(os.path.join(scenes, "effects.json")), "--headless", "--frames", "80", "--every", "40",
            "--width", "320", "--height", "180", "--seed", "4", "--actors", "500", "--rank-timeout", "60"]


def mpi(exe, scenes, work):
    mpiexec = mpi_launcher()
    common = mpi_run_options(scenes)
    plain = os.path.join(work, "plain")
    run(exe, plain, *common)
    runs = {n: run_ranks(exe, mpiexec, n, os.path.join(work, f"ranks-{n}"), common) for n in (1, 2, 3, 4)}
    reference = stats_without_timing(plain)
    reference_frames = frames(plain)
    for n, out in runs.items():
        other = stats_without_timing(out)
        if other != reference:
            sys.exit(f"stats.csv of {n} rank(s) differs from the plain run: {first_difference(reference, other)}")
        other_frames = frames(out)
        if other_frames != reference_frames:
            sys.exit(f"{n} rank(s) wrote other frames than the plain run ({sorted(other_frames)} against {sorted(reference_frames)})")
    actors = json.load(open(os.path.join(plain, "summary.json")))["actors"]
    crossed = {}
    for n, out in runs.items():
        if n == 1:
            continue
        rows = list(csv.DictReader(open(os.path.join(out, "stats.csv"))))
        # Each rank's share: every rank steps walkers, every walker is stepped by one rank.
        for r in rows[1:]:
            shares = [int(r[f"rank{k}_agents"]) for k in range(n)]
            if min(shares) == 0 or sum(shares) > actors:
                sys.exit(f"{n} ranks, frame {r['frame']}: the ranks stepped {shares} walkers of {actors} actors")
        # The other ranks send rank 0 only the walkers near the view: some frames leave some out, and
        # some send some (the comparison above then covers walkers left out and walkers coming back).
        left_out = sum(1 for r in rows[1:] if any(int(r[f"rank{k}_sent"]) < int(r[f"rank{k}_agents"]) for k in range(1, n)))
        sent = sum(1 for r in rows[1:] if any(int(r[f"rank{k}_sent"]) > 0 for k in range(1, n)))
        if left_out == 0 or sent == 0:
            sys.exit(f"{n} ranks: walkers were left out in {left_out} frames and sent in {sent}: the view's gather is not covered")
        across = sum(int(r[f"rank{k}_handed_to_ranks"]) for r in rows for k in range(n))
        border = sum(int(r[f"rank{k}_border_bytes"]) for r in rows for k in range(n))
        if across == 0 or border == 0:
            sys.exit(f"{n} ranks: {across} walkers crossed between the ranks and {border} bytes of ghosts and handovers travelled: "
                     "the comparison would not cover the exchange")
        # Every rank reports its peak memory; ranks that build only their walkers' world hold less.
        summary = json.load(open(os.path.join(out, "summary.json")))
        peaks = [r["peakBytes"] for r in summary["meanPerRank"]]
        if len(peaks) != n or min(peaks) <= 0 or summary["peakMemoryBytes"] <= 0:
            sys.exit(f"{n} ranks: summary.json gives peak memory {peaks} per rank, {summary.get('peakMemoryBytes')} for rank 0")
        if max(peaks[1:]) >= peaks[0]:
            sys.exit(f"{n} ranks: a rank that draws nothing held as much memory as rank 0: {peaks}")
        crossed[n] = (across, border, left_out, [p >> 20 for p in peaks])
    # A rank reading another scene, or given other --actors, --seed and --frames, stops the run before anything is built,
    # saying what differs; nothing is written.
    other_scene = os.path.abspath(os.path.join(scenes, "plain.json"))
    other = [a if a != common[1] else other_scene for a in common]
    other[other.index("--actors") + 1] = "400"
    other[other.index("--seed") + 1] = "5"
    other[other.index("--frames") + 1] = "100"
    cmd, p = start_ranks(exe, mpiexec, 2, os.path.join(work, "disagree"), common, [common, other])
    said = re.search(r"throng-town \(rank 1\): this rank would build or step another world than rank 0: its scene file .*plain\.json "
                     r".* is not rank 0's .*; --actors 400 here, 500 on rank 0; --seed 5 here, 4 on rank 0; --frames 100 here, 80 on rank 0", p.stderr)
    if p.returncode == 0 or not said:
        sys.exit(f"rank 1 with another scene, --actors, --seed and --frames: exit {p.returncode}, not the error expected:\n{p.stderr}")
    written = [os.path.join(d, f) for d in ("rank0", "rank1") for f in os.listdir(os.path.join(work, "disagree", d))]
    if written:
        sys.exit(f"the run whose ranks disagree wrote {written}")
    print(f"plain and 1 to 4 ranks over TCP (separate working folders) agree: {len(reference)} rows, {len(reference_frames)} frames; "
          f"a rank with another scene, --actors, --seed and --frames stops the run (exit {p.returncode}), nothing written")
    for n, (across, border, left_out, peaks) in crossed.items():
        print(f"  {n} ranks: {across} walkers crossed between ranks, {border} border bytes, walkers left out of the gather in "
              f"{left_out} frames; peak MiB per rank {peaks}")


def mpiPosing(exe, scenes, work):
    """--pose-on-ranks: every rank culls and poses the walkers it steps and sends rank 0 draw records."""
    mpiexec = mpi_launcher()
    # The effects scene: gaze (a walker may look at another rank's), impostors and key-pose caches
    # with hysteresis (tiers handed over with the walkers), occlusion with rests (rank 0's buffer),
    # standing people and a flock posed on rank 0.
    common = mpi_run_options(scenes)
    # Refused before anything is built: what posing on the ranks cannot do.
    for extra, said in ((["--processing", "traditional"], "traditional processing reads every actor"),
                        (["--gather", "all"], "--gather all contradicts it")):
        p = subprocess.run([exe, "--out", os.path.join(work, "refused"), *common, "--pose-on-ranks", *extra], capture_output=True, text=True)
        if p.returncode != 2 or said not in p.stderr:
            sys.exit(f"--pose-on-ranks {' '.join(extra)}: exit {p.returncode}, not 2 saying '{said}':\n{p.stderr}")
    plain = os.path.join(work, "plain")
    run(exe, plain, *common)
    reference = stats_without_timing(plain)
    reference_frames = frames(plain)
    # Occlusion's cell shortcut must have worked for its counts to be compared (cells are split by
    # the region stepping their walkers, so that each rank forms one process's cells).
    if sum(int(r["occlusion_cells_hidden"]) for r in reference) == 0:
        sys.exit("the effects scene hid no cell of walkers: the occlusion counts compare nothing")
    for n in (1, 2, 3):
        out = run_ranks(exe, mpiexec, n, os.path.join(work, f"ranks-{n}"), [*common, "--pose-on-ranks"])
        other = stats_without_timing(out)
        if len(other) != len(reference):
            sys.exit(f"--pose-on-ranks, {n} rank(s): {len(other)} rows of stats.csv, not {len(reference)}")
        if other != reference:
            sys.exit(f"--pose-on-ranks, {n} rank(s): stats.csv differs from the plain run: {first_difference(reference, other)}")
        if frames(out) != reference_frames:
            sys.exit(f"--pose-on-ranks, {n} rank(s) wrote other frames than the plain run")
        rows = list(csv.DictReader(open(os.path.join(out, "stats.csv"))))
        # Every rank posed walkers and sent their records; rank 0 drew what all of them posed.
        for k in range(n):
            posed = sum(int(r[f"rank{k}_posed_items"]) for r in rows)
            sent = sum(int(r[f"rank{k}_posing_bytes"]) for r in rows)
            if posed == 0 or (n > 1 and sent == 0):
                sys.exit(f"--pose-on-ranks, {n} rank(s): rank {k} posed {posed} items and sent {sent} bytes for them over the run")
        for r in rows:
            posed = sum(int(r[f"rank{k}_posed_items"]) for k in range(n))
            if posed > int(r["draw_items"]):
                sys.exit(f"--pose-on-ranks, {n} rank(s), frame {r['frame']}: the ranks posed {posed} items, rank 0 drew {r['draw_items']}")
        if n > 1 and sum(int(r[f"rank{k}_handed_to_ranks"]) for r in rows for k in range(n)) == 0:
            sys.exit(f"--pose-on-ranks, {n} ranks: no walker crossed between the ranks: the tiers' handover is not covered")
    # A rank that would not pose its walkers while rank 0 expects it to stops the run, saying so.
    cmd, p = start_ranks(exe, mpiexec, 2, os.path.join(work, "disagree"), common, [[*common, "--pose-on-ranks"], common])
    if p.returncode == 0 or "--pose-on-ranks off here, on on rank 0" not in p.stderr:
        sys.exit(f"rank 1 without --pose-on-ranks: exit {p.returncode}, not the error expected:\n{p.stderr}")
    print(f"--pose-on-ranks with 1, 2 and 3 ranks over TCP (separate working folders) draws the plain run's {len(reference_frames)} "
          f"frames and writes its {len(reference)} rows of stats.csv; refusals and a disagreeing rank stop the run")


def process_of_rank(launcher_pid, rank):
    """The pid of MPI rank `rank` among the launcher's descendants (Open MPI marks each rank's environment)."""
    for pid in os.listdir("/proc"):
        if not pid.isdigit():
            continue
        try:
            environ = open(f"/proc/{pid}/environ", "rb").read().split(b"\0")
        except OSError:
            continue
        if f"OMPI_COMM_WORLD_RANK={rank}".encode() in environ and b"THRONG_HANG_TEST=" + str(launcher_pid).encode() in environ:
            return int(pid)
    return None


def start_two_ranks(exe, scenes, out, timeout):
    """A long run of plain.json on 2 ranks under $THRONG_MPIEXEC over TCP only, each rank marked with this process's id."""
    mpiexec = mpi_launcher()
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [mpiexec, *TCP_ONLY, "-np", "2", "-x", "THRONG_HANG_TEST", exe, "--out", out, "--scene", os.path.join(scenes, "plain.json"),
           "--headless", "--frames", "100000", "--every", "0", "--width", "64", "--height", "36", "--rank-timeout", str(timeout)]
    env = dict(os.environ)
    env["THRONG_HANG_TEST"] = str(os.getpid())
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)


def mpiHang(exe, scenes, work):
    out = os.path.join(work, "hang")
    timeout = 5
    p = start_two_ranks(exe, scenes, out, timeout)
    # Wait until rank 1 steps (rank 0 has written rows), then stop it as a hung process would be.
    wait_for_rows(p, out, 20, 120)
    rank1 = process_of_rank(os.getpid(), 1)
    if rank1 is None:
        p.kill()
        sys.exit("rank 1's process was not found")
    os.kill(rank1, signal.SIGSTOP)
    stopped = time.time()
    try:
        _, err = p.communicate(timeout=timeout + 60)
    except subprocess.TimeoutExpired:
        os.kill(rank1, signal.SIGKILL)
        p.kill()
        sys.exit(f"the run still hung {timeout + 60} s after rank 1 stopped")
    finally:
        try:
            os.kill(rank1, signal.SIGKILL)
        except OSError:
            pass
    took = time.time() - stopped
    if p.returncode == 0:
        sys.exit("the run succeeded although rank 1 stopped")
    if "rank 1 did not take part" not in err:
        sys.exit(f"the error does not name rank 1:\n{err}")
    print(f"rank 1 stopped: the run ended after {took:.1f} s (timeout {timeout} s) naming it")


def whole_stats(out):
    """stats.csv as rows, checking that every line is whole (as many fields as the header)."""
    text = open(os.path.join(out, "stats.csv")).read()
    if text and not text.endswith("\n"):
        sys.exit(f"{out}/stats.csv ends inside a line: {text[-80:]!r}")
    rows = list(csv.reader(text.splitlines()))
    widths = {len(r) for r in rows}
    if len(widths) != 1:
        sys.exit(f"{out}/stats.csv has lines of {sorted(widths)} fields")
    return rows[1:]


def leftovers(out):
    """Temporary files a whole-file write would leave if it were interrupted or failed."""
    found = []
    for folder, _, names in os.walk(out):
        found += [os.path.join(folder, n) for n in names if ".partial-" in n]
    return found


def start_long_run(exe, scenes, out, *extra, preexec=None):
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [exe, "--out", out, "--scene", os.path.join(scenes, "plain.json"), "--headless", "--frames", "100000",
           "--width", "64", "--height", "36", *extra]
    return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=preexec)


def wait_for_rows(p, out, rows, seconds=180):
    stats = os.path.join(out, "stats.csv")
    deadline = time.time() + seconds
    while time.time() < deadline and (not os.path.exists(stats) or sum(1 for _ in open(stats)) < rows + 1):
        if p.poll() is not None:
            sys.exit(f"the run ended early ({p.returncode}):\n{p.stderr.read()}")
        time.sleep(0.1)
    if time.time() >= deadline:
        p.kill()
        sys.exit(f"no {rows} rows in {stats} within {seconds} s")


def signals(exe, scenes, work):
    for sig, code in ((signal.SIGINT, 130), (signal.SIGTERM, 143)):
        name = signal.Signals(sig).name
        out = os.path.join(work, name)
        p = start_long_run(exe, scenes, out, "--every", "0")
        wait_for_rows(p, out, 10)
        os.kill(p.pid, sig)
        sent = time.time()
        _, err = p.communicate(timeout=120)
        if p.returncode != code:
            sys.exit(f"{name}: exit {p.returncode}, not {code}:\n{err}")
        said = re.search(rf"stopped by {name} after (\d+) of 100000 frames; stats.csv, summary.json in ", err)
        if not said:
            sys.exit(f"{name}: no line saying the run stopped:\n{err}")
        rows = whole_stats(out)
        summary = json.load(open(os.path.join(out, "summary.json")))
        if summary.get("completed") is not False or summary.get("stoppedBy") != name:
            sys.exit(f"{name}: summary.json says completed={summary.get('completed')}, stoppedBy={summary.get('stoppedBy')}")
        if not (summary["frames"] == len(rows) == int(said.group(1))):
            sys.exit(f"{name}: summary.json counts {summary['frames']} frames, stats.csv {len(rows)}, the message {said.group(1)}")
        if leftovers(out):
            sys.exit(f"{name}: temporary files left: {leftovers(out)}")
        print(f"{name}: exit {code} {time.time() - sent:.2f} s after the signal, {len(rows)} frames in both files")
    # A second signal: at once, whatever the run was doing; whatever stats.csv holds is whole lines.
    out = os.path.join(work, "twice")
    p = start_long_run(exe, scenes, out, "--every", "0")
    wait_for_rows(p, out, 10)
    os.kill(p.pid, signal.SIGINT)
    os.kill(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=30)
    if p.returncode != 130:
        sys.exit(f"two SIGINTs: exit {p.returncode}, not 130:\n{err}")
    print(f"two SIGINTs: exit 130, {len(whole_stats(out))} whole lines in stats.csv")
    # While building: nothing to keep, nothing written.
    out = os.path.join(work, "building")
    p = start_long_run(exe, scenes, out, "--every", "0")
    line = p.stderr.readline()
    if not line.startswith("building"):
        p.kill()
        sys.exit(f"expected the building progress first, got {line!r}")
    os.kill(p.pid, signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    if p.returncode != 143 or "stopped by SIGTERM while building; nothing written" not in err:
        sys.exit(f"SIGTERM while building: exit {p.returncode}:\n{err}")
    if os.path.exists(os.path.join(out, "stats.csv")) or os.path.exists(os.path.join(out, "summary.json")):
        sys.exit("SIGTERM while building left files")
    print("SIGTERM while building: exit 143, nothing written")


def fileLimit(exe, scenes, work):
    import resource
    limit = 40_000  # bytes: stats.csv passes it after some 150 frames

    def limited():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    out = os.path.join(work, "stats")
    p = start_long_run(exe, scenes, out, "--every", "0", preexec=limited)
    _, err = p.communicate(timeout=600)
    if p.returncode != 3 or not re.search(r"stats.csv: cannot be written: File too large", err):
        sys.exit(f"stats.csv over the limit: exit {p.returncode}:\n{err}")
    rows = whole_stats(out)
    summary = json.load(open(os.path.join(out, "summary.json")))
    if summary.get("completed") is not False or "stats.csv" not in summary.get("error", "") or summary["frames"] < len(rows):
        sys.exit(f"summary.json after the error: completed={summary.get('completed')} error={summary.get('error')} frames={summary.get('frames')}")
    if leftovers(out):
        sys.exit(f"temporary files left: {leftovers(out)}")
    print(f"stats.csv over {limit} bytes: exit 3 naming it, {len(rows)} whole lines ({os.path.getsize(os.path.join(out, 'stats.csv'))} bytes) kept")
    # A frame PNG larger than the limit: the run stops at its first frame and no PNG, whole or part, is left.
    out = os.path.join(work, "png")
    if os.path.exists(out):
        shutil.rmtree(out)
    cmd = [exe, "--out", out, "--scene", os.path.join(scenes, "plain.json"), "--headless", "--frames", "3", "--every", "1",
           "--width", "640", "--height", "360"]
    p = subprocess.run(cmd, capture_output=True, text=True, preexec_fn=limited)
    if p.returncode != 3 or "frame_000000.png: cannot be written: File too large" not in p.stderr:
        sys.exit(f"a PNG over the limit: exit {p.returncode}:\n{p.stderr}")
    if os.listdir(os.path.join(out, "frames")) or leftovers(out):
        sys.exit(f"a PNG over the limit left {os.listdir(os.path.join(out, 'frames'))} {leftovers(out)}")
    print("a PNG over the limit: exit 3 naming it, no file left")


def process_alive(pid):
    try:
        return open(f"/proc/{pid}/stat").read().split(")")[-1].split()[0] != "Z"
    except OSError:
        return False


def mpiKill(exe, scenes, work):
    out = os.path.join(work, "kill")
    timeout = 5
    p = start_two_ranks(exe, scenes, out, timeout)
    wait_for_rows(p, out, 20)
    rank0, rank1 = process_of_rank(os.getpid(), 0), process_of_rank(os.getpid(), 1)
    if rank0 is None or rank1 is None:
        p.kill()
        sys.exit("the ranks' processes were not found")
    os.kill(rank1, signal.SIGKILL)
    killed = time.time()
    try:
        _, err = p.communicate(timeout=timeout + 10)
    except subprocess.TimeoutExpired:
        p.kill()
        sys.exit(f"the run still ran {timeout + 10} s after rank 1 was killed")
    # mpirun may end a moment before its ranks are reaped: rank 0 must be gone (or a zombie) within the limit too.
    while time.time() - killed < timeout + 10 and process_alive(rank0):
        time.sleep(0.1)
    gone = time.time() - killed
    if process_alive(rank0):
        sys.exit(f"rank 0 (pid {rank0}) still runs {gone:.1f} s after rank 1 was killed")
    if p.returncode == 0:
        sys.exit("the run succeeded although rank 1 was killed")
    named = [line for line in err.splitlines() if re.search(r"rank 1\b", line)]
    if not named:
        sys.exit(f"no message names rank 1:\n{err}")
    rows = whole_stats(out)
    print(f"rank 1 killed: every process gone after {gone:.1f} s (timeout {timeout} s), {len(rows)} whole lines in stats.csv; "
          f"named in: {named[0].strip()}")


def scale(exe, scenes, work):
    import resource
    for actors in (50_000, 100_000):
        out = os.path.join(work, str(actors))
        if os.path.exists(out):
            shutil.rmtree(out)
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        started = time.time()
        cmd = [exe, "--out", out, "--actors", str(actors), "--frames", "2", "--headless", "--every", "0", "--width", "320", "--height", "180"]
        p = subprocess.run(cmd, capture_output=True, text=True)
        took = time.time() - started
        if p.returncode != 0:
            sys.exit(f"{actors} actors: exit {p.returncode}:\n{p.stderr}")
        for phase in ("laying out the town", "building the navigation mesh", "placing actors", "baking impostors"):
            if phase not in p.stderr:
                sys.exit(f"{actors} actors: no progress line for '{phase}':\n{p.stderr}")
        summary = json.load(open(os.path.join(out, "summary.json")))
        if summary["frames"] != 2 or summary.get("completed") is not True:
            sys.exit(f"{actors} actors: summary.json says {summary['frames']} frames, completed={summary.get('completed')}")
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        print(f"{actors} actors: 2 frames, {took:.1f} s from start to exit (frames: {summary['wallSeconds']:.1f} s), "
              f"peak memory {max(peak, before) / 1024:.0f} MiB{' (at least)' if peak <= before else ''}")


def memoryLimit(exe, scenes, work):
    import resource
    limit = 4 << 30

    def limited():
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    out = os.path.join(work, "limited")
    if os.path.exists(out):
        shutil.rmtree(out)
    p = subprocess.run([exe, "--out", out, "--actors", "1000000", "--frames", "1", "--headless"], capture_output=True, text=True,
                       preexec_fn=limited)
    said = re.search(r"1000000 actors need about [\d.]+ GiB of memory .*, but (.*) leaves [\d.]+ GiB: about (\d+) actors fit", p.stderr)
    if p.returncode != 2 or not said:
        sys.exit(f"1,000,000 actors under a 4 GiB address space: exit {p.returncode}:\n{p.stderr}")
    if os.path.exists(out):
        sys.exit("the refused run left its output folder")
    print(f"1,000,000 actors under a 4 GiB address space: refused before building ({said.group(1)}; {said.group(2)} actors fit)")


def effects(exe, scenes, work):
    summaries = {}
    for scene in ("plain", "effects"):
        out = os.path.join(work, scene)
        run(exe, out, "--scene", os.path.join(scenes, scene + ".json"), "--headless", "--frames", "30", "--every", "0",
            "--width", "160", "--height", "90")
        summaries[scene] = json.load(open(os.path.join(out, "summary.json")))["effects"]
    for effect in ("avoidance", "gaze", "flight", "occluders", "key-pose cache"):
        off = summaries["plain"][effect]
        on = summaries["effects"][effect]
        if off["constructed"] != 0 or off["ticks"] != 0:
            sys.exit(f"undeclared {effect} was constructed {off['constructed']} times and ticked {off['ticks']} times")
        # Occluders and key-pose caches are built, never ticked; what they do shows in stats.csv below.
        if on["constructed"] < 1 or (on["ticks"] < 1 and effect not in ("occluders", "key-pose cache")):
            sys.exit(f"declared {effect} was not running: {on}")
    for effect in ("locomotion", "idle"):
        if summaries["plain"][effect]["ticks"] < 1:
            sys.exit(f"the plain scene's {effect} never ticked")
    # Occlusion culling: declared, it draws occluders and tests spheres; undeclared, it does nothing.
    for scene, declared in (("plain", False), ("effects", True)):
        rows = list(csv.DictReader(open(os.path.join(work, scene, "stats.csv"))))
        drawn = sum(int(r["occluders_drawn"]) for r in rows)
        tests = sum(int(r["occlusion_tests"]) for r in rows)
        if declared and (drawn == 0 or tests == 0):
            sys.exit(f"declared occlusion drew {drawn} occluders and made {tests} tests")
        # The effects scene lets occlusion rest after frames that hid little: a rested frame builds and tests nothing.
        rested = [r for r in rows if r["occlusion_rested"] == "1"]
        if declared and not (0 < len(rested) < len(rows)):
            sys.exit(f"declared occlusion with rest rested on {len(rested)} of {len(rows)} frames; expected some, not all")
        for r in rested:
            if int(r["occlusion_tests"]) or int(r["occluders_drawn"]) or float(r["occlusion_buffer_ms"]) or int(r["occluded_refpoint"]):
                sys.exit(f"frame {r['frame']} rested yet drew {r['occluders_drawn']} occluders and made {r['occlusion_tests']} tests")
        if not declared and (drawn != 0 or tests != 0 or any(float(r["occlusion_buffer_ms"]) != 0 or r["occlusion_rested"] != "0" for r in rows)):
            sys.exit(f"undeclared occlusion drew {drawn} occluders and made {tests} tests")
        # Key-pose caches: declared, actors of the band are drawn from them; undeclared, no band.
        band = sum(int(r["key_pose_band"]) for r in rows)
        cached = sum(int(r["key_pose_actors"]) for r in rows)
        if declared and (band == 0 or cached == 0):
            sys.exit(f"declared key-pose caches saw {band} actors in their band and served {cached}")
        if not declared and (band != 0 or cached != 0 or any(int(r["key_pose_fills"]) != 0 for r in rows)):
            sys.exit(f"undeclared key-pose caches saw {band} actors in their band and served {cached}")
    print(json.dumps(summaries, indent=1))


BUDGET_COLUMNS = ["budget_ms", "app_cull_draw_ms", "over_budget", "budget_rung", "lod_scale", "impostor_distance",
                  "key_pose_distance", "morph_budget", "render_scale", "town_lod_scale"]


def budget(exe, scenes, work):
    runs = {}
    for name, ms in (("tiny", "0.001"), ("huge", "1000000")):
        out = os.path.join(work, name)
        run(exe, out, "--scene", os.path.join(scenes, "effects.json"), "--headless", "--frames", "40", "--every", "0",
            "--width", "320", "--height", "180", "--frame-budget", ms)
        rows = list(csv.DictReader(open(os.path.join(out, "stats.csv"))))
        summary = json.load(open(os.path.join(out, "summary.json")))["frameBudget"]
        if len(rows) != 40:
            sys.exit(f"{name}: {len(rows)} rows instead of 40")
        missing = [c for c in BUDGET_COLUMNS if c not in rows[0]]
        if missing:
            sys.exit(f"{name}: stats.csv lacks {missing}")
        rungs = summary["rungs"]
        within = 0
        for r in rows:
            rung = int(r["budget_rung"])
            if not 0 <= rung < len(rungs):
                sys.exit(f"{name}: frame {r['frame']}: rung {rung} is not in the ladder of {len(rungs)}")
            settings = {"render-scale": "1", "town-lod-scale": "0", **dict(kv.split("=") for kv in rungs[rung]["settings"].split())}
            for column, key in (("lod_scale", "lod-scale"), ("impostor_distance", "impostor-distance"),
                                ("key_pose_distance", "key-pose-distance"), ("morph_budget", "morph-budget"),
                                ("render_scale", "render-scale"), ("town_lod_scale", "town-lod-scale")):
                if abs(float(r[column]) - float(settings[key])) > 1e-6 * max(1.0, float(settings[key])):
                    sys.exit(f"{name}: frame {r['frame']}: {column} {r[column]} is not rung {rung}'s {settings[key]}")
            if float(r["budget_ms"]) != float(ms):
                sys.exit(f"{name}: frame {r['frame']}: budget_ms {r['budget_ms']} instead of {ms}")
            cost = float(r["app_cull_draw_ms"])
            app_cull = sum(float(r[c]) for c in ("app_ms", "refpoint_ms", "matrices_bounds_ms", "occlusion_buffer_ms", "cull_ms",
                                                  "refpoint_occlusion_ms", "skeleton_root_ms", "cull2_ms", "pose_ms", "cull3_ms", "draw_list_ms"))
            if abs(cost - (app_cull + float(r["draw_ms"]))) > 0.01 + 1e-4 * cost:
                sys.exit(f"{name}: frame {r['frame']}: app_cull_draw_ms {cost} is not APP+CULL {app_cull} + DRAW {r['draw_ms']}")
            over = int(r["over_budget"])
            if over != (1 if cost > float(ms) else 0):
                sys.exit(f"{name}: frame {r['frame']}: over_budget {over} for {cost} ms against {ms}")
            within += 1 - over
        if summary["framesWithinBudget"] != within or abs(summary["shareWithinBudget"] - within / 40) > 1e-9:
            sys.exit(f"{name}: summary says {summary['framesWithinBudget']} frames within budget, stats.csv {within}")
        counts = [sum(1 for r in rows if int(r["budget_rung"]) == i) for i in range(len(rungs))]
        if counts != [g["frames"] for g in rungs]:
            sys.exit(f"{name}: the summary's rung histogram {[g['frames'] for g in rungs]} is not stats.csv's {counts}")
        runs[name] = rows
    cheapest = len(rungs) - 1
    # Nothing meets 0.001 ms: the cheapest rung from the start (the ladder says so) and never up.
    late = [int(r["budget_rung"]) for r in runs["tiny"]]
    if set(late) != {cheapest}:
        sys.exit(f"a budget of 0.001 ms left the cheapest rung {cheapest}: rungs {sorted(set(late))}")
    if {int(r["budget_rung"]) for r in runs["huge"]} != {0}:
        sys.exit("a budget of 1000 s left the most accurate rung")
    # The settings took effect: the cheapest rung draws more impostors and evaluates fewer nodes.
    def total(rows, column):
        return sum(float(r[column]) for r in rows[2:])
    if not total(runs["tiny"], "impostors") > total(runs["huge"], "impostors"):
        sys.exit(f"the cheapest rung drew {total(runs['tiny'], 'impostors')} impostors, the most accurate {total(runs['huge'], 'impostors')}")
    if not total(runs["tiny"], "skeleton_nodes") < total(runs["huge"], "skeleton_nodes"):
        sys.exit("the cheapest rung evaluated no fewer skeleton nodes than the most accurate")
    print(f"budget: {total(runs['tiny'], 'impostors'):.0f} impostors on the cheapest rung, {total(runs['huge'], 'impostors'):.0f} on the most accurate")


def gpuCheck(exe, scenes, work):
    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "benchmarks", "gpu-check")
    out = os.path.join(work, "check.csv")
    base = [script, "run", "--town", exe, "--scene", os.path.join(scenes, "plain.json"), "--sizes", "320x180", "--threads", "2"]
    p = subprocess.run([*base, "--actors", "150,300", "--frames", "8", "--out", out, "--work", os.path.join(work, "runs")],
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"gpu-check run failed ({p.returncode}):\n{p.stdout}\n{p.stderr}")
    rows = list(csv.DictReader(open(out)))
    if [r["actors"] for r in rows] != ["150", "300"] or any(r["status"] != "completed" for r in rows):
        sys.exit(f"gpu-check: rows {[(r['actors'], r['status']) for r in rows]}, expected 150 and 300 completed")
    for r in rows:
        if not r["context"].startswith("EGL") or r["frames_run"] != "8" or r["frames_measured"] != "8":
            sys.exit(f"gpu-check: row {r}: expected EGL, 8 frames run and measured (no warm-up at 8 frames)")
        for column in ("step_ms", "app_cull_ms", "draw_ms", "draw_cpu_ms", "frame_ms", "fps"):
            if not float(r[column]) > 0:
                sys.exit(f"gpu-check: {column} = {r[column]} in {r}")
        # The run's own stats.csv agrees with the row: the mean of its DRAW CPU column.
        stats = list(csv.DictReader(open(os.path.join(work, "runs", f"{r['actors']}-320x180", "stats.csv"))))
        mean = sum(float(s["draw_cpu_ms"]) for s in stats) / len(stats)
        if abs(mean - float(r["draw_cpu_ms"])) > 0.002:
            sys.exit(f"gpu-check: draw_cpu_ms {r['draw_cpu_ms']} is not the mean of stats.csv's ({mean:.4f})")
    about = open(out + ".about").read()
    if "EGL devices:" not in about or "--gl egl:" not in about or "gpu-check: commit: " not in about:
        sys.exit("gpu-check: the .about lacks the commit or the EGL devices:\n" + about)
    if "150-320x180: step " not in open(out + ".log").read():
        sys.exit("gpu-check: the log lacks the runs' lines")
    # The page from that CSV: a row per run, with the context the runs used.
    page = os.path.join(work, "page.md")
    p = subprocess.run([script, "page", "--out", page, out], capture_output=True, text=True)
    text = open(page).read() if p.returncode == 0 else ""
    if p.returncode != 0 or "| 150 | 320x180 | 8 |" not in text or "| 300 | 320x180 | 8 |" not in text or "(EGL" not in text:
        sys.exit(f"gpu-check page: exit {p.returncode}\n{p.stderr}\n{text}")
    # Without --work the runs' folder is temporary, removed at exit without a shell error.
    p = subprocess.run([*base, "--actors", "150", "--frames", "2", "--out", out], capture_output=True, text=True)
    if p.returncode != 0 or re.search(r"gpu-check: line \d+: ", p.stdout + p.stderr):
        sys.exit(f"gpu-check without --work: exit {p.returncode}:\n{p.stdout}{p.stderr}")
    # Nothing fits a budget of 1 s: every run is skipped, said in the CSV, and the check fails.
    p = subprocess.run([*base, "--actors", "150", "--frames", "8", "--budget", "1", "--out", out], capture_output=True, text=True)
    rows = list(csv.DictReader(open(out)))
    if p.returncode != 1 or [r["status"] for r in rows] != ["skipped (budget)"]:
        sys.exit(f"gpu-check with a budget of 1 s: exit {p.returncode}, rows {rows}")
    p = subprocess.run([*base, "--frames", "0"], capture_output=True, text=True)
    if p.returncode != 2 or "--frames: must be a whole number from 1, got '0'" not in p.stderr:
        sys.exit(f"gpu-check --frames 0: exit {p.returncode}:\n{p.stderr}")
    print("gpu-check: 2 runs measured, a spent budget skips, a bad option is refused")


def window(exe, scenes, work):
    out = os.path.join(work, "window")
    p = run(exe, out, "--scene", os.path.join(scenes, "plain.json"), "--frames", "5", "--width", "320", "--height", "180")
    if "running headless" in p.stderr:
        sys.exit("no window opened:\n" + p.stderr)
    frames_run = json.load(open(os.path.join(out, "summary.json")))["frames"]
    if frames_run != 5:
        sys.exit(f"the window ran {frames_run} frames instead of 5")
    print("a window ran 5 frames")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    exe, mode, scenes, work = sys.argv[1:]
    os.makedirs(work, exist_ok=True)
    {"determinism": determinism, "effects": effects, "window": window, "mpi": mpi, "mpiHang": mpiHang,
     "mpiKill": mpiKill, "budget": budget, "signals": signals, "fileLimit": fileLimit, "scale": scale,
     "memoryLimit": memoryLimit, "gpuCheck": gpuCheck, "mpiPosing": mpiPosing}[mode](exe, scenes, work)
