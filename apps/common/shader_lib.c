/* shader_lib.c - the shaders a program knows by name: the built-in library, then the shared
 * objects given with --shaders, checked before anything of theirs is used. A library either
 * comes in whole or not at all, so a refused one leaves the registry as it was. */
#define _POSIX_C_SOURCE 200809L /* stat */
#include "shader_lib.h"

#include <dlfcn.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "builtin.h"

/* Longest shader name accepted: it appears in messages and file names of reports. */

typedef struct known {
    const sgShaderInfo *info; /* inside its library, which stays loaded as long as s */
    int library;              /* index into sc_shaders.sources */
} known;

struct sc_shaders {
    known *shaders;
    size_t count, cap;
    char **sources; /* per library: "the built-in library" or "library 'PATH'" */
    void **handles; /* per library: its dlopen handle, NULL for the built-in one */
    size_t library_count;
};

const sgShaderInfo *sc_shaders_find(const sc_shaders *s, const char *name) {
    if (!s || !name) return NULL;
    for (size_t i = 0; i < s->count; i++)
        if (strcmp(s->shaders[i].info->name, name) == 0) return s->shaders[i].info;
    return NULL;
}

/* Why a library's shader cannot be used, or NULL. */
static const char *bad_shader(const sgShaderInfo *info) {
    if (!info->name) return "has no name";
    if (!sc_shader_name_valid(info->name)) return "has a name that is not 1 to 64 of A-Z a-z 0-9 _";
    if (!info->desc.vertex || !info->desc.fragment)
        return "lacks a vertex or a fragment stage (a shader has both)";
    if (info->desc.varying_count < 0 || info->desc.varying_count > SG_MAX_VARYINGS)
        return "has a varying_count outside 0..16";
    if (info->desc.texture_count < 0 || info->desc.texture_count > SG_MAX_DRAW_TEXTURES)
        return "has a texture_count outside 0..8";
    if (info->uniform_count < 0 || info->uniform_count > SG_MAX_UNIFORM_SIZE / (int)sizeof(float))
        return "has a uniform_count outside 0..16384";
    return NULL;
}

/* Adds a library's shaders, `count` of them at list[0..] (all checked first); source is taken
 * over, even on failure. */
static bool add_shaders(sc_shaders *s, const sgShaderInfo *const *list, int count, char *source,
                        void *handle, sc_msg *err) {
    bool ok = false;
    if (!source) {
        sc_msg_set(err, "out of memory");
        if (handle) dlclose(handle);
        return false;
    }
    for (int i = 0; i < count; i++) {
        const sgShaderInfo *info = list[i];
        const char *why = bad_shader(info);
        if (why) {
            sc_msg_set(err, "%s: shaders[%d]%s%s%s %s", source, i, info->name ? " ('" : "",
                       info->name && strlen(info->name) <= SC_MAX_SHADER_NAME ? info->name : "",
                       info->name ? "')" : "", why);
            goto done;
        }
        for (size_t k = 0; k < s->count; k++) {
            if (strcmp(s->shaders[k].info->name, info->name) == 0) {
                sc_msg_set(err, "%s: shader '%s' is already defined by %s", source, info->name,
                           s->sources[s->shaders[k].library]);
                goto done;
            }
        }
        for (int k = 0; k < i; k++) {
            if (strcmp(list[k]->name, info->name) == 0) {
                sc_msg_set(err, "%s: shader '%s' is defined twice (shaders[%d] and [%d])", source,
                           info->name, k, i);
                goto done;
            }
        }
    }
    size_t need = s->count + (size_t)count;
    if (need > s->cap) {
        size_t cap = s->cap ? s->cap : 16;
        while (cap < need) cap *= 2;
        known *k = realloc(s->shaders, cap * sizeof *k);
        if (!k) {
            sc_msg_set(err, "out of memory");
            goto done;
        }
        s->shaders = k;
        s->cap = cap;
    }
    char **src = realloc(s->sources, (s->library_count + 1) * sizeof *src);
    if (src) s->sources = src;
    void **h = src ? realloc(s->handles, (s->library_count + 1) * sizeof *h) : NULL;
    if (h) s->handles = h;
    if (!src || !h) {
        sc_msg_set(err, "out of memory");
        goto done;
    }
    for (int i = 0; i < count; i++)
        s->shaders[s->count++] = (known){list[i], (int)s->library_count};
    s->sources[s->library_count] = source;
    s->handles[s->library_count++] = handle;
    return true;
done:
    free(source);
    if (handle) dlclose(handle);
    return ok;
}

bool sc_shaders_open(sc_shaders **out, sgSimd simd, sc_msg *err) {
    *out = NULL;
    sc_shaders *s = calloc(1, sizeof *s);
    if (!s) {
        sc_msg_set(err, "out of memory");
        return false;
    }
    int n = 0;
    const sgShaderInfo *const *builtin = sg_builtin_shaders(simd, &n);
    if (!add_shaders(s, builtin, n, sc_format("the built-in library"), NULL, err)) {
        sc_shaders_close(s);
        return false;
    }
    *out = s;
    return true;
}

/* Whether the file starts as an ELF object does; false with a message otherwise. */
static bool check_elf(const char *path, sc_msg *err) {
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        sc_msg_set(err, "shader library '%s': %s", path, strerror(errno));
        return false;
    }
    unsigned char magic[4] = {0};
    size_t n = fread(magic, 1, sizeof magic, fp);
    fclose(fp);
    if (n != sizeof magic || memcmp(magic, "\177ELF", 4) != 0) {
        sc_msg_set(err,
                   "shader library '%s' is not a shared object (no ELF header): build it with "
                   "cc -O2 -shared -fPIC -I include lib.c -o lib.so -lm",
                   path);
        return false;
    }
    return true;
}

bool sc_shaders_load(sc_shaders *s, const char *path, sc_msg *err) {
    struct stat st;
    if (stat(path, &st) != 0) {
        sc_msg_set(err, "shader library '%s': %s", path, strerror(errno));
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        sc_msg_set(err, "shader library '%s' is not a regular file", path);
        return false;
    }
    if (!check_elf(path, err)) return false;
    /* dlopen searches the library path for a bare name: "./" makes it the file named. */
    char *file = strchr(path, '/') ? sc_format("%s", path) : sc_format("./%s", path);
    if (!file) {
        sc_msg_set(err, "out of memory");
        return false;
    }
    /* RTLD_NOW: a symbol the library needs and the program lacks is an error here, not a crash
     * in the middle of a frame. RTLD_LOCAL: two libraries' own symbols never meet. */
    void *h = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    free(file);
    if (!h) {
        const char *why = dlerror();
        sc_msg_set(err, "shader library '%s' cannot be loaded: %s", path, why ? why : "?");
        return false;
    }
    void *sym = dlsym(h, SGAPI_SHADER_LIBRARY_SYMBOL);
    if (!sym) {
        sc_msg_set(err,
                   "shader library '%s' has no function %s: it is a shared object, but not a "
                   "sgapi shader library (sgapi/sgapi_shaders.h)",
                   path, SGAPI_SHADER_LIBRARY_SYMBOL);
        dlclose(h);
        return false;
    }
    sgShaderLibraryFn fn;
    memcpy(&fn, &sym, sizeof fn); /* POSIX: dlsym's result may be used as a function pointer */
    const sgShaderLibrary *lib = fn();
    if (!lib) {
        sc_msg_set(err, "shader library '%s': %s() returned NULL", path,
                   SGAPI_SHADER_LIBRARY_SYMBOL);
        dlclose(h);
        return false;
    }
    if (lib->abi_version != SGAPI_SHADER_ABI_VERSION) {
        sc_msg_set(err,
                   "shader library '%s' is of shader ABI version %d, and this program takes "
                   "version %d: rebuild it against this sgapi's headers",
                   path, lib->abi_version, SGAPI_SHADER_ABI_VERSION);
        dlclose(h);
        return false;
    }
    if (lib->count < 0 || (lib->count > 0 && !lib->shaders)) {
        sc_msg_set(err, "shader library '%s': its shader list is malformed (count %d, shaders %s)",
                   path, lib->count, lib->shaders ? "set" : "NULL");
        dlclose(h);
        return false;
    }
    /* The registry keeps pointers: the library's array, one entry each. */
    const sgShaderInfo **list = malloc(((size_t)lib->count + 1) * sizeof *list);
    if (!list) {
        sc_msg_set(err, "out of memory");
        dlclose(h);
        return false;
    }
    for (int i = 0; i < lib->count; i++) list[i] = &lib->shaders[i];
    bool ok = add_shaders(s, list, lib->count, sc_format("shader library '%s'", path), h, err);
    free(list);
    return ok;
}

/* "a, b, c": the known names, in the order they were added. */
static char *known_names(const sc_shaders *s) {
    size_t len = 1;
    for (size_t i = 0; i < s->count; i++) len += strlen(s->shaders[i].info->name) + 2;
    char *out = malloc(len);
    if (!out) return NULL;
    out[0] = '\0';
    size_t at = 0;
    for (size_t i = 0; i < s->count; i++) {
        const char *n = s->shaders[i].info->name;
        size_t k = strlen(n);
        if (i) memcpy(out + at, ", ", 2), at += 2;
        memcpy(out + at, n, k + 1);
        at += k;
    }
    return out;
}

bool sc_shaders_check(const sc_shaders *s, const sc_file *f, sc_msg *err) {
    for (size_t i = 0; i < f->scene_count; i++) {
        const sc_scene *sc = &f->scenes[i];
        for (size_t j = 0; j < sc->draw_count; j++) {
            const sc_draw *d = &sc->draws[j];
            if (!d->shader) continue;
            const sgShaderInfo *info = sc_shaders_find(s, d->shader);
            if (!info) {
                char *names = known_names(s);
                sc_msg_set(err,
                           "%s: scenes[%zu] ('%s'), draws[%zu]: unknown shader '%s' (known: %s; "
                           "others come from a library given with --shaders)",
                           f->path, i, sc->name, j, d->shader, names ? names : "?");
                free(names);
                return false;
            }
            if (d->uniform_count != info->uniform_count) {
                sc_msg_set(err,
                           "%s: scenes[%zu] ('%s'), draws[%zu]: shader '%s' takes %d uniform%s, "
                           "and 'uniforms' has %d",
                           f->path, i, sc->name, j, d->shader, info->uniform_count,
                           info->uniform_count == 1 ? "" : "s", d->uniform_count);
                return false;
            }
            if (d->shader_texture_count < info->desc.texture_count) {
                sc_msg_set(err,
                           "%s: scenes[%zu] ('%s'), draws[%zu]: shader '%s' samples %d "
                           "texture%s, and 'textures' names %d",
                           f->path, i, sc->name, j, d->shader, info->desc.texture_count,
                           info->desc.texture_count == 1 ? "" : "s", d->shader_texture_count);
                return false;
            }
        }
    }
    return true;
}

void sc_shaders_close(sc_shaders *s) {
    if (!s) return;
    for (size_t i = 0; i < s->library_count; i++) {
        free(s->sources[i]);
        if (s->handles[i]) dlclose(s->handles[i]);
    }
    free(s->sources);
    free(s->handles);
    free(s->shaders);
    free(s);
}

bool sc_shaders_prepare(sc_shaders **out, sgSimd simd, const char *const *libs, int nlibs,
                        const sc_file *files, int nfiles, sc_msg *err) {
    bool ok = sc_shaders_open(out, simd, err);
    for (int i = 0; ok && i < nlibs; i++) ok = sc_shaders_load(*out, libs[i], err);
    for (int i = 0; ok && i < nfiles; i++) ok = sc_shaders_check(*out, &files[i], err);
    if (!ok) {
        sc_shaders_close(*out);
        *out = NULL;
    }
    return ok;
}
