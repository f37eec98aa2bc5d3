/* markup.h - text escaped for the markup sgapi-render writes: the JUnit XML file (junit.c) and the
 * HTML report (report.c). */
#ifndef RG_MARKUP_H
#define RG_MARKUP_H

#include <stdio.h>

/* Which markup the text goes into: they differ in the apostrophe's entity and in what becomes of
 * control characters. */
typedef enum rg_markup { RG_MARKUP_XML, RG_MARKUP_HTML } rg_markup;

/** Writes s to f with the markup characters escaped, fit for an element or a quoted attribute. In
 *  XML, control characters (which XML 1.0 cannot hold) but tab, newline and CR become '?'. */
void rg_put_markup(FILE *f, const char *s, rg_markup kind);

#endif
