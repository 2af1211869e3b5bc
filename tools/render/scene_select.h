/* scene_select.h - resolve a scene's material-table and adaptive materials into explicit
 * models with the paper's flowchart (abrdf_select), or give every material the model of
 * --model, before rendering or exporting. */
#ifndef ABRDF_SCENE_SELECT_H
#define ABRDF_SCENE_SELECT_H

#include <stdio.h>
#include "abrdf_fit.h"
#include "materials.h"
#include "scene.h"

/* Every SCENE_MAT_TABLE / SCENE_MAT_ADAPTIVE material of s becomes SCENE_MAT_MODELS with the
 * selection's diffuse + specular models and parameters. force_goal >= 0 (an abrdf_goal)
 * makes every material adaptive with that goal, explicit ones included (their parameters
 * describe the material). `table` may be NULL if no material names an entry. If explain is
 * not NULL, each choice is printed with the selection's trace. Returns 0, or -1 with
 * "SCENE:LINE: problem" in err. */
int scene_select_materials(scene *s, const char *scene_name, const mat_table *table, int force_goal,
                           FILE *explain, char *err, size_t err_size);

/* The same, with budget materials: `adaptive budget=B` lines (and, with force_budget > 0,
 * every material, explicit ones included) are resolved by the selection's budget mode with
 * that NMSE budget, predicted on scene_budget_view (spp: the render's samples per pixel); the
 * ambient reflectance stays the reference's. force_goal and force_budget exclude each other
 * (force_budget < 0: none). */
int scene_select_budgets(scene *s, const char *scene_name, const mat_table *table, int force_goal,
                         double force_budget, int spp, FILE *explain, char *err, size_t err_size);

/* The prediction's view of a budget material in scene s (abrdf_view, abrdf_fit.h): the
 * analytic sphere seen from the camera (view_dir toward it, up its up), sampled as finely as
 * the render samples a unit sphere at the camera's target (rows * sqrt(spp) over the view's
 * height at that distance), under the scene's lights (a point light as the directional light
 * it casts at the camera's target; no light: the default set). lights: room for
 * SCENE_MAX_LIGHTS entries, referenced by v. */
void scene_budget_view(const scene *s, int spp, abrdf_view *v, abrdf_light_dir *lights);

/* Does any material need the material table (or does force_goal make them adaptive)? */
int scene_needs_table(const scene *s);

/* scene_select_budgets with the material table loaded as `abrdf render` and `abrdf export`
 * do: data/materials.csv (data_path.h) if a material names an entry, force_goal >= 0 or
 * force_budget > 0, then each of the nfiles --materials files merged over it. force_budget > 0
 * resolves every material by the budget mode with that NMSE budget; spp: the image's samples
 * per pixel for the prediction's view. Returns 0, or -1 with the message. */
int scene_resolve_budget(scene *s, const char *scene_name, const char *const *files, int nfiles,
                         int force_goal, double force_budget, int spp, FILE *explain, char *err,
                         size_t err_size);

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
