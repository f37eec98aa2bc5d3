/* sgapi-view - an interactive viewer of scene and model files: sgapi renders each frame on the
 * CPU, the pixels are copied into an SDL2 window's surface (no GPU API draws anything).
 *
 * The camera is a transform applied on top of the scene's own view space: orbit about the centre
 * of the scene's bounding sphere, dolly, and fly. Objects are the scene's draws plus the standard
 * shapes added at run time.
 */
#include <math.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <SDL.h>
#include <sgapi/sgapi.h>
#include <sgapi/sgapi_util.h>

#include "cli.h"
#include "image_io.h"
#include "model.h"
#include "scene.h"
#include "scene_keys.h"
#include "scene_sgapi.h"

#define PROG "sgapi-view"
#define PI   3.14159265358979323846

typedef struct options {
    const char **files;
    int file_count;
    const char *scene; /* --scene NAME: of a scene file; NULL: its first */
    int width, height;
    int threads;
    int frames;               /* --frames N: render N frames, print the rate and quit; 0: run */
    bool print_fps;           /* --print-fps: the rate once a second on stdout */
    bool strict;              /* --strict: an unknown key in the scene file is an error */
    int samples;              /* --samples: every scene's samples a pixel (0: the scenes') */
    const char *save_dir;     /* --save-dir: where F12 writes frame-NNNN.png */
    const char **shader_libs; /* --shaders: shader libraries, in order */
    int shader_lib_count;
    int mipmap; /* --mipmap: an sc_mipmap every draw takes; -1: as the scene says */
} options;

/* The camera, on top of the scene's view space: orbit angles about the target, a dolly along
 * the view axis, and a flight offset. */
typedef struct camera {
    double target[3]; /* the orbit's centre, in the scene's view space */
    double radius;    /* of the scene's bounding sphere: the unit of zoom and flight */
    double yaw, pitch;
    double dolly;  /* > 0: closer */
    double fly[3]; /* moves the scene in view space, the opposite of the camera's flight */
} camera;

/* One drawn object: a draw of the scene and what the viewer does to it. */
typedef struct object {
    float base[16];   /* the draw's worldView as loaded (or as placed, for a shape) */
    double centre[3]; /* of its vertices in the scene's view space, for spinning */
    bool spins;       /* added shapes turn while the animation runs */
    double angle;     /* degrees */
} object;

typedef struct viewer {
    sgDevice *dev;
    sc_file file;
    sc_scene *scene; /* file.scenes[0]: the one shown */
    sc_draw *loaded; /* the draws' states as loaded (the shading mode cycles from there) */
    object *objects; /* per draw */
    sc_light lights[SC_MAX_LIGHTS];
    ss_uploads uploads;
    bool uploaded;
    ss_pso_cache cache;
    sc_shaders *shaders; /* what the scene's "shader" keys name */
    sgPipelineStateObject *psos;
    sgImage2D color, depth;
    sgPassDesc pass;
    ss_shadow shadow;
    camera cam, cam0;
    int selected;   /* draw index, -1: none */
    bool wireframe; /* every draw as lines */
    int shading;    /* 0: as loaded, 1 none, 2 flat, 3 gouraud, 4 phong */
    bool cull;      /* back faces culled */
    bool animate;
    int next_shape;
    int saved;            /* frames saved so far */
    const char *save_dir; /* where they go */
    sc_png_writer *png;
    double start_ms;              /* when the first frame began */
    double render_ms, present_ms; /* time spent so far in each, for --frames */
} viewer;

static void usage(FILE *f) {
    fprintf(f, "usage: sgapi-view [options] SCENE.json | MODEL.obj|MODEL.off...\n"
               "Shows a scene file (its first scene, or --scene NAME) or model files in a window;\n"
               "sgapi renders every frame on the CPU.\n"
               "  --scene NAME    the scene of a scene file to show\n"
               "  --size WxH      window size (default 1024x768)\n"
               "  --threads T     sgapi's threads (default 0: all cores)\n"
               "  --save-dir DIR  where F12 saves frames (default .): DIR/frame-0001.png ...\n"
               "  --frames N      render N frames, print frames per second, quit (a benchmark)\n"
               "  --print-fps     print frames per second once a second\n"
               "  --mipmap MODE   every draw's \"mipmap\" (none, nearest, linear), whatever the\n"
               "                  scene says\n"
               "  --shaders LIB.so\n"
               "                  load the shaders of a shader library (repeatable)\n"
               "  --samples N     samples a pixel, 1 or 4, for every scene (default: the scene's)\n"
               "  --strict        an unknown key in the scene file is an error (exit 1, nothing\n"
               "                  shown), not a warning\n"
               "Mouse:\n"
               "  left drag       orbit about the centre of the scene\n"
               "  wheel           zoom (dolly towards the centre)\n"
               "Keys:\n"
               "  W A S D, arrows fly forward, left, back, right;  Q / E  down / up\n"
               "  L               wireframe on/off\n"
               "  M               shading: as loaded, unlit, flat, Gouraud, Phong (shader\n"
               "                  draws keep their shader)\n"
               "  C               back-face culling on/off\n"
               "  N               add the next standard shape at the view centre (cube,\n"
               "                  tetrahedron, octahedron, icosphere, sphere, cylinder, cone,\n"
               "                  torus) and select it\n"
               "  Tab             select the next object (the title names the selected one)\n"
               "  Delete, X       delete the selected object\n"
               "  Space           animation on/off (added shapes spin)\n"
               "  R               reset the camera\n"
               "  F12             save the frame as PNG\n"
               "  Esc             quit\n"
               "The window title shows frames per second.\n");
}

/* ---- matrices (row-major, column vectors, in double) --------------------------------------- */

static void mat_mul(const double a[16], const double b[16], double out[16]) {
    double r[16];
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += a[i * 4 + k] * b[k * 4 + j];
            r[i * 4 + j] = s;
        }
    memcpy(out, r, sizeof r);
}

static void mat_identity(double m[16]) {
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1;
}

static void mat_translate(double m[16], double x, double y, double z) {
    mat_identity(m);
    m[3] = x, m[7] = y, m[11] = z;
}

static void mat_rot_x(double m[16], double a) {
    mat_identity(m);
    m[5] = cos(a), m[6] = -sin(a), m[9] = sin(a), m[10] = cos(a);
}

static void mat_rot_y(double m[16], double a) {
    mat_identity(m);
    m[0] = cos(a), m[2] = sin(a), m[8] = -sin(a), m[10] = cos(a);
}

/* The camera's transform of the scene's view space: fly, dolly, then the orbit about target. */
static void camera_matrix(const camera *c, double out[16]) {
    double t[16], m[16];
    mat_translate(m, c->fly[0], c->fly[1], c->fly[2] + c->dolly);
    mat_translate(t, c->target[0], c->target[1], c->target[2]);
    mat_mul(m, t, m);
    mat_rot_x(t, c->pitch);
    mat_mul(m, t, m);
    mat_rot_y(t, c->yaw);
    mat_mul(m, t, m);
    mat_translate(t, -c->target[0], -c->target[1], -c->target[2]);
    mat_mul(m, t, out);
}

/* The inverse of a rigid transform (rotation and translation). */
static void rigid_inverse(const double m[16], double out[16]) {
    double r[16];
    mat_identity(r);
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[i * 4 + j] = m[j * 4 + i];
    for (int i = 0; i < 3; i++)
        r[i * 4 + 3] = -(r[i * 4] * m[3] + r[i * 4 + 1] * m[7] + r[i * 4 + 2] * m[11]);
    memcpy(out, r, sizeof r);
}

/* ---- scene state ------------------------------------------------------------------------------
 */

/* The centre of a draw's vertices' box in the scene's view space (its worldView applied). */
static void object_centre(const sc_file *f, const sc_draw *d, double out[3]) {
    sc_scene one = {0};
    one.draws = (sc_draw *)d;
    one.draw_count = 1;
    double r;
    if (!sc_scene_bounds(f, &one, out, &r)) out[0] = out[1] = out[2] = 0;
}

/* Every draw's worldView, the lights and the pipelines for this frame. */
static bool update_draws(viewer *v, double seconds) {
    double cam[16];
    camera_matrix(&v->cam, cam);
    sc_scene *s = v->scene;
    for (size_t i = 0; i < s->draw_count; i++) {
        object *o = &v->objects[i];
        if (o->spins && v->animate) o->angle = fmod(o->angle + 45.0 * seconds, 360.0);
        double m[16], t[16], b[16];
        for (int k = 0; k < 16; k++) b[k] = o->base[k];
        /* A spin turns the object about the vertical through its own centre. */
        mat_translate(m, o->centre[0], o->centre[1], o->centre[2]);
        mat_rot_y(t, o->angle * PI / 180);
        mat_mul(m, t, m);
        mat_translate(t, -o->centre[0], -o->centre[1], -o->centre[2]);
        mat_mul(m, t, m);
        mat_mul(m, b, m);
        mat_mul(cam, m, m);
        sc_draw *d = &s->draws[i];
        for (int k = 0; k < 16; k++) d->world_view[k] = (float)m[k];
        /* The state: as loaded, then the viewer's toggles. */
        const sc_draw *l = &v->loaded[i];
        const sc_mesh *mesh = &v->file.meshes[d->mesh];
        d->polygon_mode = v->wireframe ? SC_POLYGON_MODE_LINE : l->polygon_mode;
        d->cull = v->cull ? SC_CULL_BACK : l->cull;
        d->lighting = l->lighting;
        d->receives_shadow = l->receives_shadow;
        /* Flat lighting takes faces: a mesh with lines keeps its own lighting. */
        if (v->shading > 0 && !mesh->line_index_count && !d->shader)
            d->lighting = (sc_lighting)(v->shading - 1);
        if (d->lighting == SC_LIGHTING_FLAT || d->lighting == SC_LIGHTING_GOURAUD)
            d->receives_shadow = false;
        sgPipelineDesc desc;
        if (!ss_pipeline_desc(PROG, &v->file, d, v->shaders, &desc) ||
            !ss_get_pso(PROG, v->dev, &v->cache, &desc, &v->psos[i]))
            return false;
    }
    /* The lights belong to the world: they turn and move with it. */
    for (int k = 0; k < s->light_count; k++) {
        sc_light *dst = &s->lights[k];
        const sc_light *src = &v->lights[k];
        for (int r = 0; r < 3; r++) {
            double a = 0, p = cam[r * 4 + 3];
            for (int c = 0; c < 3; c++) {
                a += cam[r * 4 + c] * src->direction[c];
                p += cam[r * 4 + c] * src->position[c];
            }
            dst->direction[r] = (float)a;
            dst->position[r] = (float)p;
        }
    }
    if (s->has_shadow && !ss_fit_shadow(PROG, &v->file, s, &v->shadow)) {
        /* Casters the light cannot be fitted to (all deleted, say): the frame goes without. */
        ss_destroy_shadow(v->dev, &v->shadow);
        s->has_shadow = false;
    }
    return true;
}

/* (Re)creates the geoms and images of every mesh and texture, after the file changed. */
static bool upload(viewer *v) {
    if (v->uploaded) ss_destroy_uploads(v->dev, &v->uploads);
    v->uploaded = ss_upload(PROG, v->dev, &v->file, &v->uploads);
    return v->uploaded;
}

/* The colour and depth targets (and the shadow) at the window's size. */
static bool create_targets(viewer *v, int width, int height) {
    if (v->color.id) sgDestroyImage2D(v->dev, v->color);
    if (v->depth.id) sgDestroyImage2D(v->dev, v->depth);
    v->color.id = v->depth.id = 0;
    ss_destroy_shadow(v->dev, &v->shadow);
    v->scene->width = width;
    v->scene->height = height;
    return ss_create_targets(PROG, v->dev, v->scene, &v->color, &v->depth, &v->pass) &&
           ss_create_shadow(PROG, v->dev, &v->cache, &v->file, v->scene, &v->shadow);
}

/* Room for one more draw in the per-draw arrays. */
static bool grow_draws(viewer *v, size_t n) {
    sc_draw *l = realloc(v->loaded, n * sizeof *l);
    if (l) v->loaded = l;
    object *o = realloc(v->objects, n * sizeof *o);
    if (o) v->objects = o;
    sgPipelineStateObject *p = realloc(v->psos, n * sizeof *p);
    if (p) v->psos = p;
    return l && o && p;
}

/* Adds the next standard shape at the view centre, a third of the scene's size. */
static bool add_shape(viewer *v) {
    static const sguShape shapes[] = {
        SGU_SHAPE_CUBE,      SGU_SHAPE_TETRAHEDRON, SGU_SHAPE_OCTAHEDRON, SGU_SHAPE_ICOSPHERE,
        SGU_SHAPE_UV_SPHERE, SGU_SHAPE_CYLINDER,    SGU_SHAPE_CONE,       SGU_SHAPE_TORUS};
    static const char *const names[] = {"cube",   "tetrahedron", "octahedron", "icosphere",
                                        "sphere", "cylinder",    "cone",       "torus"};
    static const float colors[][3] = {{0.9f, 0.3f, 0.2f},   {0.3f, 0.8f, 0.3f}, {0.3f, 0.5f, 0.95f},
                                      {0.95f, 0.8f, 0.2f},  {0.8f, 0.4f, 0.9f}, {0.2f, 0.8f, 0.8f},
                                      {0.95f, 0.55f, 0.2f}, {0.9f, 0.9f, 0.9f}};
    int k = v->next_shape++ % 8;
    sguShapeDesc d = {.shape = shapes[k], .subdivisions = 2};
    sc_mesh mesh;
    char source[64]; /* "shape NAME (added)": the names above fit */
    sc_msg err = {0};
    if (!sc_shape_mesh(&d, &mesh, &err)) {
        fprintf(stderr, PROG ": %s\n", err.text);
        sc_msg_free(&err);
        return false;
    }
    snprintf(source, sizeof source, "shape %s (added)", names[k]);
    sc_draw draw = {0};
    if (!sc_file_add_mesh(&v->file, &mesh, source, &draw.mesh) ||
        !grow_draws(v, v->scene->draw_count + 1)) {
        fprintf(stderr, PROG ": out of memory\n");
        return false;
    }
    /* The view centre: the point of the view axis level with the orbit's target. */
    double cam[16], inv[16];
    camera_matrix(&v->cam, cam);
    rigid_inverse(cam, inv);
    double tz = cam[8] * v->cam.target[0] + cam[9] * v->cam.target[1] + cam[10] * v->cam.target[2] +
                cam[11];
    if (tz > -v->cam.radius * 0.5) tz = -v->cam.radius * 2; /* the target behind: in front */
    double p[3];
    for (int r = 0; r < 3; r++) p[r] = inv[r * 4 + 2] * tz + inv[r * 4 + 3];
    double scale = v->cam.radius * 0.3;
    /* In the scene's view space, turned back from the camera's: it faces the viewer. */
    object o = {0};
    double m[16], sc[16];
    memcpy(m, inv, sizeof m);
    m[3] = p[0], m[7] = p[1], m[11] = p[2];
    mat_identity(sc);
    sc[0] = sc[5] = sc[10] = scale;
    mat_mul(m, sc, m);
    for (int i = 0; i < 16; i++) o.base[i] = (float)m[i];
    memcpy(o.centre, p, sizeof p);
    o.spins = true;
    draw.texture = -1;
    draw.depth_write = true;
    memcpy(draw.color, colors[k], sizeof colors[k]);
    draw.color[3] = 1;
    draw.lighting = SC_LIGHTING_PHONG;
    draw.specular[0] = draw.specular[1] = draw.specular[2] = 0.3f;
    draw.shininess = 32;
    draw.casts_shadow = true;
    draw.receives_shadow = true;
    memcpy(draw.world_view, o.base, sizeof o.base);
    memcpy(draw.proj, v->scene->draw_count ? v->scene->draws[0].proj : draw.proj, 64);
    if (!v->scene->draw_count)
        sc_perspective(50 * PI / 180, (double)v->scene->width / v->scene->height, 0.05, 100,
                       draw.proj);
    if (!sc_scene_add_draw(v->scene, &draw)) {
        fprintf(stderr, PROG ": out of memory\n");
        return false;
    }
    v->loaded[v->scene->draw_count - 1] = draw;
    v->objects[v->scene->draw_count - 1] = o;
    v->selected = (int)v->scene->draw_count - 1;
    return upload(v);
}

static void delete_selected(viewer *v) {
    int i = v->selected;
    sc_scene *s = v->scene;
    if (i < 0 || (size_t)i >= s->draw_count) return;
    size_t tail = s->draw_count - (size_t)i - 1;
    sc_draw_free(&s->draws[i]);
    memmove(&s->draws[i], &s->draws[i + 1], tail * sizeof *s->draws);
    memmove(&v->loaded[i], &v->loaded[i + 1], tail * sizeof *v->loaded);
    memmove(&v->objects[i], &v->objects[i + 1], tail * sizeof *v->objects);
    memmove(&v->psos[i], &v->psos[i + 1], tail * sizeof *v->psos);
    s->draw_count--;
    v->selected = s->draw_count ? (int)s->draw_count - 1 : -1;
}

/* A frame read back: RGBA8, top row first. */
typedef struct frame {
    unsigned char *pixels;
    size_t cap;
    int width, height;
} frame;

/* Writes a frame to save_dir/frame-NNNN.png. */
static void save_frame(viewer *v, const frame *f) {
    char *path = sc_format("%s/frame-%04d.png", v->save_dir, ++v->saved);
    sc_msg err = {0};
    if (!path)
        fprintf(stderr, PROG ": out of memory for the path of frame %d\n", v->saved);
    else if (!sc_png_writer_write(v->png, path, f->width, f->height, f->pixels, &err))
        fprintf(stderr, PROG ": %s\n", err.text);
    else
        printf("saved %s\n", path);
    fflush(stdout);
    sc_msg_free(&err);
    free(path);
}

/* One frame, read back into f. */
static bool render(viewer *v, double seconds, frame *f) {
    size_t need = (size_t)v->scene->width * v->scene->height * 4;
    if (need > f->cap) {
        unsigned char *p = realloc(f->pixels, need);
        if (!p) {
            fprintf(stderr, PROG ": out of memory\n");
            return false;
        }
        f->pixels = p;
        f->cap = need;
    }
    if (!update_draws(v, seconds) ||
        !ss_draw_frame(PROG, v->dev, &v->file, v->scene, &v->uploads, v->psos, &v->pass,
                       v->scene->has_shadow ? &v->shadow : NULL))
        return false;
    sgResult r = sgReadImage2D(v->dev, v->color, f->pixels, 0);
    if (r != SG_OK) return ss_fail(PROG, v->dev, r, "sgReadImage2D");
    f->width = v->scene->width;
    f->height = v->scene->height;
    return true;
}

/* Copies a frame into the window: RGBA bytes converted to the surface's format. */
static bool present(const frame *f, SDL_Window *win) {
    SDL_Surface *surf = SDL_GetWindowSurface(win);
    if (!surf) {
        fprintf(stderr, PROG ": SDL_GetWindowSurface: %s\n", SDL_GetError());
        return false;
    }
    int w = f->width < surf->w ? f->width : surf->w;
    int h = f->height < surf->h ? f->height : surf->h;
    if (SDL_MUSTLOCK(surf)) SDL_LockSurface(surf);
    int rc = SDL_ConvertPixels(w, h, SDL_PIXELFORMAT_ABGR8888, f->pixels, f->width * 4,
                               surf->format->format, surf->pixels, surf->pitch);
    if (SDL_MUSTLOCK(surf)) SDL_UnlockSurface(surf);
    if (rc != 0 || SDL_UpdateWindowSurface(win) != 0) {
        fprintf(stderr, PROG ": blit: %s\n", SDL_GetError());
        return false;
    }
    return true;
}

/* Rendering runs on a thread of its own, so that the next frame renders while the window
 * system shows the last one (showing waits on the X server, a process that needs the CPU too).
 * `state` guards the viewer and its device: the renderer holds it for a whole frame, the event
 * loop for its events, so a frame sees every event before it whole. Three frames: the one shown,
 * one ready to be shown, one being rendered; the renderer waits for the ready one to be taken
 * before it publishes the next, so no rendered frame goes unshown. */
typedef struct pipeline {
    viewer *v;
    SDL_mutex *state;
    SDL_mutex *lock; /* guards the fields below */
    SDL_cond *cond;
    frame frames[3];
    int ready;   /* the frame to show next, or -1 */
    int showing; /* the frame the event loop shows, or -1 */
    bool quit, failed;
    bool save;        /* F12: save the next frame rendered (guarded by state) */
    double render_ms; /* time spent rendering, for --frames */
    int rendered;     /* frames rendered */
} pipeline;

static int render_loop(void *arg) {
    pipeline *p = arg;
    double prev = ss_now_ms();
    for (;;) {
        /* A frame neither shown nor ready. */
        SDL_LockMutex(p->lock);
        while (p->ready >= 0 && !p->quit) SDL_CondWait(p->cond, p->lock);
        int b = 0;
        while (b == p->showing || b == p->ready) b++;
        bool quit = p->quit;
        SDL_UnlockMutex(p->lock);
        if (quit) break;

        SDL_LockMutex(p->state);
        double now = ss_now_ms();
        bool ok = render(p->v, (now - prev) / 1000.0, &p->frames[b]);
        p->render_ms += ss_now_ms() - now;
        p->rendered++;
        prev = now;
        bool save = p->save;
        p->save = false;
        if (ok && save) save_frame(p->v, &p->frames[b]);
        SDL_UnlockMutex(p->state);

        SDL_LockMutex(p->lock);
        if (ok) {
            p->ready = b;
        } else {
            p->failed = p->quit = true;
        }
        SDL_CondBroadcast(p->cond);
        SDL_UnlockMutex(p->lock);
        if (!ok) break;
    }
    return 0;
}

/* What a key does; false to quit. */
static bool on_key(viewer *v, SDL_Keycode k, bool *ok) {
    double step = v->cam.radius * 0.1;
    switch (k) {
    case SDLK_ESCAPE:
        return false;
    case SDLK_w:
    case SDLK_UP:
        v->cam.fly[2] += step;
        break;
    case SDLK_s:
    case SDLK_DOWN:
        v->cam.fly[2] -= step;
        break;
    case SDLK_a:
    case SDLK_LEFT:
        v->cam.fly[0] += step;
        break;
    case SDLK_d:
    case SDLK_RIGHT:
        v->cam.fly[0] -= step;
        break;
    case SDLK_q:
        v->cam.fly[1] += step;
        break;
    case SDLK_e:
        v->cam.fly[1] -= step;
        break;
    case SDLK_l:
        v->wireframe = !v->wireframe;
        break;
    case SDLK_m:
        v->shading = (v->shading + 1) % 5;
        break;
    case SDLK_c:
        v->cull = !v->cull;
        break;
    case SDLK_n:
        *ok = add_shape(v);
        break;
    case SDLK_TAB:
        if (v->scene->draw_count)
            v->selected = (int)((size_t)(v->selected + 1) % v->scene->draw_count);
        break;
    case SDLK_DELETE:
    case SDLK_x:
        delete_selected(v);
        break;
    case SDLK_SPACE:
        v->animate = !v->animate;
        break;
    case SDLK_r:
        v->cam = v->cam0;
        break;
    default:
        break;
    }
    return true;
}

static int parse_args(int argc, char **argv, options *o) {
    o->width = 1024, o->height = 768;
    o->save_dir = ".";
    o->files = calloc((size_t)argc, sizeof *o->files);
    o->shader_libs = calloc((size_t)argc, sizeof *o->shader_libs);
    if (!o->files || !o->shader_libs) return 2;
    o->mipmap = -1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool takes = !strcmp(a, "--scene") || !strcmp(a, "--size") || !strcmp(a, "--threads") ||
                     !strcmp(a, "--save-dir") || !strcmp(a, "--frames") ||
                     !strcmp(a, "--shaders") || !strcmp(a, "--samples") || !strcmp(a, "--mipmap");
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 1;
        }
        if (takes && !value) {
            fprintf(stderr, PROG ": %s needs a value\n", a);
            return 2;
        }
        if (!strcmp(a, "--scene")) {
            o->scene = value;
        } else if (!strcmp(a, "--size")) {
            char w[16] = "", h[16] = "";
            const char *x = strchr(value, 'x');
            if (x && x - value < (long)sizeof w && strlen(x + 1) < sizeof h) {
                memcpy(w, value, (size_t)(x - value));
                strcpy(h, x + 1);
            }
            if (!sc_parse_int(w, 16, 8192, &o->width) || !sc_parse_int(h, 16, 8192, &o->height)) {
                fprintf(stderr, PROG ": --size needs WxH, each 16..8192, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--threads")) {
            if (!sc_parse_int(value, 0, 1024, &o->threads)) {
                fprintf(stderr, PROG ": --threads needs 0..1024, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--samples")) {
            if (!sc_parse_samples(value, &o->samples)) {
                fprintf(stderr, PROG ": --samples needs 1 or 4, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--frames")) {
            if (!sc_parse_int(value, 1, 1000000, &o->frames)) {
                fprintf(stderr, PROG ": --frames needs 1..1000000, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--save-dir")) {
            o->save_dir = value;
        } else if (!strcmp(a, "--shaders")) {
            o->shader_libs[o->shader_lib_count++] = value;
        } else if (!strcmp(a, "--mipmap")) {
            sc_mipmap m;
            if (!sc_mipmap_from_name(value, &m)) {
                fprintf(stderr, PROG ": --mipmap needs none, nearest or linear, not '%s'\n", value);
                return 2;
            }
            o->mipmap = (int)m;
        } else if (!strcmp(a, "--print-fps")) {
            o->print_fps = true;
            continue;
        } else if (!strcmp(a, "--strict")) {
            o->strict = true;
            continue;
        } else if (a[0] == '-' && a[1]) {
            fprintf(stderr, PROG ": unknown option '%s' (see --help)\n", a);
            return 2;
        } else {
            o->files[o->file_count++] = a;
            continue;
        }
        i++;
    }
    if (o->file_count == 0) {
        usage(stderr);
        return 2;
    }
    bool models = sc_is_model_path(o->files[0]);
    for (int i = 1; i < o->file_count; i++) {
        if (sc_is_model_path(o->files[i]) != models || !models) {
            fprintf(stderr, PROG ": give one scene file, or model files (.obj, .off)\n");
            return 2;
        }
    }
    return 0;
}

/* Loads the file(s) into v->file with the shown scene first. */
static bool load(viewer *v, const options *o) {
    sc_msg err = {0};
    if (sc_is_model_path(o->files[0])) {
        sc_warnings w = {0};
        bool ok = sc_model_scene(o->files, o->file_count, "models", o->width, o->height, &v->file,
                                 &w, &err);
        for (int k = 0; k < w.count; k++) fprintf(stderr, PROG ": warning: %s\n", w.text[k].text);
        sc_warnings_free(&w);
        if (!ok) {
            fprintf(stderr, PROG ": %s\n", err.text);
            sc_msg_free(&err);
            return false;
        }
    } else if (!sc_load(o->files[0], &v->file, &err)) {
        fprintf(stderr, PROG ": %s\n", err.text);
        sc_msg_free(&err);
        return false;
    } else if (!sc_report_warnings(&v->file, PROG, o->strict)) {
        sc_free(&v->file);
        return false;
    }
    if (o->samples) sc_set_samples(&v->file, o->samples);
    if (o->mipmap >= 0) sc_override_mipmap(&v->file, (sc_mipmap)o->mipmap);
    size_t k = 0;
    if (o->scene) {
        while (k < v->file.scene_count && strcmp(v->file.scenes[k].name, o->scene)) k++;
        if (k == v->file.scene_count) {
            fprintf(stderr, PROG ": %s has no scene '%s'\n", o->files[0], o->scene);
            return false;
        }
    }
    if (k) {
        sc_scene t = v->file.scenes[0];
        v->file.scenes[0] = v->file.scenes[k];
        v->file.scenes[k] = t;
    }
    v->scene = &v->file.scenes[0];
    sc_scene *s = v->scene;
    /* The projection is rebuilt for the window's aspect: the file's vertical field, its near and
     * far planes (an OpenGL perspective matrix; others are kept as they are). */
    if (!grow_draws(v, s->draw_count ? s->draw_count : 1)) return false;
    for (size_t i = 0; i < s->draw_count; i++) {
        sc_draw *d = &s->draws[i];
        v->loaded[i] = *d;
        memset(&v->objects[i], 0, sizeof v->objects[i]);
        memcpy(v->objects[i].base, d->world_view, sizeof d->world_view);
        object_centre(&v->file, d, v->objects[i].centre);
        if (d->proj[14] == -1 && d->proj[15] == 0 && d->proj[0] != 0)
            d->proj[0] = (float)(d->proj[5] * (double)o->height / o->width);
    }
    /* Added shapes are lit: a scene without lights gets one over the eye's shoulder (its own
     * draws are unlit then, so nothing of it changes). */
    if (s->light_count == 0) {
        s->light_count = 1;
        s->lights[0] = (sc_light){.type = SC_LIGHT_DIRECTIONAL,
                                  .direction = {-0.35f, -0.45f, -1},
                                  .color = {0.8f, 0.8f, 0.8f},
                                  .attenuation = {1, 0, 0}};
        s->ambient[0] = s->ambient[1] = s->ambient[2] = 0.3f;
    }
    memcpy(v->lights, s->lights, sizeof v->lights);
    double c[3] = {0, 0, -3}, r = 1;
    if (!sc_scene_bounds(&v->file, s, c, &r) || !(r > 0)) r = 1;
    memcpy(v->cam.target, c, sizeof c);
    v->cam.radius = r;
    v->cam0 = v->cam;
    v->selected = s->draw_count ? (int)s->draw_count - 1 : -1;
    return true;
}

int main(int argc, char **argv) {
    options o = {0};
    int status = parse_args(argc, argv, &o);
    if (status) {
        free(o.files);
        free(o.shader_libs);
        return status == 1 ? 0 : 2;
    }
    viewer v = {0};
    v.save_dir = o.save_dir;
    SDL_Window *win = NULL;
    SDL_Thread *renderer = NULL;
    pipeline pl = {.v = &v, .ready = -1, .showing = -1};
    status = 1;
    if (!load(&v, &o)) goto done;
    /* The shaders the scene names: a problem there is a bad argument (exit 2), before any
     * frame. */
    sc_msg shader_err = {0};
    if (!sc_shaders_prepare(&v.shaders, SG_SIMD_DEFAULT, (const char *const *)o.shader_libs,
                            o.shader_lib_count, &v.file, 1, &shader_err)) {
        fprintf(stderr, PROG ": %s\n", shader_err.text);
        sc_msg_free(&shader_err);
        status = 2;
        goto done;
    }
    struct stat st;
    if (stat(o.save_dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, PROG ": --save-dir '%s' is not a folder\n", o.save_dir);
        goto done;
    }
    sgDeviceDesc dd = {0};
    dd.thread_count = o.threads;
    dd.pipeline_pool_size = 1024;
    dd.geom_pool_size = 4096;
    dd.image_pool_size = (int)v.file.texture_count + 8;
    sgResult r = sgCreateDevice(&dd, &v.dev);
    if (r != SG_OK) {
        ss_fail(PROG, NULL, r, "sgCreateDevice");
        goto done;
    }
    v.png = sc_png_writer_create(SC_PNG_LEVEL_DEFAULT);
    if (!v.png || !upload(&v) || !create_targets(&v, o.width, o.height)) goto done;

    if (SDL_Init(SDL_INIT_VIDEO) != 0) {
        fprintf(stderr, PROG ": SDL_Init: %s\n", SDL_GetError());
        goto done;
    }
    /* On X11 a frame goes to the window through the X server's shared memory, not through the
     * OpenGL texture SDL would otherwise make the window's surface of: the frame is made on the
     * CPU, and without a GPU that OpenGL is Mesa's software one, two more copies (and a crash in
     * its GLX during the first present, seen once under Xvfb). Other video drivers keep SDL's
     * choice: Wayland's surfaces exist only as textures. */
    const char *video = SDL_GetCurrentVideoDriver();
    if (video && strcmp(video, "x11") == 0) SDL_SetHint(SDL_HINT_FRAMEBUFFER_ACCELERATION, "0");
    win = SDL_CreateWindow("sgapi-view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, o.width,
                           o.height, SDL_WINDOW_RESIZABLE);
    if (!win) {
        fprintf(stderr, PROG ": SDL_CreateWindow: %s\n", SDL_GetError());
        goto done;
    }
    pl.state = SDL_CreateMutex();
    pl.lock = SDL_CreateMutex();
    pl.cond = SDL_CreateCond();
    if (!pl.state || !pl.lock || !pl.cond) {
        fprintf(stderr, PROG ": SDL: %s\n", SDL_GetError());
        goto done;
    }
    double t_count = ss_now_ms(), present_ms = 0;
    v.start_ms = t_count;
    renderer = SDL_CreateThread(render_loop, "sgapi-view render", &pl);
    if (!renderer) {
        fprintf(stderr, PROG ": SDL_CreateThread: %s\n", SDL_GetError());
        goto done;
    }
    int frames_since = 0, frames_total = 0;
    bool running = true, dragging = false;
    while (running) {
        /* The next frame, when there is one within a few milliseconds. */
        SDL_LockMutex(pl.lock);
        if (pl.ready < 0 && !pl.failed) SDL_CondWaitTimeout(pl.cond, pl.lock, 5);
        int take = pl.ready;
        if (take >= 0) {
            pl.showing = take;
            pl.ready = -1;
            SDL_CondBroadcast(pl.cond);
        }
        bool failed = pl.failed;
        SDL_UnlockMutex(pl.lock);
        if (failed) goto done;

        SDL_Event e;
        bool ok = true;
        SDL_LockMutex(pl.state);
        while (SDL_PollEvent(&e)) {
            switch (e.type) {
            case SDL_QUIT:
                running = false;
                break;
            case SDL_KEYDOWN:
                if (e.key.keysym.sym == SDLK_F12)
                    pl.save = true;
                else
                    running = on_key(&v, e.key.keysym.sym, &ok) && running;
                break;
            case SDL_MOUSEBUTTONDOWN:
                if (e.button.button == SDL_BUTTON_LEFT) dragging = true;
                break;
            case SDL_MOUSEBUTTONUP:
                if (e.button.button == SDL_BUTTON_LEFT) dragging = false;
                break;
            case SDL_MOUSEMOTION:
                if (dragging) {
                    /* A drag across the window's width turns the scene by 180 degrees. */
                    v.cam.yaw += PI * e.motion.xrel / v.scene->width;
                    v.cam.pitch += PI * e.motion.yrel / v.scene->width;
                    if (v.cam.pitch > PI / 2) v.cam.pitch = PI / 2;
                    if (v.cam.pitch < -PI / 2) v.cam.pitch = -PI / 2;
                }
                break;
            case SDL_MOUSEWHEEL: {
                /* Each notch covers a tenth of what is left to the target: never past it. */
                double cz = -v.cam.target[2] - v.cam.dolly;
                v.cam.dolly += e.wheel.y * 0.1 * (cz > 0 ? cz : v.cam.radius);
                break;
            }
            case SDL_WINDOWEVENT:
                if (e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED &&
                    (e.window.data1 != v.scene->width || e.window.data2 != v.scene->height)) {
                    int w = e.window.data1 < 16 ? 16 : e.window.data1;
                    int h = e.window.data2 < 16 ? 16 : e.window.data2;
                    for (size_t i = 0; i < v.scene->draw_count; i++) {
                        float *pr = v.scene->draws[i].proj;
                        if (pr[14] == -1 && pr[15] == 0) pr[0] = (float)(pr[5] * (double)h / w);
                    }
                    ok = create_targets(&v, w, h);
                }
                break;
            default:
                break;
            }
        }
        SDL_UnlockMutex(pl.state);
        if (!ok) goto done;
        if (take < 0) continue;

        double t0 = ss_now_ms();
        if (!present(&pl.frames[take], win)) goto done;
        double now = ss_now_ms();
        present_ms += now - t0;
        frames_since++, frames_total++;
        if (now - t_count >= 1000) {
            double fps = frames_since * 1000.0 / (now - t_count);
            /* The selection has no mark in the image: the title names it. */
            char *sel = NULL;
            SDL_LockMutex(pl.state);
            if (v.selected >= 0 && (size_t)v.selected < v.scene->draw_count) {
                const char *src = v.file.mesh_sources[v.scene->draws[v.selected].mesh];
                const char *base = strrchr(src, '/');
                sel = sc_format("%d: %s", v.selected, base ? base + 1 : src);
            }
            SDL_UnlockMutex(pl.state);
            char *title = sc_format("sgapi-view - %s - %.1f fps - selected %s", o.files[0], fps,
                                    sel ? sel : "none");
            /* Out of memory: the title stays as it was until the next second. */
            if (title) SDL_SetWindowTitle(win, title);
            free(title);
            free(sel);
            if (o.print_fps) {
                printf("%.1f fps\n", fps);
                fflush(stdout);
            }
            t_count = now;
            frames_since = 0;
        }
        if (o.frames && frames_total == o.frames) {
            double all = now - v.start_ms;
            SDL_LockMutex(pl.state); /* the renderer's figures */
            double per_render = pl.render_ms / pl.rendered;
            SDL_UnlockMutex(pl.state);
            printf("%d frames of %dx%d in %.1f ms: %.1f frames per second (per frame: %.2f ms "
                   "rendering and reading back, %.2f ms showing, overlapped)\n",
                   o.frames, pl.frames[take].width, pl.frames[take].height, all,
                   o.frames * 1000.0 / all, per_render, present_ms / o.frames);
            running = false;
        }
    }
    status = 0;
done:
    if (renderer) {
        SDL_LockMutex(pl.lock);
        pl.quit = true;
        SDL_CondBroadcast(pl.cond);
        SDL_UnlockMutex(pl.lock);
        SDL_WaitThread(renderer, NULL);
    }
    for (int i = 0; i < 3; i++) free(pl.frames[i].pixels);
    if (pl.cond) SDL_DestroyCond(pl.cond);
    if (pl.lock) SDL_DestroyMutex(pl.lock);
    if (pl.state) SDL_DestroyMutex(pl.state);
    if (win) SDL_DestroyWindow(win);
    SDL_Quit();
    ss_destroy_shadow(v.dev, &v.shadow);
    if (v.uploaded) ss_destroy_uploads(v.dev, &v.uploads);
    ss_pso_cache_free(&v.cache);
    sgDestroyDevice(v.dev);
    sc_png_writer_destroy(v.png);
    sc_free(&v.file);
    sc_shaders_close(v.shaders); /* after the device: no pipeline runs a library's code any more */
    free(v.loaded);
    free(v.objects);
    free(v.psos);
    free(o.files);
    free(o.shader_libs);
    return status;
}
