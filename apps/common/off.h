/* off.h - Geomview OFF loader (OFF, COFF, NOFF, CNOFF, STOFF and their combinations) producing the
 * same plain meshes as the OBJ loader.
 *
 * API-neutral, like obj.h.
 */
#ifndef SC_OFF_H
#define SC_OFF_H

#include <stdbool.h>
#include <stddef.h>

#include "obj.h"
#include "msg.h"
#include "warn.h"

/** Parses OFF text of len bytes; name is used in messages; warnings (may be NULL) collects what
 *  was ignored, once per kind. On failure *out is zeroed and err names the line. */
bool sc_off_parse(const char *name, const char *text, size_t len, sc_mesh *out,
                  sc_warnings *warnings, sc_msg *err);
/** Reads and parses an OFF file (see sc_off_parse). */
bool sc_off_load(const char *path, sc_mesh *out, sc_warnings *warnings, sc_msg *err);

#endif
