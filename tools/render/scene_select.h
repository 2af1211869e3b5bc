/* scene_select.h - resolve a scene's material-table and adaptive materials into explicit
 * models with the paper's flowchart (abrdf_select), or give every material the model of
 * --model, before rendering or exporting. */
#ifndef ABRDF_SCENE_SELECT_H
#define ABRDF_SCENE_SELECT_H

#include <stdio.h>
#include "abrdf_fit.h"
#include "hair_store.h"
#include "materials.h"
#include "pbr_select.h"
#include "scene.h"

/* How a scene's materials are chosen, from the command line to the selection in one piece:
 * forced, every material (explicit ones included: their parameters describe the material)
 * is chosen by `all`; otherwise each table= material by the photoreal flowchart and each
 * adaptive one by its own goal= or budget=. */
/* The roughness values of a pbr material's roughness map with their shares of the texels
 * (pbr_select.h: the factor times each texel value): 0, or -1 with one line in err. */
typedef int (*scene_map_range_fn)(void *user, const scene_material *sm, pbr_range *out, char *err,
                                  size_t err_size);

typedef struct scene_selection {
    int forced;                /* every material by `all` (--adaptive) */
    select_request all;        /* with forced */
    const char *const *tables; /* material-table files merged over data/materials.csv */
    int table_count;
    int spp; /* the image's samples per pixel: the budget's view */
    /* A pbr material with a roughness map is chosen over the map's values (pbr_select.h)
     * through this; NULL: such a material is refused (the selection cannot see its texels). */
    scene_map_range_fn map_range;
    void *map_user;
    /* 1: predict a budget on the scene's own shading points (scene_points.h: a pass over the
     * camera's pixels, each material's visible hits and the lights that reach them), falling
     * back to scene_budget_view's sphere for a material with none; 0: on the sphere */
    int points;
    /* Not NULL: a budget whose reference is huang alone (a material without texture maps) is
     * predicted against huang's table from this store (hair_store_get; abrdf_budget.reference,
     * its cost hair_store_cost), so that the render reads the same table; NULL: against the
     * per-call quadrature. */
    hair_store *hair_tables;
} scene_selection;

/* A selection that forces nothing, reads no extra table, predicts on the sphere at 4
 * samples/pixel and reads no texture. */
#define SCENE_SELECTION_INIT                                                                       \
    {                                                                                              \
        0, {0, ABRDF_GOAL_PHOTOREAL, 0.0}, NULL, 0, 4, NULL, NULL, 0, NULL                         \
    }

/* Every SCENE_MAT_TABLE / SCENE_MAT_ADAPTIVE material of s (every material, forced) becomes
 * SCENE_MAT_MODELS with the selection's diffuse + specular models and parameters: the
 * flowchart's (abrdf_select) for a goal, the budget mode's (abrdf_select_budget, predicted on
 * the scene's shading points with how->points, else on scene_budget_view; the ambient
 * reflectance stays the reference's) for a budget. `table`
 * (how->tables are not read here) may be NULL if no material names an entry. If explain is
 * not NULL, each choice is printed with the selection's trace (a budget's with a line naming
 * the prediction's view). Returns 0, or -1 with
 * "SCENE:LINE: problem" in err. */
int scene_select(scene *s, const char *scene_name, const scene_selection *how,
                 const mat_table *table, FILE *explain, char *err, size_t err_size);

/* The prediction's view of a budget material in scene s (abrdf_view, abrdf_fit.h): the
 * analytic sphere seen from the camera (view_dir toward it, up its up), sampled as finely as
 * the render samples a unit sphere at the camera's target (rows * sqrt(spp) over the view's
 * height at that distance), under the scene's lights (a point light as the directional light
 * it casts at the camera's target; no light: the default set). lights: room for
 * SCENE_MAX_LIGHTS entries, referenced by v. */
void scene_budget_view(const scene *s, int spp, abrdf_view *v, abrdf_light_dir *lights);

/* Does any material name an entry of the material table? */
int scene_needs_table(const scene *s);

/* scene_select with the material table loaded as `abrdf render` and `abrdf export` do:
 * data/materials.csv (data_path.h) if a material names an entry or the selection is forced,
 * then each of how->tables merged over it. Returns 0, or -1 with the message. */
int scene_resolve(scene *s, const char *scene_name, const scene_selection *how, FILE *explain,
                  char *err, size_t err_size);

/* Every material becomes the single model `model`, keeping parameter values it shares
 * with the old models (kd, ks, f0, r, n, ...). Returns 0 or -1 with a message. */
int scene_replace_models(scene *s, abrdf_model model, char *err, size_t err_size);

/* --model NAME [--set NAME=VALUE ...] of `abrdf render` and `abrdf export`: every material of
 * s becomes model_name (scene_replace_models), then each assignment is applied to every
 * material. Returns 0; CLI_EXIT_USAGE for an unknown model or a bad assignment; 1 if the
 * scene cannot take the model. Messages go to stderr as "abrdf CMD: ...". */
int scene_set_model(const char *cmd, scene *s, const char *model_name, const char *const *sets,
                    int nsets);

#endif
