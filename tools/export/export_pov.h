/* export_pov.h - writes a parsed scene as POV-Ray 3.7 SDL that shades every object with the
 * library's models through povray_macros/abrdf.inc (docs/POVRAY.md).
 *
 *   export_pov_write   the .pov text for a prepared scene
 *
 * The camera is the built-in renderer's pinhole exactly (render.h): POV-Ray's perspective
 * camera with explicit direction/right/up vectors traces pixel centres, so rendering at k
 * times the resolution and averaging k x k blocks reproduces `abrdf render --spp k*k`
 * sample for sample. POV-Ray is left-handed: every position and direction is written with
 * z negated, which mirrors the world and leaves the image unchanged. */
#ifndef ABRDF_EXPORT_POV_H
#define ABRDF_EXPORT_POV_H

#include <stdio.h>
#include "hair_store.h"
#include "render.h"

typedef struct export_pov_options {
    int lit; /* 1: one light through POV-Ray's light_source (its shadows); 0: emissive, no shadows */
    int passes; /* several lights, shadows by passes: the file renders light k through POV-Ray's
                   light_source when povray is given Declare=Abrdf_Pass=k (ambient in pass 0),
                   and every light emissively without shadows when it is not; the images of
                   the passes sum to the scene's (docs/POVRAY.md) */
    int native; /* POV-Ray's own finishes (abrdf_native.inc): lambert, phong, blinn_phong;
                         every light a light_source (shadows), directional lights only */
    const char *source; /* scene file name for the header comment */
    const char *notes;  /* NULL, or lines written as comments (the selection's trace) */
    /* huang tables (render_options.hair_tables; NULL: none): a tabulated material i reads
     * the image table_files[i] (a name POV-Ray finds: a file name beside the .pov) that
     * export_pov_table_image's pixels are written to */
    const hair_store *hair_tables;
    const char *const *table_files;
} export_pov_options;

/* Returns 0, or -1 with a message in err (e.g. lit with more than one light, passes with
 * fewer than two or with native). Every string from the scene goes through export_text.h:
 * a path or a name never becomes SDL. */
int export_pov_write(const render_scene *rs, const export_pov_options *opt, FILE *f, char *err,
                     size_t err_size);

/* The distinct huang tables a .pov may read (abrdf_huang.inc, ABRDF__HU_TABLE_MAX): one per
 * material at most, so every scene fits (checked at compile time in export_pov.c). */
#define EXPORT_POV_HUANG_TABLES_MAX 256

/* The image abrdf_huang.inc's Abrdf_Huang_Table reads for a huang table (values: its doubles,
 * header first; sizes: its sizes): width nt np, height 3 nt nv, channel c's block from row
 * c nt nv, the first row at the top, RGB per texel: hi = the half float nearest v s, lo = the
 * half nearest v s - hi, 0, with s = export_pov_table_scale (POV-Ray reads EXR as half
 * floats; hi + lo keeps 22 significant bits where lo is a normal half, else an absolute error
 * of at most 2^-25 / s). *rgb is malloc'd (width height 3 floats, each a
 * half's value). 0, or -1 when out of memory. */
int export_pov_table_image(const double *values, const int sizes[4], float **rgb, int *width,
                           int *height);
/* The power of two the image's values are multiplied by: the largest at most 2^15. */
double export_pov_table_scale(const double *values, const int sizes[4]);

#endif
