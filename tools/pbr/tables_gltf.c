/* tables_gltf.c - `abrdf tables gltf`: for each row of the glTF mapping (pbr_error.h), what is
 * exact, what is approximated, and the approximation's measured error. */
#include <stdio.h>
#include <string.h>

#include "metrics.h"
#include "pbr_error.h"
#include "tables.h"

/* A signed error as the table prints it: 4 decimals, no sign on a zero. */
static const char *signed4(double x, char buf[16])
{
    snprintf(buf, 16, "%+.4f", x);
    if (!strcmp(buf + 1, "0.0000")) snprintf(buf, 16, "0.0000");
    return buf;
}

int tables_gltf(const table_gen *self, const tables_opts *o, const paper_data *paper)
{
    (void)self, (void)paper;
    int n;
    const pbr_error_row *rows = pbr_error_rows(&n);
    if (o->csv)
        printf("mapping,albedo_err_0,albedo_err_45,albedo_err_75,albedo_max_abs,nmse,class\n");
    else
        printf("### The glTF mapping's measured error\n\n"
               "Albedo: mapped minus glTF, white furnace seen at 0, 45 and 75 degrees (azimuths "
               "0 and 90 from\nthe tangent; the channel and azimuth of largest error). NMSE: "
               "the default sphere of\nabrdf_predict_nmse, the glTF BRDF the reference. Every "
               "row: glTF's defaults, metallic 0,\nbase (0.8, 0.3, 0.2), roughness r 0.4, but "
               "for what it names.\n\n"
               "| mapping | glTF material | exact | approximated | albedo 0 deg | 45 deg | "
               "75 deg | max abs | sphere NMSE | class |\n"
               "|---|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; ++k) {
        pbr_error_result e;
        char msg[256];
        if (pbr_error_measure(&rows[k].material, &e, msg, sizeof msg) != ABRDF_OK) {
            fprintf(stderr, "abrdf tables gltf: row '%s': %s\n", rows[k].name, msg);
            return 1;
        }
        if (o->csv)
            printf("\"%s\",%.6f,%.6f,%.6f,%.6f,%.4e,%s\n", rows[k].name, e.albedo_err[0],
                   e.albedo_err[1], e.albedo_err[2], e.albedo_max_abs, e.nmse,
                   abrdf_nmse_class(e.nmse));
        else {
            char b[3][16];
            printf("| %s | %s | %s | %s | %s | %s | %s | %.4f | %.2e | %s |\n", rows[k].name,
                   rows[k].values, rows[k].exact, rows[k].approx, signed4(e.albedo_err[0], b[0]),
                   signed4(e.albedo_err[1], b[1]), signed4(e.albedo_err[2], b[2]), e.albedo_max_abs,
                   e.nmse, abrdf_nmse_class(e.nmse));
        }
    }
    return 0;
}
