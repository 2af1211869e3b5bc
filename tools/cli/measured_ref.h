/* measured_ref.h - a measured-BRDF file as the reference of a fit: read through the format
 * table (measured_file.h), prepared as libabrdf's `measured` model (abrdf_prepare_measured),
 * and the analytic candidates fitted to it with abrdf_fit_to (docs/MEASURED.md, "Fitting
 * measured data"). What `abrdf fit --to` (fit_to.c) and `abrdf advise --measured`
 * (advise_measured.c) share.
 *
 *   measured_ref_load      read and prepare a file (one line and the exit status on failure)
 *   measured_ref_free      release it
 *   measured_ref_describe  "FILE (MERL BRDF database, 90 x 90 x 180 cells, N not measured)"
 *   measured_ref_fit       fit one candidate pair, with its cost
 *   measured_ref_cost      a pair's cost in the built-in table (ns/eval), -1 if unknown
 *   measured_ref_wall      a monotonic clock in seconds
 *   fit_to_run             `abrdf fit --to ...` (fit_to.c)
 *   advise_measured        `abrdf advise --measured FILE --budget B` (advise_measured.c)
 */
#ifndef ABRDF_MEASURED_REF_H
#define ABRDF_MEASURED_REF_H

#include <stddef.h>

#include "abrdf_fit.h"
#include "measured_table.h"

typedef struct measured_ref {
    const char *path;     /* the file as given */
    const char *format;   /* its format's name ("MERL BRDF database") */
    measured_table table; /* the values; the prepared model points at them */
    abrdf_prepared prep;  /* the `measured` model on the table */
    double read_secs;     /* wall time of reading and preparing */
} measured_ref;

/* 0, or the exit status after one line "abrdf CMD: ...": 2 for a name no format reads (a bad
 * argument), 1 for a file that cannot be read or is refused. */
int measured_ref_load(const char *cmd, const char *path, measured_ref *r);
void measured_ref_free(measured_ref *r);
void measured_ref_describe(const measured_ref *r, char *buf, size_t size);

/* The general candidates (docs/MEASURED.md, "Fitting measured data"): the specular lobes
 * that stand alone or over a diffuse term, and the diffuse terms. */
extern const abrdf_model measured_ref_specular[];
extern const int measured_ref_specular_count;
extern const abrdf_model measured_ref_diffuse[];
extern const int measured_ref_diffuse_count;

/* One candidate fitted. */
typedef struct measured_fit {
    abrdf_model diffuse, specular; /* diffuse may be ABRDF_MODEL_NONE */
    abrdf_params params;           /* the fitted block */
    abrdf_fit_result res;          /* errors, predicted NMSE */
    double cost;                   /* ns/eval (built-in table), -1 if unknown */
    double secs;                   /* wall time of the fit */
} measured_fit;

/* Fit (diffuse, specular) to r with opt in work (abrdf_fit_workspace_size(opt, NULL) bytes):
 * 0, or the library's status with its message in out->res.message. */
int measured_ref_fit(const measured_ref *r, abrdf_model diffuse, abrdf_model specular,
                     const abrdf_fit_options *opt, const abrdf_costs *costs, void *work,
                     size_t work_size, measured_fit *out);
double measured_ref_cost(const abrdf_costs *costs, abrdf_model diffuse, abrdf_model specular);
double measured_ref_wall(void);

int fit_to_run(int argc, char **argv);
int advise_measured(const char *path, double max_nmse, int json);

#endif
