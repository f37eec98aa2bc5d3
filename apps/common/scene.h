/* scene.h - scene files: lists of draws (mesh, texture, state, matrices) per named scene, with the
 * meshes and textures they use loaded once per file. The format is described in
 * docs/scene-format.md.
 *
 * API-neutral: the state is described by this file's own enums, which each renderer maps to its
 * API.
 */
#ifndef SC_SCENE_H
#define SC_SCENE_H

#include <stdbool.h>
#include <stddef.h>

#include "image_io.h"
#include "obj.h"

/* Largest scene, texture and heightmap side accepted. */
#define SC_MAX_IMAGE_SIZE 16384
/* Longest scene name: it becomes a file name, with an extension added. */
#define SC_MAX_NAME_LENGTH 200

/* In every enum, the first value (0) is the format's default. */
typedef enum sc_mode {
    SC_MODE_VERTEX_COLOR, /* fragment = interpolated vertex colour */
    SC_MODE_TEXTURE,      /* fragment = vertex colour * texel (vertex colour if texture is -1) */
} sc_mode;

typedef enum sc_filter { SC_FILTER_BILINEAR, SC_FILTER_NEAREST } sc_filter;
typedef enum sc_wrap { SC_WRAP_REPEAT, SC_WRAP_CLAMP } sc_wrap;
/* "mipmap": how a textured draw picks among its texture's mipmap levels (docs/scene-format.md). */
typedef enum sc_mipmap { SC_MIPMAP_NONE, SC_MIPMAP_NEAREST, SC_MIPMAP_LINEAR } sc_mipmap;
typedef enum sc_cull { SC_CULL_NONE, SC_CULL_BACK, SC_CULL_FRONT } sc_cull;
typedef enum sc_front_face { SC_FRONT_FACE_CCW, SC_FRONT_FACE_CW } sc_front_face;

typedef enum sc_compare {
    SC_COMPARE_LESS,
    SC_COMPARE_NEVER,
    SC_COMPARE_EQUAL,
    SC_COMPARE_LESS_EQUAL,
    SC_COMPARE_GREATER,
    SC_COMPARE_NOT_EQUAL,
    SC_COMPARE_GREATER_EQUAL,
    SC_COMPARE_ALWAYS,
} sc_compare;

typedef enum sc_blend {
    SC_BLEND_OPAQUE, /* the fragment replaces the pixel */
    SC_BLEND_ALPHA,  /* src * src_alpha + dst * (1 - src_alpha), alpha channel included */
} sc_blend;

typedef enum sc_sort {
    SC_SORT_NONE,          /* triangles in index order */
    SC_SORT_BACK_TO_FRONT, /* by view-space centroid z, farthest first (docs/scene-format.md) */
} sc_sort;

typedef enum sc_lighting {
    SC_LIGHTING_NONE,    /* the colour is not lit */
    SC_LIGHTING_FLAT,    /* once per triangle, at its view-space centroid, with its face normal */
    SC_LIGHTING_GOURAUD, /* per vertex, colours interpolated */
    SC_LIGHTING_PHONG,   /* per pixel, normal and view position interpolated */
} sc_lighting;

typedef enum sc_polygon_mode {
    SC_POLYGON_MODE_FILL, /* triangles are filled */
    SC_POLYGON_MODE_LINE, /* wireframe: each triangle's three edges (after culling), as lines */
} sc_polygon_mode;

/* Most lights of a scene (sgapi's SG_MAX_LIGHTS). */
#define SC_MAX_LIGHTS 8

typedef enum sc_light_type {
    SC_LIGHT_DIRECTIONAL, /* from infinitely far, along `direction` */
    SC_LIGHT_POINT,       /* from `position`, attenuated with distance */
} sc_light_type;

/* One light, in view space (the eye at the origin, looking down -z). */
typedef struct sc_light {
    sc_light_type type;
    float direction[3];   /* DIRECTIONAL: the way the light travels; not (0, 0, 0) */
    float position[3];    /* POINT */
    float color[3];       /* r, g, b, each finite and >= 0 */
    float attenuation[3]; /* POINT: constant, linear, quadratic, each finite and >= 0, not all 0;
                             default 1, 0, 0 */
} sc_light;

/* Defaults of a scene's "shadow" (docs/scene-format.md, "Shadows"), kept here alone so that tuning
 * them is one change. The biases are in window-depth units of the shadow map. */
#define SC_SHADOW_SIZE       2048
#define SC_SHADOW_BIAS       0.0015f
#define SC_SHADOW_SLOPE_BIAS 2.0f
#define SC_SHADOW_PCF        true

/* The shadow one light of a scene casts: the depth of the casters seen from the light, rendered
 * into a size x size map before the scene's draws, then looked up by the receivers. */
typedef struct sc_shadow {
    int light;        /* index into sc_scene.lights, < light_count */
    int size;         /* side of the square map, 1 .. SC_MAX_IMAGE_SIZE */
    float bias;       /* constant depth bias of the casters, finite */
    float slope_bias; /* times max(|dz/dx|, |dz/dy|) of each caster triangle, finite */
    bool pcf;         /* 2 x 2 percentage-closer filtering, else the one texel under the point */
} sc_shadow;

/* Longest shader name. */
#define SC_MAX_SHADER_NAME 64

/* Most textures a shader draw binds (sgapi's SG_MAX_DRAW_TEXTURES). */
#define SC_MAX_DRAW_TEXTURES 8
/* Most uniforms a shader draw gives: sgapi's SG_MAX_UNIFORM_SIZE bytes of floats. */
#define SC_MAX_UNIFORMS (65536 / 4)

/* One draw call: the mesh's triangles, then its lines, with the same state. */
typedef struct sc_draw {
    int mesh;    /* index into sc_file.meshes */
    int texture; /* index into sc_file.textures, or -1 when the draw names none (null) */
    sc_mode mode;
    sc_filter filter;
    sc_wrap wrap;
    sc_mipmap mipmap; /* the textures it samples get their full chain of levels when not NONE */
    sc_cull cull;
    sc_front_face front_face;
    sc_compare depth_compare;
    bool depth_write;
    sc_blend blend;
    float color[4]; /* r, g, b, a in [0, 1], times every vertex colour; default 1, 1, 1, 1 */
    sc_sort sort;
    sc_lighting lighting;
    float specular[3];    /* r, g, b of the specular material, each finite and >= 0; default 0 */
    float shininess;      /* specular exponent, 0 .. 128; default 0 */
    bool casts_shadow;    /* drawn into the scene's shadow map; default true */
    bool receives_shadow; /* darkened where the scene's shadow falls; default true (never true
                             with a shadow and flat or Gouraud lighting: the loader refuses it) */
    sc_polygon_mode polygon_mode; /* how the mesh's triangles are drawn; its lines are lines */
    float world_view[16];         /* row-major: elements 0..3 are the first row */
    float proj[16];               /* row-major; clip = proj * world_view * position */
    /* Programmable stages (docs/scene-format.md, "Shaders"): "shader" names a shader, built in or
     * from a library given to the app (--shaders); the app resolves the name and checks
     * uniform_count against it. NULL: the fixed shading above. */
    char *shader;
    float *uniforms; /* "uniforms": uniform_count floats (NULL when 0) */
    int uniform_count;
    int shader_textures[SC_MAX_DRAW_TEXTURES]; /* "textures": indices into sc_file.textures */
    int shader_texture_count;
    int instances; /* "instances": the mesh drawn this many times, >= 1; default 1 */
} sc_draw;

/* One image to render. */
typedef struct sc_scene {
    char *name;           /* [A-Za-z0-9_.-]+, unique in the file */
    int width, height;    /* 1 .. SC_MAX_IMAGE_SIZE */
    float clear_color[4]; /* r, g, b, a in [0, 1] */
    int samples;          /* "samples": 1 or 4 a pixel (sgPassDesc.samples); default 1 */
    sc_draw *draws;       /* in order; may be empty (the image is only cleared) */
    size_t draw_count;
    float ambient[3]; /* r, g, b of the scene's ambient light, each finite and >= 0; default 0 */
    int light_count;  /* 0 .. SC_MAX_LIGHTS */
    sc_light lights[SC_MAX_LIGHTS];
    bool has_shadow;  /* the scene has a shadow and at least one draw casts it */
    sc_shadow shadow; /* when has_shadow */
} sc_scene;

/* A loaded scene file: the scenes and everything their draws refer to. */
typedef struct sc_file {
    char *path; /* as given to sc_load / sc_parse */
    sc_scene *scenes;
    size_t scene_count;
    sc_mesh *meshes;
    char **mesh_sources; /* per mesh, where it came from (for messages): a path or heightmap spec */
    size_t mesh_count;
    sc_image *textures;     /* RGBA8, top row first */
    char **texture_sources; /* per texture, its path */
    size_t texture_count;
    /* One message per unknown key ("FILE: unknown key 'scenes[2].draws[0].lightning' (did you
     * mean 'lighting'?)"): the file loads, the key is ignored; apps print them, and --strict makes
     * them errors (sc_report_warnings in scene_keys.h). */
    char **warnings;
    size_t warning_count;
} sc_file;

/** Whether s is a shader's name: 1 to SC_MAX_SHADER_NAME of A-Z a-z 0-9 _. */
bool sc_shader_name_valid(const char *s);
/** Loads a scene file and every mesh and texture it names; on failure *out is zeroed. Every
 *  mesh has normals: a mesh without them gets smooth ones (sgu_compute_normals). */
bool sc_load(const char *path, sc_file *out, sc_msg *err);
/** Sets every scene's samples a pixel (a --samples override: 1 or 4). */
void sc_set_samples(sc_file *file, int samples);
/** Parses a --samples value (1 or 4); false: anything else. */
bool sc_parse_samples(const char *s, int *out);
/** Parses scene JSON text; path names it in messages and relative paths start at its folder. */
bool sc_parse(const char *path, const char *json, size_t len, sc_file *out, sc_msg *err);
/** Frees what one draw holds on the heap (its shader name and uniforms), leaving those fields
 *  zeroed; for a program that removes a draw from a scene. */
void sc_draw_free(sc_draw *d);
/** Frees everything a loaded file holds and zeroes it; a zeroed file is fine. */
void sc_free(sc_file *file);

/** Builds the heightmap grid mesh of an image (see docs/scene-format.md); needs 2x2 pixels. */
bool sc_heightmap_mesh(const sc_image *image, float height_scale, sc_mesh *out, sc_msg *err);

/** The mode a "mipmap" value or a --mipmap argument names ("none", "nearest", "linear"); false
 *  when it names none. */
bool sc_mipmap_from_name(const char *name, sc_mipmap *out);
/** Whether a draw of the file samples texture `texture` (an index into textures) with mipmaps:
 *  it then gets its full chain of levels. */
bool sc_texture_mipmapped(const sc_file *f, size_t texture);
/** Sets every draw's "mipmap" to mode (the apps' --mipmap overrides every scene). */
void sc_override_mipmap(sc_file *f, sc_mipmap mode);

#endif
