/* fuzz_merl.c - fuzz target of the MERL BRDF reader (tools/measured/merl.h): any bytes must
 * either be refused with one line naming the file, or read into a table whose grid is in
 * range and whose every value is -1 (not measured) or a finite f_r in [0, MERL_MAX_FR], with
 * the count of cells not measured right; now and then a table read is written back and read
 * again, to the bit. libFuzzer entry point; tests/fuzz/fuzz_driver.c runs it deterministically
 * under CTest (also in the sanitizer build). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_target.h"
#include "merl.h"

/* A broken property names itself before the abort the driver counts as a failure. */
#define FUZZ_REQUIRE(cond)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz_merl: %s does not hold (%s)\n", #cond, err);                     \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

/* Inputs read into a table, and those written back (the driver reports them). */
static unsigned long read_ok, round_trips;

/* Bytes of the format without a NUL (the "\0" token inserts one): int32 sizes (2, 90, 180,
 * -1, INT32_MAX), the high bytes of doubles (-1.0, NaN, infinity, 1e12 and beyond). */
const char *const fuzz_tokens[] = {
    "\0",       "\x02",     "\x5a",     "\xb4",     "\xff\xff\xff\xff", "\xff\xff\xff\x7f",
    "\x04\x04", "\xf0\xbf", "\xf8\x7f", "\xf0\x7f", "\xf0\xff",         "\x42",
    "\x7f",     "\x80",     "\x01",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read, %lu written back", read_ok, round_trips); }

/* Write t to a temporary file, read it again: the same grid and the same bits. */
static void round_trip(const measured_table *t)
{
    char err[512] = "", path[512];
    const char *tmp = getenv("TMPDIR");
    snprintf(path, sizeof path, "%s/fuzz_merl.%ld.binary", tmp && *tmp ? tmp : "/tmp",
             (long)getpid());
    FUZZ_REQUIRE(merl_write(path, t, err, sizeof err) == 0);
    measured_table r;
    FUZZ_REQUIRE(merl_read(path, &r, err, sizeof err) == 0);
    unlink(path);
    size_t cells = (size_t)t->n_theta_h * t->n_theta_d * t->n_phi_d;
    FUZZ_REQUIRE(r.n_theta_h == t->n_theta_h && r.n_theta_d == t->n_theta_d &&
                 r.n_phi_d == t->n_phi_d && r.unmeasured == t->unmeasured);
    FUZZ_REQUIRE(!memcmp(r.data, t->data, 3 * cells * sizeof *r.data));
    measured_table_free(&r);
    ++round_trips;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char err[512] = "";
    static const uint8_t none[1];
    /* fmemopen refuses an empty buffer; the reader refuses an empty file before reading. */
    FILE *f = fmemopen((void *)(size ? data : none), size ? size : 1, "rb");
    FUZZ_REQUIRE(f != NULL);
    measured_table t;
    int rc = merl_read_stream(f, size, "fuzz.binary", &t, err, sizeof err);
    fclose(f);
    if (rc != 0) {
        FUZZ_REQUIRE(rc == -1 && t.data == NULL && memchr(err, '\0', sizeof err));
        FUZZ_REQUIRE(!strncmp(err, "fuzz.binary: ", 13) && !strchr(err, '\n'));
        return 0;
    }
    FUZZ_REQUIRE(t.n_theta_h >= MEASURED_DIM_MIN && t.n_theta_h <= MEASURED_DIM_MAX);
    FUZZ_REQUIRE(t.n_theta_d >= MEASURED_DIM_MIN && t.n_theta_d <= MEASURED_DIM_MAX);
    FUZZ_REQUIRE(t.n_phi_d >= MEASURED_DIM_MIN && t.n_phi_d <= MEASURED_DIM_MAX);
    size_t cells = (size_t)t.n_theta_h * t.n_theta_d * t.n_phi_d, holes = 0;
    FUZZ_REQUIRE(cells <= MEASURED_MAX_CELLS && size == MERL_HEADER_BYTES + 24 * cells);
    for (size_t i = 0; i < cells; ++i) {
        int hole = 0;
        for (int c = 0; c < 3; ++c) {
            float v = t.data[3 * i + c];
            FUZZ_REQUIRE(v == -1.0f || (isfinite(v) && v >= 0 && v <= MERL_MAX_FR));
            hole |= v < 0;
        }
        holes += hole;
    }
    FUZZ_REQUIRE(holes == t.unmeasured);
    if (read_ok++ % 16 == 0) round_trip(&t); /* a file write each: not every input */
    measured_table_free(&t);
    return 0;
}
