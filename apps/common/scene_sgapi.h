/* scene_sgapi.h - the sgapi side of scene files, shared by the apps that draw them with sgapi:
 * a draw's pipeline state, a cache of pipelines, the upload of a file's meshes and textures, and
 * the timing helpers of their measurements. */
#ifndef SC_SCENE_SGAPI_H
#define SC_SCENE_SGAPI_H

#include <stdbool.h>
#include <stddef.h>

#include <sgapi/sgapi.h>

#include "scene.h"

/** The pipeline state of a draw. A texture draw without a texture uses its vertex colours. */
sgPipelineDesc ss_pipeline_desc(const sc_draw *draw);

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

/* What one file's meshes and textures became on a device. */
typedef struct ss_uploads {
    sgGeom *geoms;
    sgImage2D *images;
    size_t geom_count, image_count;
} ss_uploads;

/** Creates a geom per mesh (referencing the file's arrays) and an image per texture. */
bool ss_upload(const char *prog, sgDevice *dev, const sc_file *file, ss_uploads *out);
/** Destroys what ss_upload created. */
void ss_destroy_uploads(sgDevice *dev, ss_uploads *u);

/** Creates a scene's colour (RGBA8) and depth (D32) targets and the pass that clears them (to
 *  the scene's clear colour and depth 1.0). */
bool ss_create_targets(const char *prog, sgDevice *dev, const sc_scene *scene, sgImage2D *color,
                       sgImage2D *depth, sgPassDesc *pass);
/** One frame: sgBeginRenderPass, every draw of the scene with psos[i], sgEndRenderPass. */
bool ss_draw_frame(const char *prog, sgDevice *dev, const sc_file *file, const sc_scene *scene,
                   const ss_uploads *u, const sgPipelineStateObject *psos, const sgPassDesc *pass);

/** Prints "prog: <message>: <result name>: <device's last error>" to stderr; returns false. */
bool ss_fail(const char *prog, sgDevice *dev, sgResult r, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/** A monotonic clock in milliseconds. */
double ss_now_ms(void);
/** The median of n values (sorts them); the mean of the middle two when n is even. */
double ss_median(double *values, int n);

#endif
