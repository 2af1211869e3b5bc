/* pbr_select.h - the flowchart for a pbr material (abrdf_pbr.h) whose roughness varies over
 * a texture: one choice that covers every texel (docs/GLTF.md, "Selection over a texture").
 *
 * The flowchart runs at every value of the roughness map's histogram (the material's factor
 * times each bin's texel value, and the map's exact least and largest values). When every
 * value takes the same branch, that branch is the choice. When the map crosses a threshold
 * of the flowchart, the material takes the safe branch, and the trace says which values went
 * which way and why:
 *   photoreal    the surface's reference model (the branch with no predicted error: GGX on
 *                a general surface), which is exact for smooth texels too;
 *   performance  the cheapest Table-1 approximation that passes the tolerances at every
 *                value (its worst errors over the map), else Blinn-Phong.
 * The parameters printed and used are those of the weighted-median texel; a renderer maps
 * each texel's own values onto the chosen models (scene_pbr_params).
 *
 * PUBLIC FUNCTIONS
 *   pbr_select_range   the choice over a roughness histogram, with its trace
 *   pbr_budget_range   the budget mode over a roughness histogram
 *   pbr_budget_range_at  the same with the fits' direction-set density
 */
#ifndef ABRDF_PBR_SELECT_H
#define ABRDF_PBR_SELECT_H

#include <stddef.h>
#include "abrdf_pbr.h"
#include "abrdf_fit.h"
#include "select_trace.h"

#define PBR_RANGE_MAX 66 /* histogram bins + the least and largest values */

/* Roughness values over a texture and their shares of the texels. */
typedef struct pbr_range {
    int count;                   /* values, [1, PBR_RANGE_MAX] */
    double r[PBR_RANGE_MAX];     /* perceptual roughness (factor times texel), [0, 1] */
    double share[PBR_RANGE_MAX]; /* fraction of the texels near r (>= 0; the two extremes may
                                    have 0: they are tested, not weighed) */
    const char *what;            /* for the trace: "roughness map FILE" */
} pbr_range;

/* The choice for p (its roughness replaced by each value of range) for goal: sel, params (at
 * the weighted-median value) and the trace (the median value's steps, then one step that
 * states the range and the branch taken). tol and costs as abrdf_select (NULL: defaults).
 * Returns 0, or -1 with one line in msg (the trace is then freed). */
int pbr_select_range(const abrdf_pbr *p, const pbr_range *range, abrdf_goal goal,
                     const abrdf_tolerance *tol, const abrdf_costs *costs, abrdf_selection *sel,
                     abrdf_params *params, select_trace *trace, char *msg, size_t msg_size);

/* The budget mode over a roughness map: the values grouped into at most PBR_BUDGET_GROUPS
 * quantile groups of the texels (each at its share-weighted mean r), the budget mode run at
 * each (abrdf_select_budget: every candidate fitted against the photoreal choice there), and
 * each candidate pair's predicted image NMSE over the map taken as the share-weighted mean
 * of its predictions (texels of equal reference energy: stated in the trace). The cheapest
 * pair within max_nmse wins (of those within 15 % of its cost, the lowest NMSE, as the
 * library ranks); none within: the photoreal choice over the map (pbr_select_range). */
#define PBR_BUDGET_GROUPS 8

typedef struct pbr_budget_choice {
    abrdf_model diffuse, specular; /* diffuse may be ABRDF_MODEL_NONE */
    abrdf_params params;           /* fitted at the group of the median texel */
    /* the pair's fitted block at each group's r (ascending), for a renderer to take per
     * texel (the fallback: the photoreal choice's block at each r) */
    double group_r[PBR_BUDGET_GROUPS];
    abrdf_params group_params[PBR_BUDGET_GROUPS];
    double nmse;      /* predicted over the map; 0 for the photoreal fallback */
    double cost;      /* in the costs' unit; < 0 unknown */
    const char *unit; /* the costs' unit */
    int groups;       /* values the budget mode ran at */
    int within;       /* 1: a candidate within the budget; 0: the fallback */
} pbr_budget_choice;

/* costs NULL: the built-in table; view NULL: the default sphere. Returns 0, or -1 with one
 * line in msg. The trace receives one step per group and one per compared pair, then the
 * choice. */
int pbr_budget_range(const abrdf_pbr *p, const pbr_range *range, double max_nmse,
                     const abrdf_costs *costs, const abrdf_view *view, pbr_budget_choice *out,
                     select_trace *trace, char *msg, size_t msg_size);
/* The same with the fits' direction-set density (budget_run_at; 0: the default). */
int pbr_budget_range_at(const abrdf_pbr *p, const pbr_range *range, double max_nmse, int resolution,
                        const abrdf_costs *costs, const abrdf_view *view, pbr_budget_choice *out,
                        select_trace *trace, char *msg, size_t msg_size);

#endif
