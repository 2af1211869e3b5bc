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
#include "render.h"

typedef struct export_pov_options {
    int lit; /* 1: one light through POV-Ray's light_source (its shadows); 0: emissive, no shadows */
    int native;         /* POV-Ray's own finishes (abrdf_native.inc): lambert, phong, blinn_phong;
                         every light a light_source (shadows), directional lights only */
    const char *source; /* scene file name for the header comment */
    const char *notes;  /* NULL, or lines written as comments (the selection's trace) */
} export_pov_options;

/* Returns 0, or -1 with a message in err (e.g. lit with more than one light). Every string
 * from the scene goes through export_text.h: a path or a name never becomes SDL. */
int export_pov_write(const render_scene *rs, const export_pov_options *opt, FILE *f, char *err,
                     size_t err_size);

#endif
