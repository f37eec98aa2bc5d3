/* markup.c - text escaped for XML and HTML (see markup.h). */
#include "markup.h"

#include <stdbool.h>

void rg_put_markup(FILE *f, const char *s, rg_markup kind) {
    bool xml = kind == RG_MARKUP_XML;
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        switch (c) {
        case '&':
            fputs("&amp;", f);
            break;
        case '<':
            fputs("&lt;", f);
            break;
        case '>':
            fputs("&gt;", f);
            break;
        case '"':
            fputs("&quot;", f);
            break;
        case '\'':
            /* &apos; is XML's own; HTML 4 lacks it, so the report uses the numeric form. */
            fputs(xml ? "&apos;" : "&#39;", f);
            break;
        default:
            if (xml && c < 0x20 && c != '\t' && c != '\n' && c != '\r')
                fputc('?', f);
            else
                fputc(c, f);
        }
    }
}
