/* measured_standin.h - measured materials for the hosts (`abrdf export`): POV-Ray and Cycles
 * cannot read a measured table, so each material with a `measured` lobe is exported as the
 * analytic stand-in fitted to its table (abrdf_fit_to), its fit's errors written into the
 * file's comments (docs/MEASURED.md, "In other renderers").
 *
 *   measured_standins  replace every measured lobe of a scene by its fitted stand-in
 */
#ifndef ABRDF_MEASURED_STANDIN_H
#define ABRDF_MEASURED_STANDIN_H

#include <stddef.h>
#include <stdio.h>

#include "scene.h"

/* For every material of s with a measured lobe: the best of a few candidates by predicted
 * image NMSE against the table (a diffuse + specular pair for a table alone; a specular lobe
 * beside the material's own diffuse lobe), written into the material (its lobes and
 * parameters; it no longer reads the table), one comment line per material into notes. 0, or
 * -1 with one line in err. */
int measured_standins(scene *s, FILE *notes, char *err, size_t err_size);

#endif
