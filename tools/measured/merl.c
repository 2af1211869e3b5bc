/* merl.c - MERL BRDF database files (merl.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>

#include "in_file.h"
#include "merl.h"
#include "path_msg.h"

/* Doubles per read or write: the fixed buffer (8 KiB) beside the table. */
#define MERL_CHUNK 1024

static const char *const channel_names[3] = {"red", "green", "blue"};
static const double channel_scales[3] = {MERL_SCALE_R, MERL_SCALE_G, MERL_SCALE_B};

/* ---- little-endian bytes, whatever the host's order ------------------------------------- */

static uint64_t le_u64(const unsigned char *p)
{
    uint64_t u = 0;
    for (int k = 7; k >= 0; --k) u = u << 8 | p[k];
    return u;
}

static double le_double(const unsigned char *p)
{
    uint64_t u = le_u64(p);
    double d;
    memcpy(&d, &u, sizeof d);
    return d;
}

static long long le_i32(const unsigned char *p)
{
    uint32_t u = (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
    return u <= 0x7fffffffu ? (long long)u : (long long)u - 0x100000000ll;
}

static void put_le_u32(unsigned char *p, uint32_t u)
{
    for (int k = 0; k < 4; ++k) p[k] = (unsigned char)(u >> (8 * k));
}

static void put_le_double(unsigned char *p, double d)
{
    uint64_t u;
    memcpy(&u, &d, sizeof u);
    for (int k = 0; k < 8; ++k) p[k] = (unsigned char)(u >> (8 * k));
}

/* ---- the grid ----------------------------------------------------------------------------- */

/* "red channel, cell 1234 (ih 0, id 6, ip 154)" */
static void cell_name(char *dst, size_t size, int c, size_t i, int nd, int np)
{
    size_t ip = i % (size_t)np, id = i / (size_t)np % (size_t)nd, ih = i / ((size_t)np * nd);
    snprintf(dst, size, "%s channel, cell %zu (ih %zu, id %zu, ip %zu)", channel_names[c], i, ih,
             id, ip);
}

/* Are the three dimensions a grid a table may hold? (Each is checked before the product, so
 * the product cannot overflow: at most 1024^3.) */
static int grid_ok(long long nh, long long nd, long long np)
{
    if (nh < MEASURED_DIM_MIN || nh > MEASURED_DIM_MAX || nd < MEASURED_DIM_MIN ||
        nd > MEASURED_DIM_MAX || np < MEASURED_DIM_MIN || np > MEASURED_DIM_MAX)
        return 0;
    return (unsigned long long)nh * (unsigned long long)nd * (unsigned long long)np <=
           MEASURED_MAX_CELLS;
}

static void grid_refusal(char *err, size_t err_size, const char *name, long long nh, long long nd,
                         long long np)
{
    path_msg(err, err_size, name,
             ": absurd sizes %lld x %lld x %lld (theta_h x theta_d x phi_d: each %d to %d cells, "
             "%zu cells in all at most); not a MERL BRDF file?",
             nh, nd, np, MEASURED_DIM_MIN, MEASURED_DIM_MAX, (size_t)MEASURED_MAX_CELLS);
}

/* ---- reading ------------------------------------------------------------------------------ */

int merl_read_stream(FILE *f, unsigned long long size, const char *name, measured_table *out,
                     char *err, size_t err_size)
{
    out->n_theta_h = out->n_theta_d = out->n_phi_d = 0;
    out->data = NULL;
    out->unmeasured = 0;
    unsigned char head[MERL_HEADER_BYTES];
    if (size < MERL_HEADER_BYTES) {
        path_msg(err, err_size, name,
                 ": %llu bytes, shorter than the 12-byte header of a MERL BRDF file", size);
        return -1;
    }
    if (fread(head, 1, sizeof head, f) != sizeof head) goto read_failed;
    long long nh = le_i32(head), nd = le_i32(head + 4), np = le_i32(head + 8);
    if (!grid_ok(nh, nd, np)) {
        grid_refusal(err, err_size, name, nh, nd, np);
        return -1;
    }
    size_t cells = (size_t)nh * (size_t)nd * (size_t)np;
    unsigned long long expected = MERL_HEADER_BYTES + 24ull * cells;
    if (size != expected) {
        if (size < expected)
            path_msg(err, err_size, name,
                     ": truncated: %llu bytes, where a %lld x %lld x %lld table takes %llu", size,
                     nh, nd, np, expected);
        else
            path_msg(err, err_size, name,
                     ": %llu trailing bytes: %llu bytes, where a %lld x %lld x %lld table takes "
                     "%llu",
                     size - expected, size, nh, nd, np, expected);
        return -1;
    }
    char why[256];
    if (measured_table_alloc(out, (int)nh, (int)nd, (int)np, why, sizeof why) != 0) {
        path_msg(err, err_size, name, ": %s", why);
        return -1;
    }
    unsigned char buf[MERL_CHUNK * 8];
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < cells; i += MERL_CHUNK) {
            size_t k = cells - i < MERL_CHUNK ? cells - i : MERL_CHUNK;
            if (fread(buf, 8, k, f) != k) goto read_failed;
            for (size_t j = 0; j < k; ++j) {
                double v = le_double(buf + 8 * j);
                float *dst = out->data + 3 * (i + j) + c;
                if (!isfinite(v) || v * channel_scales[c] > MERL_MAX_FR) {
                    char where[128];
                    cell_name(where, sizeof where, c, i + j, (int)nd, (int)np);
                    if (isfinite(v))
                        path_msg(err, err_size, name,
                                 ": %s: f_r = %g 1/sr, above the plausibility bound of %g 1/sr",
                                 where, v * channel_scales[c], MERL_MAX_FR);
                    else
                        path_msg(err, err_size, name, ": %s: %s, not a number", where,
                                 isnan(v) ? "NaN" : "an infinity");
                    measured_table_free(out);
                    return -1;
                }
                *dst = v < 0 ? -1.0f : (float)(v * channel_scales[c]);
            }
        }
    out->unmeasured = 0;
    for (size_t i = 0; i < cells; ++i) {
        const float *v = out->data + 3 * i;
        out->unmeasured += v[0] < 0 || v[1] < 0 || v[2] < 0;
    }
    return 0;
read_failed:
    if (ferror(f))
        path_msg(err, err_size, name, ": read failed: %s", strerror(errno ? errno : EIO));
    else
        path_msg(err, err_size, name, ": ended while reading (the file shrank?)");
    measured_table_free(out);
    return -1;
}

int merl_read(const char *path, measured_table *out, char *err, size_t err_size)
{
    out->n_theta_h = out->n_theta_d = out->n_phi_d = 0;
    out->data = NULL;
    out->unmeasured = 0;
    FILE *f = in_file_open(path, err, err_size);
    if (!f) return -1;
    struct stat st;
    if (fstat(fileno(f), &st) != 0) {
        path_msg(err, err_size, path, ": cannot open: %s", strerror(errno));
        fclose(f);
        return -1;
    }
    int rc = merl_read_stream(f, (unsigned long long)st.st_size, path, out, err, err_size);
    fclose(f);
    return rc;
}

/* ---- writing ------------------------------------------------------------------------------ */

/* Can t be written so that merl_read gives it back? */
static int table_check(const measured_table *t, const char *name, char *err, size_t err_size)
{
    if (!t->data || !grid_ok(t->n_theta_h, t->n_theta_d, t->n_phi_d)) {
        grid_refusal(err, err_size, name, t->n_theta_h, t->n_theta_d, t->n_phi_d);
        return -1;
    }
    size_t cells = (size_t)t->n_theta_h * (size_t)t->n_theta_d * (size_t)t->n_phi_d;
    for (size_t i = 0; i < cells; ++i)
        for (int c = 0; c < 3; ++c) {
            float v = t->data[3 * i + c];
            if (isfinite(v) && v <= MERL_MAX_FR) continue;
            char where[128];
            cell_name(where, sizeof where, c, i, t->n_theta_d, t->n_phi_d);
            if (isfinite(v))
                path_msg(err, err_size, name,
                         ": %s: f_r = %g 1/sr, above the plausibility bound of %g 1/sr; nothing "
                         "was written",
                         where, (double)v, MERL_MAX_FR);
            else
                path_msg(err, err_size, name, ": %s: %s in the table; nothing was written", where,
                         isnan(v) ? "NaN" : "an infinity");
            return -1;
        }
    return 0;
}

static void write_body(out_file *o, const measured_table *t)
{
    unsigned char buf[MERL_CHUNK * 8];
    put_le_u32(buf, (uint32_t)t->n_theta_h);
    put_le_u32(buf + 4, (uint32_t)t->n_theta_d);
    put_le_u32(buf + 8, (uint32_t)t->n_phi_d);
    out_file_write(o, buf, MERL_HEADER_BYTES);
    size_t cells = (size_t)t->n_theta_h * (size_t)t->n_theta_d * (size_t)t->n_phi_d;
    for (int c = 0; c < 3; ++c)
        for (size_t i = 0; i < cells; i += MERL_CHUNK) {
            size_t k = cells - i < MERL_CHUNK ? cells - i : MERL_CHUNK;
            for (size_t j = 0; j < k; ++j) {
                float v = t->data[3 * (i + j) + c];
                put_le_double(buf + 8 * j, v < 0 ? -1.0 : (double)v / channel_scales[c]);
            }
            out_file_write(o, buf, 8 * k);
        }
}

int merl_write_to(out_file *o, const measured_table *t, char *err, size_t err_size)
{
    if (table_check(t, o->target ? o->target : "", err, err_size) != 0) return -1;
    write_body(o, t);
    return out_file_close(o, err, err_size);
}

int merl_write(const char *path, const measured_table *t, char *err, size_t err_size)
{
    if (table_check(t, path, err, err_size) != 0) return -1;
    out_file o;
    if (out_file_open(&o, path, err, err_size) != 0) return -1;
    write_body(&o, t);
    out_file *const files[1] = {&o};
    int rc = out_file_close(&o, err, err_size) || out_file_commit(files, 1, err, err_size);
    out_file_discard(&o);
    return rc ? -1 : 0;
}
