/* quad.c - hemisphere quadrature and random directions shared by tools and tests (quad.h). */
#include <math.h>
#include "quad.h"

static const double PI = 3.14159265358979323846;

void quad_gauss_legendre01(int n, double *x, double *w)
{
    for (int i = 0; i < (n + 1) / 2; ++i) {
        double z = cos(PI * (i + 0.75) / (n + 0.5)), dp = 1.0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1.0, p1 = 0.0;
            for (int k = 1; k <= n; ++k) {
                double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p2) / k;
            }
            dp = n * (z * p0 - p1) / (z * z - 1.0);
            double dz = p0 / dp;
            z -= dz;
            if (fabs(dz) < 1e-15) break;
        }
        x[i] = 0.5 * (1.0 - z);
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[i] = w[n - 1 - i] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
}

double quad_albedo(abrdf_model m, const abrdf_params *p, double theta_deg, double a, int n, int c)
{
    double x[QUAD_ORDER_MAX], w[QUAD_ORDER_MAX];
    if (n > QUAD_ORDER_MAX) n = QUAD_ORDER_MAX;
    quad_gauss_legendre01(n, x, w);
    double ti = theta_deg * PI / 180.0;
    double wi[3] = {sin(ti), 0.0, cos(ti)};
    int nphi = 2 * n;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        double mv = 1.0 - x[i], u = 1.0 - mv * mv;
        double t2 = a * a * u / (mv * mv), tn = sqrt(t2);
        if (!(tn > 0.0)) continue;
        double ch = 1.0 / sqrt(1.0 + t2), sh = tn * ch;
        /* theta(u) = atan(a sqrt(u/(1-u))): dtheta/du = a^2 / (2 tan (1 + tan^2) (1-u)^2) */
        double dth = a * a / (2.0 * tn * (1.0 + t2) * mv * mv * mv * mv) * 2.0 * mv * w[i];
        for (int j = 0; j < nphi; ++j) {
            double phi = 2.0 * PI * (j + 0.5) / nphi;
            double h[3] = {sh * cos(phi), sh * sin(phi), ch};
            double cd = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
            if (!(cd > 0.0)) continue;
            double wo[3] = {2 * cd * h[0] - wi[0], 2 * cd * h[1] - wi[1], 2 * cd * h[2] - wi[2]};
            if (!(wo[2] > 0.0)) continue;
            double f[3];
            abrdf_eval(m, p, NULL, wi, wo, f);
            sum += f[c] * wo[2] * 4.0 * cd * sh * dth * (2.0 * PI / nphi); /* dwo = 4 (wi.h) dwh */
        }
    }
    return sum;
}

double quad_rand(unsigned *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (*s >> 8) / 16777216.0;
}

void quad_rand_dir(unsigned *s, double zmin, double out[3])
{
    double z = zmin + (1.0 - zmin) * quad_rand(s), phi = 2.0 * PI * quad_rand(s);
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    out[0] = r * cos(phi);
    out[1] = r * sin(phi);
    out[2] = z;
}
