/* paper_images.h - the image experiment of Zavalniuk & Romanyuk 2024 (Tables 6 and 7):
 * render the robot with the Disney GGX specular at every alpha_g of the paper (the
 * reference), render each candidate lobe at every exponent n of the paper, and report per
 * alpha_g the minimum NMSE over n and its argmin. Set-up and discussion: docs/TABLES.md,
 * "Tables 6 and 7".
 *
 *   paper_images_defaults   the documented default set-up
 *   paper_images_compute    run the experiment for Table 6 or 7 into a result
 *   tables_images           `abrdf tables 6|7`: compute and print beside the published values
 *                           (declared in tables.h with the other generators)
 */
#ifndef ABRDF_PAPER_IMAGES_H
#define ABRDF_PAPER_IMAGES_H

#include <stddef.h>

#define PAPER_IMAGES_ROWS 18      /* alpha_g values of the paper */
#define PAPER_IMAGES_EXPONENTS 18 /* n values searched */
#define PAPER_IMAGES_MODELS 4     /* candidates per table */
#define PAPER_IMAGES_QUADRATIC                                                                     \
    2 /* the cosine-quadratic lobe's column, whose Table-8
                                      thresholds are reported */

typedef struct paper_images_options {
    int width, height; /* image size in pixels; default 128 x 128 */
    int spp;           /* samples per pixel, a square; default 1 (pixel centres) */
    int threads;       /* render threads, >= 1; default: online CPUs */
    double f0;         /* Fresnel F0 of the reference and the Fresnel lobes; default 0.04 */
    double kd;         /* Lambert albedo under the specular lobe; default 0.5; 0: specular only */
    const char *scene_path; /* scene file; NULL: the built-in copy of scenes/robot.scene */
    int progress;           /* progress on stderr */
} paper_images_options;

typedef struct paper_images_result {
    int table;                              /* 6 or 7 */
    const char *model[PAPER_IMAGES_MODELS]; /* candidate names, table order */
    const char *label[PAPER_IMAGES_ROWS];   /* alpha_g as the paper prints it */
    double alpha_g[PAPER_IMAGES_ROWS];
    int defined[PAPER_IMAGES_ROWS];                      /* 0: the reference image is black */
    double nmse[PAPER_IMAGES_ROWS][PAPER_IMAGES_MODELS]; /* minimum over n */
    double n[PAPER_IMAGES_ROWS][PAPER_IMAGES_MODELS];    /* its argmin (first of ties) */
    int renders;                                         /* images rendered */
} paper_images_result;

/* The exponents searched, as listed in the paper (Sec. 4). */
extern const double paper_images_exponents[PAPER_IMAGES_EXPONENTS];

void paper_images_defaults(paper_images_options *o);
/* Returns 0, or -1 with a one-line message in err. */
int paper_images_compute(int table, const paper_images_options *o, paper_images_result *r,
                         char *err, size_t err_size);

#endif
