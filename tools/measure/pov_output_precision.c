/* pov_output_precision.c - measures the precision of POV-Ray 3.7's HDR output formats: a
 * 1024 x 1 emissive ramp of known values v(x) = 2^((x - 512)/37) (1 + x/997) (6.8e-5 to 2.9e4)
 * is rendered as EXR (+FE) and Radiance HDR (+FH) and read back; prints the largest relative
 * error per format (docs/POVRAY.md).
 *   pov_output_precision POVRAY WORK_DIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "image_io.h"
#include "out_file.h"

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: pov_output_precision POVRAY WORK_DIR\n");
        return 2;
    }
    char pov[4096], out[4096], cmd[16384], err[512];
    snprintf(pov, sizeof pov, "%s/precision.pov", argv[2]);
    out_file o;
    FILE *f = out_file_or_stdout(&o, pov, "pov_output_precision");
    if (!f) return 1;
    /* the pigment keeps [0, 1]: divide by a power of two, scale back in the colour map */
    fprintf(f, "#version 3.7;\nglobal_settings { assumed_gamma 1 }\n#declare S = pow(2, 24);\n"
               "#declare V = function(x) { pow(2, (floor(x) - 512) / 37) * (1 + floor(x) / 997) }\n"
               "camera { orthographic location <512, 0.5, -1> direction z right 1024 * x up y }\n"
               "plane { z, 0 texture { pigment { function { min(V(x) / S, 1) } color_map { [0 rgb "
               "0] [1 rgb S] } }\n"
               "  finish { ambient 0 diffuse 0 emission 1 } } }\n");
    if (out_file_finish(&o, "pov_output_precision")) return 1;
    const char *fmt[2][3] = {{"E", "exr", "EXR (+FE)"}, {"H", "hdr", "Radiance HDR (+FH)"}};
    printf("| POV-Ray output | max relative error over [6.8e-5, 2.9e4] |\n|---|---|\n");
    for (int k = 0; k < 2; ++k) {
        snprintf(out, sizeof out, "%s/precision.%s", argv[2], fmt[k][1]);
        snprintf(cmd, sizeof cmd, "'%s' -D -GA +I'%s' +O'%s' +F%s +W1024 +H1 -A >/dev/null 2>&1",
                 argv[1], pov, out, fmt[k][0]);
        abrdf_image img;
        if (system(cmd) != 0 || abrdf_image_read(out, &img, err, sizeof err)) {
            fprintf(stderr, "pov_output_precision: %s failed\n", fmt[k][2]);
            return 1;
        }
        double worst = 0;
        for (int x = 0; x < img.width; ++x) {
            double v = pow(2.0, (x - 512) / 37.0) * (1 + x / 997.0);
            for (int c = 0; c < 3; ++c) worst = fmax(worst, fabs(img.pixels[3 * x + c] - v) / v);
        }
        abrdf_image_free(&img);
        printf("| %s | %.2e |\n", fmt[k][2], worst);
    }
    return 0;
}
