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
 */
#ifndef ABRDF_PBR_SELECT_H
#define ABRDF_PBR_SELECT_H

#include <stddef.h>
#include "abrdf_pbr.h"
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

#endif
