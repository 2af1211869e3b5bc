/* quickstart.c - evaluate one reflectance model with the installed libabrdf.
 *   cc quickstart.c $(pkg-config --cflags --libs abrdf) -o quickstart   (or CMake: see CMakeLists.txt) */
#include <stdio.h>
#include <abrdf.h>

int main(void)
{
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p); /* the model's defaults */
    p.r = 0.3;                                    /* perceptual roughness; alpha_g = r^2 */
    abrdf_prepared mat; /* validated and precomputed once, then evaluated per sample */
    int st = abrdf_prepare(ABRDF_DISNEY_SPECULAR, &p, &mat);
    if (st != ABRDF_OK) {
        fprintf(stderr, "abrdf: %s\n", abrdf_strerror(st));
        return 1;
    }
    const double n[3] = {0, 0, 1}, wi[3] = {0.3, 0, 1}, wo[3] = {-0.2, 0.1, 1};
    abrdf_frame frame;
    abrdf_frame_make(n, NULL, &frame); /* N, T, B from the normal */
    double f[3];                       /* f_r per RGB channel, 1/sr, no cosine */
    abrdf_eval_prepared(&mat, &frame, wi, wo, f);
    printf("abrdf %s: disney_specular f_r = %.6f %.6f %.6f\n", abrdf_version(), f[0], f[1], f[2]);
    return 0;
}
