/* text_scan.h - what the line-based model loaders (obj.c, mtl.c, off.c) share: the place an error
 * is reported at, and cutting a line into tokens and numbers. Internal to the loaders.
 */
#ifndef SC_TEXT_SCAN_H
#define SC_TEXT_SCAN_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"

/* Where a loader is in its file, and where its error message goes; each parser embeds one. */
typedef struct ts_source {
    const char *name; /* the file as messages name it */
    size_t line;      /* 1-based; 0 for what concerns the whole file */
    sc_msg *err;      /* the caller's message; may be NULL */
} ts_source;

/** Formats "name:line: message" (or "name: message" when line is 0) into src->err; always
 *  returns false, so a parser can `return ts_fail(...)`. */
bool ts_fail(ts_source *src, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);

/** A blank within a line: space, tab, CR, vertical tab, form feed (never the newline). */
bool ts_is_space(char c);

/** Next blank-separated token of [*s, e) into [*tb, *te), *s moved past it; false when none is
 *  left (then *s is unchanged). */
bool ts_next_token(const char **s, const char *e, const char **tb, const char **te);

/** Whether the token [tb, te) is exactly word. */
bool ts_token_is(const char *tb, const char *te, const char *word);

/** [s, e) with blanks trimmed at both ends, as a new string; NULL when out of memory. */
char *ts_copy_trimmed(const char *s, const char *e);

/** How many bytes of a UTF-8 byte-order mark text starts with: 3 or 0. */
size_t ts_bom_length(const char *text, size_t len);

/** One number token into *out: an error naming it when it is not a number or overflows, but
 *  "nan" and "inf" spelled out pass. With integer non-NULL, *integer tells whether it was written
 *  as an integer (no point, no exponent). */
bool ts_parse_number(ts_source *src, const char *tb, const char *te, float *out, bool *integer);

#endif
