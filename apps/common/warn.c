/* warn.c - once-per-kind warnings of the model loaders. */
#include "warn.h"

#include <stdarg.h>
#include <stdio.h>

void sc_warn(sc_warnings *w, unsigned kind, const char *fmt, ...) {
    if (!w || (w->kinds & kind) || w->count >= SC_MAX_WARNINGS) return;
    w->kinds |= kind;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(w->text[w->count++], SC_WARNING_LENGTH, fmt, ap);
    va_end(ap);
}
