/* hair_test_util.c - helpers shared by the hair suites (hair_test_util.h). */
#include <math.h>
#include "hair_test_util.h"

static const double PI = 3.14159265358979323846;

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
