/* warn.c - once-per-kind warnings of the model loaders. */
#include "warn.h"

#include <stdarg.h>
#include <string.h>

void sc_warn(sc_warnings *w, unsigned kind, const char *fmt, ...) {
    if (!w || (w->kinds & kind) || w->count >= SC_MAX_WARNINGS) return;
    w->kinds |= kind;
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vset(&w->text[w->count++], fmt, ap);
    va_end(ap);
}

void sc_warnings_free(sc_warnings *w) {
    if (!w) return;
    for (int i = 0; i < w->count; i++) sc_msg_free(&w->text[i]);
    memset(w, 0, sizeof *w);
}
