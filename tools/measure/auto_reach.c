/* auto_reach.c - how far the fit's AUTO metric (Bieron & Peers 2020: fit with each metric,
 * keep the best predicted) moves a candidate: for every candidate of every material of the
 * table (or --only a,b,...), the predicted NMSE of the L2 fit and of the AUTO fit on the
 * default sphere, and whether a candidate the L2 fit puts at 4 x 1e-3 or beyond comes into a
 * Table-8 class with AUTO - why the budget mode refits every candidate with every metric
 * rather than the promising ones only (docs/SELECTION.md, "3. The selection within a budget").
 *
 *   auto_reach [--only NAME,...] [--skip-hair]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_fit.h"
#include "data_path.h"
#include "materials.h"

static int in_list(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *p = list; (p = strstr(p, name)) != NULL; p += n)
        if ((p == list || p[-1] == ',') && (p[n] == '\0' || p[n] == ',')) return 1;
    return 0;
}

int main(int argc, char **argv)
{
    const char *only = NULL;
    int skip_hair = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--only") && i + 1 < argc)
            only = argv[++i];
        else if (!strcmp(argv[i], "--skip-hair"))
            skip_hair = 1;
        else {
            fprintf(stderr, "usage: auto_reach [--only NAME,...] [--skip-hair]\n");
            return 2;
        }
    }
    char path[1024], err[MAT_ERR_MAX];
    mat_table t = {NULL, 0, 0};
    if (data_path_find("materials.csv", path, sizeof path) ||
        mat_table_load(&t, path, err, sizeof err)) {
        fprintf(stderr, "auto_reach: cannot load the material table\n");
        return 1;
    }
    abrdf_fit_options o;
    abrdf_fit_options_init(&o);
    size_t ws = abrdf_fit_workspace_size(&o, NULL);
    void *w = malloc(ws);
    const double noticeable = abrdf_select_rules_get()->nmse_class_max[2];
    int fits = 0, gained = 0, entered = 0;
    double worst_gain_outside = 1.0, best_outside = INFINITY;
    for (int i = 0; i < t.count; ++i) {
        const mat_entry *e = &t.items[i];
        if (only && !in_list(only, e->name)) continue;
        if (skip_hair && e->m.type == ABRDF_SURFACE_HAIR) continue;
        abrdf_selection sel;
        abrdf_params ref;
        abrdf_selection_init(&sel);
        abrdf_params_init(ABRDF_MODEL_NONE, &ref);
        if (abrdf_select(&e->m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, &ref, NULL, NULL)) continue;
        abrdf_model d, s;
        for (int k = 1; abrdf_budget_candidate(&e->m, k, &d, &s) == ABRDF_OK; ++k) {
            double nm[2];
            for (int q = 0; q < 2; ++q) {
                abrdf_params c;
                abrdf_fit_result r;
                abrdf_params_init(s, &c);
                abrdf_fit_result_init(&r);
                o.metric = q ? ABRDF_FIT_AUTO : ABRDF_FIT_L2;
                if (abrdf_fit(sel.diffuse, sel.specular, &ref, d, s, &c, &o, &r, w, ws)) {
                    fprintf(stderr, "auto_reach: %s: %s\n", e->name, r.message);
                    return 1;
                }
                nm[q] = r.nmse_pred;
            }
            ++fits;
            gained += nm[1] < nm[0];
            /* NMSE infinite: the reference's image is black (a highlight no sample hits), the
             * candidate's is not; no metric changes that */
            if (nm[0] >= 4.0 * noticeable && isfinite(nm[0])) {
                /* a candidate the budget does not refit: how much could AUTO have helped? */
                worst_gain_outside = fmin(worst_gain_outside, nm[1] / nm[0]);
                best_outside = fmin(best_outside, nm[1]);
                if (nm[1] < noticeable) {
                    ++entered;
                    printf("%s: %s%s%s enters a class with AUTO: %.3g -> %.3g\n", e->name,
                           d != ABRDF_MODEL_NONE ? abrdf_model_get(d)->name : "",
                           d != ABRDF_MODEL_NONE ? " + " : "", abrdf_model_get(s)->name, nm[0],
                           nm[1]);
                }
            }
        }
    }
    printf("%d candidate fits: AUTO lowered the predicted NMSE of %d; of the candidates whose L2 "
           "fit is predicted >= %g, AUTO brought %d below %g (the smallest AUTO NMSE among them "
           "%.3g, the largest gain a factor %.3g)\n",
           fits, gained, 4.0 * noticeable, entered, noticeable, best_outside,
           worst_gain_outside > 0 ? 1.0 / worst_gain_outside : INFINITY);
    free(w);
    mat_table_free(&t);
    return 0;
}
