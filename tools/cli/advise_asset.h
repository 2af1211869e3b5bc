/* advise_asset.h - `abrdf advise FILE.gltf|FILE.glb|FILE.mtlx|FILE.scene`: the choice for
 * every glTF-style (`pbr`) material of a file, each with its trace (advise_asset.c). */
#ifndef ABRDF_ADVISE_ASSET_H
#define ABRDF_ADVISE_ASSET_H

#include "abrdf_fit.h"
#include "materials.h"
#include "scene.h"
#include "select_trace.h"

/* Is `name` a file `abrdf advise` reads whole (by its extension) rather than a table entry? */
int advise_is_asset(const char *name);

/* The printer of one flowchart choice (cmd_advise.c's; e: the material's name and source). */
typedef void (*advise_printer)(const abrdf_selection *s, const abrdf_params *p,
                               const select_trace *trace, const mat_entry *e,
                               const abrdf_tolerance *tol, int json);

/* Every pbr material of the file `path`: the flowchart's choice for rq's goal (over the
 * roughness map's values for a textured one), or the budget mode's for rq's budget, printed
 * by print as text or (json) in one JSON object {"file", "materials": [...]}. costs NULL:
 * the paper's table (the built-in one for a budget). Returns the exit status. */
int advise_asset(const char *path, const select_request *rq, const abrdf_tolerance *tol,
                 const abrdf_costs *costs, int json, advise_printer print);

/* The materials of an asset file as a scene: .scene and .gltf/.glb through their readers,
 * .mtlx through the Python package's MaterialX reader (python -m abrdf.scene_materials; the
 * interpreter is $ABRDF_PYTHON, else python3). 0, or -1 with one line in err. */
int advise_asset_load(const char *path, scene *out, char *err, size_t err_size);

#endif
