/* cl_quad.h - the batch check of the cloth and layered suites; their quadrature and
 * random directions are tools/common/quad.h. */
#ifndef ABRDF_CL_QUAD_H
#define ABRDF_CL_QUAD_H
#include "abrdf.h"
#include "quad.h" /* quad_albedo, quad_rand_dir, ... (tools/) */

/* Float batch path == double scalar path: n <= CLQ_BATCH_MAX random pairs (quad_rand_dir
 * from seed, zmin 0.05), each of the nm models at its defaults; channel 0 must agree to
 * tu_close(rel, abs_tol). */
#define CLQ_BATCH_MAX 2000
void clq_batch_matches_scalar(const abrdf_model *ms, int nm, int n, unsigned seed, double rel,
                              double abs_tol);
#endif
