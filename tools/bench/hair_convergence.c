/* hair_convergence.c - what huang's quadrature grids cost and how far each is from the
 * converged model, on the convergence cylinder of docs/MODELS.md ("What a converged reference
 * costs"): the hair of data/materials.csv's hair_brown on a fibre cylinder under the two
 * directional lights of scenes/mixed.scene (tests/unit/hair_test_util.c, htu_cylinder_image;
 * test_hair_huang renders the same image). Each grid's image NMSE against a reference grid, and
 * its work per evaluation relative to the default's, n1^2 (1 + n2^2) refine / (6^2 (1 + 3^2)).
 *
 *   hair_convergence [--reference N1,N2,REFINE] [N1,N2,REFINE ...]
 *
 * The reference defaults to 16,8,4 (185 times the default's work, a few seconds); the grids
 * to the table of the page. REFINE divides the Simpson steps (not a parameter of the model). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hair.h"
#include "hair_test_util.h"

typedef struct grids {
    int n1, n2, refine;
} grids;

static int parse(const char *s, grids *g)
{
    char tail;
    if (sscanf(s, "%d,%d,%d%c", &g->n1, &g->n2, &g->refine, &tail) != 3 || g->n1 < 1 ||
        g->n1 > ABRDF__HUANG_GRID_MAX || g->n2 < 1 || g->n2 > ABRDF__HUANG_GRID_MAX ||
        g->refine < 1 || g->refine > 16) {
        fprintf(stderr, "hair_convergence: '%s' is not N1,N2,REFINE (grids 1-%d, refine 1-16)\n", s,
                ABRDF__HUANG_GRID_MAX);
        return 0;
    }
    return 1;
}

static void eval_fn(const void *m, const double wi[3], const double wo[3], double f[3])
{
    abrdf__huang_eval(m, wi, wo, f);
}

static void image(const grids *g, double img[HTU_CYL_SAMPLES][3])
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.melanin = 0.73; /* hair_brown */
    abrdf__huang m;
    abrdf__huang_setup(&p, &m);
    m.n1 = g->n1, m.n2 = g->n2, m.refine = g->refine;
    htu_cylinder_image(eval_fn, &m, img);
}

int main(int argc, char **argv)
{
    static const grids table[] = {{6, 3, 1},  {6, 3, 2},  {8, 3, 2},  {10, 3, 2}, {8, 4, 2},
                                  {12, 3, 2}, {10, 4, 2}, {12, 4, 2}, {12, 6, 1}, {12, 6, 2}};
    grids ref = {16, 8, 4}, list[64];
    int n = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--reference")) {
            if (i + 1 >= argc) {
                fprintf(stderr, "hair_convergence: --reference needs N1,N2,REFINE\n");
                return 2;
            }
            if (!parse(argv[++i], &ref)) return 2;
        } else if (n == (int)(sizeof list / sizeof list[0])) {
            fprintf(stderr, "hair_convergence: at most %d grids\n", n);
            return 2;
        } else if (!parse(argv[i], &list[n++])) {
            return 2;
        }
    }
    if (n == 0)
        for (n = 0; n < (int)(sizeof table / sizeof table[0]); ++n) list[n] = table[n];
    static double want[HTU_CYL_SAMPLES][3], img[HTU_CYL_SAMPLES][3];
    image(&ref, want);
    printf("reference: grids (%d, %d), Simpson x%d\n", ref.n1, ref.n2, ref.refine);
    for (int k = 0; k < n; ++k) {
        image(&list[k], img);
        double work =
            list[k].n1 * list[k].n1 * (1.0 + list[k].n2 * list[k].n2) * list[k].refine /
            (ABRDF__HUANG_N1 * ABRDF__HUANG_N1 * (1.0 + ABRDF__HUANG_N2 * ABRDF__HUANG_N2));
        printf("grids (%d, %d), Simpson x%d: work %.1f, NMSE vs the reference %.1e\n", list[k].n1,
               list[k].n2, list[k].refine, work, htu_image_nmse(want, img));
    }
    return 0;
}
