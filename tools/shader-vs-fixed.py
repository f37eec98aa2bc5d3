#!/usr/bin/python3
"""shader-vs-fixed.py - what a shader pipeline costs against the fixed path on the same scenes.

Rewrites every draw of a scene file that a built-in shader expresses exactly into that shader's
draw: unlit vertex-coloured and textured draws into "unlit", Phong-lit untextured ones under a
single directional light into "phong", other Phong-lit ones (up to four lights, directional or
point, a texture) into "phong_lights" (the fixed equations as shaders, apps/shaders/unlit.c,
phong.c and phong_lights.c), and times each scene, fixed and rewritten, with sgapi-render in
turns. A draw no shader expresses (flat or Gouraud lighting, an unlit draw colour, more than four
lights, a shadow) stays fixed in the rewritten scene, and the table says how many of a scene's
draws are shaders; a scene with none is listed as skipped.

  tools/shader-vs-fixed.py [--build DIR] [--frames N] [--rounds R] [--threads T] SCENES.json...

Prints a markdown table (shader draws, fixed ms, shader ms, ratio) per scene and the geometric
mean of the ratios; the figures are medians of R rounds of N frames each.
"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import tempfile


def absolute(base, path):
    return path if os.path.isabs(path) else os.path.normpath(os.path.join(base, path))


def phong_uniforms(draw, scene, top):
    """phong's 17 uniforms (apps/shaders/phong.c) for a Phong-lit draw, or None where phong cannot
    express it: it takes one directional light and no texture."""
    lights = scene.get("lights", top.get("lights", []))
    if len(lights) != 1 or lights[0].get("type") != "directional":
        return None
    if draw.get("mode") == "texture" and draw.get("texture"):
        return None
    light = lights[0]
    u = list(draw.get("color", [1, 1, 1, 1]))
    u += list(scene.get("ambient", top.get("ambient", [0, 0, 0])))
    u += list(light["direction"]) + list(light.get("color", [1, 1, 1]))
    u += list(draw.get("specular", [0, 0, 0])) + [draw.get("shininess", 0)]
    return u


def phong_lights_uniforms(draw, scene, top):
    """phong_lights' 53 uniforms (apps/shaders/phong_lights.c) for a Phong-lit draw, or None where
    it cannot express it: more than four lights."""
    lights = scene.get("lights", top.get("lights", []))
    if len(lights) > 4:
        return None
    textured = draw.get("mode") == "texture" and draw.get("texture")
    u = list(draw.get("color", [1, 1, 1, 1])) + [1 if textured else 0]
    u += list(scene.get("ambient", top.get("ambient", [0, 0, 0])))
    u += list(draw.get("specular", [0, 0, 0])) + [draw.get("shininess", 0), len(lights)]
    for light in lights:
        if light.get("type") == "point":
            att = list(light.get("attenuation", [1, 0, 0]))
            if att == [0, 0, 0]:  # read as [1, 0, 0], as sgapi does
                att = [1, 0, 0]
            u += [1] + list(light["position"]) + list(light.get("color", [1, 1, 1])) + att
        else:
            u += [0] + list(light["direction"]) + list(light.get("color", [1, 1, 1])) + [1, 0, 0]
    return u + [0] * (53 - len(u))


def rewrite(draw, scene, top):
    """The shader draw that draws `draw` as the fixed path does, or None."""
    if "shader" in draw:  # a shader draw already: nothing fixed to compare with
        return None
    if draw.get("receives_shadow") is True or draw.get("casts_shadow") is True:
        return None
    if "shadow" in scene or "shadow" in top:
        return None
    lighting = draw.get("lighting", "none")
    out = {k: v for k, v in draw.items()
           if k not in ("mode", "texture", "lighting", "color", "specular", "shininess")}
    textured = draw.get("mode") == "texture" and draw.get("texture")
    if textured:
        out["textures"] = [draw["texture"]]
    if lighting == "none":
        if draw.get("color", [1, 1, 1, 1]) != [1, 1, 1, 1]:
            return None
        out["shader"] = "unlit"
        out["uniforms"] = [1 if textured else 0]
        return out
    if lighting == "phong":
        u = phong_uniforms(draw, scene, top)
        if u is not None:
            out["shader"] = "phong"
            out["uniforms"] = u
            return out
        u = phong_lights_uniforms(draw, scene, top)
        if u is None:
            return None
        out["shader"] = "phong_lights"
        out["uniforms"] = u
        return out
    return None


def convert(path, workdir):
    """Two files: the scene file with absolute paths (fixed), and its rewritten scenes."""
    with open(path) as f:
        top = json.load(f)
    base = os.path.dirname(os.path.abspath(path))
    fixed, shader, skipped, shares = [], [], [], {}
    for scene in top["scenes"]:
        for d in scene["draws"]:
            for key in ("mesh", "texture"):
                if isinstance(d.get(key), str):
                    d[key] = absolute(base, d[key])
            if isinstance(d.get("textures"), list):
                d["textures"] = [absolute(base, t) if isinstance(t, str) else t
                                 for t in d["textures"]]
            if isinstance(d.get("mesh"), dict):  # a generated mesh may name a file (heightmap)
                for k, v in d["mesh"].items():
                    if isinstance(v, str) and os.path.exists(os.path.join(base, v)):
                        d["mesh"][k] = absolute(base, v)
        drawn = [rewrite(d, scene, top) for d in scene["draws"]]
        rewritten = sum(d is not None for d in drawn)
        if not rewritten:
            skipped.append(scene["name"])
            continue
        fixed.append(scene)
        shader.append(dict(scene, draws=[r or d for r, d in zip(drawn, scene["draws"])]))
        shares[scene["name"]] = "%d of %d" % (rewritten, len(drawn))
    stem = os.path.splitext(os.path.basename(path))[0]
    out = []
    for kind, scenes in (("fixed", fixed), ("shader", shader)):
        name = os.path.join(workdir, "%s-%s.json" % (stem, kind))
        with open(name, "w") as f:
            json.dump(dict(top, scenes=scenes), f)
        out.append(name)
    return out[0], out[1], shares, skipped


def times(render, file, frames, threads, outdir):
    run = subprocess.run([render, file, "--frames", str(frames), "--threads", str(threads),
                          "--no-write", "--quiet", "-o", outdir],
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit("shader-vs-fixed: %s failed:\n%s" % (file, run.stderr))
    found = {}
    for line in run.stdout.splitlines():
        m = re.match(r"(\S+)\s+([0-9.]+) ms/frame", line)
        if m:
            found[m.group(1)] = float(m.group(2))
    return found


def median(values):
    v = sorted(values)
    return v[len(v) // 2] if len(v) % 2 else (v[len(v) // 2 - 1] + v[len(v) // 2]) / 2


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default="build")
    ap.add_argument("--frames", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    render = os.path.join(a.build, "apps", "sgapi-render")
    with tempfile.TemporaryDirectory() as work:
        print("| scene | shader draws | fixed ms | shader ms | shader / fixed |")
        print("| --- | ---: | ---: | ---: | ---: |")
        ratios, skipped_all = [], []
        for path in a.files:
            fixed, shader, shares, skipped = convert(path, work)
            names = list(shares)
            skipped_all += skipped
            if not names:
                continue
            got = {"fixed": {n: [] for n in names}, "shader": {n: [] for n in names}}
            for _ in range(a.rounds):
                for kind, file in (("fixed", fixed), ("shader", shader)):
                    t = times(render, file, a.frames, a.threads, os.path.join(work, "out"))
                    for n in names:
                        got[kind][n].append(t[n])
            for n in names:
                f, s = median(got["fixed"][n]), median(got["shader"][n])
                ratios.append(s / f)
                print("| %s | %s | %.3f | %.3f | %.2f |" % (n, shares[n], f, s, s / f))
        if ratios:
            gm = math.exp(sum(math.log(r) for r in ratios) / len(ratios))
            print("\ngeometric mean of shader / fixed over %d scenes: %.2f (worst %.2f), %d "
                  "threads" % (len(ratios), gm, max(ratios), a.threads))
        if skipped_all:
            print("skipped (no draw a built-in shader expresses): " + ", ".join(skipped_all))


if __name__ == "__main__":
    main()
