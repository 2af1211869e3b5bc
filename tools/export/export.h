/* export.h - writers of the same scene for other renderers (`abrdf export`). Each takes the
 * parsed scene and the renderer's prepared view of it (render_prepare: camera vectors,
 * materials with their ambient term, light irradiances), so an exported scene uses the very
 * numbers the built-in renderer uses.
 *
 * PUBLIC FUNCTIONS
 *   export_cycles   a Blender/Cycles (bpy) Python script (tools/export/export_cycles.c)
 */
#ifndef ABRDF_EXPORT_H
#define ABRDF_EXPORT_H

#include <stdio.h>
#include "render.h"

typedef struct export_options {
    const char *scene_path; /* for the header comment */
    const char *osl_dir;    /* directory holding abrdf_osl.h, abrdf_trace.h, abrdf_material.osl */
    int spp;                /* samples per pixel of the host renderer */
    const char *mode;       /* default mode of the script: "eval" or "closure" */
    const char *notes;      /* NULL, or lines written as comments (the selection's trace) */
    const hair_store *hair_tables; /* the huang tables render_prepare read (the materials it
                                    * tabulated), written beside the script; NULL: none */
} export_options;

/* Write the script to f; returns 0, or -1 with a message in err. */
int export_cycles(FILE *f, const render_scene *rs, const export_options *opt, char *err,
                  size_t err_size);

#endif
