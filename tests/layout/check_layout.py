#!/usr/bin/env python3
"""The layout's one-way dependencies, checked on the sources: the installed libraries
(scenegraph/, actors/, actors/gltf/, render/, render/vtk/, sim/) include nothing of the apps
(throng/support/, throng/scenes/) nor of the non-installed research library (throng/research/).

Usage: check_layout.py SOURCE_DIR. One line per offending include, with file and line; exit 1 if any.
"""
import os
import re
import sys

SOURCE = os.path.abspath(sys.argv[1])
LIBRARIES = ["scenegraph", "actors", "render", "sim"]
NOT_IN_LIBRARIES = re.compile(r'#\s*include\s*[<"]throng/(support|scenes|research)/')
problems = []
for lib in LIBRARIES:
    for root, dirs, files in os.walk(os.path.join(SOURCE, lib)):
        rel = os.path.relpath(root, SOURCE)
        if rel.startswith(os.path.join("actors", "research")):  # research may use the libraries, not the reverse
            dirs[:] = []
            continue
        for f in files:
            if not f.endswith((".h", ".hpp", ".cpp", ".cc")):
                continue
            path = os.path.join(root, f)
            with open(path, encoding="utf-8", errors="replace") as text:
                for n, line in enumerate(text, 1):
                    m = NOT_IN_LIBRARIES.search(line)
                    if m:
                        problems.append(f"{os.path.relpath(path, SOURCE)}:{n}: an installed library includes throng/{m.group(1)}/")
for p in problems:
    print(p)
print(f"check_layout: {len(problems)} include(s) against the layout" if problems else "check_layout: the libraries include no app or research code")
sys.exit(1 if problems else 0)
