/* hair_huang_lobes.c - the huang fibre function S lobe by lobe, for the Cycles oracle
 * (test_hair_cycles_oracle.py; docs/MODELS.md, "Cycles as an oracle").
 *
 *   hair_huang_lobes [--h-nodes] [--trrt-const] [--refine K] [NAME=VALUE ...] < directions
 *
 * Each input line holds a light and a view direction in the fibre's local frame (fibre along
 * +x, major axis of the section along +y; hair.h): "wix wiy wiz wox woy woz". Each output
 * line holds S (hair.h's convention: the radiance that a directional light of unit
 * irradiance makes the fibre scatter toward the viewer) for the lobe masks of
 * abrdf__huang_fibre, R (1), TT (2), TRT (4), TRRT+ (8) and all of them (15): 15 numbers, RGB
 * each. Without options this is the model. The options switch to parts of Blender 5.0 Cycles'
 * far-field quadrature (hair.h, cycles_nodes): --h-nodes, Simpson over h clipped to +-0.999;
 * --trrt-const, TRRT+ weighted by the constant 2/pi. With both, S is what a Cycles render
 * estimates, up to Cycles' energy tables and its noise. --refine K divides the Simpson steps
 * by K (K = 8: the converged integral, over gamma or over h), which tells the quadratures'
 * errors apart. Parameters are the library's names (abrdf models), checked by the library.
 * A test program: it reaches the internal lobe mask, which the public API does not expose. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hair.h"

static const unsigned LOBES[5] = {1u, 2u, 4u, 8u, 15u};

static int set_param(abrdf_params *p, const char *arg)
{
    char name[64];
    const char *eq = strchr(arg, '=');
    if (!eq || (size_t)(eq - arg) >= sizeof name) return -1;
    memcpy(name, arg, (size_t)(eq - arg));
    name[eq - arg] = '\0';
    int id;
    char *end;
    double v = strtod(eq + 1, &end);
    if (*end != '\0' || abrdf_param_find(name, &id) != 0) return -1;
    return abrdf_param_set(p, id, &v, 1);
}

int main(int argc, char **argv)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_HUANG, &p);
    unsigned cycles_nodes = 0;
    int refine = 1;
    for (int i = 1; i < argc; ++i) {
        if (strcmp(argv[i], "--h-nodes") == 0)
            cycles_nodes |= ABRDF__HUANG_CYCLES_H;
        else if (strcmp(argv[i], "--trrt-const") == 0)
            cycles_nodes |= ABRDF__HUANG_CYCLES_TRRT;
        else if (strcmp(argv[i], "--refine") == 0 && i + 1 < argc)
            refine = atoi(argv[++i]);
        else if (set_param(&p, argv[i]) != 0) {
            fprintf(stderr, "hair_huang_lobes: bad argument '%s'\n", argv[i]);
            return 2;
        }
    }
    char msg[256];
    if (abrdf_params_check(ABRDF_HUANG, &p, msg, sizeof msg) != 0) {
        fprintf(stderr, "hair_huang_lobes: %s\n", msg);
        return 2;
    }
    if (refine < 1 || refine > 64) {
        fprintf(stderr, "hair_huang_lobes: --refine takes 1 to 64\n");
        return 2;
    }
    abrdf__huang m;
    abrdf__huang_setup(&p, &m);
    m.cycles_nodes = cycles_nodes;
    m.refine = refine;
    double wi[3], wo[3];
    while (scanf("%lf %lf %lf %lf %lf %lf", &wi[0], &wi[1], &wi[2], &wo[0], &wo[1], &wo[2]) == 6) {
        for (int l = 0; l < 5; ++l) {
            double s[3];
            abrdf__huang_fibre(&m, wi, wo, LOBES[l], s);
            printf("%.9g %.9g %.9g%s", s[0], s[1], s[2], l == 4 ? "\n" : " ");
        }
    }
    return 0;
}
