/* json_lines.c - the line of each value of a parsed JSON text. cJSON builds the tree without
 * positions; the text is walked again beside the tree (members and elements come in text order),
 * and each node's line is kept in a table sorted by the node's address for lookups. */
#include "json_lines.h"

#include <stdint.h>
#include <stdlib.h>

typedef struct scan {
    const char *p, *end;
    int line;
    sc_json_lines *out;
    size_t cap;
    bool oom;
} scan;

static void skip_ws(scan *s) {
    /* what cJSON skips: every byte up to the space */
    while (s->p < s->end && (unsigned char)*s->p <= 32) s->line += *s->p++ == '\n';
}

/* Past a string that starts at s->p ('"'); false when it does not end. */
static bool skip_string(scan *s) {
    for (s->p++; s->p < s->end; s->p++) {
        if (*s->p == '\\') {
            if (++s->p == s->end) return false;
        } else if (*s->p == '"') {
            s->p++;
            return true;
        }
        s->line += *s->p == '\n';
    }
    return false;
}

static bool record(scan *s, const cJSON *node, int line) {
    sc_json_lines *o = s->out;
    if (o->count == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 64;
        sc_json_line_of *at = realloc(o->at, cap * sizeof *at);
        if (!at) {
            s->oom = true;
            return false;
        }
        o->at = at;
        s->cap = cap;
    }
    o->at[o->count++] = (sc_json_line_of){node, line};
    return true;
}

/* Past the value of node, recording its children; false when the text does not follow the tree
 * (or out of memory). */
static bool walk(scan *s, const cJSON *node) {
    skip_ws(s);
    if (s->p == s->end) return false;
    if (cJSON_IsObject(node) || cJSON_IsArray(node)) {
        const bool object = cJSON_IsObject(node);
        if (*s->p != (object ? '{' : '[')) return false;
        s->p++;
        for (const cJSON *c = node->child; c; c = c->next) {
            skip_ws(s);
            if (s->p == s->end) return false;
            if (c != node->child) {
                if (*s->p != ',') return false;
                s->p++;
                skip_ws(s);
                if (s->p == s->end) return false;
            }
            if (!record(s, c, s->line)) return false;
            if (object) {
                if (*s->p != '"' || !skip_string(s)) return false;
                skip_ws(s);
                if (s->p == s->end || *s->p != ':') return false;
                s->p++;
            }
            if (!walk(s, c)) return false;
        }
        skip_ws(s);
        if (s->p == s->end || *s->p != (object ? '}' : ']')) return false;
        s->p++;
        return true;
    }
    if (cJSON_IsString(node)) return *s->p == '"' && skip_string(s);
    /* a number, true, false or null */
    while (s->p < s->end && (unsigned char)*s->p > 32 && *s->p != ',' && *s->p != ']' &&
           *s->p != '}')
        s->p++;
    return true;
}

static int by_address(const void *a, const void *b) {
    uintptr_t x = (uintptr_t)((const sc_json_line_of *)a)->node;
    uintptr_t y = (uintptr_t)((const sc_json_line_of *)b)->node;
    return (x > y) - (x < y);
}

bool sc_json_lines_build(const char *text, size_t len, const cJSON *root, sc_json_lines *out) {
    *out = (sc_json_lines){0};
    scan s = {.p = text, .end = text + len, .line = 1, .out = out};
    skip_ws(&s);
    if (!record(&s, root, s.line)) goto oom;
    walk(&s, root); /* what it could follow is recorded */
    if (s.oom) goto oom;
    qsort(out->at, out->count, sizeof *out->at, by_address);
    return true;
oom:
    sc_json_lines_free(out);
    return false;
}

int sc_json_line(const sc_json_lines *l, const cJSON *node) {
    size_t lo = 0, hi = l->count;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if ((uintptr_t)l->at[mid].node < (uintptr_t)node)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo < l->count && l->at[lo].node == node ? l->at[lo].line : 0;
}

void sc_json_lines_free(sc_json_lines *l) {
    free(l->at);
    *l = (sc_json_lines){0};
}
