/* hair_test_util.c - helpers shared by the hair suites (hair_test_util.h). */
#include <math.h>
#include "hair_test_util.h"

static const double PI = 3.14159265358979323846;

void htu_table_dir(double theta, double phi, double w[3])
{
    w[0] = sin(theta);
    w[1] = cos(theta) * sin(phi);
    w[2] = cos(theta) * cos(phi);
}

void htu_uniforms(unsigned *seed, double a[4])
{
    for (int k = 0; k < 4; ++k) {
        *seed = *seed * 1664525u + 1013904223u;
        a[k] = (*seed >> 8) / 16777216.0;
    }
}

void htu_fdir(double theta, double phi, double w[3])
{
    w[0] = sin(theta);
    w[1] = cos(theta) * cos(phi);
    w[2] = cos(theta) * sin(phi);
}

double htu_fibre_albedo(htu_fibre_fn S, const void *m, double theta_o, unsigned lobes, int nt,
                        int np)
{
    double wo[3], sum = 0.0;
    htu_fdir(theta_o, 0.3, wo);
    for (int i = 0; i < nt; ++i) {
        double th = -PI / 2 + (i + 0.5) * PI / nt;
        for (int j = 0; j < np; ++j) {
            double wi[3], s[3];
            htu_fdir(th, -PI + (j + 0.5) * 2 * PI / np, wi);
            S(m, wi, wo, lobes, s);
            sum += s[0] * cos(th);
        }
    }
    return sum * (PI / nt) * (2 * PI / np);
}

void htu_cylinder_image(htu_eval_fn eval, const void *m, double img[HTU_CYL_SAMPLES][3])
{
    htu_cylinder_image_lit(eval, m, 0, img);
}

void htu_cylinder_image_lit(htu_eval_fn eval, const void *m, int backlit,
                            double img[HTU_CYL_SAMPLES][3])
{
    static const double front[2][3] = {{-0.45, 0.75, 0.55}, {0.7, 0.25, 0.45}};
    static const double back[2][3] = {{-0.45, 0.75, 0.55}, {0.7, 0.25, -0.45}};
    const double(*dir)[3] = backlit ? back : front;
    static const double irr[2][3] = {{2.5, 2.5, 2.5}, {0.72, 0.76, 0.8}};
    for (int k = 0; k < HTU_CYL_SAMPLES; ++k) {
        double x = -1.0 + (k + 0.5) * 2.0 / HTU_CYL_SAMPLES, z = sqrt(1.0 - x * x);
        const double n[3] = {x, 0.0, z}, t[3] = {0.0, 1.0, 0.0}, b[3] = {-z, 0.0, x}; /* N x T */
        const double wo[3] = {0.0, x, z}; /* V = +z: (V.T, V.B, V.N), unit */
        img[k][0] = img[k][1] = img[k][2] = 0.0;
        for (int l = 0; l < 2; ++l) {
            double d = sqrt(dir[l][0] * dir[l][0] + dir[l][1] * dir[l][1] + dir[l][2] * dir[l][2]);
            double w[3] = {dir[l][0] / d, dir[l][1] / d, dir[l][2] / d};
            double wi[3] = {w[0] * t[0] + w[1] * t[1] + w[2] * t[2],
                            w[0] * b[0] + w[1] * b[1] + w[2] * b[2],
                            w[0] * n[0] + w[1] * n[1] + w[2] * n[2]};
            if (!(wi[2] > 0.0)) continue;
            double f[3];
            eval(m, wi, wo, f);
            for (int c = 0; c < 3; ++c) img[k][c] += irr[l][c] * wi[2] * f[c];
        }
    }
}

double htu_image_nmse(const double ref[HTU_CYL_SAMPLES][3], const double img[HTU_CYL_SAMPLES][3])
{
    double num = 0.0, den = 0.0;
    for (int k = 0; k < HTU_CYL_SAMPLES; ++k)
        for (int c = 0; c < 3; ++c) {
            num += (img[k][c] - ref[k][c]) * (img[k][c] - ref[k][c]);
            den += ref[k][c] * ref[k][c];
        }
    return num / den;
}
