/* paper_images.h - the image experiment of Zavalniuk & Romanyuk 2024 (Tables 6 and 7):
 * render the robot with the Disney GGX specular at every alpha_g of the paper, render each
 * candidate lobe at every exponent n of the paper, and report per alpha_g the minimum NMSE
 * over n (and its argmin) beside the published values. Set-up and discussion:
 * docs/TABLES_6_7.md.
 *
 *   paper_images_defaults   the documented default set-up
 *   paper_images_run        compute and print Table 6 or 7 for given options
 *   paper_images_cmd        command-line entry: `abrdf tables 6|7 [options]` (argv[0] = "6"|"7")
 */
#ifndef ABRDF_PAPER_IMAGES_H
#define ABRDF_PAPER_IMAGES_H

#include <stdio.h>

typedef struct paper_images_options {
    int table;              /* 6 (f_phe, f_be, f_2e, f_16e) or 7 (f_ge, f_ctphe, f_ct2e, f_ct16e) */
    int width, height;      /* image size in pixels; default 128 x 128 */
    int spp;                /* samples per pixel, a square; default 1 */
    int threads;            /* render threads, >= 1 */
    double f0;              /* Fresnel reflectance at normal incidence, [0, 1]; default 0.04 */
    double kd;              /* Lambert albedo under the specular lobe, [0, 1]; default 0.5; 0: specular only */
    const char *scene_path; /* scene file; NULL: the built-in copy of scenes/robot.scene */
    int csv;                /* print CSV rows instead of the table */
    int progress;           /* progress on stderr */
} paper_images_options;

void paper_images_defaults(paper_images_options *o);
/* Renders and prints to out. Returns 0, or -1 with a message in err. */
int paper_images_run(const paper_images_options *o, FILE *out, char *err, size_t err_size);
/* `abrdf tables 6|7 [--width W] [--height H] [--spp N] [--threads N] [--f0 V] [--kd V]
 * [--scene FILE] [--csv]`; argv[0] is "6" or "7". Exit status 0, 1 (run failed), 2 (usage). */
int paper_images_cmd(int argc, char **argv);

#endif
