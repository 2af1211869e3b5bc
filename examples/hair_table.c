/* hair_table.c - huang hair with its residual lobes tabulated once per material
 * (abrdf.h, "huang tabulated"): build the table, prepare on it, evaluate as any huang, and
 * let the budget mode measure its stand-ins against it (abrdf_fit.h, abrdf_budget.reference).
 *   cc hair_table.c $(pkg-config --cflags --libs abrdf) -o hair_table
 * The sizes here are small, for a quick run; ABRDF_HUANG_TABLE_SIZES are the ones measured
 * in docs/MODELS.md ("A tabulated huang"), about a minute of one core to build. */
#include <stdio.h>
#include <stdlib.h>
#include <abrdf.h>
#include <abrdf_fit.h>

/* The budget mode for m against its tabulated photoreal choice, which costs `cost` (the
 * built-in table's unit, ns per evaluation): its choice printed. */
static int budget_to_table(const abrdf_material *m, const abrdf_prepared *table, double cost)
{
    abrdf_view view; /* a small sphere: a quick prediction */
    abrdf_view_init(&view);
    view.resolution = 16;
    abrdf_budget b;
    abrdf_budget_init(&b); /* "slight" */
    b.view = &view;
    b.resolution = 1;
    b.reference = table;
    b.reference_cost = cost;
    size_t ws = abrdf_fit_workspace_size(NULL, &view);
    void *work = malloc(ws);
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    int st =
        work ? abrdf_select_budget(m, &b, NULL, &sel, NULL, NULL, NULL, work, ws) : ABRDF_E_NULL;
    free(work);
    if (st != ABRDF_OK) {
        fprintf(stderr, "abrdf: %s\n", work ? sel.message : "out of memory");
        return 1;
    }
    printf("budget slight against the table: %s, predicted NMSE %g\n",
           abrdf_model_get(sel.specular)->name, sel.err_nmse);
    return 0;
}

int main(void)
{
    abrdf_material m; /* brown hair */
    abrdf_material_init(&m);
    m.type = ABRDF_SURFACE_HAIR;
    m.r = 0.3;
    m.eta = 1.55;
    m.melanin = 0.73;
    abrdf_selection photoreal;
    abrdf_selection_init(&photoreal);
    abrdf_params p; /* the flowchart's photoreal choice, huang, and its parameters */
    abrdf_params_init(ABRDF_MODEL_NONE, &p);
    int st = abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &photoreal, &p, NULL, NULL);
    const int sizes[4] = {8, 3, 12, 1}; /* theta nodes, view azimuths, light azimuths, sets */
    long n = 0;
    int rows = 0;
    if (st == ABRDF_OK) st = abrdf_huang_table_size(&p, sizes, &n, &rows);
    double *table = st == ABRDF_OK ? malloc((size_t)n * sizeof *table) : NULL;
    if (!table) {
        fprintf(stderr, "abrdf: %s\n", st == ABRDF_OK ? "out of memory" : abrdf_strerror(st));
        return 1;
    }
    /* The rows are independent: a renderer hands them to its threads (row0, row1 ranges). */
    st = abrdf_huang_table_build(&p, sizes, 0, rows, table);
    abrdf_prepared tabulated, integrated;
    if (st == ABRDF_OK) st = abrdf_prepare_huang_table(&p, sizes, table, &tabulated);
    if (st == ABRDF_OK) st = abrdf_prepare(ABRDF_HUANG, &p, &integrated);
    if (st != ABRDF_OK) {
        fprintf(stderr, "abrdf: %s\n", abrdf_strerror(st));
        free(table);
        return 1;
    }
    /* local frame: the fibre along T = +x, the ribbon's normal N = +z */
    const double wi[3] = {0.2, 0.5, 0.84}, wo[3] = {-0.1, -0.3, 0.95};
    double ft[3], fq[3];
    abrdf_eval_prepared(&tabulated, NULL, wi, wo, ft);
    abrdf_eval_prepared(&integrated, NULL, wi, wo, fq);
    printf("huang f_r, tabulated (%d values): %.5f %.5f %.5f\n", (int)n, ft[0], ft[1], ft[2]);
    printf("huang f_r, integrated per call:  %.5f %.5f %.5f\n", fq[0], fq[1], fq[2]);
    /* A table costs about 1/150 of the quadrature per call (docs/MODELS.md): measure it on
     * the renderer's own path; here a round figure in the built-in table's unit. */
    int rc = budget_to_table(&m, &tabulated, 2000.0);
    free(table); /* after the last evaluation of `tabulated` */
    return rc;
}
