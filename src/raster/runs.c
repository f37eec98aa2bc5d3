/* runs.c - shading the runs a bin collected, triangle by triangle (see runs.h). */
#include "raster/runs.h"

#include "raster/framebuffer.h"

void sg_runs_flush(const sg_bin_pass *p, sg_run_set *s, const sg_run_target *to) {
    uint16_t start[SG_RUN_CAP];
    sg_run sorted[SG_RUN_CAP];
    uint64_t sorted_samples[SG_RUN_CAP];
    int at = 0;
    for (int g = 0; g < s->groups; g++) {
        start[g] = (uint16_t)at;
        at += s->group_n[g];
    }
    if (to->planes)
        for (int i = 0; i < s->n; i++) {
            const int j = start[s->run_group[i]]++;
            sorted[j] = s->run[i];
            sorted_samples[j] = s->samples[i];
        }
    else
        for (int i = 0; i < s->n; i++) sorted[start[s->run_group[i]]++] = s->run[i];
    at = 0;
    for (int g = 0; g < s->groups; g++) {
        const sg_tri *t = &p->binner->tris[s->group_id[g] - 1];
        const sg_draw_state *d = &p->draws[t->draw];
        d->runs_fn(&d->ctx, t, to->x0, to->y0, sorted + at, s->group_n[g], to->color);
        if (to->planes) /* before the next group's pixels take the scratch plane's place */
            for (int i = at; i < at + s->group_n[g]; i++) {
                const size_t base = (size_t)sorted[i].tile * SG_TILE_PIXELS;
                p->fb->put_samples(to->planes, base, to->color + base, sorted_samples[i]);
            }
        at += s->group_n[g];
        s->slot[s->group_slot[g]] = 0;
    }
    s->n = s->groups = 0;
}
