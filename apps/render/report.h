/* report.h - the HTML report of an image regression run: DIR/index.html, the images it shows
 * (copies of the expected, actual and heat-map images under DIR/img/) and DIR/results.json, the
 * same data for tools. The folder opens from disk with nothing fetched from the network. */
#ifndef RG_REPORT_H
#define RG_REPORT_H

#include <stdbool.h>
#include <stddef.h>

#include "regression.h"

/** The path of a scene's image inside the report folder, "img/<scene>.<kind>.png" (kind:
 *  expected, actual or heat), as a new string; NULL when out of memory. */
char *rg_report_image_name(const char *scene, const char *kind);
/** The command line as a shell would take it back (arguments quoted where needed), for the
 *  report to show; NULL when out of memory. */
char *rg_command_line(int argc, char **argv);
/** Writes the report of n scenes (in run order) into dir (which exists and is writable):
 *  copies the images, then index.html and results.json. `command` is the command line shown,
 *  `golden` the golden folder. On failure err says why. */
bool rg_write_report(const char *dir, const rg_scene *scenes, size_t n, const char *command,
                     const char *golden, sc_msg *err);

#endif
