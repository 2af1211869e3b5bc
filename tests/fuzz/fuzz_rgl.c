/* fuzz_rgl.c - fuzz target of the RGL .bsdf reader (tools/measured/rgl_bsdf.h): any bytes must
 * either be refused with one line naming the file, or read into a material whose f_r is
 * finite and non-negative for directions all over the sphere (0 below the horizon).
 * libFuzzer entry point; tests/fuzz/fuzz_driver.c runs it deterministically under CTest (also
 * in the sanitizer build), from the small files of corpus/rgl/ (rgl_write's output). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_target.h"
#include "rgl_bsdf.h"

#define FUZZ_REQUIRE(cond)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz_rgl: %s does not hold (%s)\n", #cond, err);                      \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

static unsigned long accepted, refused;

/* The format's words: the magic, field names, type bytes, extents, hostile floats. */
const char *const fuzz_tokens[] = {
    "tensor_file",
    "\0",
    "\x01",
    "\x0a",
    "\x0b",
    "\x09",
    "\xff",
    "\x02\x00",
    "\x05\x00",
    "\xff\xff",
    "\xff\xff\xff\xff",
    "\x00\x00\xc0\x7f",
    "\x00\x00\x80\x7f",
    "\x00\x00\x80\xbf",
    "rgb",
    "ndf",
    "sigma",
    "vndf",
    "luminance",
    "theta_i",
    "phi_i",
    "jacobian",
    "description",
    "spectra",
    "wavelengths",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read and evaluated, %lu refused", accepted, refused); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    rgl_bsdf *b;
    char err[512] = "";
    if (rgl_parse(data, size, "fuzz.bsdf", &b, err, sizeof err) != 0) {
        FUZZ_REQUIRE(b == NULL && memchr(err, '\0', sizeof err) && !strncmp(err, "fuzz.bsdf:", 10));
        FUZZ_REQUIRE(!strchr(err, '\n'));
        ++refused;
        return 0;
    }
    ++accepted;
    for (int k = 0; k < 64; ++k) {
        double ti = k * 0.05, pi = k * 0.7, to = (63 - k) * 0.05, po = k * 1.3;
        double wi[3] = {sin(ti) * cos(pi), sin(ti) * sin(pi), cos(ti)};
        double wo[3] = {sin(to) * cos(po), sin(to) * sin(po), cos(to)}, f[3];
        rgl_eval(b, wi, wo, f);
        for (int c = 0; c < 3; ++c) {
            FUZZ_REQUIRE(isfinite(f[c]) && f[c] >= 0);
            FUZZ_REQUIRE(wi[2] > 0 && wo[2] > 0 ? 1 : f[c] == 0);
        }
    }
    rgl_free(b);
    return 0;
}
