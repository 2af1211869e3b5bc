/* pbr_reference.h - the glTF 2.0 metallic-roughness BRDF as the specification writes it, in
 * double precision: the reference abrdf_pbr_lobes (abrdf_pbr.h) is measured against
 * (pbr_error.h). Not a libabrdf model: it reads abrdf_pbr directly and keeps every layer the
 * specification has, where the mapping keeps two lobes.
 *
 * Sources (the specification sections each formula comes from):
 *   glTF 2.0, Appendix B "BRDF Implementation": B.2.1 the metal and dielectric mix and
 *     fresnel_mix, B.3.2 Schlick's Fresnel, B.3.3 the GGX distribution (alpha =
 *     roughness^2) and the height-correlated Smith visibility, B.3.4 the Lambertian diffuse.
 *   KHR_materials_ior, KHR_materials_specular: f0 = min(((ior - 1)/(ior + 1))^2
 *     specularColor, 1), the dielectric's Fresnel weighted by specular (fresnel_mix).
 *   KHR_materials_anisotropy: alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha, the
 *     anisotropic GGX distribution and visibility (tangent = the frame's x axis here).
 *   KHR_materials_clearcoat: fresnel_coat, mix(base, coat, clearcoat Fc(V.N)), Fc Schlick
 *     of f0 0.04 (ior 1.5), the coat a GGX specular of alpha = clearcoatRoughness^2.
 *   KHR_materials_sheen: the Charlie distribution and visibility (Estevez & Kulla 2017),
 *     alpha = sheenRoughness^2 (the Khronos sample viewer's reading), and the base scaled by
 *     min(1 - max3(sheenColor) E(N.V), 1 - max3(sheenColor) E(N.L)), E the sheen lobe's
 *     directional albedo, integrated here at prepare time (no fitted table).
 *   KHR_materials_transmission: the reflection part only, the diffuse mixed with the
 *     transmission BTDF by transmission (the BTDF sends light below the surface).
 *
 * Directions as abrdf.h: local frame (x tangent, y bitangent, z normal), wi toward the light,
 * wo toward the viewer; f_r without the cosine. Both below the horizon: 0.
 *
 *   pbr_ref_prepare        validate (abrdf_pbr_check) and precompute, sheen albedo included
 *   pbr_ref_eval           f_r per RGB channel
 *   pbr_ref_sheen_e        the tabulated sheen albedo E(cos) the prepare step integrated
 *   pbr_ref_d_ggx, pbr_ref_d_ggx_aniso, pbr_ref_v_ggx, pbr_ref_v_ggx_aniso,
 *   pbr_ref_f_schlick, pbr_ref_d_charlie, pbr_ref_lambda_charlie, pbr_ref_v_charlie
 *                          the named terms, for the tests */
#ifndef ABRDF_PBR_REFERENCE_H
#define ABRDF_PBR_REFERENCE_H

#include <stddef.h>

#include "abrdf_pbr.h"

/* Entries of the sheen albedo table over cos theta in [0, 1], uniformly spaced. */
#define PBR_REF_SHEEN_N 65

typedef struct pbr_ref {
    double base[3];      /* base colour */
    double metallic;     /* [0, 1] */
    double alpha_t;      /* GGX width along the tangent (alpha_t = alpha if isotropic) */
    double alpha_b;      /* GGX width along the bitangent */
    double f0d[3];       /* dielectric normal reflectance, clamped to 1 */
    double spec_w;       /* specular weight of fresnel_mix */
    double transmission; /* [0, 1] */
    double clearcoat;    /* [0, 1] */
    double coat_alpha;   /* the coat's GGX width */
    double sheen[3];     /* sheen colour (all 0: no sheen layer) */
    double sheen_max;    /* max3(sheen colour) */
    double sheen_alpha;  /* the Charlie width, sheenRoughness^2 (at least PBR_REF_ALPHA_MIN) */
    double sheen_e[PBR_REF_SHEEN_N]; /* E(cos) at cos = i / (N - 1) */
} pbr_ref;

/* The smallest width a GGX or Charlie lobe is evaluated with: a roughness-0 material is a
 * mirror, which a function of directions cannot hold; 1e-7 keeps alpha^2 a normal double. */
#define PBR_REF_ALPHA_MIN 1e-7

/* ABRDF_OK, or abrdf_pbr_check's status with its message in msg. */
int pbr_ref_prepare(const abrdf_pbr *p, pbr_ref *out, char *msg, size_t msg_size);
void pbr_ref_eval(const pbr_ref *r, const double wi[3], const double wo[3], double f[3]);
double pbr_ref_sheen_e(const pbr_ref *r, double cos_theta);

/* The terms (cosines of the local frame; the anisotropic forms take local vectors). */
double pbr_ref_f_schlick(double f0, double f90, double cos_vh);
double pbr_ref_d_ggx(double alpha, double cos_h);
double pbr_ref_d_ggx_aniso(double at, double ab, const double h[3]);
/* V = G2 / (4 |N.L| |N.V|), height-correlated Smith. */
double pbr_ref_v_ggx(double alpha, double cos_l, double cos_v);
double pbr_ref_v_ggx_aniso(double at, double ab, const double l[3], const double v[3]);
double pbr_ref_d_charlie(double alpha, double cos_h);
double pbr_ref_lambda_charlie(double alpha, double cos_theta);
double pbr_ref_v_charlie(double alpha, double cos_l, double cos_v);

#endif
