#!/usr/bin/env python3
"""Checks the README and docs/ against the repository and the built programs.

- README.md is an entry point: at most 200 lines.
- Every relative link and image resolves to a file of the repository.
- A code block announced by `<!-- excerpt: PATH -->` is a verbatim run of lines of PATH, so the code
  a reader copies is the code the build compiles and the tests run.
- Every program a shell block runs (`throng-*`, `./run-town`) is one the build makes, and every
  `--option` given to it is one its `--help` lists; `cmake --preset`/`ctest --preset` name presets
  that exist; a script run by path (`./setup.sh`, `benchmarks/check-baseline`) exists.
- The pages speak of the project only: no machine's absolute paths.

Usage: check_docs.py SOURCE_DIR BINARY_DIR [BINARY_DIR ...]. Prints one line per problem with the
file and line, and exits 1 if there is any.
"""
import json
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from doc_pages import fenced_blocks, pages, shell_commands, simple_commands  # noqa: E402

SOURCE = os.path.abspath(sys.argv[1])
BINARY_DIRS = [os.path.abspath(d) for d in sys.argv[2:]]
problems = []


def problem(path, line, text):
    problems.append(f"{os.path.relpath(path, SOURCE)}:{line}: {text}")


programs_help = {}


def find_program(name):
    for d in BINARY_DIRS:
        for root, dirs, files in os.walk(d):
            dirs[:] = [x for x in dirs if x not in ("CMakeFiles", "Testing", "install")]
            if name in files and os.access(os.path.join(root, name), os.X_OK):
                return os.path.join(root, name)
    return None


def help_of(name):
    if name not in programs_help:
        exe = find_program(name)
        text = None
        if exe:
            run = subprocess.run([exe, "--help"], capture_output=True, text=True, timeout=60)
            text = run.stdout + run.stderr
        programs_help[name] = text
    return programs_help[name]


with open(os.path.join(SOURCE, "CMakePresets.json")) as f:
    presets = {p["name"] for p in json.load(f)["configurePresets"]}
# The programs the project makes, from its CMake files (a build may leave some out: the sanitizer
# preset builds no benchmarks, so their options are checked only where they were built).
known_programs = set()
for root, dirs, files in os.walk(SOURCE):
    dirs[:] = [x for x in dirs if x not in ("build", ".git")]
    if "CMakeLists.txt" in files:
        with open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8") as f:
            known_programs.update(re.findall(r"add_executable\((throng-[\w-]+)", f.read()))


def check_command(path, line, words):
    if not words:
        return
    first = words[0]
    base = os.path.basename(first)
    if first in ("cmake", "ctest") and "--preset" in words:
        i = words.index("--preset")
        if i + 1 < len(words) and words[i + 1] not in presets:
            problem(path, line, f"preset '{words[i + 1]}' is not in CMakePresets.json")
        return
    program = "throng-town" if base == "run-town" else base if base.startswith("throng-") else None
    if program is None:
        if (first.startswith("./") or first.startswith("benchmarks/")) and "/build/" not in first and not first.startswith("./build"):
            if not os.path.exists(os.path.join(SOURCE, first)):
                problem(path, line, f"'{first}' does not exist")
        return
    if program not in known_programs:
        problem(path, line, f"'{program}' is not a program the project makes")
        return
    text = help_of(program)  # None where this build did not make it
    if text is None:
        return
    for w in words[1:]:
        opt = w.split("=", 1)[0]
        if re.fullmatch(r"--[a-z][a-z0-9-]*", opt) and not re.search(re.escape(opt) + r"\b", text):
            problem(path, line, f"{program} has no option {opt} (not in its --help)")


for path in pages(SOURCE):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    lines = text.split("\n")
    if path.endswith(os.path.join(SOURCE, "README.md")) and len(lines) - (lines[-1] == "") > 200:
        problem(path, 1, f"the README has {len(lines)} lines, more than 200")
    for n, l in enumerate(lines, 1):
        if re.search(r"(?<![\w.])/(work|home|root|tmp)/", l):
            problem(path, n, "names an absolute path of a machine")
        for target in re.findall(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)", l):
            if re.match(r"^(https?:|mailto:|#)", target):
                continue
            file = target.split("#", 1)[0]
            if not os.path.exists(os.path.normpath(os.path.join(os.path.dirname(path), file))):
                problem(path, n, f"link to '{target}' leads nowhere")
    for lang, first, body, before in fenced_blocks(lines):
        m = re.search(r"<!--\s*excerpt:\s*(\S+)\s*-->", before)
        if m:
            source = os.path.join(SOURCE, m.group(1))
            if not os.path.exists(source):
                problem(path, first, f"excerpt of '{m.group(1)}', which does not exist")
            else:
                with open(source, encoding="utf-8") as f:
                    src = f.read().split("\n")
                if not any(src[k:k + len(body)] == body for k in range(len(src) - len(body) + 1)):
                    problem(path, first, f"the code block is no longer a verbatim excerpt of {m.group(1)}")
        if lang in ("sh", "bash", "shell"):
            for start, command in shell_commands(first, body):
                for words in simple_commands(command):
                    # mpirun's app contexts (separated by ':'), each with launcher options of its own
                    contexts = [[]]
                    for w in words:
                        if w == ":" and words[0] == "mpirun":
                            contexts.append(["mpirun"])
                        else:
                            contexts[-1].append(w)
                    for words in contexts:
                        if words and words[0] in ("mpirun", "xvfb-run", "time", "env", "sudo"):
                            # the program the wrapper runs: its first word that is a Throng program or a path
                            runs = [i for i, w in enumerate(words) if i > 0 and
                                    (os.path.basename(w).startswith("throng-") or w.startswith("./"))]
                            words = words[runs[0]:] if runs else []
                        check_command(path, start, words)

for p in problems:
    print(p)
print(f"check_docs: {len(problems)} problem(s) in the README and docs/" if problems else "check_docs: README and docs/ are consistent")
sys.exit(1 if problems else 0)
