/* shader_lib_standin.c - a minimal shader registry (apps/common/shader_lib.h) for sgapi-ref alone,
 * built only while the shared one (apps/common/shader_lib.c) is not in the tree: no built-in
 * shaders, only the libraries given with --shaders. It goes away when the shared one lands. */
#define _POSIX_C_SOURCE 200809L

#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

#include "shader_lib.h"

struct sc_shaders {
    void **handles; /* dlopen handles, one per library */
    size_t handle_count;
    const sgShaderInfo **shaders; /* every shader known, in the order they were added */
    size_t shader_count;
};

bool sc_shaders_open(sc_shaders **out, sc_msg *err) {
    *out = calloc(1, sizeof **out);
    if (!*out) sc_msg_set(err, "out of memory");
    return *out != NULL;
}

bool sc_shaders_load(sc_shaders *s, const char *path, sc_msg *err) {
    /* Lazy: sgapi-ref runs the twins, never the C stages, so what they call (sgSample) need
     * not be there. */
    /* A bare name is a file here, not one for dlopen's library search. */
    char *file = strchr(path, '/') ? sc_format("%s", path) : sc_format("./%s", path);
    if (!file) {
        sc_msg_set(err, "out of memory");
        return false;
    }
    void *h = dlopen(file, RTLD_LAZY | RTLD_LOCAL);
    free(file);
    if (!h) {
        sc_msg_set(err, "%s: cannot load the shader library: %s", path, dlerror());
        return false;
    }
    /* POSIX allows this cast from dlsym's void *. */
    sgShaderLibraryFn fn;
    *(void **)&fn = dlsym(h, SGAPI_SHADER_LIBRARY_SYMBOL);
    const sgShaderLibrary *lib = fn ? fn() : NULL;
    const char *why = !fn    ? "has no " SGAPI_SHADER_LIBRARY_SYMBOL " function"
                      : !lib ? "returned no library"
                             : NULL;
    if (!why && lib->abi_version != SGAPI_SHADER_ABI_VERSION) why = "is of another ABI version";
    if (!why && (lib->count < 0 || (lib->count > 0 && !lib->shaders))) why = "lists no shaders";
    if (why) {
        sc_msg_set(err, "%s: the shader library %s", path, why);
        dlclose(h);
        return false;
    }
    void **handles = realloc(s->handles, (s->handle_count + 1) * sizeof *handles);
    const sgShaderInfo **shaders =
        realloc(s->shaders, (s->shader_count + (size_t)lib->count + 1) * sizeof *shaders);
    if (handles) s->handles = handles;
    if (shaders) s->shaders = shaders;
    if (!handles || !shaders) {
        sc_msg_set(err, "out of memory");
        dlclose(h);
        return false;
    }
    for (int i = 0; i < lib->count; i++) {
        const sgShaderInfo *info = &lib->shaders[i];
        if (!info->name || sc_shaders_find(s, info->name)) {
            sc_msg_set(err, "%s: shader '%s' is known already", path,
                       info->name ? info->name : "(null)");
            dlclose(h);
            return false;
        }
    }
    for (int i = 0; i < lib->count; i++) s->shaders[s->shader_count++] = &lib->shaders[i];
    s->handles[s->handle_count++] = h;
    return true;
}

const sgShaderInfo *sc_shaders_find(const sc_shaders *s, const char *name) {
    for (size_t i = 0; i < s->shader_count; i++)
        if (strcmp(s->shaders[i]->name, name) == 0) return s->shaders[i];
    return NULL;
}

bool sc_shaders_check(const sc_shaders *s, const sc_file *f, sc_msg *err) {
    for (size_t si = 0; si < f->scene_count; si++)
        for (size_t di = 0; di < f->scenes[si].draw_count; di++) {
            const sc_draw *d = &f->scenes[si].draws[di];
            if (!d->shader) continue;
            const sgShaderInfo *info = sc_shaders_find(s, d->shader);
            if (!info) {
                sc_msg_set(err, "%s: scene '%s', draw %zu: unknown shader '%s' (known:", f->path,
                           f->scenes[si].name, di, d->shader);
                for (size_t i = 0; i < s->shader_count; i++)
                    sc_msg_append(err, " %s", s->shaders[i]->name);
                sc_msg_append(err, "%s)", s->shader_count ? "" : " none");
                return false;
            }
            if (info->uniform_count != d->uniform_count) {
                sc_msg_set(err, "%s: scene '%s', draw %zu: shader '%s' takes %d uniforms, got %d",
                           f->path, f->scenes[si].name, di, d->shader, info->uniform_count,
                           d->uniform_count);
                return false;
            }
        }
    return true;
}

void sc_shaders_close(sc_shaders *s) {
    if (!s) return;
    for (size_t i = 0; i < s->handle_count; i++) dlclose(s->handles[i]);
    free(s->handles);
    free(s->shaders);
    free(s);
}
