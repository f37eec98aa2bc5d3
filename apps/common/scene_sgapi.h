/* scene_sgapi.h - the sgapi side of scene files, shared by the apps that draw them with sgapi:
 * a draw's pipeline state, a cache of pipelines, the upload of a file's meshes and textures, and
 * the timing helpers of their measurements. */
#ifndef SC_SCENE_SGAPI_H
#define SC_SCENE_SGAPI_H

#include <stdbool.h>
#include <stddef.h>

#include <sgapi/sgapi.h>

#include "scene.h"
#include "shader_lib.h"

/** The pipeline state of a draw into *out. A texture draw without a texture uses its vertex
 *  colours; a shader draw takes its shader's stages from shaders (filter and wrap for its
 *  textures), and false, with a message naming prog, file and shader, when shaders does not know
 *  it (sc_shaders_check refuses such a file before). */
bool ss_pipeline_desc(const char *prog, const sc_file *file, const sc_draw *draw,
                      const sc_shaders *shaders, sgPipelineDesc *out);

/* Pipelines created on first use of a state and reused for every draw with it. */
typedef struct ss_pso_cache {
    sgPipelineDesc *descs;
    sgPipelineStateObject *psos;
    size_t count, cap;
} ss_pso_cache;

/** The pipeline for a state (creating it the first time); false and a message on failure. */
bool ss_get_pso(const char *prog, sgDevice *dev, ss_pso_cache *cache, const sgPipelineDesc *desc,
                sgPipelineStateObject *out);
/** Frees the cache's arrays (the pipelines go with their device). */
void ss_pso_cache_free(ss_pso_cache *cache);
/** A pipeline pool size (sgDeviceDesc.pipeline_pool_size) that holds every pipeline the files'
 *  draws and shadows can need, times `settings` variants of each, within sgapi's limit. */
int ss_pipeline_pool_size(const sc_file *files, int file_count, int settings);

/* What one file's meshes and textures became on a device. A mesh's triangles and its lines are
 * two geoms over the same vertex arrays; a geom whose id is 0 does not exist (no such primitives).
 */
typedef struct ss_uploads {
    sgGeom *geoms;      /* per mesh: its triangles (SG_PRIMITIVE_TRIANGLES) */
    sgGeom *line_geoms; /* per mesh: its lines (SG_PRIMITIVE_LINES) */
    sgImage2D *images;
    size_t geom_count, image_count; /* meshes and textures uploaded so far */
    /* Per mesh: its tangents (sgu_compute_tangents, 4 floats a vertex), the geoms' attribute 0,
     * when a shader draw uses the mesh and it has normals and texture coordinates; else NULL. */
    float **tangents;
    size_t mesh_count; /* entries of tangents */
} ss_uploads;

/** Creates the geoms of every mesh (referencing the file's arrays) and an image per texture; a
 *  mesh that a shader draw uses gets its tangents as attribute 0 when it has normals and texture
 *  coordinates. */
bool ss_upload(const char *prog, sgDevice *dev, const sc_file *file, ss_uploads *out);
/** How many geoms ss_upload creates for a file: one per mesh with triangles, one per mesh with
 *  lines. */
size_t ss_geom_count(const sc_file *file);
/** Destroys what ss_upload created. */
void ss_destroy_uploads(sgDevice *dev, ss_uploads *u);

/** Creates a scene's colour (RGBA8) and depth (D32) targets and the pass that clears them (to
 *  the scene's clear colour and depth 1.0). */
bool ss_create_targets(const char *prog, sgDevice *dev, const sc_scene *scene, sgImage2D *color,
                       sgImage2D *depth, sgPassDesc *pass);
/* A scene's shadow on a device: the map and its depth-only pass, the casters' pipelines and
 * world-views into it, and what the receivers get. All zero for a scene without a shadow. */
typedef struct ss_shadow {
    sgImage2D map;               /* D32, size x size */
    sgPassDesc pass;             /* depth only: clears the map to 1.0 */
    sgPipelineStateObject *psos; /* per draw of the scene; set for casters */
    float (*world_view)[16];     /* per draw: the light's view x the draw's worldView */
    float proj[16];              /* the light's projection */
    sgShadow receiver;           /* given to every draw that receives the shadow */
} ss_shadow;

/** Creates what a scene's shadow needs (nothing when the scene has none), once, with its
 *  targets: the map, the casters' pipelines (from the cache) and their matrices. */
bool ss_create_shadow(const char *prog, sgDevice *dev, ss_pso_cache *cache, const sc_file *file,
                      const sc_scene *scene, ss_shadow *out);
/** Fits an existing shadow (of ss_create_shadow) to the scene's casters again, after they or the
 *  light moved (a turntable frame): the casters' world-views and the receivers' matrix. */
bool ss_fit_shadow(const char *prog, const sc_file *file, const sc_scene *scene, ss_shadow *shadow);
/** Destroys the map and frees what ss_create_shadow made; a zeroed one is fine. */
void ss_destroy_shadow(sgDevice *dev, ss_shadow *shadow);

/** One frame: the shadow's depth-only pass when the scene has one (every caster into the map),
 *  then sgBeginRenderPass, every draw of the scene with psos[i] (receivers with the shadow; shader
 *  draws with their uniforms, textures and instance count), sgEndRenderPass. A draw is its mesh's
 * triangles, then its lines, both with its pipeline (lines are lines whatever the polygon mode).
 * shadow may be NULL for a scene without one. */
bool ss_draw_frame(const char *prog, sgDevice *dev, const sc_file *file, const sc_scene *scene,
                   const ss_uploads *u, const sgPipelineStateObject *psos, const sgPassDesc *pass,
                   const ss_shadow *shadow);

/** Prints "prog: <message>: <result name>: <device's last error>" to stderr; returns false. */
bool ss_fail(const char *prog, sgDevice *dev, sgResult r, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/** A monotonic clock in milliseconds. */
double ss_now_ms(void);
/** The median of n values (sorts them); the mean of the middle two when n is even. */
double ss_median(double *values, int n);

#endif
