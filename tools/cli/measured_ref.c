/* measured_ref.c - a measured-BRDF file as the reference of a fit (measured_ref.h). */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "cli.h"
#include "measured_file.h"
#include "measured_ref.h"

/* The specular lobes of the budget mode's general class (docs/SELECTION.md, "3. The selection
 * within a budget"): the microfacet lobes, Blinn-Phong and Phong, the paper's Table-1
 * approximations and its Table-5 energy-conserving lobes. The anisotropic lobe is left out: a
 * measured table is isotropic. */
const abrdf_model measured_ref_specular[] = {ABRDF_DISNEY_SPECULAR,
                                             ABRDF_COOK_TORRANCE,
                                             ABRDF_BLINN_PHONG,
                                             ABRDF_PHONG,
                                             ABRDF_F2,
                                             ABRDF_F4,
                                             ABRDF_F8,
                                             ABRDF_F16,
                                             ABRDF_FS,
                                             ABRDF_FKV,
                                             ABRDF_FKUB,
                                             ABRDF_F_PHE,
                                             ABRDF_F_BE,
                                             ABRDF_F_2E,
                                             ABRDF_F_16E,
                                             ABRDF_F_GE,
                                             ABRDF_F_CTPHE,
                                             ABRDF_F_CT2E,
                                             ABRDF_F_CT16E};
const int measured_ref_specular_count =
    (int)(sizeof measured_ref_specular / sizeof measured_ref_specular[0]);

/* Lambert first: the cheapest, and the diffuse term Ngan et al. (EGSR 2005) fitted under
 * every lobe; the two rough-diffuse models where the data asks for them. */
const abrdf_model measured_ref_diffuse[] = {ABRDF_LAMBERT, ABRDF_DISNEY_DIFFUSE, ABRDF_OREN_NAYAR};
const int measured_ref_diffuse_count =
    (int)(sizeof measured_ref_diffuse / sizeof measured_ref_diffuse[0]);

double measured_ref_wall(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

int measured_ref_load(const char *cmd, const char *path, measured_ref *r)
{
    char err[1024];
    memset(r, 0, sizeof *r);
    r->path = path;
    const measured_format *format = measured_file_format(path, 0, err, sizeof err);
    if (!format) return cli_fail(cmd, "%s", err);
    r->format = format->name;
    double t0 = measured_ref_wall();
    if (format->read(path, &r->table, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", cmd, err);
        return 1;
    }
    abrdf_measured desc;
    abrdf_measured_init(&desc);
    desc.n_theta_h = r->table.n_theta_h;
    desc.n_theta_d = r->table.n_theta_d;
    desc.n_phi_d = r->table.n_phi_d;
    desc.data = r->table.data;
    int st = abrdf_prepare_measured(&desc, &r->prep);
    r->read_secs = measured_ref_wall() - t0;
    if (st != ABRDF_OK) { /* the readers keep the grid's bounds: not expected */
        fprintf(stderr, "abrdf %s: %s: %s\n", cmd, path, abrdf_strerror(st));
        measured_table_free(&r->table);
        return 1;
    }
    return 0;
}

void measured_ref_free(measured_ref *r) { measured_table_free(&r->table); }

void measured_ref_describe(const measured_ref *r, char *buf, size_t size)
{
    snprintf(buf, size, "%s (%s, %d x %d x %d cells, %zu not measured)", r->path, r->format,
             r->table.n_theta_h, r->table.n_theta_d, r->table.n_phi_d, r->table.unmeasured);
}

double measured_ref_cost(const abrdf_costs *costs, abrdf_model diffuse, abrdf_model specular)
{
    double c = abrdf_costs_get(costs, specular);
    if (c < 0.0) return -1.0;
    if (diffuse != ABRDF_MODEL_NONE) {
        double d = abrdf_costs_get(costs, diffuse);
        if (d < 0.0) return -1.0;
        c += d;
    }
    return c;
}

int measured_ref_fit(const measured_ref *r, abrdf_model diffuse, abrdf_model specular,
                     const abrdf_fit_options *opt, const abrdf_costs *costs, void *work,
                     size_t work_size, measured_fit *out)
{
    out->diffuse = diffuse;
    out->specular = specular;
    abrdf_params_init(specular, &out->params);
    abrdf_fit_result_init(&out->res);
    double t0 = measured_ref_wall();
    int st =
        abrdf_fit_to(&r->prep, diffuse, specular, &out->params, opt, &out->res, work, work_size);
    out->secs = measured_ref_wall() - t0;
    out->cost = measured_ref_cost(costs, diffuse, specular);
    return st;
}
