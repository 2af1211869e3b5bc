/* pov_ported.h - whether the POV-Ray port has a model: povray_macros/abrdf_models.inc, or the
 * model's own include abrdf_<model>.inc (loaded on first use), defines its function
 * abrdf_<model> (the rule tools/gen/pov_includes.py uses). Shared by the cross-check tools,
 * which list the other models as "no POV-Ray twin" instead of rendering. */
#ifndef ABRDF_POV_PORTED_H
#define ABRDF_POV_PORTED_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 1 if INC_DIR/FILE has a line starting with WANT, else 0. */
static inline int pov_has_line(const char *inc_dir, const char *file, const char *want)
{
    char path[4096], line[1024];
    snprintf(path, sizeof path, "%s/%s", inc_dir, file);
    FILE *f = fopen(path, "r");
    int found = 0;
    while (f && !found && fgets(line, sizeof line, f))
        found = strncmp(line, want, strlen(want)) == 0;
    if (f) fclose(f);
    return found;
}

/* 1 if INC_DIR/abrdf_models.inc or INC_DIR/abrdf_NAME.inc has a line
 * "#declare abrdf_NAME = function", else 0. */
static inline int pov_ported(const char *inc_dir, const char *name)
{
    char want[256], own[256];
    snprintf(want, sizeof want, "#declare abrdf_%s = function", name);
    snprintf(own, sizeof own, "abrdf_%s.inc", name);
    return pov_has_line(inc_dir, "abrdf_models.inc", want) || pov_has_line(inc_dir, own, want);
}

#endif
