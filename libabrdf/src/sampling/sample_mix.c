/* sample_mix.c - the sampler of every model: which components it mixes (sample_lobe.c),
 * with which probabilities, and the table abrdf_model_sampler hands out.
 * docs/RENDERER.md, "Importance sampling" explains each choice.
 *
 * Selection probabilities estimate each component's share of the albedo for this wo from
 * what the parameters say (colour means, Fresnel at N.wo, the layers' transmission); they
 * need not be right, only > 0 wherever a component's lobe is not 0: the weight is
 * f cos / sum_k P_k pdf_k exactly (one-sample MIS, E. Veach, "Robust Monte Carlo methods
 * for light transport simulation", PhD thesis, Stanford 1997, Sec. 9.2.4). */
#include <math.h>

#include "sample.h"
#include "k_dispatch.h"
#include "layered.h"
#include "layered_optics.h"

/* The share of the hair samplers' cosine component: a defensive mixture (T. Hesterberg,
 * "Weighted average importance sampling and defensive mixture distributions",
 * Technometrics 37(2), 1995) that keeps the weights bounded where the proposal of
 * sample_hair.c misses what the models scatter (huang's TRRT+, marschner's glints). */
#define ABRDF__HAIR_SAMPLE_COSINE 0.1

static double mean3(const double v[3]) { return (v[0] + v[1] + v[2]) / 3.0; }

static abrdf__lobe *add(abrdf__mixture *mx, abrdf__lobe_kind kind, double weight)
{
    static const abrdf__lobe zero;
    abrdf__lobe *l = &mx->lobe[mx->count++];
    *l = zero;
    l->kind = kind;
    l->prob = weight;
    return l;
}

static void add_dist(abrdf__mixture *mx, abrdf__lobe_kind kind, double weight, abrdf__dist_kind dk,
                     double n, int m, double a)
{
    abrdf__lobe *l = add(mx, kind, weight);
    l->dist.kind = dk;
    l->dist.n = n;
    l->dist.m = m;
    l->dist.a = a;
    abrdf__dist_setup(&l->dist, kind == ABRDF__LOBE_MIRROR ? -1.0 : 0.0);
}

static void add_vndf(abrdf__mixture *mx, double weight, double ax, double ay)
{
    abrdf__lobe *l = add(mx, ABRDF__LOBE_GGX_VNDF, weight);
    l->ax = ax;
    l->ay = ay;
}

/* Probabilities from the weights; components of weight 0 are dropped (their lobes are 0),
 * unless every weight is 0 (then f = 0 too and any density will do: equal shares). */
static void normalise(abrdf__mixture *mx)
{
    double sum = 0.0;
    for (int i = 0; i < mx->count; ++i) sum += fmax(mx->lobe[i].prob, 0.0);
    if (!(sum > 0.0) || !isfinite(sum)) {
        for (int i = 0; i < mx->count; ++i) mx->lobe[i].prob = 1.0 / mx->count;
        return;
    }
    int n = 0;
    for (int i = 0; i < mx->count; ++i)
        if (mx->lobe[i].prob > 0.0) {
            mx->lobe[n] = mx->lobe[i];
            mx->lobe[n++].prob /= sum;
        }
    mx->count = n;
}

/* Integral of cos^n over [-pi/2, pi/2]: sqrt(pi) Gamma((n + 1)/2) / Gamma(n/2 + 1). */
static double cos_power_width(double n)
{
    return exp(0.5 * log(ABRDF__PI) + lgamma(0.5 * (n + 1.0)) - lgamma(0.5 * n + 1.0));
}

/* Weidlich-Wilkie: one GGX visible-normal component per interface, weighted by the light
 * the stack reflects there at N.wo (exact Fresnel, transmission and absorption of the
 * layers above, Snell's law for the cosine), and the cosine for the Lambert base below the
 * last dielectric. Inner interfaces see the same half vector as the top (refraction at H
 * keeps L' + V' along H; layered_ww.c), so their D(H) is drawn about wo as well. */
static void setup_ww(const abrdf_params *p, abrdf__mixture *mx)
{
    double c = mx->wo[2], through = 1.0;
    int n = p->layer_count < ABRDF_MAX_LAYERS ? p->layer_count : ABRDF_MAX_LAYERS;
    for (int k = 0; k < n; ++k) {
        const abrdf_layer *ly = &p->layers[k];
        double ag = fmax(ly->r * ly->r, ABRDF__ALPHA_G_MIN);
        double f = abrdf__fresnel_exact(c, ly->eta, ly->kappa);
        add_vndf(mx, through * f, ag, ag);
        if (ly->kappa > 0.0) return; /* a conductor ends the stack: no base */
        double s2 = (1.0 - c * c) / (ly->eta * ly->eta);
        if (!(s2 < 1.0)) return; /* total internal reflection: nothing below */
        c = sqrt(1.0 - s2);
        through *= (1.0 - f) * exp(-2.0 * mean3(ly->sigma_a) * ly->depth / fmax(c, 1e-3));
    }
    add(mx, ABRDF__LOBE_COSINE, through * mean3(p->kd));
}

/* Belcour: one GGX visible-normal component per lobe of Eq. 16, energies and roughnesses
 * taken at the mean direction cos = N.wo, as the sampling of Belcour's reference code and
 * of the Photon-v2 port does (the evaluation takes them at H.L; MODELS.md B8.2). */
static void setup_belcour(const abrdf_params *p, abrdf__mixture *mx)
{
    double e[ABRDF_MAX_LAYERS][3], alpha[ABRDF_MAX_LAYERS];
    int n = abrdf__belcour_lobes(p, mx->wo[2], e, alpha);
    for (int k = 0; k < n; ++k) add_vndf(mx, mean3(e[k]), alpha[k], alpha[k]);
}

void abrdf__mixture_setup(abrdf_model model, const abrdf_params *p, const double wo[3],
                          abrdf__mixture *mx)
{
    const abrdf__lobe_kind mirror = ABRDF__LOBE_MIRROR, half = ABRDF__LOBE_HALF;
    mx->count = 0;
    for (int c = 0; c < 3; ++c) mx->wo[c] = wo[c];
    abrdf__kp k;
    switch (model) {
    case ABRDF_LAMBERT:
    case ABRDF_LAMBERT_FRESNEL:
    case ABRDF_DISNEY_DIFFUSE:
    case ABRDF_OREN_NAYAR: add(mx, ABRDF__LOBE_COSINE, 1.0); break;
    /* lobes on R.V: their own distribution about the mirror direction */
    case ABRDF_PHONG:
    case ABRDF_F_PHE: add_dist(mx, mirror, 1.0, ABRDF__DIST_POW, p->n, 0, 0.0); break;
    case ABRDF_F_2E: add_dist(mx, mirror, 1.0, ABRDF__DIST_FM, p->n, 2, 0.0); break;
    case ABRDF_F_16E: add_dist(mx, mirror, 1.0, ABRDF__DIST_FM, p->n, 16, 0.0); break;
    /* lobes on N.H: the half vector from the lobe (fkub: Blinn-Phong's, docs/RENDERER.md) */
    case ABRDF_BLINN_PHONG:
    case ABRDF_F_BE:
    case ABRDF_F_GE:
    case ABRDF_F_CTPHE:
    case ABRDF_FKUB: add_dist(mx, half, 1.0, ABRDF__DIST_POW, p->n, 0, 0.0); break;
    case ABRDF_F2:
    case ABRDF_F_CT2E: add_dist(mx, half, 1.0, ABRDF__DIST_FM, p->n, 2, 0.0); break;
    case ABRDF_F4: add_dist(mx, half, 1.0, ABRDF__DIST_FM, p->n, 4, 0.0); break;
    case ABRDF_F8: add_dist(mx, half, 1.0, ABRDF__DIST_FM, p->n, 8, 0.0); break;
    case ABRDF_F16:
    case ABRDF_F_CT16E: add_dist(mx, half, 1.0, ABRDF__DIST_FM, p->n, 16, 0.0); break;
    case ABRDF_FS: add_dist(mx, half, 1.0, ABRDF__DIST_SCHLICK, p->n, 0, 0.0); break;
    case ABRDF_FKV: add_dist(mx, half, 1.0, ABRDF__DIST_LINEAR, 0.0, 0, 0.786 * p->n); break;
    /* microfacet */
    case ABRDF_COOK_TORRANCE:
        k_microfacet_setup(&k, p);
        add_dist(mx, half, 1.0, ABRDF__DIST_BECKMANN, 0.0, 0, k.ag);
        break;
    case ABRDF_DISNEY_SPECULAR:
        k_microfacet_setup(&k, p);
        add_vndf(mx, 1.0, k.ag, k.ag);
        break;
    case ABRDF_DISNEY_SPECULAR_ANISO:
        k_disney_specular_aniso_setup(&k, p);
        add_vndf(mx, 1.0, k.ax, k.ay);
        break;
    case ABRDF_DISNEY_CLEARCOAT:
        k_disney_clearcoat_setup(&k, p);
        add_dist(mx, half, 1.0, ABRDF__DIST_GTR1, 0.0, 0, k.cc_alpha);
        break;
    /* cloth */
    case ABRDF_NEUBELT_PETTINEO: {
        /* cosine for the diffuse term, uniform for the sheen, whose f cos is nearly flat over
         * the hemisphere: measured better than the velvet D cos (docs/RENDERER.md, "Importance
         * sampling"). The sheen's albedo with F = 1 is 0.15-0.6 (0.3 typical) over r, k_amp,
         * theta_o. */
        double f = f_schlick(mean3(p->f0), wo[2]);
        add(mx, ABRDF__LOBE_COSINE, mean3(p->kd) * (1.0 - f));
        add(mx, ABRDF__LOBE_UNIFORM, mean3(p->ks) * f * 0.3);
        break;
    }
    case ABRDF_KAJIYA_KAY: {
        double s2 = fmax(wo[1] * wo[1] + wo[2] * wo[2], 0.05);    /* sin^2 of the cone */
        add(mx, ABRDF__LOBE_FIBRE_SIN, mean3(p->kd) * 8.0 / 3.0); /* int sin(T,w) N.w dw */
        add(mx, ABRDF__LOBE_FIBRE_CONE, mean3(p->ks) * 2.0 * s2 * cos_power_width(p->n))->n = p->n;
        break;
    }
    /* hair */
    case ABRDF_MARSCHNER:
    case ABRDF_HUANG:
        abrdf__hair_sampler_setup(model, p, wo, &mx->hair);
        add(mx, ABRDF__LOBE_HAIR, 1.0 - ABRDF__HAIR_SAMPLE_COSINE);
        add(mx, ABRDF__LOBE_COSINE, ABRDF__HAIR_SAMPLE_COSINE);
        break;
    /* layered */
    case ABRDF_WEIDLICH_WILKIE: setup_ww(p, mx); break;
    case ABRDF_BELCOUR: setup_belcour(p, mx); break;
    default: break;
    }
    if (mx->count == 0) add(mx, ABRDF__LOBE_COSINE, 1.0); /* every model is listed above */
    normalise(mx);
}

void abrdf__mixture_setup_measured(const abrdf__measured *m, const double wo[3], abrdf__mixture *mx)
{
    mx->count = 0;
    for (int c = 0; c < 3; ++c) mx->wo[c] = wo[c];
    add(mx, ABRDF__LOBE_COSINE, 1.0 - m->p_lobe);
    add_vndf(mx, m->p_lobe, m->alpha, m->alpha);
    normalise(mx);
}

int abrdf__mixture_sample(const abrdf__mixture *mx, double u1, double u2, double wi[3])
{
    int i = 0;
    double c = 0.0;
    while (i < mx->count - 1 && u1 >= c + mx->lobe[i].prob) c += mx->lobe[i++].prob;
    /* reuse u1: its position inside the chosen component's share, back on [0, 1) */
    double u = fmin(fmax((u1 - c) / mx->lobe[i].prob, 0.0), ABRDF__SAMPLE_U_MAX);
    if (abrdf__lobe_sample(&mx->lobe[i], mx, u, fmin(u2, ABRDF__SAMPLE_U_MAX), wi)) return 1;
    wi[0] = wi[1] = 0.0;
    wi[2] = 1.0;
    return 0;
}

double abrdf__mixture_pdf(const abrdf__mixture *mx, const double wi[3])
{
    double pdf = 0.0;
    for (int i = 0; i < mx->count; ++i)
        pdf += mx->lobe[i].prob * abrdf__lobe_pdf(&mx->lobe[i], mx, wi);
    return pdf;
}

/* ---- the table of abrdf_model_sampler ------------------------------------------------- */

#define BELOW ABRDF_SAMPLER_BELOW
#define MIX ABRDF_SAMPLER_MIXTURE
#define CIT_MALLEY                                                                                 \
    "Malley's method (Pharr, Jakob, Humphreys, Physically Based Rendering, 4th ed., App. A.5)"
#define CIT_LW                                                                                     \
    "E. Lafortune, Y. Willems, Using the modified Phong reflectance model for physically based "   \
    "rendering, KU Leuven TR CW197, 1994"
#define CIT_WALTER                                                                                 \
    "B. Walter, S. Marschner, H. Li, K. Torrance, Microfacet models for refraction through rough " \
    "surfaces, EGSR 2007"
#define CIT_VNDF                                                                                   \
    "E. Heitz, Sampling the GGX distribution of visible normals, JCGT 7(4), 2018; J. Dupuy, A. "   \
    "Benyoub, Sound and robust sampling of the GGX distribution of visible normals, HPG 2023"
#define CIT_BURLEY                                                                                 \
    "B. Burley, Physically-Based Shading at Disney, SIGGRAPH 2012 course notes, App. B"
#define CIT_VEACH                                                                                  \
    "E. Veach, Robust Monte Carlo methods for light transport simulation, PhD thesis, Stanford "   \
    "1997, Sec. 9.2.4"
#define CIT_HAIR                                                                                   \
    "E. d'Eon, G. Francois, M. Hill, J. Letteri, J.-M. Aubry, An energy-conserving hair "          \
    "reflectance model, EGSR 2011; Pharr, Jakob, Humphreys, Physically Based Rendering, 4th ed., " \
    "Sec. 9.9"
#define HALF_BP "half vector from (n + 1) cos^n(theta_h) / (2 pi) about N, wi = reflect(wo, h)"
#define HALF_FM "half vector from the lobe's own ((n/m)(N.h - 1) + 1)^m, inverted in closed form"
#define MIRROR_FM                                                                                  \
    "wi from the lobe's own ((n/m)(R.wi - 1) + 1)^m about the mirror direction R of wo"

/* clang-format off */
static const abrdf_sampler_info samplers[ABRDF_MODEL_COUNT] = {
    [ABRDF_LAMBERT] = {"cosine", "cosine-weighted hemisphere: weight = kd exactly", CIT_MALLEY, 0},
    [ABRDF_LAMBERT_FRESNEL] = {"cosine", "cosine-weighted hemisphere", CIT_MALLEY, 0},
    [ABRDF_DISNEY_DIFFUSE] = {"cosine", "cosine-weighted hemisphere", CIT_MALLEY, 0},
    [ABRDF_OREN_NAYAR] = {"cosine", "cosine-weighted hemisphere", CIT_MALLEY, 0},
    [ABRDF_PHONG] = {"phong_lobe", "wi from (n + 1) cos^n / (2 pi) about the mirror direction of wo (the lobe's own)", CIT_LW, BELOW},
    [ABRDF_BLINN_PHONG] = {"blinn_phong_half", HALF_BP " (the lobe's own)", CIT_WALTER, BELOW},
    [ABRDF_F2] = {"power_form_half", HALF_FM ", m = 2", CIT_WALTER, BELOW},
    [ABRDF_F4] = {"power_form_half", HALF_FM ", m = 4", CIT_WALTER, BELOW},
    [ABRDF_F8] = {"power_form_half", HALF_FM ", m = 8", CIT_WALTER, BELOW},
    [ABRDF_F16] = {"power_form_half", HALF_FM ", m = 16", CIT_WALTER, BELOW},
    [ABRDF_FS] = {"schlick_half", "half vector from 1/(1 + n (1 - N.h)), the tail of Schlick's form (its ratio to the lobe is <= 1)", CIT_WALTER, BELOW},
    [ABRDF_FKV] = {"linear_half", "half vector from 1 - 0.786 n (1 - N.h) on its support, the lobe without its factor N.h", CIT_WALTER, BELOW},
    [ABRDF_FKUB] = {"blinn_phong_half", HALF_BP ": the fitted cubic has no closed-form inverse and is within 0.11 of cos^n on its zone, where cos^n >= 0.1", CIT_WALTER, BELOW},
    [ABRDF_F_PHE] = {"phong_lobe", "wi from (n + 1) cos^n / (2 pi) about the mirror direction of wo (the lobe's own)", CIT_LW, BELOW},
    [ABRDF_F_BE] = {"blinn_phong_half", HALF_BP " (the lobe's own)", CIT_WALTER, BELOW},
    [ABRDF_F_2E] = {"power_form_mirror", MIRROR_FM ", m = 2", CIT_LW, BELOW},
    [ABRDF_F_16E] = {"power_form_mirror", MIRROR_FM ", m = 16", CIT_LW, BELOW},
    [ABRDF_F_GE] = {"blinn_phong_half", HALF_BP " (the lobe's own)", CIT_WALTER, BELOW},
    [ABRDF_F_CTPHE] = {"blinn_phong_half", HALF_BP " (D's own)", CIT_WALTER, BELOW},
    [ABRDF_F_CT2E] = {"power_form_half", HALF_FM ", m = 2 (D's own)", CIT_WALTER, BELOW},
    [ABRDF_F_CT16E] = {"power_form_half", HALF_FM ", m = 16 (D's own)", CIT_WALTER, BELOW},
    [ABRDF_COOK_TORRANCE] = {"beckmann_d_cos", "half vector from D_Beckmann cos(theta_h), tan^2 = -alpha^2 log(1 - u)", CIT_WALTER, BELOW},
    [ABRDF_DISNEY_SPECULAR] = {"ggx_vndf", "GGX visible normals of wo (spherical caps), reflected: weight = F G1(wi)", CIT_VNDF, BELOW},
    [ABRDF_DISNEY_SPECULAR_ANISO] = {"ggx_vndf", "anisotropic GGX visible normals of wo (spherical caps), reflected: weight = F G1(wi)", CIT_VNDF, BELOW},
    [ABRDF_DISNEY_CLEARCOAT] = {"gtr1_d_cos", "half vector from D_GTR1 cos(theta_h), cos^2 = (1 - alpha^(2(1-u)))/(1 - alpha^2)", CIT_BURLEY, BELOW},
    [ABRDF_NEUBELT_PETTINEO] = {"cosine_uniform", "cosine for (1 - F) kd/pi, uniform hemisphere for the sheen (its f cos is nearly flat; the velvet D cos measured worse); one-sample MIS", CIT_MALLEY "; " CIT_VEACH, MIX},
    [ABRDF_KAJIYA_KAY] = {"fibre_lobes", "kd sin(T, wi) N.wi exactly; trimmed logistic about the specular cone for the ks lobe; one-sample MIS", CIT_VEACH, MIX},
    [ABRDF_MARSCHNER] = {"hair_lobes", "far-field R/TT/TRT above the ribbon: (offset h, lobe) by attenuation, logistic theta_i about M_p's peak, logistic azimuth about Phi(p, h); 10% cosine", CIT_HAIR, MIX},
    [ABRDF_HUANG] = {"hair_lobes", "marschner's R/TT/TRT proposal with widths from the GGX roughness (approximate: no exact sampler of Huang's integrals), 10% cosine", CIT_HAIR, MIX},
    [ABRDF_WEIDLICH_WILKIE] = {"layered_vndf_cosine", "GGX visible normals per interface, cosine for the Lambert base, shares from Fresnel and transmission at N.wo", CIT_VNDF "; " CIT_VEACH, MIX | BELOW},
    [ABRDF_MEASURED] = {"measured_vndf_cosine", "cosine, and GGX visible normals with the roughness and share fitted to the table at prepare (its lobe at normal incidence); one-sample MIS", CIT_VNDF "; " CIT_VEACH, MIX | BELOW},
    [ABRDF_BELCOUR] = {"belcour_vndf", "GGX visible normals per lobe of Eq. 16, energies and roughnesses at N.wo", CIT_VNDF "; " CIT_VEACH, MIX | BELOW},
};
/* clang-format on */

const abrdf_sampler_info *abrdf_model_sampler(abrdf_model model)
{
    if ((int)model < 0 || model >= ABRDF_MODEL_COUNT || !abrdf_model_get(model)) return NULL;
    const abrdf_sampler_info *s = &samplers[model];
    return s->name ? s : NULL;
}
