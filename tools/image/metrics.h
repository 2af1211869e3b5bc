/* metrics.h - image difference metrics of the paper's image experiment (Zavalniuk &
 * Romanyuk 2024, Sec. 4, Table 8) for float images in memory. Plain C99, no allocation.
 *
 *   abrdf_metrics_compute   NMSE, MSE, PSNR and maximum error of a test image vs a reference
 *   abrdf_nmse_class        the paper's Table-8 visibility class of an NMSE value
 *
 * NMSE = sum_p sum_c (I_pc - R_pc)^2 / sum_p sum_c R_pc^2, R the reference, I the test image
 * (not symmetric in I and R); sums over every pixel (background included) and every channel,
 * accumulated in double. An all-black reference has no NMSE (nmse_defined = 0). */
#ifndef ABRDF_METRICS_H
#define ABRDF_METRICS_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abrdf_metrics {
    double nmse;       /* sum (I-R)^2 / sum R^2; 0 when !nmse_defined */
    int nmse_defined;  /* 0 if the reference is all zero (sum R^2 == 0) */
    double sse;        /* sum over pixels and channels of (I-R)^2 */
    double ref_energy; /* sum over pixels and channels of R^2 */
    double mse;        /* sse / (pixels * channels) */
    double peak;       /* largest channel value in either image (as OpenImageIO's compare) */
    double psnr;       /* 10 log10(peak^2 / mse) dB; +inf if mse == 0, -inf if peak <= 0 < mse */
    double max_abs;    /* largest |I - R| over pixels and channels */
    int max_x, max_y;  /* pixel of max_abs (first in row-major order), column x, row y from top */
    int max_c;         /* channel of max_abs (0 R, 1 G, 2 B) */
} abrdf_metrics;

enum {
    ABRDF_METRICS_OK = 0,
    ABRDF_METRICS_BAD_ARGS = -1, /* NULL buffer, non-positive size or channel count */
    ABRDF_METRICS_NONFINITE = -2 /* a NaN or infinity in either image */
};

/* Compare test image I with reference R, both width*height*channels floats (interleaved,
 * same layout). On ABRDF_METRICS_NONFINITE, *m->max_x/max_y/max_c name the first bad sample. */
int abrdf_metrics_compute(const float *test, const float *ref, int width, int height, int channels,
                          abrdf_metrics *m);

/* Table 8 of the paper, with half-open intervals (the paper leaves the boundaries unstated):
 *   [0, 1e-4) "none"   [1e-4, 2.5e-4) "slight"   [2.5e-4, 1e-3) "noticeable"
 *   [1e-3, inf) "significant". Negative or NaN input: "undefined". */
#define ABRDF_NMSE_SLIGHT 1e-4
#define ABRDF_NMSE_NOTICEABLE 2.5e-4
#define ABRDF_NMSE_SIGNIFICANT 1e-3
const char *abrdf_nmse_class(double nmse);
/* The class as the paper words it ("no visible difference", "slight", ...). */
const char *abrdf_nmse_class_description(double nmse);

#ifdef __cplusplus
}
#endif
#endif
