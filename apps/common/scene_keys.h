/* scene_keys.h - warnings for the unknown keys of a scene file (scene_keys.c). */
#ifndef SC_SCENE_KEYS_H
#define SC_SCENE_KEYS_H

#include <stdbool.h>

#include <cJSON.h>

#include "scene.h"

/** Adds to f->warnings one message per unknown key of the parsed file (naming f->path and the
 *  key's path, with "did you mean" for a known key one edit away); false: out of memory. */
bool sc_check_keys(const cJSON *root, sc_file *f);

/** Prints f's warnings to stderr as "PROGRAM: warning: ..."; with strict, as errors, and then
 *  returns false when there was any (the caller renders nothing and exits 1). */
bool sc_report_warnings(const sc_file *f, const char *program, bool strict);

#endif
