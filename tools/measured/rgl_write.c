/* rgl_write.c - an isotropic RGL .bsdf file made from a BRDF given as a function (rgl_bsdf.h).
 *
 * The fields are derived numerically as the acquisition of Dupuy & Jakob, "An Adaptive
 * Parameterization for Efficient Material Acquisition and Rendering", ACM TOG 37(6), 2018,
 * derives them from measurements, with these simplifications (docs/MEASURED.md, "RGL .bsdf files"):
 *  - ndf: D(theta) from the back-scattered luminance, D ~ Y(f_r(w, w)) cos^2(theta) (the
 *    retro-reflection of a microfacet BRDF is F D G / (4 cos^2); the paper refines
 *    it by power iteration, here the shadowing G is taken as 1), floored at 1e-4 of its peak
 *    and normalised so that the projected microfacet area is 1;
 *  - sigma(theta_i) = integral of D(m) <wi, m>+ over the hemisphere, by quadrature;
 *  - vndf: D(m) <wi, m>+ / sigma(wi) on the square (u_theta, u_phi), times the square's
 *    Jacobian 2 pi^2 u_theta sin(theta_m), plus 0.1 of its mean: every row can then be
 *    inverted (the lobe's azimuthal far side is empty at grazing incidence), and the warp
 *    keeps nodes near the pole, where the Jacobian vanishes as u_theta^3 (with 1e-3 the first
 *    column of a 64-node square spans 11 degrees of theta_m there, and a Lambert BRDF read
 *    back was off by 7% near the mirror direction; with 0.1, 1.3%);
 *  - rgb: at each node of the warped square, f_r cos(theta_o) / (D(m) / (4 sigma(wi))) for
 *    the m the warp gives and wo = m's mirror of wi (jacobian = 1: the sampling weight of the
 *    visible normals, smooth where the BRDF is microfacet-like), 0 where wo is below the
 *    horizon;
 *  - luminance: the luminance of that weight plus 1e-4 of its peak (a density for sampling);
 *  - one phi_i slice (isotropic), theta_i uniform in 0 to 90 degrees; the 90-degree slice is
 *    tabulated 0.06 degrees above the horizon, where f_r is still defined.
 */
#include "rgl_bsdf.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "out_file.h"
#include "path_msg.h"
#include "rgl_warp.h"

#define PI 3.14159265358979323846
#define GRAZING_EPS 1e-3 /* radians below 90 degrees where the last slice is tabulated */
#define NDF_FLOOR 1e-4   /* of D's peak: D > 0 everywhere, so that the ratio is finite */
#define VNDF_FLOOR 0.1   /* of the vndf's mean: the warp's rows invertible, nodes near the pole */
#define LUM_FLOOR 1e-4   /* of the luminance's peak: a density positive everywhere */
#define SIGMA_QUAD 256   /* quadrature nodes per axis of sigma's integral */

static double luminance(const double c[3]) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

static void direction(double theta, double phi, double d[3])
{
    d[0] = sin(theta) * cos(phi);
    d[1] = sin(theta) * sin(phi);
    d[2] = cos(theta);
}

/* D at u_theta, interpolated linearly as the file's reader does. */
static double ndf_at(const float *ndf, int n, double u)
{
    double x = u * (n - 1);
    int k = (int)x;
    if (k > n - 2) k = n - 2;
    if (k < 0) k = 0;
    double t = x - k;
    return ndf[k] + (ndf[k + 1] - (double)ndf[k]) * t;
}

/* integral of D(m) <w, m>+ over the hemisphere, w at elevation theta, on the square of
 * (u_theta, u_phi) with its Jacobian 2 pi^2 u sin(theta_m). */
static double projected_area(const float *ndf, int n, double theta)
{
    double w[3], m[3], sum = 0;
    direction(theta, 0, w);
    for (int a = 0; a < SIGMA_QUAD; ++a) {
        double u = (a + 0.5) / SIGMA_QUAD, tm = u * u * (PI / 2), d = ndf_at(ndf, n, u);
        for (int b = 0; b < SIGMA_QUAD; ++b) {
            direction(tm, (b + 0.5) / SIGMA_QUAD * 2 * PI - PI, m);
            double c = w[0] * m[0] + w[1] * m[1] + w[2] * m[2];
            if (c > 0) sum += d * c * 2 * PI * PI * u * sin(tm);
        }
    }
    return sum / ((double)SIGMA_QUAD * SIGMA_QUAD);
}

typedef struct tensor {
    const char *name;
    unsigned type; /* 1 u8, 10 f32 */
    unsigned rank;
    uint64_t shape[5];
    const void *data;
    uint64_t count, offset;
} tensor;

static void put(unsigned char **p, uint64_t v, int n)
{
    for (int k = 0; k < n; ++k) (*p)[k] = (unsigned char)(v >> (8 * k));
    *p += n;
}

/* The tensor file: header, then each field's data at an offset aligned to 8 bytes. */
static int write_tensors(const char *path, tensor *t, int n, char *err, size_t err_size)
{
    size_t header = 12 + 2 + 4;
    for (int i = 0; i < n; ++i) {
        t[i].count = 1;
        for (unsigned k = 0; k < t[i].rank; ++k) t[i].count *= t[i].shape[k];
        header += 2 + strlen(t[i].name) + 2 + 1 + 8 + 8 * t[i].rank;
    }
    uint64_t at = header;
    for (int i = 0; i < n; ++i) {
        at = (at + 7) / 8 * 8;
        t[i].offset = at;
        at += t[i].count * (t[i].type == 1 ? 1 : 4);
    }
    unsigned char *head = malloc(header), *p = head;
    if (!head) {
        path_msg(err, err_size, path, ": out of memory");
        return -1;
    }
    memcpy(p, "tensor_file", 12);
    p += 12;
    put(&p, 1, 1);
    put(&p, 0, 1);
    put(&p, (uint64_t)n, 4);
    for (int i = 0; i < n; ++i) {
        size_t len = strlen(t[i].name);
        put(&p, len, 2);
        memcpy(p, t[i].name, len);
        p += len;
        put(&p, t[i].rank, 2);
        put(&p, t[i].type, 1);
        put(&p, t[i].offset, 8);
        for (unsigned k = 0; k < t[i].rank; ++k) put(&p, t[i].shape[k], 8);
    }
    out_file o = OUT_FILE_INIT;
    if (out_file_open(&o, path, err, err_size)) {
        free(head);
        return -1;
    }
    out_file_write(&o, head, header);
    free(head);
    uint64_t pos = header;
    static const unsigned char zeros[8] = {0};
    for (int i = 0; i < n; ++i) {
        out_file_write(&o, zeros, (size_t)(t[i].offset - pos));
        if (t[i].type == 1) {
            out_file_write(&o, t[i].data, (size_t)t[i].count);
        } else {
            const float *f = t[i].data;
            unsigned char buf[4096];
            size_t k = 0;
            while (k < t[i].count) {
                size_t m = 0;
                for (; m < sizeof buf / 4 && k < t[i].count; ++m, ++k) {
                    uint32_t u;
                    memcpy(&u, &f[k], 4);
                    unsigned char *q = buf + 4 * m;
                    put(&q, u, 4);
                }
                out_file_write(&o, buf, 4 * m);
            }
        }
        pos = t[i].offset + t[i].count * (t[i].type == 1 ? 1 : 4);
    }
    out_file *all[1] = {&o};
    int r = out_file_close(&o, err, err_size) || out_file_commit(all, 1, err, err_size) ? -1 : 0;
    out_file_discard(&o);
    return r;
}

int rgl_write(const char *path, rgl_brdf_fn f, void *user, const rgl_write_grid *grid,
              const char *description, char *err, size_t err_size)
{
    int T = grid->n_theta_i, nn = grid->n_ndf, nw = grid->n_warp;
    if (T < 2 || T > 64 || nn < 2 || nn > 512 || nw < 2 || nw > 256) {
        path_msg(err, err_size, path,
                 ": grid %d theta_i, %d ndf, %d warp nodes: expected [2, 64], [2, 512], [2, 256]",
                 T, nn, nw);
        return -1;
    }
    size_t slice = (size_t)nw * nw;
    float *theta_i = malloc(T * sizeof *theta_i), phi_i[1] = {0};
    float *ndf = malloc(2 * (size_t)nn * sizeof *ndf),
          *sigma = malloc(2 * (size_t)nn * sizeof *sigma);
    float *vndf = malloc(T * slice * sizeof *vndf), *lum = malloc(T * slice * sizeof *lum);
    float *rgb = malloc(3 * T * slice * sizeof *rgb);
    rgl_warp warp = {0, 0, 0, NULL, NULL, NULL};
    int r = -1;
    if (!theta_i || !ndf || !sigma || !vndf || !lum || !rgb) {
        path_msg(err, err_size, path, ": out of memory");
        goto done;
    }

    /* ndf from the back-scattering, normalised: integral of D cos over the hemisphere = 1. */
    double peak = 0;
    for (int j = 0; j < nn; ++j) {
        double u = (double)j / (nn - 1), th = fmin(u * u * (PI / 2), PI / 2 - GRAZING_EPS), w[3];
        double c[3];
        direction(th, 0, w);
        f(user, w, w, c);
        double d = luminance(c) * cos(th) * cos(th);
        ndf[j] = (float)(isfinite(d) && d > 0 ? d : 0);
        if (ndf[j] > peak) peak = ndf[j];
    }
    for (int j = 0; j < nn; ++j) ndf[j] = peak > 0 ? (float)fmax(ndf[j], NDF_FLOOR * peak) : 1.0f;
    double area = projected_area(ndf, nn, 0); /* = integral of D cos */
    for (int j = 0; j < nn; ++j) ndf[j] = ndf[nn + j] = (float)(ndf[j] / area);
    for (int j = 0; j < nn; ++j) {
        double u = (double)j / (nn - 1);
        sigma[j] = sigma[nn + j] = (float)projected_area(ndf, nn, u * u * (PI / 2));
    }
    rgl_grid ndf_g = {nn, 2, 1, ndf}, sigma_g = {nn, 2, 1, sigma};
    rgl_mix one = {{0}, {1}, 1};

    /* vndf per incident slice, then the warp that the reader will build from those floats. */
    for (int k = 0; k < T; ++k) {
        theta_i[k] = (float)(k * (PI / 2) / (T - 1));
        double th = fmin(theta_i[k], PI / 2 - GRAZING_EPS), wi[3], m[3];
        direction(th, 0, wi);
        double ui[2] = {sqrt(theta_i[k] * (2 / PI)), 0.5};
        double sig = rgl_grid_eval(&sigma_g, &one, ui), mean = 0;
        float *v = vndf + k * slice;
        for (int y = 0; y < nw; ++y)
            for (int x = 0; x < nw; ++x) {
                double u[2] = {(double)x / (nw - 1), (double)y / (nw - 1)};
                double tm = u[0] * u[0] * (PI / 2);
                direction(tm, 2 * PI * u[1] - PI, m);
                double c = wi[0] * m[0] + wi[1] * m[1] + wi[2] * m[2];
                double d = c > 0 ? rgl_grid_eval(&ndf_g, &one, u) * c / sig : 0;
                v[y * nw + x] = (float)(d * 2 * PI * PI * u[0] * sin(tm));
                mean += v[y * nw + x];
            }
        mean /= (double)slice;
        for (size_t q = 0; q < slice; ++q) /* uniform if the grid misses the lobe */
            v[q] = mean > 0 ? (float)(v[q] + VNDF_FLOOR * mean) : 1.0f;
    }
    if (rgl_warp_init(&warp, vndf, T, nw, nw)) { /* each slice is positive: only memory */
        path_msg(err, err_size, path, ": out of memory for the warp");
        goto done;
    }

    /* rgb: the sampling weight at each node of the warped square; luminance: its density. */
    for (int k = 0; k < T; ++k) {
        double th = fmin(theta_i[k], PI / 2 - GRAZING_EPS), wi[3], m[3], wo[3];
        direction(th, 0, wi);
        double ui[2] = {sqrt(theta_i[k] * (2 / PI)), 0.5};
        double sig = rgl_grid_eval(&sigma_g, &one, ui), lpeak = 0;
        for (int y = 0; y < nw; ++y)
            for (int x = 0; x < nw; ++x) {
                double s[2] = {(double)x / (nw - 1), (double)y / (nw - 1)}, u[2], c[3] = {0, 0, 0};
                rgl_warp_sample(&warp, k, s, u);
                direction(u[0] * u[0] * (PI / 2), 2 * PI * u[1] - PI, m);
                double dot = wi[0] * m[0] + wi[1] * m[1] + wi[2] * m[2];
                for (int a = 0; a < 3; ++a) wo[a] = 2 * dot * m[a] - wi[a];
                if (dot > 0 && wo[2] > 0) {
                    f(user, wi, wo, c);
                    double weight = wo[2] * 4 * sig / rgl_grid_eval(&ndf_g, &one, u);
                    for (int a = 0; a < 3; ++a) c[a] = isfinite(c[a]) ? c[a] * weight : 0;
                }
                for (int a = 0; a < 3; ++a) rgb[(k * 3 + a) * slice + y * nw + x] = (float)c[a];
                double l = fmax(luminance(c), 0);
                lum[k * slice + y * nw + x] = (float)l;
                if (l > lpeak) lpeak = l;
            }
        for (size_t q = 0; q < slice; ++q)
            lum[k * slice + q] = (float)(lum[k * slice + q] + (lpeak > 0 ? LUM_FLOOR * lpeak : 1));
    }

    const char *text = description ? description : "";
    unsigned char jac = 1;
    tensor t[] = {
        {"description", 1, 1, {strlen(text)}, text, 0, 0},
        {"jacobian", 1, 1, {1}, &jac, 0, 0},
        {"theta_i", 10, 1, {(uint64_t)T}, theta_i, 0, 0},
        {"phi_i", 10, 1, {1}, phi_i, 0, 0},
        {"ndf", 10, 2, {2, (uint64_t)nn}, ndf, 0, 0},
        {"sigma", 10, 2, {2, (uint64_t)nn}, sigma, 0, 0},
        {"vndf", 10, 4, {1, (uint64_t)T, (uint64_t)nw, (uint64_t)nw}, vndf, 0, 0},
        {"luminance", 10, 4, {1, (uint64_t)T, (uint64_t)nw, (uint64_t)nw}, lum, 0, 0},
        {"rgb", 10, 5, {1, (uint64_t)T, 3, (uint64_t)nw, (uint64_t)nw}, rgb, 0, 0},
    };
    r = write_tensors(path, t, (int)(sizeof t / sizeof t[0]), err, err_size);
done:
    rgl_warp_free(&warp);
    free(theta_i);
    free(ndf);
    free(sigma);
    free(vndf);
    free(lum);
    free(rgb);
    return r;
}
