#!/usr/bin/env python3
"""Runs every shell command the README and docs/ show, so none of them rots.

Each command runs as written, with these changes a reader's copy would not need:
- `./build/<preset>/…` and `build/<preset>` name this build's folder (the command's program and
  options are the page's; the build that made them is the one under test);
- sizes are made small: every count option (actors, frames, ticks, steps, warm-up, rounds,
  samples, repetitions) and the image size the command gives, or the program's `--help` gives a
  larger default for, is set to a few (the page's value when it is smaller), within the range the
  help states; a program whose every run is a sweep runs one value of it (NARROW); a Google
  Benchmark suite runs the first (smallest) instance of each benchmark the page selects;
- a program that opens a window runs under `xvfb-run -a` when there is no display;
- it runs in a scratch copy of the repository's root (`../shared` beside it, the scripts it calls
  linked in), so outputs never land in the repository; an input another, skipped command would
  have made is made from what earlier commands wrote (INPUTS).
A file a page shows and marks with `<!-- saved-as: NAME -->` before its fence is written first.

The commands that cannot run inside the suite are listed in SKIPPED with the reason; any other
command that fails, times out or names a program this build did not make fails the test. Prints
one line per command (ran, skipped, FAILED) with its page and line.

Usage: run_doc_commands.py SOURCE_DIR BINARY_DIR WORK_DIR
"""
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_pages import fenced_blocks, pages, shell_commands, simple_commands  # noqa: E402

SOURCE, BINARY, WORK = (os.path.abspath(a) for a in sys.argv[1:4])

# (pattern of the command, why it is not run inside the suite)
SKIPPED = [
    (r"^\./run-(town|tests)\b",
     "installs packages and builds the release preset: CI runs ./run-tests as written (.ci/run); "
     "what run-town runs (throng-town and its options) is run below"),
    (r"^(\w+=(\"[^\"]*\"|\S+) )*(cmake|ctest)\b",
     "the project's own configure, build, install and test steps: CI runs them (./run-tests), "
     "and the package.* tests install the libraries and build the consumer"),
    (r"^(\w+=(\"[^\"]*\"|\S+) )*benchmarks/(run-report|check-baseline|update-frame-results|update-validation-results|update-avoidance-results)\b",
     "builds the release preset and measures for many minutes (run before an issue is resolved); "
     "the programs it runs are run below, one command each"),
    (r"^(benchmarks|build/gpu-check)/gpu-check\b",
     "builds a second release tree (the lean throng-town) and measures for minutes; town.gpuCheck runs "
     "its run step small with the suite's throng-town"),
    (r"^paraview\b", "ParaView is a desktop program, not installed here; the command that writes what it opens runs"),
    (r"--hostfile|^cat > hosts", "the two-host example needs two machines"),
    (r"--wdir run/rank", "ranks in working folders of their own over TCP: test town.mpi runs these options with the suite's "
                         "throng-town (tests/town/check_town.py, run_ranks); the folders the command makes are made here"),
]

# Count options and how small they get (the page's value when smaller).
SMALL = [
    (re.compile(r"--([a-z]+-)*actors"), 150),
    (re.compile(r"--([a-z]+-)*(frames|ticks|steps)"), 2),
    (re.compile(r"--warmup"), 0),
    (re.compile(r"--([a-z]+-)*(rounds|samples)|--benchmark_repetitions"), 1),
    (re.compile(r"--width"), 320),
    (re.compile(r"--height"), 180),
]
# Programs whose every run is a sweep: the page's command, on one value of the sweep (appended
# when the page does not choose).
NARROW = {
    "bench_accuracy": ["--knobs", "lod-scale", "--cameras", "street"],
    "throng-impostor-quality": ["--sections", "morph", "--asset", "CesiumMan=../shared/assets/characters/CesiumMan.glb:animation0",
                                "--size", "32", "--views", "4x1", "--keyframes", "4"],
    "bench_osg_peer": ["--scenes", "table2"],
}
# Inputs a page's command reads that another command makes (one the suite does not run): made
# here from what earlier commands of the pages wrote.
INPUTS = {
    "report/accuracy": ["accuracy.csv", "impostors.csv", "keypose.csv"],
}
# Programs that open a window unless told to take a screenshot (run under xvfb-run without a display).
WINDOWED = {"throng-vtk"}
PER_COMMAND_TIMEOUT = 300
BUILD_PATH = re.compile(r"^(\./)?build/[\w-]+(/|$)")

help_cache = {}


def help_of(program):
    """A CLI11 program's --help text, or ''."""
    if program not in help_cache:
        try:
            run = subprocess.run([program, "--help"], capture_output=True, text=True, timeout=60)
            help_cache[program] = run.stdout + run.stderr
        except (OSError, subprocess.TimeoutExpired):
            help_cache[program] = ""
    return help_cache[program]


def small_value(option, value, help_text):
    """The value `option` gets, or None when it is not a count option."""
    for pattern, small in SMALL:
        if pattern.fullmatch(option):
            break
    else:
        return None
    m = re.search(re.escape(option) + r"\b[^\n]*INT in \[(-?\d+) - ", help_text)
    low = int(m.group(1)) if m else 0
    values = []
    for i, v in enumerate(value.split(",")):
        try:
            n = int(float(v))
        except ValueError:
            return value
        target = small * (i + 1) if small > 2 and "," in value else small  # keep a list's values distinct
        values.append(str(max(low, min(n, target))))
    return ",".join(values)


def program_index(words):
    """Where the program a wrapper (xvfb-run, mpirun, python3) runs is, or 0."""
    for i, w in enumerate(words):
        if BUILD_PATH.match(w) or os.path.basename(w).startswith(("throng-", "bench_")):
            return i
    return 0


def prepared(words):
    """The command as it runs here, and a problem (or None)."""
    words = [os.path.join(BINARY, BUILD_PATH.sub("", w)) if BUILD_PATH.match(w) else w for w in words]
    words = [BINARY if w == BINARY + "/" else w for w in words]
    p = program_index(words)
    program = words[p]
    if os.path.isabs(program) and program.startswith(BINARY) and not os.access(program, os.X_OK):
        return words, f"{os.path.relpath(program, BINARY)} was not built in this build"
    help_text = help_of(program) if program.startswith(BINARY) else ""
    out = words[: p + 1]
    given = set()
    k = p + 1
    while k < len(words):
        w = words[k]
        option, eq, value = w.partition("=")
        if not eq and k + 1 < len(words) and not words[k + 1].startswith("--"):
            value = words[k + 1]
        small = small_value(option, value, help_text) if option.startswith("--") and value else None
        if small is not None:
            given.add(option)
            out += [f"{option}={small}"] if eq else [option, small]
            k += 1 if eq else 2
            continue
        out.append(w)
        k += 1
    for extra in range(0, len(NARROW.get(os.path.basename(program), [])), 2):
        option, value = NARROW[os.path.basename(program)][extra:extra + 2]
        if option not in words:
            out += [option, value]
            given.add(option)
    # Larger defaults the help states (either of CLI11's two help layouts), made small too.
    defaults = re.findall(r"^\s+(--[\w-]+) [A-Z,.]+\s.*\(default: \[?([\d,]+)\]?\)\s*$", help_text, re.M)
    defaults += re.findall(r"^\s+(--[\w-]+) [A-Z]+:[^=\n]*=\[?([\d,]+)\]?", help_text, re.M)
    for option, default in defaults:
        if option in given or all(v == "0" for v in default.split(",")):
            continue
        small = small_value(option, default, help_text)
        if small is not None and small != default:
            out += [option, small]
    if "--benchmark_filter" in help_text:
        out = smallest_benchmarks(out)
    if (os.path.basename(program) in WINDOWED and "--screenshot" not in out and out[0] != "xvfb-run" and
            not os.environ.get("DISPLAY")):
        out = ["xvfb-run", "-a"] + out
    return out, None


def smallest_benchmarks(words):
    """A Google Benchmark suite's command narrowed to the first (smallest) instance of each
    benchmark the page's filter selects, each run for a millisecond where the suite lets it."""
    page_filter = next((w.split("=", 1)[1] for w in words if w.startswith("--benchmark_filter=")), None)
    listing = subprocess.run([w for w in words if not w.startswith("--benchmark_")] + ["--benchmark_list_tests=true"] +
                             ([f"--benchmark_filter={page_filter}"] if page_filter else []),
                             capture_output=True, text=True, timeout=60).stdout.splitlines()
    first = {}
    for name in listing:  # the suite may print prose around the names
        if re.fullmatch(r"[A-Za-z_]\w*(/\S*)?", name):
            first.setdefault(name.split("/", 1)[0], name)
    narrowed = "^(" + "|".join(re.escape(n) for n in first.values()) + ")$"
    return [w for w in words if not w.startswith("--benchmark_filter=")] + [f"--benchmark_filter={narrowed}",
                                                                          "--benchmark_min_time=0.001"]


def main():
    if os.path.exists(WORK):
        shutil.rmtree(WORK)
    root = os.path.join(WORK, "repo")
    os.makedirs(root)
    os.symlink(os.path.join(os.path.dirname(SOURCE), "shared"), os.path.join(WORK, "shared"))
    for name in ("benchmarks", "apps", "tests", "docs"):
        # Read-only parts of the tree a command reads (scripts, scenes); apps/ is a real folder
        # whose subfolders link back file by file, images left out: a screenshot written under
        # apps/vtk lands here, not through a link onto the committed picture.
        if name == "apps":
            for sub in os.listdir(os.path.join(SOURCE, "apps")):
                if not os.path.isdir(os.path.join(SOURCE, "apps", sub)):
                    os.makedirs(os.path.join(root, "apps"), exist_ok=True)
                    os.symlink(os.path.join(SOURCE, "apps", sub), os.path.join(root, "apps", sub))
                    continue
                os.makedirs(os.path.join(root, "apps", sub))
                for f in os.listdir(os.path.join(SOURCE, "apps", sub)):
                    if f.endswith(".png"):
                        continue
                    os.symlink(os.path.join(SOURCE, "apps", sub, f), os.path.join(root, "apps", sub, f))
        else:
            os.symlink(os.path.join(SOURCE, name), os.path.join(root, name))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_btl_vader_single_copy_mechanism="none")

    failures, ran, skipped, done = [], 0, 0, set()
    for page in pages(SOURCE):
        where_page = os.path.relpath(page, SOURCE)
        with open(page, encoding="utf-8") as f:
            lines = f.read().split("\n")
        for lang, first, body, before in fenced_blocks(lines):
            m = re.search(r"<!--\s*saved-as:\s*(\S+)\s*-->", before)
            if m:
                with open(os.path.join(root, m.group(1)), "w", encoding="utf-8") as f:
                    f.write("\n".join(body) + "\n")
            if lang not in ("sh", "bash", "shell"):
                continue
            for line, command in shell_commands(first, body):
                where = f"{where_page}:{line}"
                reason = next((why for pattern, why in SKIPPED if re.search(pattern, command)), None)
                if reason:
                    skipped += 1
                    print(f"skipped {where}: {command.splitlines()[0]}\n        ({reason})")
                    continue
                for words in simple_commands(command):
                    words, problem = prepared(words)
                    shown = " ".join(words).replace(BINARY, "<build>")
                    if problem:
                        failures.append(f"{where}: {problem}")
                        print(f"FAILED  {where}: {problem}")
                        continue
                    if tuple(words) in done:
                        print(f"ran     {where}: (the same as above) {shown}")
                        continue
                    done.add(tuple(words))
                    for folder, files in INPUTS.items():
                        if folder in words and not os.path.isdir(os.path.join(root, folder)):
                            os.makedirs(os.path.join(root, folder))
                            for f in files:
                                if os.path.exists(os.path.join(root, f)):
                                    shutil.copy(os.path.join(root, f), os.path.join(root, folder, f))
                    start = time.monotonic()
                    try:
                        run = subprocess.run(words, cwd=root, env=env, capture_output=True, text=True,
                                             timeout=PER_COMMAND_TIMEOUT)
                        code, output = run.returncode, run.stdout + run.stderr
                    except subprocess.TimeoutExpired:
                        code, output = "timeout", ""
                    seconds = time.monotonic() - start
                    ran += 1
                    if code != 0:
                        tail = "\n".join(output.strip().splitlines()[-8:])
                        failures.append(f"{where}: exit {code}: {shown}\n{tail}")
                        print(f"FAILED  {where} ({seconds:.1f} s, exit {code}): {shown}\n{tail}")
                    else:
                        print(f"ran     {where} ({seconds:.1f} s): {shown}")
    print(f"run_doc_commands: {ran} commands ran, {skipped} skipped with their reason, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
