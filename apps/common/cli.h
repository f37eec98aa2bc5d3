/* cli.h - reading numbers from command-line arguments, the same way in every app. */
#ifndef SC_CLI_H
#define SC_CLI_H

#include <stdbool.h>

/** A whole decimal number in [lo, hi], nothing else in the string. */
bool sc_parse_int(const char *s, int lo, int hi, int *out);
/** A finite number >= lo, nothing else in the string. */
bool sc_parse_double(const char *s, double lo, double *out);

#endif
