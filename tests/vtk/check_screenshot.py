#!/usr/bin/env python3
"""Runs throng-vtk --screenshot and checks the PNG it writes: it exists, has the size asked for and
is not one flat colour (the town and its crowd were drawn). Standard library only: the PNG is
decoded here (8-bit RGB or RGBA, non-interlaced, as vtkPNGWriter writes a render window).
Then, with --window, runs the window (its interactor's timer stepping the world) for the same
FRAMES and checks that it closed by itself at the simulation time the screenshot was taken at.
With --draw throng, Throng's renderer draws the crowd inside VTK, and the scene must declare
impostors and key-pose caches: the actors drawn must include both (the VTK mapper's never do).

usage: check_screenshot.py THRONG_VTK SCENE OUT.png WIDTH HEIGHT FRAMES [--window | --draw throng]"""
import os
import re
import struct
import subprocess
import sys
import zlib


def read_png(path):
    """(width, height, channels, rows of bytes) of an 8-bit RGB/RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        sys.exit(f"{path}: not a PNG")
    pos, chunks = 8, {}
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunks.setdefault(kind, []).append(data[pos + 8:pos + 8 + length])
        pos += 12 + length
    width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", chunks[b"IHDR"][0])
    channels = {2: 3, 6: 4}.get(colour)
    if depth != 8 or channels is None or interlace:
        sys.exit(f"{path}: unexpected PNG format (depth {depth}, colour type {colour}, interlace {interlace})")
    raw = zlib.decompress(b"".join(chunks[b"IDAT"]))
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, rows


def main():
    exe, scene, out, width, height, frames = sys.argv[1:7]
    window = sys.argv[7:] == ["--window"]
    throng_drawing = sys.argv[7:] == ["--draw", "throng"]
    if os.path.exists(out):
        os.remove(out)
    run = subprocess.run([exe, "--scene", scene, "--screenshot", out, "--frames", frames, "--width", width, "--height", height]
                         + (["--draw", "throng"] if throng_drawing else []), capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"throng-vtk exited with {run.returncode}:\n{run.stderr}")
    drew = re.search(r"drew (\d+) actors: (\d+) meshes, (\d+) key-poses, (\d+) impostors", run.stderr)
    if not drew:
        sys.exit(f"throng-vtk did not say what it drew:\n{run.stderr}")
    total, meshes, key_poses, impostors = (int(g) for g in drew.groups())
    if total != meshes + key_poses + impostors or total == 0:
        sys.exit(f"bad drawing statistics: {drew.group(0)}")
    if throng_drawing and (key_poses == 0 or impostors == 0):
        sys.exit(f"Throng's renderer should draw the scene's key-pose caches and impostors: {drew.group(0)}")
    rendered = re.search(r"Throng's renderer: (\d+) key-pose items, (\d+) impostor quads", run.stderr)
    if throng_drawing and (not rendered or int(rendered.group(1)) < key_poses or int(rendered.group(2)) != impostors):
        sys.exit(f"Throng's renderer did not draw what the cascade chose: {drew.group(0)}; "
                 f"{rendered.group(0) if rendered else 'no renderer statistics'}")
    if not throng_drawing and rendered:
        sys.exit(f"the VTK mapper was asked for, yet Throng's renderer drew: {rendered.group(0)}")
    if not throng_drawing and meshes != total:
        sys.exit(f"the VTK mapper draws meshes only: {drew.group(0)}")
    print(drew.group(0))
    if not os.path.isfile(out):
        sys.exit(f"throng-vtk wrote no {out}")
    w, h, channels, rows = read_png(out)
    if (w, h) != (int(width), int(height)):
        sys.exit(f"{out} is {w}x{h}, asked for {width}x{height}")
    colours = set()
    for row in rows:
        for x in range(0, w * channels, channels):
            colours.add(row[x:x + 3])
    if len(colours) < 2:
        sys.exit(f"{out} is one flat colour {colours}")
    # The sky is one colour; the tiles, actors and overlay add many more (lit, shaded surfaces).
    if len(colours) < 50:
        sys.exit(f"{out} has only {len(colours)} colours: the town was not drawn")
    print(f"{out}: {w}x{h}, {len(colours)} colours")
    if window:
        shot_time = re.search(r"after \d+ steps \(time ([0-9.]+) s\)", run.stderr)
        run = subprocess.run([exe, "--scene", scene, "--frames", frames, "--width", width, "--height", height],
                             capture_output=True, text=True, timeout=600)
        if run.returncode != 0:
            sys.exit(f"throng-vtk (window) exited with {run.returncode}:\n{run.stderr}")
        closed = re.search(r"window closed at time ([0-9.]+) s", run.stderr)
        if not shot_time or not closed or closed.group(1) != shot_time.group(1):
            sys.exit(f"the window did not step {frames} times: screenshot {shot_time and shot_time.group(0)}, "
                     f"window {closed and closed.group(0)}\n{run.stderr}")
        print(f"window: closed after {frames} steps at time {closed.group(1)} s")


if __name__ == "__main__":
    main()
