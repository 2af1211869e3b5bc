/* rgl_oracle.c - the .bsdf reader and writer (rgl_bsdf.h) as commands for the test that holds
 * them to Mitsuba 3 (tests/cli/test_rgl_mitsuba.py):
 *
 *   rgl_oracle write FILE MODEL [N_THETA_I N_NDF N_WARP]   tabulate a closed form (rgl_models.h)
 *   rgl_oracle eval FILE N SEED     N random direction pairs above the horizon, one a line:
 *                                   wi (3), wo (3), the file's f_r (3), the model's f_r (3)
 *                                   when MODEL is given as a fourth argument
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include "rgl_bsdf.h"
#include "rgl_models.h"

/* A direction above the horizon, uniform on the hemisphere, from a 64-bit LCG (Knuth's MMIX
 * constants): the same pairs on every machine. */
static double uniform(unsigned long long *s)
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(*s >> 11) / 9007199254740992.0;
}

static void hemisphere(unsigned long long *s, double d[3])
{
    double z = 0.02 + 0.98 * uniform(s), phi = 2 * 3.14159265358979323846 * uniform(s);
    double r = sqrt(1 - z * z);
    d[0] = r * cos(phi), d[1] = r * sin(phi), d[2] = z;
}

int main(int argc, char **argv)
{
    char err[512];
    if (argc >= 4 && strcmp(argv[1], "write") == 0) {
        rgl_brdf_fn f = rgl_model_by_name(argv[3]);
        rgl_write_grid g = RGL_WRITE_GRID_DEFAULT;
        if (argc == 7)
            g.n_theta_i = atoi(argv[4]), g.n_ndf = atoi(argv[5]), g.n_warp = atoi(argv[6]);
        if (!f || (argc != 4 && argc != 7)) {
            fprintf(stderr, "rgl_oracle: write FILE lambert|ggx [N_THETA_I N_NDF N_WARP]\n");
            return 2;
        }
        if (rgl_write(argv[2], f, NULL, &g, argv[3], err, sizeof err)) {
            fprintf(stderr, "rgl_oracle: %s\n", err);
            return 1;
        }
        return 0;
    }
    if ((argc == 5 || argc == 6) && strcmp(argv[1], "eval") == 0) {
        rgl_brdf_fn f = argc == 6 ? rgl_model_by_name(argv[5]) : NULL;
        rgl_bsdf *b;
        if (rgl_load(argv[2], &b, err, sizeof err)) {
            fprintf(stderr, "rgl_oracle: %s\n", err);
            return 1;
        }
        long n = atol(argv[3]);
        unsigned long long s = strtoull(argv[4], NULL, 10);
        for (long k = 0; k < n; ++k) {
            double wi[3], wo[3], c[3], m[3] = {0, 0, 0};
            hemisphere(&s, wi);
            hemisphere(&s, wo);
            rgl_eval(b, wi, wo, c);
            if (f) f(NULL, wi, wo, m);
            printf("%.17g %.17g %.17g %.17g %.17g %.17g %.9g %.9g %.9g %.9g %.9g %.9g\n", wi[0],
                   wi[1], wi[2], wo[0], wo[1], wo[2], c[0], c[1], c[2], m[0], m[1], m[2]);
        }
        rgl_free(b);
        return 0;
    }
    fprintf(stderr, "rgl_oracle: write FILE MODEL [N_THETA_I N_NDF N_WARP] | eval FILE N SEED "
                    "[MODEL]\n");
    return 2;
}
