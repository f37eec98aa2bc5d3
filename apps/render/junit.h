/* junit.h - the results of an image regression run as JUnit XML, the form CI systems (GitLab,
 * Jenkins, GitHub test-report actions) show: one testsuite per scene file, one testcase per scene.
 */
#ifndef RG_JUNIT_H
#define RG_JUNIT_H

#include <stdbool.h>
#include <stddef.h>

#include "regression.h"

/** Writes the JUnit file of n scenes (in run order): classname the suite, name the scene, time the
 *  render time, a <failure> with the reason for each failing scene, and the paths of its actual
 *  image and heat map as [[ATTACHMENT|path]] lines in <system-out> (the report's copies when
 *  report_dir is not NULL). On failure err says why. */
bool rg_write_junit(const char *path, const rg_scene *scenes, size_t n, const char *report_dir,
                    sc_msg *err);

#endif
