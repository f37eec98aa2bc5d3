/* json_lines.h - the line of each value of a parsed JSON text (cJSON keeps no positions), so a
 * message about a key can name the line an editor opens (json_lines.c). */
#ifndef SC_JSON_LINES_H
#define SC_JSON_LINES_H

#include <stdbool.h>
#include <stddef.h>

#include <cJSON.h>

typedef struct sc_json_line_of {
    const cJSON *node;
    int line; /* where node starts (an object member: its key), from 1 */
} sc_json_line_of;

typedef struct sc_json_lines {
    sc_json_line_of *at; /* sorted by node address */
    size_t count;
} sc_json_lines;

/** Walks text (len bytes, which cJSON parsed into root) beside root and records each value's line;
 *  false only when out of memory. A text the walk cannot follow leaves out what it missed. */
bool sc_json_lines_build(const char *text, size_t len, const cJSON *root, sc_json_lines *out);

/** The line of node (a value of the tree the lines were built from), or 0 when not known. */
int sc_json_line(const sc_json_lines *l, const cJSON *node);

/** Frees what sc_json_lines_build allocated; l is left empty. */
void sc_json_lines_free(sc_json_lines *l);

#endif
