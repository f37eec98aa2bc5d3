#!/usr/bin/python3
"""Explains every pixel where sgapi's and the reference's coverage of a scene's lines differ.

    tools/line-mismatch.py SCENES.json SCENE SGAPI.png REFERENCE.png

Reads the scene's line meshes (OBJ `l`) and wireframe draws, takes every segment to the window
in double precision (snapped to 1/256 pixel as both renderers do), and sorts each pixel that one
image covers and the other does not (the scene's clear colour as background) by what the
diamond-exit rule says there, for the segments whose line passes within a pixel of it:

  tie      the line crosses the edge between two pixels exactly at this pixel's major-axis
           centre: the rule's move of the end points decides (sgapi), the reference's
           parallelogram and fill rule decide the other way for half the slopes
  end      within a pixel of an end point's major-axis position: the reference tests the ends
           in float and moves them by up to half a pixel before drawing
  near     within 4/256 pixel of such an edge: the reference's end-point move, rounded to 1/256
           again, tilts its line by that much
  clipped  on a segment cut by a clip plane, or leaving the image, within 2/256 pixel of such an
           edge or a pixel of its ends: the two renderers cut it at different places (the
           reference may cut at the image's edge) and round the new end point differently
  other    none of these (an unexplained difference)

Prints the counts per class and renderer, and the first `other` pixels. Exit status 1 when
there is any `other`. Pure Python 3 (PNG decoding included), for checking, not speed.
"""
import json
import os
import struct
import sys
import zlib

ONE = 256


def read_png(path):
    data = open(path, "rb").read()
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        chunk = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", chunk[:10])
            assert depth == 8 and ctype in (2, 6), "8-bit RGB(A) only"
            bpp = 4 if ctype == 6 else 3
        elif kind == b"IDAT":
            idat += chunk
        pos += 12 + n
    raw, stride = zlib.decompress(idat), w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b, c = prev[x], prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + ((a + b) >> 1)) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x * bpp:x * bpp + 3]) for x in range(w)])
        prev = line
    return w, h, rows


def read_obj(path):
    verts, lines, faces = [], [], []
    for text in open(path):
        t = text.split()
        if not t:
            continue
        if t[0] == "v":
            verts.append([float(v) for v in t[1:4]] + [float(t[4]) if len(t) == 5 else 1.0])
        elif t[0] in ("l", "f"):
            idx = [int(v.split("/")[0]) for v in t[1:]]
            idx = [i - 1 if i > 0 else len(verts) + i for i in idx]
            (lines if t[0] == "l" else faces).append(idx)
    return verts, lines, faces


def mat_mul(a, b):
    return [sum(a[r * 4 + k] * b[k * 4 + c] for k in range(4)) for r in range(4) for c in range(4)]


def segments(scene_file, scene, width, height):
    """(start, end, clipped) per segment, start and end in 1/256 pixel."""
    base = os.path.dirname(scene_file)
    out = []
    for d in scene["draws"]:
        mesh = d["mesh"]
        if not isinstance(mesh, str):
            continue
        verts, lines, faces = read_obj(os.path.join(base, mesh))
        pairs = [(p[i], p[i + 1]) for p in lines for i in range(len(p) - 1)]
        if d.get("polygon_mode") == "line":  # each triangle's edges, v2 -> v0 first
            for f in faces:
                for k in range(1, len(f) - 1):
                    t = (f[0], f[k], f[k + 1])
                    pairs += [(t[2], t[0]), (t[0], t[1]), (t[1], t[2])]
        m = mat_mul(d["proj"], d["worldView"])
        guard = 2.0 * 32768.0 / width - 1.0
        for a, b in pairs:
            c = [[sum(m[r * 4 + k] * verts[i][k] for k in range(4)) for r in range(4)] for i in (a, b)]
            # Clip in homogeneous space (near plane, w above 0, the guard band), as sgapi does.
            planes = [lambda p: p[2] + p[3], lambda p: p[3] - 1e-9, lambda p: guard * p[3] - p[0],
                      lambda p: guard * p[3] + p[0], lambda p: guard * p[3] - p[1],
                      lambda p: guard * p[3] + p[1], lambda p: p[3] - p[2]]
            clipped, gone = False, False
            for dist in planes:
                d0, d1 = dist(c[0]), dist(c[1])
                if d0 < 0 and d1 < 0:
                    gone = True
                    break
                if d0 < 0 or d1 < 0:
                    clipped = True
                    i, o = (0, 1) if d0 >= 0 else (1, 0)
                    t = dist(c[i]) / (dist(c[i]) - dist(c[o]))
                    c[o] = [c[i][k] + t * (c[o][k] - c[i][k]) for k in range(4)]
            if gone:
                continue
            ends = []
            for p in c:
                x = (p[0] / p[3] * 0.5 + 0.5) * width
                y = (0.5 - p[1] / p[3] * 0.5) * height
                ends.append((round(x * ONE), round(y * ONE)))
            # Lines that leave the image: the reference may cut them at its edge, not at the
            # guard band, and round the new end point its own way.
            inside = all(0 <= e[0] <= width * ONE and 0 <= e[1] <= height * ONE for e in ends)
            out.append((ends[0], ends[1], clipped or not inside))
    return out


def classify(segs, px, py):
    cx, cy = px * ONE + ONE // 2, py * ONE + ONE // 2
    found = set()
    for (ax, ay), (bx, by), clipped in segs:
        dx, dy = bx - ax, by - ay
        if dx == 0 and dy == 0:
            continue
        xm = abs(dx) >= abs(dy)
        u, v = (cx, cy) if xm else (cy, cx)
        ua, va, ub, vb = (ax, ay, bx, by) if xm else (ay, ax, by, bx)
        if ua > ub:
            ua, va, ub, vb = ub, vb, ua, va
        du, dv = ub - ua, vb - va
        if not ua - 2 * ONE <= u <= ub + 2 * ONE:
            continue
        off = va * du + (u - ua) * dv - v * du  # du x (line - centre), minor axis
        if abs(off) > ONE * du:
            continue
        edge = min(abs(off - ONE // 2 * du), abs(off + ONE // 2 * du))
        if clipped:
            if edge <= 2 * du or u // ONE <= ua // ONE + 1 or u // ONE >= ub // ONE - 1:
                found.add("clipped")
            continue
        if u // ONE <= ua // ONE + 1 or u // ONE >= ub // ONE - 1:
            found.add("end")
        elif edge == 0:
            found.add("tie")
        elif edge <= 4 * du:
            found.add("near")
    for k in ("tie", "end", "near", "clipped"):
        if k in found:
            return k
    return "other"


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    scene_file, name, sg, ref = sys.argv[1:]
    doc = json.load(open(scene_file))
    scene = next(s for s in doc["scenes"] if s["name"] == name)
    clear = scene.get("clear_color", doc.get("clear_color", [0, 0, 0, 0]))
    bg = tuple(int(c * 255 + 0.5) for c in clear[:3])
    w, h, a = read_png(sg)
    _, _, b = read_png(ref)
    segs = segments(scene_file, scene, scene.get("width", doc.get("width")), scene.get("height", doc.get("height")))
    counts, others = {}, []
    for y in range(h):
        for x in range(w):
            fa, fb = a[y][x] != bg, b[y][x] != bg
            if fa == fb:
                continue
            key = (classify(segs, x, y), "sgapi only" if fa else "reference only")
            counts[key] = counts.get(key, 0) + 1
            if key[0] == "other" and len(others) < 10:
                others.append((x, y, key[1]))
    total = sum(counts.values())
    print(f"{name}: {total} pixels differ in coverage")
    for (kind, who), n in sorted(counts.items()):
        print(f"  {kind:8s} {who:15s} {n}")
    for x, y, who in others:
        print(f"  unexplained: pixel ({x}, {y}), {who}")
    return 1 if others else 0


if __name__ == "__main__":
    sys.exit(main())
