/* scene_keys.h - warnings for the unknown keys of a scene file (scene_keys.c). */
#ifndef SC_SCENE_KEYS_H
#define SC_SCENE_KEYS_H

#include <stdbool.h>

#include <cJSON.h>

#include "scene.h"

/** Adds to f->warnings one message per unknown key of root, parsed from text (len bytes), naming
 *  f->path, the key's line and path, with "did you mean" for a known key one edit away; false: out
 *  of memory. */
bool sc_check_keys(const char *text, size_t len, const cJSON *root, sc_file *f);

/** Prints f's warnings to stderr as "PROGRAM: warning: ..."; with strict, as errors, and then
 *  returns false when there was any (the caller renders nothing and exits 1). */
bool sc_report_warnings(const sc_file *f, const char *program, bool strict);

#endif
