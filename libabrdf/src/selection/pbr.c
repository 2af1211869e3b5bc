/* pbr.c - glTF metallic-roughness materials (and the inputs that share its fields) as abrdf
 * lobes and as the flowchart's material: abrdf_pbr.h states the mapping, docs/GLTF.md its
 * measured error. */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>
#include "abrdf_pbr.h"

/* The first layout: every field of this release (fields are appended after it). */
#define PBR_SIZE_FIRST (offsetof(abrdf_pbr, transmission) + sizeof(double))

static void pbr_defaults(abrdf_pbr *p)
{
    memset(p, 0, sizeof *p);
    p->struct_size = sizeof *p;
    for (int c = 0; c < 3; ++c) p->base_color[c] = 1, p->specular_color[c] = 1;
    p->metallic = 1;
    p->roughness = 1;
    p->ior = 1.5;
    p->specular = 1;
}

int abrdf_pbr_init_sized(abrdf_pbr *p, size_t struct_size)
{
    if (!p) return ABRDF_E_NULL;
    if (struct_size < PBR_SIZE_FIRST) return ABRDF_E_SIZE;
    abrdf_pbr d;
    pbr_defaults(&d);
    memset(p, 0, struct_size);
    memcpy(p, &d, struct_size < sizeof d ? struct_size : sizeof d); /* the caller's layout */
    p->struct_size = struct_size;
    return ABRDF_OK;
}

/* The caller's block over the defaults (a later caller's extra fields are not read). */
static int pbr_read(const abrdf_pbr *src, abrdf_pbr *out)
{
    if (!src) return ABRDF_E_NULL;
    if (src->struct_size < PBR_SIZE_FIRST) return ABRDF_E_SIZE;
    pbr_defaults(out);
    size_t n = src->struct_size < sizeof *out ? src->struct_size : sizeof *out;
    memcpy(out, src, n);
    out->struct_size = sizeof *out;
    return ABRDF_OK;
}

typedef struct pbr_field {
    const char *name;
    size_t offset;
    int count; /* 1 or 3 */
    double min, max;
} pbr_field;

#define PBR_FIELD(f, n, lo, hi)                                                                    \
    {                                                                                              \
#f, offsetof(abrdf_pbr, f), n, lo, hi                                                      \
    }
static const pbr_field pbr_fields[] = {
    PBR_FIELD(base_color, 3, 0, 1),   PBR_FIELD(metallic, 1, 0, 1),
    PBR_FIELD(roughness, 1, 0, 1),    PBR_FIELD(ior, 1, 1, 4),
    PBR_FIELD(specular, 1, 0, 1),     PBR_FIELD(specular_color, 3, 0, 100),
    PBR_FIELD(clearcoat, 1, 0, 1),    PBR_FIELD(clearcoat_roughness, 1, 0, 1),
    PBR_FIELD(sheen_color, 3, 0, 1),  PBR_FIELD(sheen_roughness, 1, 0, 1),
    PBR_FIELD(anisotropy, 1, 0, 1),   PBR_FIELD(anisotropy_rotation, 1, -1e3, 1e3),
    PBR_FIELD(transmission, 1, 0, 1),
};

static int pbr_valid(const abrdf_pbr *p, char *msg, size_t msg_size)
{
    for (size_t i = 0; i < sizeof pbr_fields / sizeof pbr_fields[0]; ++i) {
        const pbr_field *f = &pbr_fields[i];
        const double *v = (const double *)((const char *)p + f->offset);
        for (int c = 0; c < f->count; ++c) {
            if (v[c] >= f->min && v[c] <= f->max) continue;
            char name[48];
            if (f->count == 3)
                snprintf(name, sizeof name, "%s[%d]", f->name, c);
            else
                snprintf(name, sizeof name, "%s", f->name);
            if (msg && msg_size) {
                if (!isfinite(v[c]))
                    snprintf(msg, msg_size, "%s = %g is not finite", name, v[c]);
                else
                    snprintf(msg, msg_size, "%s = %.9g is outside [%g, %g]", name, v[c], f->min,
                             f->max);
            }
            return ABRDF_E_RANGE;
        }
    }
    if (msg && msg_size) msg[0] = '\0';
    return ABRDF_OK;
}

int abrdf_pbr_check(const abrdf_pbr *p, char *msg, size_t msg_size)
{
    abrdf_pbr q;
    int st = pbr_read(p, &q);
    if (st != ABRDF_OK) {
        if (msg && msg_size)
            snprintf(msg, msg_size, "%s",
                     st == ABRDF_E_NULL ? "no material (NULL)" : "struct_size below the layout");
        return st;
    }
    return pbr_valid(&q, msg, msg_size);
}

/* The mapped values shared by both uses (abrdf_pbr.h gives the formulas). */
typedef struct pbr_mapped {
    double kd[3], ks[3], f0[3];
    double r;          /* perceptual roughness of the specular lobe */
    double anisotropy; /* Disney anisotropic, 0 = isotropic */
} pbr_mapped;

static void pbr_map(const abrdf_pbr *p, pbr_mapped *m)
{
    double m1 = p->metallic, w = p->specular;
    double e = (p->ior - 1) / (p->ior + 1);
    double ks = (1 - m1) * w + m1;
    double f0d[3], f0d_max = 0;
    for (int c = 0; c < 3; ++c) {
        f0d[c] = fmin(e * e * p->specular_color[c], 1.0);
        f0d_max = fmax(f0d_max, f0d[c]);
    }
    for (int c = 0; c < 3; ++c) {
        m->kd[c] = (1 - m1) * (1 - p->transmission) * p->base_color[c];
        m->ks[c] = ks;
        /* ks * Schlick(f0) == (1 - m) w Schlick(f0_d) + m Schlick(base): the same value at
         * normal incidence and at grazing (f90 = ks), and both are linear in between */
        m->f0[c] = ks > 0 ? ((1 - m1) * w * f0d[c] + m1 * p->base_color[c]) / ks : 0;
        m->f0[c] = fmin(fmax(m->f0[c], 0.0), 1.0);
        /* The diffuse: glTF's 1 - w max_c Schlick(f0_d) against lambert_fresnel's
         * 1 - Schlick(f0). With w = 1 both are (1 - f0')(1 - (1 - cos)^5), so their ratio
         * (1 - max f0_d) / (1 - f0) is a constant, folded into kd: exact for any metallic
         * and a coloured f0_d. With w < 1 no constant is exact (docs/GLTF.md measures it). */
        if (w == 1 && m->f0[c] < 1) m->kd[c] = fmin(m->kd[c] * (1 - f0d_max) / (1 - m->f0[c]), 1.0);
    }
    double alpha = p->roughness * p->roughness;
    m->r = p->roughness;
    m->anisotropy = 0;
    if (p->anisotropy > 0 && alpha > 0) {
        /* glTF: alpha_t = mix(alpha, 1, s^2), alpha_b = alpha. Disney (Eq. 7): alpha_x =
         * r^2 / aspect, alpha_y = r^2 aspect, aspect = sqrt(1 - 0.9 anisotropic). Equal
         * products give r; equal ratios give aspect^2 = alpha_b / alpha_t, within Disney's
         * reach (aspect^2 >= 0.1). */
        double s2 = p->anisotropy * p->anisotropy;
        double at = alpha + (1 - alpha) * s2, ab = alpha;
        m->r = fmin(sqrt(sqrt(at * ab)), 1.0);
        m->anisotropy = fmin((1 - ab / at) / 0.9, 1.0);
    }
}

int abrdf_pbr_lobes(const abrdf_pbr *p, abrdf_model lobes[ABRDF_PBR_MAX_LOBES], int *lobe_count,
                    abrdf_params *params)
{
    abrdf_pbr q;
    if (!lobes || !lobe_count || !params) return ABRDF_E_NULL;
    int st = pbr_read(p, &q);
    if (st == ABRDF_OK) st = pbr_valid(&q, NULL, 0);
    if (st != ABRDF_OK) return st;
    size_t out_size = params->struct_size;
    if (out_size < offsetof(abrdf_params, entry_grid)) return ABRDF_E_SIZE;
    pbr_mapped m;
    pbr_map(&q, &m);
    abrdf_model spec = m.anisotropy > 0 ? ABRDF_DISNEY_SPECULAR_ANISO : ABRDF_DISNEY_SPECULAR;
    abrdf_params full;
    abrdf_params_init(spec, &full);
    memcpy(full.kd, m.kd, sizeof m.kd);
    memcpy(full.ks, m.ks, sizeof m.ks);
    memcpy(full.f0, m.f0, sizeof m.f0);
    full.r = m.r;
    full.anisotropic = m.anisotropy;
    full.struct_size = out_size; /* the caller's layout: its struct_size bytes */
    memcpy(params, &full, out_size < sizeof full ? out_size : sizeof full);
    lobes[0] = ABRDF_LAMBERT_FRESNEL;
    lobes[1] = spec;
    *lobe_count = 2;
    return ABRDF_OK;
}

/* An interface's index from its normal reflectance (kappa 0): f0 = ((eta-1)/(eta+1))^2. */
static double eta_of_f0(double f0)
{
    double s = sqrt(fmin(fmax(f0, 0.0), 0.99));
    return fmin((1 + s) / (1 - s), 4.0);
}

int abrdf_pbr_material(const abrdf_pbr *p, abrdf_material *out)
{
    abrdf_pbr q;
    if (!out) return ABRDF_E_NULL;
    int st = pbr_read(p, &q);
    if (st == ABRDF_OK) st = pbr_valid(&q, NULL, 0);
    if (st != ABRDF_OK) return st;
    size_t out_size = out->struct_size;
    abrdf_material m;
    abrdf_material_init(&m);
    pbr_mapped v;
    pbr_map(&q, &v);
    memcpy(m.kd, v.kd, sizeof v.kd);
    memcpy(m.ks, v.ks, sizeof v.ks);
    memcpy(m.f0, v.f0, sizeof v.f0);
    m.r = v.r;
    m.anisotropy = v.anisotropy;
    double sheen = fmax(q.sheen_color[0], fmax(q.sheen_color[1], q.sheen_color[2]));
    if (q.clearcoat > 0) {
        int metal = q.metallic >= 0.5;
        m.type = metal ? ABRDF_SURFACE_LAYERED_METAL : ABRDF_SURFACE_LAYERED_PLASTIC;
        m.layer_count = metal ? 2 : 1;
        abrdf_layer coat = {1.5, 0, q.clearcoat_roughness, {0, 0, 0}, 0};
        m.layers[0] = coat;
        if (metal) { /* the metal below the coat: its normal reflectance, as an index */
            double f0 = 0.2126 * v.f0[0] + 0.7152 * v.f0[1] + 0.0722 * v.f0[2];
            abrdf_layer base = {fmax(eta_of_f0(f0) / 1.5, 0.25), 0, q.roughness, {0, 0, 0}, 0};
            m.layers[1] = base;
        }
    } else if (sheen > 0) {
        m.type = q.sheen_roughness >= 0.5 ? ABRDF_SURFACE_CLOTH_ROUGH : ABRDF_SURFACE_CLOTH_SHINY;
    }
    /* the caller's layout: its struct_size bytes */
    if (out_size < offsetof(abrdf_material, layers)) return ABRDF_E_SIZE;
    size_t n = out_size < sizeof m ? out_size : sizeof m;
    m.struct_size = out_size;
    memcpy(out, &m, n);
    return ABRDF_OK;
}
