/* rgl_bsdf.h - measured BRDFs in the RGL material database's .bsdf files: the adaptive
 * parameterization of Dupuy & Jakob, "An Adaptive Parameterization for Efficient Material
 * Acquisition and Rendering", ACM TOG 37(6) (SIGGRAPH Asia 2018), the format Mitsuba 3's
 * `measured` plugin reads (docs/MEASURED.md, "RGL .bsdf files").
 *
 * THE FILE is a tensor file: "tensor_file\0", version bytes 1 0, a u32 field count, then per
 * field a u16 name length, the name, a u16 rank, a u8 type (1 u8, 2 i8, 3 u16, 4 i16, 5 u32,
 * 6 i32, 7 u64, 8 i64, 9 f16, 10 f32, 11 f64), a u64 offset of the data from the start of
 * the file and rank u64 extents; all little-endian, the data row-major. A material has the
 * fields theta_i [T], phi_i [P] (the incident direction's slices), ndf [a, b] and sigma
 * [c, d] (the microfacet distribution D and its projected area, on the unit square of
 * (u_theta, u_phi)), vndf and luminance [P, T, h, w] (the visible normals' warp and the
 * sampling density), rgb [P, T, 3, h, w] (f_r cos(theta_o) on the warped square, divided by
 * D(m) / (4 sigma(wi)) when jacobian [1] is 1) and description [n] (u8 text).
 *
 * DIRECTIONS. The file's incident direction (theta_i, phi_i) is the light, as measured; the
 * evaluator takes wi toward the light and wo toward the viewer (abrdf.h) and returns f_r in
 * 1/sr, without the cosine. Mitsuba 3 passes its si.wi (the camera side of its path tracer) as
 * the file's incident direction: for a reciprocal BRDF the two agree.
 *
 * WHAT IS READ: isotropic materials (one or two phi_i slices) with an `rgb` field. Refused,
 * each with one line: spectral-only files (no `rgb`: the database offers RGB files),
 * anisotropic ones (the tools' table is isotropic), and any file that is not a consistent
 * tensor file (every bound checked against the file's size before any data is copied, NaN
 * and Inf refused).
 *
 *   rgl_parse          a material from bytes in memory ("name" names it in messages)
 *   rgl_load           a material from a file
 *   rgl_free           release it
 *   rgl_eval           f_r RGB for local wi, wo (N = +z), as Mitsuba 3 evaluates the file
 *   rgl_read           a file resampled onto the tools' measured table (measured_table.h)
 *   rgl_write          an isotropic .bsdf file made from any BRDF given as a function
 */
#ifndef ABRDF_RGL_BSDF_H
#define ABRDF_RGL_BSDF_H

#include <stddef.h>

#include "measured_table.h"

#define RGL_MAX_FILE_BYTES ((size_t)256 << 20) /* the database's RGB files are a few MiB */
#define RGL_MAX_FIELDS 64                      /* a material has 10 or 11 */
#define RGL_MAX_RANK 8                         /* a material's largest rank is 5 */

typedef struct rgl_bsdf rgl_bsdf;

/* 0 and *out, or -1 with "NAME: reason" in err and *out NULL. */
int rgl_parse(const unsigned char *data, size_t size, const char *name, rgl_bsdf **out, char *err,
              size_t err_size);
/* 0 and *out, or -1 with "PATH: reason" in err and *out NULL (not a regular file, larger than
 * RGL_MAX_FILE_BYTES, unreadable, or any reason of rgl_parse). */
int rgl_load(const char *path, rgl_bsdf **out, char *err, size_t err_size);
void rgl_free(rgl_bsdf *b);
/* The text of the description field (NUL-terminated). */
const char *rgl_description(const rgl_bsdf *b);
/* f_r (1/sr, linear RGB, >= 0) for unit wi (toward the light) and wo (toward the viewer);
 * 0 when either is at or below the horizon. */
void rgl_eval(const rgl_bsdf *b, const double wi[3], const double wo[3], double rgb[3]);

/* Read the file at path and fill *out (allocated here, grid as given) with f_r at each cell's
 * directions (measured_table_directions); cells with wi or wo at or below the horizon, or
 * within its last degree (RGL_READ_Z_MIN), are not measured (-1), as in the MERL files a
 * measurement makes.
 * 0, or -1 with "PATH: reason" in err and nothing allocated. */
#define RGL_READ_Z_MIN 0.0174524 /* cos 89 degrees: rgl_read's last measured elevation */
int rgl_read(const char *path, measured_table *out, int n_theta_h, int n_theta_d, int n_phi_d,
             char *err, size_t err_size);

/* A BRDF to tabulate: f_r (1/sr, linear RGB, without the cosine) for unit wi, wo above the
 * horizon. */
typedef void (*rgl_brdf_fn)(void *user, const double wi[3], const double wo[3], double rgb[3]);

typedef struct rgl_write_grid {
    int n_theta_i; /* incident elevations, 0 to 90 degrees [2, 64]; 16 is plenty */
    int n_ndf;     /* ndf and sigma: n_ndf elevations (u_theta) [2, 512] */
    int n_warp;    /* vndf, luminance and rgb: n_warp x n_warp per slice [2, 256] */
} rgl_write_grid;

#define RGL_WRITE_GRID_DEFAULT                                                                     \
    {                                                                                              \
        16, 128, 64                                                                                \
    }

/* Write an isotropic .bsdf file of f (docs/MEASURED.md, "RGL .bsdf files": how each field is derived) to
 * path, whole or not at all. description is stored as the description field (NULL: none).
 * 0, or -1 with "PATH: reason" in err. */
int rgl_write(const char *path, rgl_brdf_fn f, void *user, const rgl_write_grid *grid,
              const char *description, char *err, size_t err_size);

#endif
