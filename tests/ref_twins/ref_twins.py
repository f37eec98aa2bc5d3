#!/usr/bin/env python3
"""Checks sgapi-ref's shader draws against its fixed ones: every unlit draw of the given scene files
becomes a shader draw of tests/ref_twins/ref_twins.c, which redoes the fixed shading in GLSL, and
each scene must render to the same PNG bytes. Scenes with a shadow keep their fixed draws (a shader
draw receives none), lit draws too.

    ref_twins.py SGAPI_REF LIB.so OUT_DIR SCENE.json...

Exits 0 when every scene is identical, 1 otherwise, 77 (skipped) when the scene loader does not
know shader draws.
"""
import json
import os
import subprocess
import sys


def absolute(base, value):
    if isinstance(value, str):
        return os.path.normpath(os.path.join(base, value))
    if isinstance(value, dict) and "heightmap" in value:
        value = dict(value)
        value["heightmap"] = absolute(base, value["heightmap"])
    return value


def rewrite(path):
    """The file with absolute paths, and its shader version: (fixed, twins, converted draws)."""
    with open(path) as f:
        doc = json.load(f)
    base = os.path.dirname(os.path.abspath(path))
    converted = 0
    fixed_scenes, twin_scenes = [], []
    for scene in doc.get("scenes", []):
        fixed = json.loads(json.dumps(scene))
        twin = json.loads(json.dumps(scene))
        for d in fixed["draws"] + twin["draws"]:
            d["mesh"] = absolute(base, d["mesh"])
            if d.get("texture"):
                d["texture"] = absolute(base, d["texture"])
        # Twins receive no shadow: scenes with one keep their fixed draws.
        if "shadow" not in scene and "shadow" not in doc:
            for d in twin["draws"]:
                if d.get("lighting", "none") != "none":
                    continue
                tex = d.pop("texture", None)
                mode = d.pop("mode", "texture" if tex else "vertex_color")
                d["uniforms"] = d.pop("color", [1, 1, 1, 1])
                if mode == "texture" and tex:
                    d["shader"] = "ref_texture"
                    d["textures"] = [tex]
                else:
                    d["shader"] = "ref_color"
                converted += 1
        fixed_scenes.append(fixed)
        twin_scenes.append(twin)
    fixed_doc, twin_doc = dict(doc), dict(doc)
    fixed_doc["scenes"], twin_doc["scenes"] = fixed_scenes, twin_scenes
    return fixed_doc, twin_doc, converted


def main():
    ref, lib, out = sys.argv[1], sys.argv[2], sys.argv[3]
    failures = total = 0
    for path in sys.argv[4:]:
        name = os.path.splitext(os.path.basename(path))[0]
        fixed, twin, converted = rewrite(path)
        dirs = {}
        for kind, doc in (("fixed", fixed), ("twin", twin)):
            d = os.path.join(out, name, kind)
            os.makedirs(d, exist_ok=True)
            scene = os.path.join(d, name + ".json")
            with open(scene, "w") as f:
                json.dump(doc, f)
            args = [ref, "--strict", "--shaders", lib, scene, "-o", d]
            run = subprocess.run(args, capture_output=True, text=True)
            if kind == "twin" and converted and "unknown key" in run.stderr and ".shader'" in run.stderr:
                print("ref_twins: skipped: the scene loader does not know shader draws")
                return 77
            if run.returncode != 0:
                print(f"ref_twins: {' '.join(args)} exited {run.returncode}:\n{run.stderr}")
                return 1
            dirs[kind] = d
        for scene in twin["scenes"]:
            total += 1
            png = scene["name"] + ".png"
            with open(os.path.join(dirs["fixed"], png), "rb") as a, open(
                os.path.join(dirs["twin"], png), "rb"
            ) as b:
                same = a.read() == b.read()
            if not same:
                failures += 1
                print(f"ref_twins: {name}: scene {scene['name']}: the twins' image differs")
        print(f"ref_twins: {name}: {converted} draws made shader draws")
    print(f"ref_twins: {total - failures} of {total} scenes identical")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
