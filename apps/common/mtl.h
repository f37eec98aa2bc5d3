/* mtl.h - Wavefront material libraries (.mtl): the diffuse colour, its texture and the opacity of
 * each material, and the specular colour and exponent, for the OBJ files that name them.
 *
 * API-neutral, like obj.h.
 */
#ifndef SC_MTL_H
#define SC_MTL_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"
#include "warn.h"

/* One material (newmtl). */
typedef struct sc_material {
    char *name;        /* as written after newmtl (may hold spaces) */
    float diffuse[3];  /* Kd; default 1, 1, 1 */
    float alpha;       /* d, or 1 - Tr; default 1 */
    float specular[3]; /* Ks; default 0, 0, 0 */
    float shininess;   /* Ns, clamped to 0..128; default 0 */
    char *diffuse_map; /* map_Kd's file name, '\' turned into '/', or NULL */
} sc_material;

typedef struct sc_mtl {
    sc_material *materials;
    size_t count;
} sc_mtl;

/** Parses MTL text; name is used in messages. A malformed value is an error naming the line;
 *  statements that are not used are ignored with one warning per file. */
bool sc_mtl_parse(const char *name, const char *text, size_t len, sc_mtl *out,
                  sc_warnings *warnings, sc_msg *err);
/** Reads and parses an MTL file (see sc_mtl_parse). */
bool sc_mtl_load(const char *path, sc_mtl *out, sc_warnings *warnings, sc_msg *err);
/** The material of that name, or NULL. */
const sc_material *sc_mtl_find(const sc_mtl *mtl, const char *name);
/** Frees a library and zeroes it; a zeroed one is fine. */
void sc_mtl_free(sc_mtl *mtl);

#endif
