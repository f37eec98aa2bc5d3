/* text_scan.c - error messages and tokens of the model loaders (see text_scan.h). */
#include "text_scan.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bool ts_fail(ts_source *src, const char *fmt, ...) {
    if (!src->err) return false;
    if (src->line)
        sc_msg_set(src->err, "%s:%zu: ", src->name, src->line);
    else
        sc_msg_set(src->err, "%s: ", src->name);
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vappend(src->err, fmt, ap);
    va_end(ap);
    return false;
}

bool ts_is_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

bool ts_next_token(const char **s, const char *e, const char **tb, const char **te) {
    const char *q = *s;
    while (q < e && ts_is_space(*q)) q++;
    if (q == e) return false;
    *tb = q;
    while (q < e && !ts_is_space(*q)) q++;
    *te = *s = q;
    return true;
}

bool ts_token_is(const char *tb, const char *te, const char *word) {
    size_t n = strlen(word);
    return (size_t)(te - tb) == n && memcmp(tb, word, n) == 0;
}

char *ts_copy_trimmed(const char *s, const char *e) {
    while (s < e && ts_is_space(*s)) s++;
    while (e > s && ts_is_space(e[-1])) e--;
    char *r = malloc((size_t)(e - s) + 1);
    if (r) {
        memcpy(r, s, (size_t)(e - s));
        r[e - s] = '\0';
    }
    return r;
}

size_t ts_bom_length(const char *text, size_t len) {
    /* Editors on some systems start a UTF-8 file with one. */
    return len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0 ? 3 : 0;
}

bool ts_parse_number(ts_source *src, const char *tb, const char *te, float *out, bool *integer) {
    /* strtof needs a NUL-terminated string, so the token is copied; no valid number is this
     * long. */
    char buf[64];
    size_t n = (size_t)(te - tb);
    if (n >= sizeof buf) return ts_fail(src, "number too long: '%.20s...'", tb);
    memcpy(buf, tb, n);
    buf[n] = '\0';
    char *end;
    float f = strtof(buf, &end);
    if (end != buf + n) return ts_fail(src, "not a number: '%s'", buf);
    /* "nan" and "inf" spelled out pass through: the renderer drops such triangles, and test
     * scenes need a way to say so. A finite-looking number that overflows is an error. */
    if (!isfinite(f) && !strpbrk(buf, "nNiI"))
        return ts_fail(src, "number out of range: '%s'", buf);
    *out = f;
    if (integer) *integer = !strpbrk(buf, ".eEnNiI");
    return true;
}
