#!/bin/sh
# Writes a scene file of small scenes for the turntable tests to $1 (a file), with the meshes and
# textures of $2/scenes/assets: a Phong-lit cube over a floor with a shadow, a point light and a
# directional light; a textured cube of odd size; and a scene without draws.
#   tiny_scenes.sh OUT.json SOURCE_DIR
set -eu
a=$2/scenes/assets
proj='[2.414214, 0, 0, 0,  0, 2.414214, 0, 0,  0, 0, -1.002002, -0.2002,  0, 0, -1, 0]'
cat >"$1" <<EOF
{
  "width": 48, "height": 36, "clear_color": [0.1, 0.1, 0.2, 1],
  "scenes": [
    {
      "name": "lit_shadow", "ambient": [0.2, 0.2, 0.2],
      "lights": [
        {"type": "directional", "direction": [1, -1, -0.5], "color": [0.9, 0.9, 0.8]},
        {"type": "point", "position": [0.5, 1, -2], "color": [0.4, 0.4, 0.5]}
      ],
      "shadow": {"light": 0, "size": 128},
      "draws": [
        {"mesh": "$a/plane.obj", "lighting": "phong", "color": [0.9, 0.9, 0.85, 1],
         "worldView": [2.5, 0, 0, 0,  0, 2.301541, -0.976171, -0.294597,
                       0, 0.976171, 2.301541, -3.275013,  0, 0, 0, 1], "proj": $proj},
        {"mesh": "$a/cube_rgb.obj", "lighting": "phong", "specular": [0.5, 0.5, 0.5],
         "shininess": 20,
         "worldView": [0.3, 0, 0.1, 0.2,  0, 0.3, 0, 0.02,  -0.1, 0, 0.3, -3.2,  0, 0, 0, 1],
         "proj": $proj}
      ]
    },
    {
      "name": "textured", "width": 33, "height": 25,
      "draws": [
        {"mesh": "$a/cube_wide_uv.obj", "mode": "texture", "texture": "$a/mosaic.png",
         "cull": "back",
         "worldView": [0.5, 0, 0.3, 0,  0.1, 0.55, -0.1, 0,  -0.3, 0.1, 0.5, -3,  0, 0, 0, 1],
         "proj": $proj}
      ]
    },
    {"name": "empty", "draws": []}
  ]
}
EOF
