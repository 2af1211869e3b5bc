/* pov_ported.h - whether the POV-Ray port has a model: povray_macros/abrdf_models.inc
 * defines its function abrdf_<model> (the rule tools/gen_pov_params.py uses). Shared by the
 * cross-check tools, which list the other models as "no POV-Ray twin" instead of rendering. */
#ifndef ABRDF_POV_PORTED_H
#define ABRDF_POV_PORTED_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 1 if INC_DIR/abrdf_models.inc has a line "#declare abrdf_NAME = function", else 0. */
static inline int pov_ported(const char *inc_dir, const char *name)
{
    char path[4096], want[256], line[1024];
    snprintf(path, sizeof path, "%s/abrdf_models.inc", inc_dir);
    snprintf(want, sizeof want, "#declare abrdf_%s = function", name);
    FILE *f = fopen(path, "r");
    int found = 0;
    while (f && !found && fgets(line, sizeof line, f)) found = strncmp(line, want, strlen(want)) == 0;
    if (f) fclose(f);
    return found;
}

#endif
