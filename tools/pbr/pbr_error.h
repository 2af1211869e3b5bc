/* pbr_error.h - the measured error of the glTF mapping (abrdf_pbr_lobes) against the glTF
 * BRDF as specified (pbr_reference.h): furnace albedo at a few view angles, and the image NMSE
 * on the sphere of abrdf_predict_nmse's default view. docs/GLTF.md, "The mapping", quotes
 * what `abrdf tables gltf` prints from these.
 *
 * The sphere is rendered here, not by abrdf_predict_nmse: that function takes its reference
 * as libabrdf lobes, and the glTF BRDF is not one. The render follows predict.c's convention
 * exactly (orthographic view along +z, axis +y, 128 samples across, the tangent around the
 * axis, the two default lights, four grids shifted by half a spacing, the largest of their
 * NMSEs); a unit test holds the two renders to each other on a pair of libabrdf BRDFs.
 *
 *   pbr_brdf_fn          a BRDF as a function of local directions
 *   pbr_mapped_make      the mapped lobes and parameters of a material; pbr_mapped_eval
 *   pbr_ref_brdf         pbr_ref_eval as a pbr_brdf_fn
 *   pbr_albedo           furnace albedo seen from one direction (quadrature over the light)
 *   pbr_sphere_nmse      image NMSE of one BRDF against another on the default sphere
 *   pbr_error_rows       the table's rows: a material each, with what is exact and what is not
 *   pbr_error_measure    one row measured */
#ifndef ABRDF_PBR_ERROR_H
#define ABRDF_PBR_ERROR_H

#include <stddef.h>

#include "abrdf_pbr.h"
#include "pbr_reference.h"

typedef void (*pbr_brdf_fn)(const void *ctx, const double wi[3], const double wo[3], double f[3]);

typedef struct pbr_mapped {
    abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
    int count;
    abrdf_params params;
} pbr_mapped;

/* abrdf_pbr_lobes into m; its status. */
int pbr_mapped_make(const abrdf_pbr *p, pbr_mapped *m);
/* ctx: a pbr_mapped; the lobes' sum (abrdf_eval, local frame). */
void pbr_mapped_eval(const void *ctx, const double wi[3], const double wo[3], double f[3]);
/* ctx: a pbr_ref. */
void pbr_ref_brdf(const void *ctx, const double wi[3], const double wo[3], double f[3]);

/* Largest count of lobe widths pbr_albedo takes. */
#define PBR_ALBEDO_WIDTHS_MAX 4

/* rho(wo) = int f(wi, wo) cos(theta_i) dwi per channel (the radiance a white furnace of
 * radiance 1 returns toward wo). The light is sampled by several sets of `order`
 * Gauss-Legendre nodes in a radial coordinate times 2 order azimuths: one cosine-weighted
 * (the diffuse lobe, the sheen), and one of half vectors distributed as a GGX lobe of each
 * width in `widths` (the BRDF's specular lobes); the sets are combined by the balance
 * heuristic, so each lobe is integrated by the set that fits it. */
void pbr_albedo(pbr_brdf_fn fn, const void *ctx, const double wo[3], const double *widths,
                int width_count, int order, double rho[3]);

/* NMSE of `test` against `ref` on the default sphere of abrdf_predict_nmse (the header's
 * convention) with `resolution` samples across (0: 128). ABRDF_OK, or ABRDF_E_RANGE for a
 * resolution outside [0, 1024] or a black reference. */
int pbr_sphere_nmse(pbr_brdf_fn test, const void *test_ctx, pbr_brdf_fn ref, const void *ref_ctx,
                    int resolution, double *nmse);

/* The view angles of the albedo columns, degrees, and the azimuths (from the tangent) each
 * is taken at, the largest error over them kept (anisotropy makes them differ). */
#define PBR_ERROR_ANGLES 3
#define PBR_ERROR_AZIMUTHS 2
extern const double pbr_error_angle_deg[PBR_ERROR_ANGLES];
extern const double pbr_error_azimuth_deg[PBR_ERROR_AZIMUTHS];

typedef struct pbr_error_row {
    const char *name;   /* the mapping's row, e.g. "metallic 0.5" */
    const char *values; /* the material's glTF values, as the table prints them */
    const char *exact;  /* what the mapping keeps exactly */
    const char *approx; /* what it approximates or leaves out */
    abrdf_pbr material;
} pbr_error_row;

/* The rows (static, initialised on the first call); *count receives their number. */
const pbr_error_row *pbr_error_rows(int *count);

typedef struct pbr_error_result {
    /* mapped - reference albedo at each angle: the signed error of largest magnitude over
     * channels and azimuths */
    double albedo_err[PBR_ERROR_ANGLES];
    double albedo_max_abs; /* the largest |albedo_err| */
    double nmse;           /* the sphere's NMSE of the mapped lobes against the reference */
} pbr_error_result;

/* One material measured; abrdf_pbr_check's status and message on a bad material. */
int pbr_error_measure(const abrdf_pbr *p, pbr_error_result *out, char *msg, size_t msg_size);

#endif
