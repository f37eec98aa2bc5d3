/* light.c - a draw's lights and material, checked and prepared once per draw, and the normal
 * matrix (see light.h). */
#include "pipeline/light.h"

#include <stdarg.h>

static bool finite_nonneg(const float *v, int n) {
    for (int i = 0; i < n; i++)
        if (!(v[i] >= 0.0f && v[i] <= FLT_MAX)) return false; /* false for NaN */
    return true;
}

static bool finite3(const float *v) {
    for (int i = 0; i < 3; i++)
        if (!(v[i] >= -FLT_MAX && v[i] <= FLT_MAX)) return false;
    return true;
}

/* Tells fail why, when there is one to tell; false. */
static bool refuse(sg_light_fail_fn fail, void *user, int code, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static bool refuse(sg_light_fail_fn fail, void *user, int code, const char *fmt, ...) {
    if (!fail) return false;
    va_list ap;
    va_start(ap, fmt);
    fail(user, code, fmt, ap);
    va_end(ap);
    return false;
}

#define FAIL(c, ...) return refuse(fail, user, (c), __VA_ARGS__)

bool sg_light_prepare(const sgLighting *in, const float specular[3], float shininess,
                      sg_lights *out, sg_light_fail_fn fail, void *user) {
    memset(out, 0, sizeof *out);
    if (!finite_nonneg(specular, 3))
        FAIL(SG_ERROR_INVALID_VALUE, "params->specular must be 3 finite values >= 0");
    if (!(shininess >= 0.0f && shininess <= 128.0f))
        FAIL(SG_ERROR_INVALID_VALUE, "params->shininess = %g is outside [0, 128]",
             (double)shininess);
    memcpy(out->specular, specular, sizeof out->specular);
    out->shininess = shininess;
    out->has_specular = specular[0] > 0.0f || specular[1] > 0.0f || specular[2] > 0.0f;
    if (!in) return true;
    if (in->light_count < 0 || in->light_count > SG_MAX_LIGHTS)
        FAIL(SG_ERROR_INVALID_COUNT, "params->lighting->light_count = %d is outside 0..%d",
             in->light_count, SG_MAX_LIGHTS);
    if (!finite_nonneg(in->ambient, 3))
        FAIL(SG_ERROR_INVALID_VALUE, "params->lighting->ambient must be 3 finite values >= 0");
    memcpy(out->ambient, in->ambient, sizeof out->ambient);
    out->count = in->light_count;
    for (int i = 0; i < in->light_count; i++) {
        const sgLight *l = &in->lights[i];
        if (l->type != SG_LIGHT_DIRECTIONAL && l->type != SG_LIGHT_POINT)
            FAIL(SG_ERROR_INVALID_ENUM,
                 "params->lighting->lights[%d].type = %d is not an sgLightType", i, (int)l->type);
        if (!finite_nonneg(l->color, 3))
            FAIL(SG_ERROR_INVALID_VALUE,
                 "params->lighting->lights[%d].color must be 3 finite values >= 0", i);
        memcpy(out->light[i].color, l->color, sizeof l->color);
        if (l->type == SG_LIGHT_DIRECTIONAL) {
            if (!finite3(l->direction))
                FAIL(SG_ERROR_INVALID_VALUE,
                     "params->lighting->lights[%d].direction must be 3 finite values", i);
            /* In double, so that a tiny but non-zero direction still normalises. */
            double d[3] = {l->direction[0], l->direction[1], l->direction[2]};
            double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            if (!(len > 0.0))
                FAIL(SG_ERROR_INVALID_VALUE, "params->lighting->lights[%d].direction is zero", i);
            for (int k = 0; k < 3; k++) out->light[i].v[k] = (float)(-d[k] / len);
        } else {
            if (!finite3(l->position))
                FAIL(SG_ERROR_INVALID_VALUE,
                     "params->lighting->lights[%d].position must be 3 finite values", i);
            if (!finite_nonneg(l->attenuation, 3))
                FAIL(SG_ERROR_INVALID_VALUE,
                     "params->lighting->lights[%d].attenuation must be 3 finite values >= 0", i);
            out->light[i].point = 1;
            memcpy(out->light[i].v, l->position, sizeof l->position);
            memcpy(out->light[i].att, l->attenuation, sizeof l->attenuation);
            /* All zero (a zero-initialised light): no attenuation. */
            if (l->attenuation[0] == 0.0f && l->attenuation[1] == 0.0f && l->attenuation[2] == 0.0f)
                out->light[i].att[0] = 1.0f;
        }
    }
    return true;
}

void sg_normal_matrix(const float wv[16], float out[9]) {
    double a[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = wv[r * 4 + c];
    /* cof[r][c] is the cofactor of a[r][c]: inverse transpose = cofactors / determinant. */
    double cof[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, c1 = (c + 1) % 3, c2 = (c + 2) % 3;
            cof[r][c] = a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1];
        }
    double det = a[0][0] * cof[0][0] + a[0][1] * cof[0][1] + a[0][2] * cof[0][2];
    bool ok = det != 0.0 && isfinite(det);
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) {
            double v = ok ? cof[r][c] / det : 0.0;
            out[r * 3 + c] = isfinite(v) ? (float)v : 0.0f;
        }
}
