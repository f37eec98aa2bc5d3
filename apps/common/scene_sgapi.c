/* scene_sgapi.c - drawing scene files with sgapi: pipeline state, pipeline cache, uploads. */
#define _POSIX_C_SOURCE 200809L
#include "scene_sgapi.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <sgapi/sgapi_util.h>

#include "shadow.h"

static const sgCompare compare_map[] = {
    [SC_COMPARE_LESS] = SG_COMPARE_LESS,
    [SC_COMPARE_NEVER] = SG_COMPARE_NEVER,
    [SC_COMPARE_EQUAL] = SG_COMPARE_EQUAL,
    [SC_COMPARE_LESS_EQUAL] = SG_COMPARE_LESS_EQUAL,
    [SC_COMPARE_GREATER] = SG_COMPARE_GREATER,
    [SC_COMPARE_NOT_EQUAL] = SG_COMPARE_NOT_EQUAL,
    [SC_COMPARE_GREATER_EQUAL] = SG_COMPARE_GREATER_EQUAL,
    [SC_COMPARE_ALWAYS] = SG_COMPARE_ALWAYS,
};

static const sgLightingMode lighting_map[] = {
    [SC_LIGHTING_NONE] = SG_LIGHTING_NONE,
    [SC_LIGHTING_FLAT] = SG_LIGHTING_FLAT,
    [SC_LIGHTING_GOURAUD] = SG_LIGHTING_GOURAUD,
    [SC_LIGHTING_PHONG] = SG_LIGHTING_PHONG,
};

static const sgMipmap mipmap_map[] = {
    [SC_MIPMAP_NONE] = SG_MIPMAP_NONE,
    [SC_MIPMAP_NEAREST] = SG_MIPMAP_NEAREST,
    [SC_MIPMAP_LINEAR] = SG_MIPMAP_LINEAR,
};

bool ss_pipeline_desc(const char *prog, const sc_file *f, const sc_draw *d,
                      const sc_shaders *shaders, sgPipelineDesc *out) {
    sgPipelineDesc p;
    memset(&p, 0, sizeof p);
    if (d->shader) {
        /* The shader replaces shade and lighting (left at their defaults) and samples the draw's
         * textures with its filter and wrap; the loader refuses a texture or lighting with it. */
        const sgShaderInfo *info = sc_shaders_find(shaders, d->shader);
        if (!info) {
            fprintf(stderr, "%s: %s: unknown shader '%s'\n", prog, f ? f->path : "?", d->shader);
            return false;
        }
        p.shader = info->desc;
        p.filter = d->filter == SC_FILTER_NEAREST ? SG_FILTER_NEAREST : SG_FILTER_BILINEAR;
        p.wrap = d->wrap == SC_WRAP_CLAMP ? SG_WRAP_CLAMP_TO_EDGE : SG_WRAP_REPEAT;
        p.mipmap = mipmap_map[d->mipmap];
    } else {
        /* A texture draw without a texture is drawn with its vertex colours: the OpenGL
         * reference binds an incomplete texture there, which disables texturing. */
        bool textured = d->mode == SC_MODE_TEXTURE && d->texture >= 0;
        p.shade = textured ? SG_SHADE_TEXTURE_MODULATE : SG_SHADE_VERTEX_COLOR;
        /* Filter and wrap only matter when a texture is sampled; left at their defaults
         * otherwise, so that more draws share one pipeline. */
        if (textured) {
            p.filter = d->filter == SC_FILTER_NEAREST ? SG_FILTER_NEAREST : SG_FILTER_BILINEAR;
            p.wrap = d->wrap == SC_WRAP_CLAMP ? SG_WRAP_CLAMP_TO_EDGE : SG_WRAP_REPEAT;
            p.mipmap = mipmap_map[d->mipmap];
        }
        p.lighting = lighting_map[d->lighting];
    }
    p.depth.compare = compare_map[d->depth_compare];
    p.depth.write = d->depth_write;
    p.cull = d->cull == SC_CULL_BACK    ? SG_CULL_BACK
             : d->cull == SC_CULL_FRONT ? SG_CULL_FRONT
                                        : SG_CULL_NONE;
    p.front_face = d->front_face == SC_FRONT_FACE_CW ? SG_FRONT_FACE_CW : SG_FRONT_FACE_CCW;
    p.blend = d->blend == SC_BLEND_ALPHA ? SG_BLEND_ALPHA : SG_BLEND_OPAQUE;
    p.polygon_mode =
        d->polygon_mode == SC_POLYGON_MODE_LINE ? SG_POLYGON_MODE_LINE : SG_POLYGON_MODE_FILL;
    *out = p;
    return true;
}

/* The scene's ambient and lights as sgapi takes them. */
static void scene_lighting(const sc_scene *s, sgLighting *out) {
    memset(out, 0, sizeof *out);
    memcpy(out->ambient, s->ambient, sizeof out->ambient);
    out->light_count = s->light_count;
    for (int i = 0; i < s->light_count; i++) {
        const sc_light *l = &s->lights[i];
        sgLight *o = &out->lights[i];
        o->type = l->type == SC_LIGHT_POINT ? SG_LIGHT_POINT : SG_LIGHT_DIRECTIONAL;
        memcpy(o->direction, l->direction, sizeof o->direction);
        memcpy(o->position, l->position, sizeof o->position);
        memcpy(o->color, l->color, sizeof o->color);
        memcpy(o->attenuation, l->attenuation, sizeof o->attenuation);
    }
}

static bool same_shader(const sgShaderDesc *a, const sgShaderDesc *b) {
    return a->vertex == b->vertex && a->fragment == b->fragment &&
           a->varying_count == b->varying_count && a->flat_varyings == b->flat_varyings &&
           a->texture_count == b->texture_count;
}

static bool same_desc(const sgPipelineDesc *a, const sgPipelineDesc *b) {
    return same_shader(&a->shader, &b->shader) && a->shade == b->shade && a->filter == b->filter &&
           a->wrap == b->wrap && a->depth.compare == b->depth.compare &&
           a->depth.write == b->depth.write && a->depth.bias_constant == b->depth.bias_constant &&
           a->depth.bias_slope == b->depth.bias_slope && a->cull == b->cull &&
           a->front_face == b->front_face && a->blend == b->blend && a->lighting == b->lighting &&
           a->polygon_mode == b->polygon_mode && a->mipmap == b->mipmap;
}

bool ss_get_pso(const char *prog, sgDevice *dev, ss_pso_cache *c, const sgPipelineDesc *desc,
                sgPipelineStateObject *out) {
    for (size_t i = 0; i < c->count; i++) {
        if (same_desc(&c->descs[i], desc)) {
            *out = c->psos[i];
            return true;
        }
    }
    if (c->count == c->cap) {
        size_t n = c->cap ? c->cap * 2 : 16;
        sgPipelineDesc *d = realloc(c->descs, n * sizeof *d);
        if (d) c->descs = d;
        sgPipelineStateObject *p = d ? realloc(c->psos, n * sizeof *p) : NULL;
        if (p) c->psos = p;
        if (!d || !p) {
            fprintf(stderr, "%s: out of memory\n", prog);
            return false;
        }
        c->cap = n;
    }
    sgResult r = sgCreatePipelineStateObject(dev, desc, out);
    if (r != SG_OK) return ss_fail(prog, dev, r, "sgCreatePipelineStateObject");
    c->descs[c->count] = *desc;
    c->psos[c->count++] = *out;
    return true;
}

void ss_pso_cache_free(ss_pso_cache *c) {
    free(c->descs);
    free(c->psos);
    memset(c, 0, sizeof *c);
}

int ss_pipeline_pool_size(const sc_file *files, int file_count, int settings) {
    /* ss_pipeline_desc has 13 colour sources (vertex colour; texture x 2 filters x 2 wraps x 3
     * mipmap modes) x
     * 8 compares x 2 depth writes x 3 culls x 2 front faces x 2 blends x 4 lighting modes x
     * 2 polygon modes; a file may use fewer states than it has draws. A shadow's casters take at
     * most 3 culls x 2 front faces x 2 polygon modes with the scene's depth bias. */
    uint64_t draws = 0, casters = 0, shader_draws = 0;
    for (int i = 0; i < file_count; i++) {
        for (size_t j = 0; j < files[i].scene_count; j++) {
            const sc_scene *s = &files[i].scenes[j];
            /* A shader draw's state has a shader besides: counted apart, one each. */
            for (size_t k = 0; k < s->draw_count; k++) {
                if (s->draws[k].shader)
                    shader_draws++;
                else
                    draws++;
            }
            if (s->has_shadow) casters += s->draw_count < 12 ? s->draw_count : 12;
        }
    }
    const uint64_t states = 13 * 8 * 2 * 3 * 2 * 2 * 4 * 2, limit = 65535;
    uint64_t n = (draws < states ? draws : states) * (uint64_t)(settings > 0 ? settings : 1);
    n += casters + shader_draws * (uint64_t)(settings > 0 ? settings : 1);
    return n < 64 ? 64 : n > limit ? (int)limit : (int)n;
}

void ss_destroy_uploads(sgDevice *dev, ss_uploads *u) {
    for (size_t i = 0; i < u->geom_count; i++) {
        if (u->geoms[i].id) sgDestroyGeom(dev, u->geoms[i]);
        if (u->line_geoms[i].id) sgDestroyGeom(dev, u->line_geoms[i]);
    }
    for (size_t i = 0; i < u->image_count; i++) sgDestroyImage2D(dev, u->images[i]);
    if (u->tangents)
        for (size_t i = 0; i < u->mesh_count; i++) free(u->tangents[i]);
    free(u->tangents);
    free(u->geoms);
    free(u->line_geoms);
    free(u->images);
    memset(u, 0, sizeof *u);
}

size_t ss_geom_count(const sc_file *f) {
    size_t n = 0;
    for (size_t i = 0; i < f->mesh_count; i++)
        n += (f->meshes[i].index_count > 0) + (f->meshes[i].line_index_count > 0);
    return n;
}

/* One geom of a mesh: its triangles or its lines, over the mesh's vertex arrays. */
static bool upload_geom(const char *prog, sgDevice *dev, const sc_file *f, const ss_uploads *u,
                        size_t mesh, bool lines, sgGeom *out) {
    const sc_mesh *m = &f->meshes[mesh];
    /* The loader caps every count at INT32_MAX, so they fit. The loaded file outlives the geom,
     * so the arrays need not be copied. */
    sgGeomDesc desc = {
        .vertex_count = (int)m->vertex_count,
        .positions = m->positions,
        .colors = m->colors,
        .texcoords = m->texcoords,
        .normals = m->normals,
        .attributes = {u->tangents[mesh]},
        .index_count = (int)(lines ? m->line_index_count : m->index_count),
        .indices = lines ? m->line_indices : m->indices,
        .primitive = lines ? SG_PRIMITIVE_LINES : SG_PRIMITIVE_TRIANGLES,
        .storage = SG_STORAGE_REFERENCE,
    };
    sgResult r = sgCreateGeom(dev, &desc, out);
    if (r != SG_OK)
        return ss_fail(prog, dev, r, "mesh '%s'%s", f->mesh_sources[mesh], lines ? ": lines" : "");
    return true;
}

/* The tangents of the meshes that shader draws use, where they have normals and texture
 * coordinates: every program that runs shaders gives them the same attribute 0. */
static bool make_tangents(const char *prog, const sc_file *f, ss_uploads *u) {
    for (size_t i = 0; i < f->scene_count; i++) {
        for (size_t j = 0; j < f->scenes[i].draw_count; j++) {
            const sc_draw *d = &f->scenes[i].draws[j];
            const sc_mesh *m = &f->meshes[d->mesh];
            if (!d->shader || u->tangents[d->mesh] || !m->normals || !m->texcoords) continue;
            float *t = malloc((size_t)m->vertex_count * 4 * sizeof *t);
            /* The counts fit an int: the loader caps them at INT32_MAX. */
            if (!t ||
                sgu_compute_tangents(m->positions, m->normals, m->texcoords, (int)m->vertex_count,
                                     m->indices, (int)m->index_count, 0, t) != 0) {
                free(t);
                fprintf(stderr, "%s: mesh '%s': out of memory for its tangents\n", prog,
                        f->mesh_sources[d->mesh]);
                return false;
            }
            u->tangents[d->mesh] = t;
        }
    }
    return true;
}

bool ss_upload(const char *prog, sgDevice *dev, const sc_file *f, ss_uploads *u) {
    memset(u, 0, sizeof *u);
    u->geoms = calloc(f->mesh_count ? f->mesh_count : 1, sizeof *u->geoms);
    u->line_geoms = calloc(f->mesh_count ? f->mesh_count : 1, sizeof *u->line_geoms);
    u->images = calloc(f->texture_count ? f->texture_count : 1, sizeof *u->images);
    u->tangents = calloc(f->mesh_count ? f->mesh_count : 1, sizeof *u->tangents);
    u->mesh_count = f->mesh_count;
    if (!u->geoms || !u->line_geoms || !u->images || !u->tangents) {
        fprintf(stderr, "%s: out of memory\n", prog);
        return false;
    }
    if (!make_tangents(prog, f, u)) return false;
    for (size_t i = 0; i < f->texture_count; i++) {
        const sc_image *t = &f->textures[i];
        sgImage2DDesc desc = {.width = t->width,
                              .height = t->height,
                              .format = SG_FORMAT_RGBA8_UNORM,
                              .data = t->pixels,
                              .mip_levels = sc_texture_mipmapped(f, i) ? SG_MIP_LEVELS_ALL : 1};
        sgResult r = sgCreateImage2D(dev, &desc, &u->images[i]);
        if (r != SG_OK) return ss_fail(prog, dev, r, "texture '%s'", f->texture_sources[i]);
        u->image_count++;
    }
    for (size_t i = 0; i < f->mesh_count; i++) {
        /* Counted first, so that ss_destroy_uploads frees what a failure leaves. */
        u->geom_count++;
        const sc_mesh *m = &f->meshes[i];
        if (m->index_count > 0 && !upload_geom(prog, dev, f, u, i, false, &u->geoms[i]))
            return false;
        if (m->line_index_count > 0 && !upload_geom(prog, dev, f, u, i, true, &u->line_geoms[i]))
            return false;
    }
    return true;
}

bool ss_create_targets(const char *prog, sgDevice *dev, const sc_scene *s, sgImage2D *color,
                       sgImage2D *depth, sgPassDesc *pass) {
    sgImage2DDesc cd = {.width = s->width, .height = s->height, .format = SG_FORMAT_RGBA8_UNORM};
    sgImage2DDesc dd = {.width = s->width, .height = s->height, .format = SG_FORMAT_D32_FLOAT};
    sgResult r = sgCreateImage2D(dev, &cd, color);
    if (r != SG_OK) return ss_fail(prog, dev, r, "scene '%s': colour target", s->name);
    r = sgCreateImage2D(dev, &dd, depth);
    if (r != SG_OK) return ss_fail(prog, dev, r, "scene '%s': depth target", s->name);
    memset(pass, 0, sizeof *pass);
    pass->color = *color;
    pass->depth = *depth;
    pass->color_load = SG_LOAD_CLEAR;
    pass->depth_load = SG_LOAD_DEFAULT;     /* clears to 1.0, the far plane */
    pass->depth_store = SG_STORE_DONT_CARE; /* nothing reads the depth after the frame */
    memcpy(pass->clear_color, s->clear_color, sizeof pass->clear_color);
    pass->samples = s->samples;
    return true;
}

bool ss_fit_shadow(const char *prog, const sc_file *f, const sc_scene *s, ss_shadow *sh) {
    if (!sh->map.id) return true;
    double view[16], proj[16];
    /* The loader has fitted this scene's light already, and a turntable moves casters and light
     * together; failing here is a bug, or a caster only a turned view sees edge-on. */
    if (!sc_shadow_light(f, s, view, proj)) {
        fprintf(stderr, "%s: scene '%s': the shadow light cannot be fitted\n", prog, s->name);
        return false;
    }
    for (int i = 0; i < 16; i++) sh->proj[i] = (float)proj[i];
    for (size_t i = 0; i < s->draw_count; i++)
        if (s->draws[i].casts_shadow)
            sc_shadow_caster_world_view(view, s->draws[i].world_view, sh->world_view[i]);
    sc_mat4_mul_to_float(proj, view, sh->receiver.matrix);
    return true;
}

bool ss_create_shadow(const char *prog, sgDevice *dev, ss_pso_cache *cache, const sc_file *f,
                      const sc_scene *s, ss_shadow *out) {
    memset(out, 0, sizeof *out);
    if (!s->has_shadow) return true;
    out->psos = calloc(s->draw_count, sizeof *out->psos);
    out->world_view = calloc(s->draw_count, sizeof *out->world_view);
    if (!out->psos || !out->world_view) {
        fprintf(stderr, "%s: out of memory\n", prog);
        ss_destroy_shadow(dev, out);
        return false;
    }
    int size = s->shadow.size;
    sgImage2DDesc md = {.width = size, .height = size, .format = SG_FORMAT_D32_FLOAT};
    sgResult r = sgCreateImage2D(dev, &md, &out->map);
    if (r != SG_OK) {
        ss_destroy_shadow(dev, out);
        return ss_fail(prog, dev, r, "scene '%s': shadow map of %dx%d", s->name, size, size);
    }
    out->pass.depth = out->map; /* no colour: a depth-only pass */
    out->pass.depth_load = SG_LOAD_CLEAR;
    out->pass.clear_depth = 1.0f;
    out->pass.depth_store = SG_STORE_STORE; /* the receivers read it */
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        if (!d->casts_shadow) continue;
        /* Only depth is written: the colour source is the cheapest, and the caster's own cull
         * and winding decide which of its faces are in the map. */
        sgPipelineDesc p;
        memset(&p, 0, sizeof p);
        p.shade = SG_SHADE_VERTEX_COLOR;
        p.depth.compare = SG_COMPARE_LESS;
        p.depth.write = true;
        p.depth.bias_constant = s->shadow.bias;
        p.depth.bias_slope = s->shadow.slope_bias;
        p.cull = d->cull == SC_CULL_BACK    ? SG_CULL_BACK
                 : d->cull == SC_CULL_FRONT ? SG_CULL_FRONT
                                            : SG_CULL_NONE;
        p.front_face = d->front_face == SC_FRONT_FACE_CW ? SG_FRONT_FACE_CW : SG_FRONT_FACE_CCW;
        /* a wireframe casts its edges */
        p.polygon_mode =
            d->polygon_mode == SC_POLYGON_MODE_LINE ? SG_POLYGON_MODE_LINE : SG_POLYGON_MODE_FILL;
        p.blend = SG_BLEND_OPAQUE;
        p.lighting = SG_LIGHTING_NONE;
        if (!ss_get_pso(prog, dev, cache, &p, &out->psos[i])) {
            ss_destroy_shadow(dev, out);
            return false;
        }
    }
    out->receiver.map = out->map;
    out->receiver.light = s->shadow.light;
    out->receiver.pcf = s->shadow.pcf;
    if (!ss_fit_shadow(prog, f, s, out)) {
        ss_destroy_shadow(dev, out);
        return false;
    }
    return true;
}

void ss_destroy_shadow(sgDevice *dev, ss_shadow *sh) {
    if (sh->map.id) sgDestroyImage2D(dev, sh->map);
    free(sh->psos);
    free(sh->world_view);
    memset(sh, 0, sizeof *sh);
}

/* A mesh's triangles, then its lines, with one pipeline: lines are lines whatever its polygon
 * mode. The order of triangles applies to triangles only (the loader sorts no mesh with lines). */
static sgResult draw_mesh(sgDevice *dev, sgPipelineStateObject pso, const ss_uploads *u, int mesh,
                          const sgDrawParams *params) {
    sgResult r = SG_OK;
    if (u->geoms[mesh].id) r = sgDraw(dev, pso, u->geoms[mesh], params);
    if (r == SG_OK && u->line_geoms[mesh].id) {
        sgDrawParams lp = *params;
        lp.sort = SG_SORT_NONE;
        r = sgDraw(dev, pso, u->line_geoms[mesh], &lp);
    }
    return r;
}

/* The shadow's depth-only pass: every caster, unlit and untextured, into the map. */
static bool draw_shadow_pass(const char *prog, sgDevice *dev, const sc_file *f, const sc_scene *s,
                             const ss_uploads *u, const ss_shadow *sh) {
    sgResult r = sgBeginRenderPass(dev, &sh->pass);
    if (r != SG_OK)
        return ss_fail(prog, dev, r, "scene '%s': shadow pass: sgBeginRenderPass", s->name);
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        if (!d->casts_shadow) continue;
        sgDrawParams params;
        memset(&params, 0, sizeof params);
        memcpy(params.world_view, sh->world_view[i], sizeof params.world_view);
        memcpy(params.proj, sh->proj, sizeof params.proj);
        r = draw_mesh(dev, sh->psos[i], u, d->mesh, &params);
        if (r != SG_OK) {
            ss_fail(prog, dev, r, "scene '%s', shadow pass, draw %zu (%s): sgDraw", s->name, i,
                    f->mesh_sources[d->mesh]);
            sgEndRenderPass(dev, &sh->pass);
            return false;
        }
    }
    r = sgEndRenderPass(dev, &sh->pass);
    if (r != SG_OK)
        return ss_fail(prog, dev, r, "scene '%s': shadow pass: sgEndRenderPass", s->name);
    return true;
}

bool ss_draw_frame(const char *prog, sgDevice *dev, const sc_file *f, const sc_scene *s,
                   const ss_uploads *u, const sgPipelineStateObject *psos, const sgPassDesc *pass,
                   const ss_shadow *shadow) {
    const bool shadowed = shadow && shadow->map.id;
    if (shadowed && !draw_shadow_pass(prog, dev, f, s, u, shadow)) return false;
    sgLighting lighting;
    scene_lighting(s, &lighting);
    sgResult r = sgBeginRenderPass(dev, pass);
    if (r != SG_OK) return ss_fail(prog, dev, r, "scene '%s': sgBeginRenderPass", s->name);
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        sgDrawParams params;
        memset(&params, 0, sizeof params);
        memcpy(params.world_view, d->world_view, sizeof params.world_view);
        memcpy(params.proj, d->proj, sizeof params.proj);
        params.sort = d->sort == SC_SORT_BACK_TO_FRONT ? SG_SORT_BACK_TO_FRONT : SG_SORT_NONE;
        sgColor color = {d->color[0], d->color[1], d->color[2], d->color[3]};
        if (d->shader) {
            /* The shader's inputs alone: no colour, texture, lighting or shadow (the loader
             * refuses them with a shader). */
            params.uniforms = d->uniform_count ? d->uniforms : NULL;
            params.uniform_size = (size_t)d->uniform_count * sizeof(float);
            for (int k = 0; k < d->shader_texture_count; k++)
                params.textures[k] = u->images[d->shader_textures[k]];
            params.instance_count = d->instances;
        } else {
            if (d->texture >= 0) params.texture = u->images[d->texture];
            /* NULL for the default white keeps such draws on the path without a colour
             * multiply. */
            bool white = color.r == 1.0f && color.g == 1.0f && color.b == 1.0f && color.a == 1.0f;
            params.color = white ? NULL : &color;
            if (d->lighting != SC_LIGHTING_NONE) {
                params.lighting = &lighting;
                memcpy(params.specular, d->specular, sizeof params.specular);
                params.shininess = d->shininess;
            }
            if (shadowed && d->receives_shadow) params.shadow = &shadow->receiver;
        }
        r = draw_mesh(dev, psos[i], u, d->mesh, &params);
        if (r != SG_OK) {
            ss_fail(prog, dev, r, "scene '%s', draw %zu (%s): sgDraw", s->name, i,
                    f->mesh_sources[d->mesh]);
            sgEndRenderPass(dev, pass); /* close the pass so the targets can be freed */
            return false;
        }
    }
    r = sgEndRenderPass(dev, pass);
    if (r != SG_OK) return ss_fail(prog, dev, r, "scene '%s': sgEndRenderPass", s->name);
    return true;
}

bool ss_fail(const char *prog, sgDevice *dev, sgResult r, const char *fmt, ...) {
    va_list ap;
    fprintf(stderr, "%s: ", prog);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    if (dev)
        fprintf(stderr, ": %s: %s\n", sgResultName(r), sgGetLastError(dev));
    else
        fprintf(stderr, ": %s\n", sgResultName(r));
    return false;
}

double ss_now_ms(void) {
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double ss_median(double *v, int n) {
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
