/* rgl_bsdf.c - reading and evaluating RGL .bsdf files (rgl_bsdf.h).
 *
 * Source: J. Dupuy, W. Jakob, "An Adaptive Parameterization for Efficient Material
 * Acquisition and Rendering", ACM TOG 37(6), 2018. A material is stored per incident
 * direction on the unit square of a warp: the visible normals' distribution D_wi(m) =
 * D(m) <wi, m> / sigma(wi), mapped to (u_theta, u_phi) = (sqrt(2 theta / pi),
 * (phi + pi) / 2 pi) and inverted through its piecewise-bilinear marginal and conditional
 * CDFs; the reflectance is tabulated on the square the warp produces, so that its
 * samples crowd where the lobe is. Evaluation undoes the warp: half vector -> (u_theta, u_phi)
 * -> warped square -> bilinear lookup, with every table also interpolated linearly between
 * the incident slices around wi, as Mitsuba 3's `measured` plugin does.
 */
#define _POSIX_C_SOURCE 200809L
#include "rgl_bsdf.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "in_file.h"
#include "path_msg.h"
#include "rgl_warp.h"

#define PI 3.14159265358979323846
#define RGL_MAX_NAME 64 /* bytes of a field's name; the format's names are a few letters */

enum { RGL_U8 = 1, RGL_F32 = 10, RGL_TYPE_MAX = 11 };
static const size_t type_bytes[RGL_TYPE_MAX + 1] = {0, 1, 1, 2, 2, 4, 4, 8, 8, 2, 4, 8};
static const char *const type_names[RGL_TYPE_MAX + 1] = {"?",     "uint8",   "int8",    "uint16",
                                                         "int16", "uint32",  "int32",   "uint64",
                                                         "int64", "float16", "float32", "float64"};

typedef struct rgl_field {
    char name[RGL_MAX_NAME + 1];
    unsigned type;
    unsigned rank;
    uint64_t shape[RGL_MAX_RANK];
    uint64_t offset, count, bytes; /* count elements, bytes of data at offset */
} rgl_field;

struct rgl_bsdf {
    int n_phi, n_theta;     /* incident slices (phi_i, theta_i) */
    float *phi_i, *theta_i; /* radians, strictly increasing */
    int jacobian;           /* rgb holds f_r cos / (D(m) / (4 sigma(wi))) */
    rgl_grid ndf, sigma;    /* D(u_m) and sigma(u_wi): one slice each, not normalised */
    rgl_warp vndf;          /* n_phi * n_theta slices, normalised, with CDFs */
    rgl_grid rgb;           /* n_phi * n_theta * 3 slices */
    char *description;
};

/* ---- bytes ----------------------------------------------------------------------------- */

static uint64_t le(const unsigned char *p, int n)
{
    uint64_t v = 0;
    for (int k = n - 1; k >= 0; --k) v = v << 8 | p[k];
    return v;
}

static float le_f32(const unsigned char *p)
{
    uint32_t u = (uint32_t)le(p, 4);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* ---- the tensor file's header ------------------------------------------------------------ */

typedef struct cursor {
    const unsigned char *p;
    size_t size, at;
} cursor;

static int take(cursor *c, size_t n, const unsigned char **out)
{
    if (n > c->size - c->at) return -1;
    *out = c->p + c->at;
    c->at += n;
    return 0;
}

static int cmp_offset(const void *a, const void *b)
{
    const rgl_field *x = *(const rgl_field *const *)a, *y = *(const rgl_field *const *)b;
    return x->offset < y->offset ? -1 : x->offset > y->offset;
}

/* The fields of the file, every one inside it and none overlapping another or the header.
 * 0, or -1 with ": reason" in why. */
static int read_header(const unsigned char *data, size_t size, rgl_field **out, unsigned *n_out,
                       char *why, size_t why_size)
{
    *out = NULL;
    *n_out = 0;
    cursor c = {data, size, 0};
    const unsigned char *p;
    if (size < 18) {
        snprintf(why, why_size, ": %zu bytes, too short for a tensor file (truncated?)", size);
        return -1;
    }
    take(&c, 12, &p);
    if (memcmp(p, "tensor_file", 12) != 0) {
        snprintf(why, why_size, ": not a tensor file (no \"tensor_file\" header)");
        return -1;
    }
    take(&c, 2, &p);
    if (p[0] != 1 || p[1] != 0) {
        snprintf(why, why_size, ": tensor file version %u.%u, expected 1.0", p[0], p[1]);
        return -1;
    }
    take(&c, 4, &p);
    uint64_t n = le(p, 4);
    if (n < 1 || n > RGL_MAX_FIELDS) {
        snprintf(why, why_size, ": %llu fields, expected 1 to %d", (unsigned long long)n,
                 RGL_MAX_FIELDS);
        return -1;
    }
    rgl_field *f = calloc((size_t)n, sizeof *f);
    rgl_field **order = calloc((size_t)n, sizeof *order);
    if (!f || !order) {
        snprintf(why, why_size, ": out of memory");
        goto fail;
    }
    for (unsigned i = 0; i < n; ++i) {
        rgl_field *g = &f[i];
        if (take(&c, 2, &p)) goto truncated;
        size_t len = (size_t)le(p, 2);
        if (len < 1 || len > RGL_MAX_NAME) {
            snprintf(why, why_size, ": field %u: a name of %zu bytes, expected 1 to %d", i, len,
                     RGL_MAX_NAME);
            goto fail;
        }
        if (take(&c, len, &p)) goto truncated;
        for (size_t k = 0; k < len; ++k)
            if (p[k] < 0x21 || p[k] > 0x7e) {
                snprintf(why, why_size, ": field %u: its name has byte 0x%02x", i, p[k]);
                goto fail;
            }
        memcpy(g->name, p, len);
        for (unsigned j = 0; j < i; ++j)
            if (strcmp(f[j].name, g->name) == 0) {
                snprintf(why, why_size, ": field \"%s\" appears twice", g->name);
                goto fail;
            }
        if (take(&c, 2 + 1 + 8, &p)) goto truncated;
        g->rank = (unsigned)le(p, 2);
        g->type = p[2];
        g->offset = le(p + 3, 8);
        if (g->type < 1 || g->type > RGL_TYPE_MAX) {
            snprintf(why, why_size, ": field \"%s\": unknown type %u", g->name, g->type);
            goto fail;
        }
        if (g->rank > RGL_MAX_RANK) {
            snprintf(why, why_size, ": field \"%s\": rank %u, at most %d", g->name, g->rank,
                     RGL_MAX_RANK);
            goto fail;
        }
        if (take(&c, 8 * (size_t)g->rank, &p)) goto truncated;
        /* Each extent and the running product stay below the file's size, so that nothing
         * overflows and no field claims more bytes than the file has. */
        g->count = 1;
        for (unsigned k = 0; k < g->rank; ++k) {
            g->shape[k] = le(p + 8 * k, 8);
            if (g->shape[k] > size || (g->shape[k] && g->count > size / g->shape[k])) {
                snprintf(why, why_size, ": field \"%s\": shape larger than the file", g->name);
                goto fail;
            }
            g->count *= g->shape[k];
        }
        if (g->count > size / type_bytes[g->type]) {
            snprintf(why, why_size, ": field \"%s\": shape larger than the file", g->name);
            goto fail;
        }
        g->bytes = g->count * type_bytes[g->type];
    }
    for (unsigned i = 0; i < n; ++i) {
        rgl_field *g = &f[i];
        if (g->bytes && (g->offset < c.at || g->offset > size || g->bytes > size - g->offset)) {
            snprintf(why, why_size,
                     ": field \"%s\": %llu bytes at offset %llu, outside the data (%zu to %zu)",
                     g->name, (unsigned long long)g->bytes, (unsigned long long)g->offset, c.at,
                     size);
            goto fail;
        }
        order[i] = g;
    }
    qsort(order, (size_t)n, sizeof *order, cmp_offset);
    /* each field with data against the last one before it with data (an empty field
     * between them overlaps nothing) */
    const rgl_field *prev = NULL;
    for (unsigned i = 0; i < n; ++i) {
        const rgl_field *b = order[i];
        if (!b->bytes) continue;
        if (prev && prev->offset + prev->bytes > b->offset) {
            snprintf(why, why_size, ": fields \"%s\" and \"%s\" overlap", prev->name, b->name);
            goto fail;
        }
        prev = b;
    }
    free(order);
    *out = f;
    *n_out = (unsigned)n;
    return 0;
truncated:
    snprintf(why, why_size, ": the field table ends past the end of the file (truncated?)");
fail:
    free(f);
    free(order);
    return -1;
}

static const rgl_field *field(const rgl_field *f, unsigned n, const char *name)
{
    for (unsigned i = 0; i < n; ++i)
        if (strcmp(f[i].name, name) == 0) return &f[i];
    return NULL;
}

/* The field's shape as text ("[1, 16, 3, 64, 64]"), for messages. */
static const char *shape_text(const rgl_field *g, char *buf, size_t size)
{
    size_t at = 0;
    at += (size_t)snprintf(buf, size, "[");
    for (unsigned k = 0; k < g->rank && at < size; ++k)
        at += (size_t)snprintf(buf + at, size - at, "%s%llu", k ? ", " : "",
                               (unsigned long long)g->shape[k]);
    if (at < size) snprintf(buf + at, size - at, "]");
    return buf;
}

/* The field exists with this type and rank, or ": reason" in why. */
static const rgl_field *need(const rgl_field *f, unsigned n, const char *name, unsigned type,
                             unsigned rank, char *why, size_t why_size)
{
    const rgl_field *g = field(f, n, name);
    if (!g)
        snprintf(why, why_size, ": no \"%s\" field (not a material of the RGL database?)", name);
    else if (g->type != type || g->rank != rank) {
        snprintf(why, why_size, ": field \"%s\": %s of rank %u, expected %s of rank %u", name,
                 type_names[g->type], g->rank, type_names[type], rank);
        g = NULL;
    }
    return g;
}

/* Copy a float32 field, refusing NaN, Inf and (if nonneg) negative values. */
static float *floats(const unsigned char *data, const rgl_field *g, int nonneg, char *why,
                     size_t why_size)
{
    float *v = malloc((size_t)(g->count ? g->count : 1) * sizeof *v);
    if (!v) {
        snprintf(why, why_size, ": out of memory for field \"%s\"", g->name);
        return NULL;
    }
    for (uint64_t k = 0; k < g->count; ++k) {
        v[k] = le_f32(data + g->offset + 4 * k);
        if (!isfinite(v[k]) || (nonneg && v[k] < 0)) {
            snprintf(why, why_size, ": field \"%s\": value %llu is %g%s", g->name,
                     (unsigned long long)k, (double)v[k], isfinite(v[k]) ? ", expected >= 0" : "");
            free(v);
            return NULL;
        }
    }
    return v;
}

static int increasing(const float *v, int n)
{
    for (int k = 1; k < n; ++k)
        if (!(v[k] > v[k - 1])) return 0;
    return 1;
}

void rgl_free(rgl_bsdf *b)
{
    if (!b) return;
    free(b->phi_i);
    free(b->theta_i);
    free(b->ndf.v);
    free(b->sigma.v);
    rgl_warp_free(&b->vndf);
    free(b->rgb.v);
    free(b->description);
    free(b);
}

/* Shapes first (nothing allocated), then the values. */
static int parse(const unsigned char *data, size_t size, rgl_bsdf **out, char *why, size_t why_size)
{
    rgl_field *f;
    unsigned n;
    char s1[96];
    if (read_header(data, size, &f, &n, why, why_size)) return -1;
    rgl_bsdf *b = NULL;
    const rgl_field *th, *ph, *ndf, *sig, *vndf, *lum, *rgb, *desc, *jac;
    if (!field(f, n, "rgb") && (field(f, n, "spectra") || field(f, n, "wavelengths"))) {
        snprintf(why, why_size,
                 ": a spectral file (no \"rgb\" field): read the database's RGB file instead");
        goto fail;
    }
    if (!(th = need(f, n, "theta_i", RGL_F32, 1, why, why_size)) ||
        !(ph = need(f, n, "phi_i", RGL_F32, 1, why, why_size)) ||
        !(ndf = need(f, n, "ndf", RGL_F32, 2, why, why_size)) ||
        !(sig = need(f, n, "sigma", RGL_F32, 2, why, why_size)) ||
        !(vndf = need(f, n, "vndf", RGL_F32, 4, why, why_size)) ||
        !(lum = need(f, n, "luminance", RGL_F32, 4, why, why_size)) ||
        !(rgb = need(f, n, "rgb", RGL_F32, 5, why, why_size)) ||
        !(desc = need(f, n, "description", RGL_U8, 1, why, why_size)) ||
        !(jac = need(f, n, "jacobian", RGL_U8, 1, why, why_size)))
        goto fail;
    uint64_t P = ph->shape[0], T = th->shape[0];
    if (P < 1 || T < 1) {
        snprintf(why, why_size, ": %llu phi_i and %llu theta_i slices, expected at least 1",
                 (unsigned long long)P, (unsigned long long)T);
        goto fail;
    }
    if (P > 2) {
        snprintf(why, why_size,
                 ": an anisotropic material (%llu phi_i slices): the measured table holds "
                 "isotropic BRDFs only",
                 (unsigned long long)P);
        goto fail;
    }
    if (jac->shape[0] != 1) {
        snprintf(why, why_size, ": field \"jacobian\": shape %s, expected [1]",
                 shape_text(jac, s1, sizeof s1));
        goto fail;
    }
    const rgl_field *grids[2] = {ndf, sig};
    for (int k = 0; k < 2; ++k)
        if (grids[k]->shape[0] < 2 || grids[k]->shape[1] < 2) {
            snprintf(why, why_size, ": field \"%s\": shape %s, expected at least [2, 2]",
                     grids[k]->name, shape_text(grids[k], s1, sizeof s1));
            goto fail;
        }
    if (vndf->shape[0] != P || vndf->shape[1] != T || vndf->shape[2] < 2 || vndf->shape[3] < 2) {
        snprintf(why, why_size, ": field \"vndf\": shape %s, expected [%llu, %llu, >= 2, >= 2]",
                 shape_text(vndf, s1, sizeof s1), (unsigned long long)P, (unsigned long long)T);
        goto fail;
    }
    if (rgb->shape[0] != P || rgb->shape[1] != T || rgb->shape[2] != 3 || rgb->shape[3] < 2 ||
        rgb->shape[3] != rgb->shape[4]) {
        snprintf(why, why_size, ": field \"rgb\": shape %s, expected [%llu, %llu, 3, n, n]",
                 shape_text(rgb, s1, sizeof s1), (unsigned long long)P, (unsigned long long)T);
        goto fail;
    }
    if (lum->shape[0] != P || lum->shape[1] != T || lum->shape[2] != rgb->shape[3] ||
        lum->shape[3] != rgb->shape[4]) {
        snprintf(why, why_size,
                 ": field \"luminance\": shape %s, expected [%llu, %llu, %llu, %llu]",
                 shape_text(lum, s1, sizeof s1), (unsigned long long)P, (unsigned long long)T,
                 (unsigned long long)rgb->shape[3], (unsigned long long)rgb->shape[4]);
        goto fail;
    }

    b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(why, why_size, ": out of memory");
        goto fail;
    }
    b->n_phi = (int)P;
    b->n_theta = (int)T;
    b->jacobian = data[jac->offset] != 0;
    float *lum_v = NULL;
    if (!(b->phi_i = floats(data, ph, 0, why, why_size)) ||
        !(b->theta_i = floats(data, th, 1, why, why_size)) ||
        !(b->ndf.v = floats(data, ndf, 1, why, why_size)) ||
        !(b->sigma.v = floats(data, sig, 1, why, why_size)) ||
        !(b->rgb.v = floats(data, rgb, 0, why, why_size)) ||
        !(lum_v = floats(data, lum, 1, why, why_size)))
        goto fail;
    free(lum_v); /* checked only: it guides sampling, not evaluation */
    if (!increasing(b->phi_i, b->n_phi) || !increasing(b->theta_i, b->n_theta) ||
        b->theta_i[b->n_theta - 1] > (float)(PI / 2) * 1.0001f) {
        snprintf(why, why_size,
                 ": theta_i and phi_i must increase strictly, theta_i within 0 to pi/2");
        goto fail;
    }
    b->ndf.h = (int)ndf->shape[0], b->ndf.w = (int)ndf->shape[1], b->ndf.n_slices = 1;
    b->sigma.h = (int)sig->shape[0], b->sigma.w = (int)sig->shape[1], b->sigma.n_slices = 1;
    b->rgb.h = (int)rgb->shape[3], b->rgb.w = (int)rgb->shape[4];
    b->rgb.n_slices = (int)(P * T * 3);
    if (b->jacobian)
        for (uint64_t k = 0; k < sig->count; ++k)
            if (!(b->sigma.v[k] > 0)) {
                snprintf(why, why_size, ": field \"sigma\": value %llu is 0 (it divides)",
                         (unsigned long long)k);
                goto fail;
            }
    float *vndf_v = floats(data, vndf, 1, why, why_size);
    if (!vndf_v) goto fail;
    int bad =
        rgl_warp_init(&b->vndf, vndf_v, (int)(P * T), (int)vndf->shape[2], (int)vndf->shape[3]);
    free(vndf_v);
    if (bad) {
        if (bad > 0)
            snprintf(why, why_size, ": field \"vndf\": slice %d integrates to 0", bad - 1);
        else
            snprintf(why, why_size, ": out of memory for the vndf's warp");
        goto fail;
    }
    b->description = malloc((size_t)desc->count + 1);
    if (!b->description) {
        snprintf(why, why_size, ": out of memory");
        goto fail;
    }
    if (desc->count) /* an empty field's offset is not checked: no pointer made from it */
        memcpy(b->description, data + desc->offset, (size_t)desc->count);
    b->description[desc->count] = '\0';
    free(f);
    *out = b;
    return 0;
fail:
    rgl_free(b);
    free(f);
    return -1;
}

int rgl_parse(const unsigned char *data, size_t size, const char *name, rgl_bsdf **out, char *err,
              size_t err_size)
{
    char why[256];
    *out = NULL;
    if (size > RGL_MAX_FILE_BYTES) {
        path_msg(err, err_size, name, ": %zu bytes, more than the %zu a .bsdf file may have", size,
                 RGL_MAX_FILE_BYTES);
        return -1;
    }
    if (parse(data, size, out, why, sizeof why)) {
        path_msg(err, err_size, name, "%s", why);
        return -1;
    }
    return 0;
}

int rgl_load(const char *path, rgl_bsdf **out, char *err, size_t err_size)
{
    *out = NULL;
    FILE *fp = in_file_open(path, err, err_size);
    if (!fp) return -1;
    struct stat st;
    if (fstat(fileno(fp), &st) != 0) {
        path_msg(err, err_size, path, ": %s", strerror(errno));
        fclose(fp);
        return -1;
    }
    if ((uintmax_t)st.st_size > RGL_MAX_FILE_BYTES) {
        path_msg(err, err_size, path, ": %jd bytes, more than the %zu a .bsdf file may have",
                 (intmax_t)st.st_size, RGL_MAX_FILE_BYTES);
        fclose(fp);
        return -1;
    }
    size_t size = (size_t)st.st_size;
    unsigned char *data = malloc(size ? size : 1);
    if (!data) {
        path_msg(err, err_size, path, ": out of memory for %zu bytes", size);
        fclose(fp);
        return -1;
    }
    size_t got = fread(data, 1, size, fp);
    int rerr = ferror(fp);
    fclose(fp);
    if (got != size) {
        path_msg(err, err_size, path, ": %s", rerr ? "read error" : "shorter than its size");
        free(data);
        return -1;
    }
    int r = rgl_parse(data, size, path, out, err, err_size);
    free(data);
    return r;
}

const char *rgl_description(const rgl_bsdf *b) { return b->description; }

/* ---- evaluation -------------------------------------------------------------------------- */

/* The elevation of unit d, accurate near the pole (2 asin(|d - z| / 2), not acos(d.z)). */
static double elevation(const double d[3])
{
    double s = sqrt(d[0] * d[0] + d[1] * d[1] + (d[2] - 1) * (d[2] - 1));
    return 2 * asin(fmin(0.5 * s, 1.0));
}

static double theta_to_u(double theta) { return sqrt(theta * (2 / PI)); }
static double phi_to_u(double phi) { return (phi + PI) * (0.5 / PI); }

/* The slices around x in values[0..n) and their weights (clamped at the ends). */
static void bracket(const float *values, int n, double x, int *i0, double *w1)
{
    *i0 = 0;
    *w1 = 0;
    if (n < 2) return;
    int lo = 1, hi = n - 1; /* the first k in [1, n-1] with values[k] >= x, else n-1 */
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (values[mid] < x)
            lo = mid + 1;
        else
            hi = mid;
    }
    *i0 = lo - 1;
    double t = (x - values[*i0]) / ((double)values[*i0 + 1] - values[*i0]);
    *w1 = t < 0 ? 0 : t > 1 ? 1 : t;
}

void rgl_eval(const rgl_bsdf *b, const double wi[3], const double wo[3], double rgb[3])
{
    rgb[0] = rgb[1] = rgb[2] = 0;
    if (!(wi[2] > 0 && wo[2] > 0)) return;
    double m[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
    double len = sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (!(len > 0)) return;
    for (int k = 0; k < 3; ++k) m[k] /= len;
    double theta_i = elevation(wi), phi_i = atan2(wi[1], wi[0]);
    double theta_m = elevation(m), phi_m = atan2(m[1], m[0]);
    double u_wi[2] = {theta_to_u(theta_i), phi_to_u(phi_i)};
    /* Isotropic: the half vector's azimuth relative to the light's. */
    double u_m[2] = {theta_to_u(theta_m), phi_to_u(phi_m - phi_i)};
    u_m[1] -= floor(u_m[1]);

    int ip, it;
    double wp, wt;
    bracket(b->phi_i, b->n_phi, phi_i, &ip, &wp);
    bracket(b->theta_i, b->n_theta, theta_i, &it, &wt);
    rgl_mix mix = {{0}, {0}, 0};
    for (int a = 0; a < 2; ++a)
        for (int c = 0; c < 2; ++c) {
            double w = (a ? wp : 1 - wp) * (c ? wt : 1 - wt);
            int pa = ip + (b->n_phi > 1 ? a : 0), tc = it + (b->n_theta > 1 ? c : 0);
            mix.slice[mix.n] = pa * b->n_theta + tc;
            mix.w[mix.n++] = w;
        }
    double s[2];
    rgl_warp_invert(&b->vndf, &mix, u_m, s);
    double scale = 1;
    if (b->jacobian) {
        rgl_mix one = {{0}, {1}, 1};
        double sigma = rgl_grid_eval(&b->sigma, &one, u_wi);
        scale = rgl_grid_eval(&b->ndf, &one, u_m) / (4 * sigma);
    }
    for (int ch = 0; ch < 3; ++ch) {
        rgl_mix mc = mix;
        for (int k = 0; k < mc.n; ++k) mc.slice[k] = mix.slice[k] * 3 + ch;
        /* The file holds f_r cos(theta_o): the cosine of the direction that is not the slice's. */
        double v = rgl_grid_eval(&b->rgb, &mc, s) * scale / wo[2];
        rgb[ch] = isfinite(v) && v > 0 ? v : 0;
    }
}

/* ---- onto the tools' table --------------------------------------------------------------- */

int rgl_read(const char *path, measured_table *out, int n_theta_h, int n_theta_d, int n_phi_d,
             char *err, size_t err_size)
{
    out->data = NULL;
    char why[256];
    if (measured_table_alloc(out, n_theta_h, n_theta_d, n_phi_d, why, sizeof why)) {
        path_msg(err, err_size, path, ": %s", why);
        return -1;
    }
    rgl_bsdf *b;
    if (rgl_load(path, &b, err, err_size)) {
        measured_table_free(out);
        return -1;
    }
    for (int ih = 0; ih < n_theta_h; ++ih)
        for (int id = 0; id < n_theta_d; ++id)
            for (int ip = 0; ip < n_phi_d; ++ip) {
                double wi[3], wo[3], f[3];
                measured_table_directions(out, ih, id, ip, wi, wo);
                float *cell = out->data + measured_table_cell(out, ih, id, ip);
                /* below the horizon, or within its last degree, where the file's warp divides
                 * by a vanishing cosine (values of 10^6 1/sr at 89.999 degrees): not measured */
                if (!(wi[2] > RGL_READ_Z_MIN && wo[2] > RGL_READ_Z_MIN)) continue;
                rgl_eval(b, wi, wo, f);
                for (int c = 0; c < 3; ++c) cell[c] = (float)f[c];
                --out->unmeasured;
            }
    rgl_free(b);
    return 0;
}
