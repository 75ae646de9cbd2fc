#!/usr/bin/env python3
"""The layout's one-way dependencies, checked on the sources.

- The installed libraries (scenegraph/, actors/, actors/gltf/, render/, render/vtk/, sim/) include
  nothing of the apps (throng/support/), the test kit (throng/testkit/), the benchmark harness
  (throng/bench/) or the non-installed research library (throng/research/).
- tests/ and benchmarks/ include no app code (throng/support/, anything under apps/) and link no
  app library (throng_app_support); a test reaches a helper of another folder through the test kit,
  never by a "../" include.

Usage: check_layout.py SOURCE_DIR. One line per offence, with file and line; exit 1 if any.
"""
import os
import re
import sys

SOURCE = os.path.abspath(sys.argv[1])
SOURCES = (".h", ".hpp", ".cpp", ".cc")
problems = []


def walk(top, skip=()):
    for root, dirs, files in os.walk(os.path.join(SOURCE, top)):
        rel = os.path.relpath(root, SOURCE)
        if any(rel == s or rel.startswith(s + os.sep) for s in skip):
            dirs[:] = []
            continue
        for f in files:
            yield os.path.join(root, f)


def scan(path, pattern, why):
    with open(path, encoding="utf-8", errors="replace") as text:
        for n, line in enumerate(text, 1):
            m = pattern.search(line)
            if m:
                problems.append(f"{os.path.relpath(path, SOURCE)}:{n}: {why(m)}")


NOT_IN_LIBRARIES = re.compile(r'#\s*include\s*[<"]throng/(support|testkit|bench|research)/')
for lib in ["scenegraph", "actors", "render", "sim"]:
    for path in walk(lib, skip=[os.path.join("actors", "research")]):  # research may use the libraries, not the reverse
        if path.endswith(SOURCES):
            scan(path, NOT_IN_LIBRARIES, lambda m: f"an installed library includes throng/{m.group(1)}/")

APP_INCLUDE = re.compile(r'#\s*include\s*[<"](throng/support/|(\.\./)*apps/)')
ACROSS = re.compile(r'#\s*include\s*"\.\./')
APP_LIBRARY = re.compile(r'\bthrong_app_support\b')
for top in ["tests", "benchmarks"]:
    for path in walk(top, skip=[os.path.join("tests", "layout")]):
        if path.endswith(SOURCES):
            scan(path, APP_INCLUDE, lambda m: f"{top}/ includes app code ({m.group(1)})")
            scan(path, ACROSS, lambda m: f'{top}/ reaches another folder by a "../" include (use the test kit)')
        elif os.path.basename(path) == "CMakeLists.txt":
            scan(path, APP_LIBRARY, lambda m: f"{top}/ links the apps' library throng_app_support")

for p in problems:
    print(p)
print(f"check_layout: {len(problems)} offence(s) against the layout" if problems
      else "check_layout: the libraries include no app, kit, harness or research code; tests and benchmarks include no app code")
sys.exit(1 if problems else 0)
