/* hair_table.c - huang hair with its residual lobes tabulated once per material
 * (abrdf.h, "huang tabulated"): build the table, prepare on it, evaluate as any huang.
 *   cc hair_table.c $(pkg-config --cflags --libs abrdf) -o hair_table
 * The sizes here are small, for a quick run; ABRDF_HUANG_TABLE_SIZES are the ones measured
 * in docs/MODELS.md ("A tabulated huang"), about 2 minutes of one core to build. */
#include <stdio.h>
#include <stdlib.h>
#include <abrdf.h>

int main(void)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    p.melanin = 0.73;                   /* brown hair */
    const int sizes[4] = {8, 3, 12, 1}; /* theta nodes, view azimuths, light azimuths, sets */
    long n;
    int rows;
    int st = abrdf_huang_table_size(&p, sizes, &n, &rows);
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
    free(table); /* after the last evaluation of `tabulated` */
    return 0;
}
