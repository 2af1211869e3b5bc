/* abrdf_pbr.h - the materials users hold, in abrdf's terms: a glTF 2.0 metallic-roughness
 * material with the KHR material extensions abrdf maps (and, through the same fields, the
 * MaterialX gltf_pbr, standard_surface and open_pbr_surface inputs, and Blender's Principled
 * BSDF). docs/GLTF.md states every mapping, what is exact and what is approximated, with
 * the approximation's measured error.
 *
 * Two uses:
 *   abrdf_pbr_lobes      the material as explicit abrdf lobes: a diffuse lobe and a specular
 *                        lobe with their shared parameters (what `abrdf render` draws for a
 *                        glTF material without a selection, and what the exporters write)
 *   abrdf_pbr_material   the material as the flowchart reads it (abrdf_material): its surface
 *                        class, roughness, colours and layers, for abrdf_select and the budget
 *
 * The glTF BRDF (glTF 2.0 specification, Appendix B) is
 *   f = mix(dielectric, metal, metallic)
 *   metal      = Schlick(base_color) * S
 *   dielectric = (1 - w max(F_d)) base_color / pi + w F_d S,  F_d = Schlick(f0_d)
 *   S = D_GGX(alpha) V_heightcorrelated(alpha),  alpha = roughness^2
 *   f0_d = min(((ior - 1)/(ior + 1))^2 specular_color, 1),  w = specular
 * abrdf_pbr_lobes maps it onto lambert_fresnel + disney_specular (Eqs. 2, 5, 6, 8, 9):
 *   kd = (1 - metallic)(1 - transmission) base_color (1 - max f0_d) / (1 - f0)   (w = 1;
 *        w < 1: without the last factor)
 *   ks = (1 - metallic) w + metallic,  f0 = ((1 - metallic) w f0_d + metallic base_color) / ks
 *   r  = roughness (alpha = r^2, the same GGX distribution)
 * The Fresnel part of the specular lobe is then exact (Schlick is linear in f0 and f90, and
 * the mix of two Schlick terms is ks times one); what differs is the masking (the paper's
 * separable Smith, Eq. 9, against glTF's height-correlated form), the diffuse lobe's Fresnel
 * factor for w < 1 (with w = 1 the factor's ratio to glTF's is a constant, folded into kd),
 * and the extensions below. Anisotropy
 * (KHR_materials_anisotropy) switches the specular lobe to disney_specular_aniso, with the
 * Disney aspect chosen so that alpha_x alpha_y and alpha_x / alpha_y match glTF's
 * alpha_t = mix(alpha, 1, strength^2), alpha_b = alpha where the Disney form can (its aspect
 * ratio is at most 1/sqrt(0.1)); the rotation is the caller's tangent frame.
 * Clearcoat and sheen have no lobe here (two lobes at most): they choose the flowchart's
 * surface class in abrdf_pbr_material (layered or cloth), and abrdf_pbr_lobes leaves them
 * out, which docs/GLTF.md measures. Transmission is light abrdf's reflection models do not
 * carry: it scales the diffuse lobe down, as the glTF mix does.
 *
 * STABLE LAYOUT (the rules of abrdf.h): abrdf_pbr starts with struct_size, set by
 * abrdf_pbr_init (a static inline that passes your sizeof); fields are appended only.
 *
 * PUBLIC FUNCTIONS
 *   abrdf_pbr_init        glTF's defaults (inline)
 *   abrdf_pbr_init_sized  the same for a struct of struct_size bytes
 *   abrdf_pbr_check       the first field out of its range, named, or ABRDF_OK
 *   abrdf_pbr_lobes       the explicit lobes and their parameters
 *   abrdf_pbr_material    the flowchart's material
 */
#ifndef ABRDF_PBR_H
#define ABRDF_PBR_H

#include "abrdf_select.h"

#ifdef __cplusplus
extern "C" {
#endif

#define ABRDF_PBR_MAX_LOBES 2

typedef struct abrdf_pbr {
    size_t struct_size;         /* bytes of this struct as the caller compiled it; set by _init */
    double base_color[3];       /* baseColorFactor (times the texel), linear RGB, [0, 1]; 1 */
    double metallic;            /* metallicFactor, [0, 1]; 1 (glTF's default) */
    double roughness;           /* roughnessFactor, perceptual (alpha = r^2), [0, 1]; 1 */
    double ior;                 /* KHR_materials_ior, [1, 4]; 1.5 */
    double specular;            /* KHR_materials_specular specularFactor, [0, 1]; 1 */
    double specular_color[3];   /* KHR_materials_specular specularColorFactor, [0, 100]; 1
                                 (f0_d = min(f0(ior) specular_color, 1), as glTF clamps) */
    double clearcoat;           /* KHR_materials_clearcoat clearcoatFactor, [0, 1]; 0 */
    double clearcoat_roughness; /* clearcoatRoughnessFactor, [0, 1]; 0 */
    double sheen_color[3];      /* KHR_materials_sheen sheenColorFactor, [0, 1]; 0 */
    double sheen_roughness;     /* sheenRoughnessFactor, [0, 1]; 0 */
    double anisotropy;          /* KHR_materials_anisotropy anisotropyStrength, [0, 1]; 0 */
    double anisotropy_rotation; /* anisotropyRotation, radians, |x| <= 1e3; 0 (the tangent
                                   frame's business: abrdf_pbr_lobes does not read it) */
    double transmission;        /* KHR_materials_transmission transmissionFactor, [0, 1]; 0 */
} abrdf_pbr;

/* glTF's defaults (base colour 1, metallic 1, roughness 1, ior 1.5, specular 1, no
 * extension); sets struct_size. ABRDF_E_SIZE, writing nothing, if struct_size is below the
 * first layout or ABRDF_E_NULL for a NULL pointer. */
ABRDF_API int abrdf_pbr_init_sized(abrdf_pbr *p, size_t struct_size);
static inline int abrdf_pbr_init(abrdf_pbr *p)
{
    return abrdf_pbr_init_sized(p, sizeof(abrdf_pbr));
}

/* ABRDF_OK, or ABRDF_E_RANGE with "FIELD = VALUE is outside [MIN, MAX]" (or "is not
 * finite") in msg for the first field out of range; ABRDF_E_NULL / ABRDF_E_SIZE for a bad
 * pointer or struct_size. msg may be NULL. */
ABRDF_API int abrdf_pbr_check(const abrdf_pbr *p, char *msg, size_t msg_size);

/* The explicit lobes (lobes[0] diffuse, lobes[1] specular; *lobe_count = 2) and their shared
 * parameters. params must carry its struct_size (abrdf_params_init); every field it holds
 * is replaced (the specular model's defaults where the mapping says nothing). Errors as
 * abrdf_pbr_check, writing nothing. */
ABRDF_API int abrdf_pbr_lobes(const abrdf_pbr *p, abrdf_model lobes[ABRDF_PBR_MAX_LOBES],
                              int *lobe_count, abrdf_params *params);

/* The flowchart's material: type general, or layered_plastic / layered_metal with a
 * clearcoat (metallic < 0.5 / >= 0.5; the coat an eta 1.5 interface of the clearcoat's
 * roughness, over the base as a conductor of the same normal reflectance for a metal),
 * or cloth_rough / cloth_shiny with a sheen and no clearcoat (sheen roughness >= 0.5 /
 * below); r = roughness, kd, ks, f0 as abrdf_pbr_lobes, anisotropy as mapped there.
 * out must carry its struct_size (abrdf_material_init); every field it holds is replaced
 * (name NULL, the rest at abrdf_material_init's defaults where the mapping says nothing).
 * Errors as abrdf_pbr_check, writing nothing. */
ABRDF_API int abrdf_pbr_material(const abrdf_pbr *p, abrdf_material *out);

#ifdef __cplusplus
}
#endif

#endif
