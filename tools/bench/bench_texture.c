/* bench_texture.c - what textures cost the built-in renderer, measured side by side in one
 * run: the same quad rendered with a textured pbr material (base colour + metallic-roughness
 * maps) and with constant factors, in both precisions, per shaded sample; and the parts of
 * the difference - one filtered TextureSystem lookup, and the per-hit abrdf_prepare of the
 * material's two lobes - timed alone. Prints OpenImageIO's statistics of the textured render.
 * Times are process CPU seconds (robust on a shared machine), the best of --reps runs, one
 * render thread. The maps are generated (float EXR, scanline: cached in 64 x 64 tiles with
 * MIP levels made on demand) in a fresh directory and removed.
 *
 * usage: bench_texture [--size N] [--spp K] [--texture-size S] [--reps R] */
#define _DEFAULT_SOURCE /* mkdtemp, P_tmpdir */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "image_io.h"
#include "render.h"

static char dir[512];

static double cpu_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static const char *in_dir(const char *name)
{
    static char path[2][700];
    static int next;
    char *p = path[next++ % 2];
    snprintf(p, sizeof path[0], "%s/%s", dir, name);
    return p;
}

static int write_bytes(const char *name, const void *data, size_t size)
{
    FILE *f = fopen(in_dir(name), "wb");
    if (!f) return -1;
    int ok = fwrite(data, 1, size, f) == size;
    return fclose(f) == 0 && ok ? 0 : -1;
}

static int write_text(const char *name, const char *text)
{
    return write_bytes(name, text, strlen(text));
}

/* A float RGB EXR of s x s pixels: value(x, y, c) smooth, in [lo, hi]. */
static int write_map(const char *name, int s, double lo, double hi, unsigned seed)
{
    float *rgb = malloc((size_t)s * s * 3 * sizeof *rgb);
    if (!rgb) return -1;
    for (int y = 0; y < s; ++y)
        for (int x = 0; x < s; ++x)
            for (int c = 0; c < 3; ++c) {
                double v = 0.5 + 0.25 * sin(0.05 * x * (c + 1) + seed) +
                           0.25 * cos(0.037 * y * (c + 2) + 2.0 * seed);
                rgb[3 * ((size_t)y * s + x) + c] = (float)(lo + (hi - lo) * v);
            }
    abrdf_bytes b;
    char err[512];
    int rc = abrdf_image_encode_linear(name, s, s, rgb, &b, err, sizeof err);
    free(rgb);
    if (rc) {
        fprintf(stderr, "bench_texture: %s\n", err);
        return -1;
    }
    rc = write_bytes(name, b.data, b.size);
    abrdf_bytes_free(&b);
    return rc;
}

typedef struct timing {
    double seconds; /* best CPU time of a render */
    render_stats st;
} timing;

static int render_best(const char *scene_name, const render_options *opt, int reps, timing *out,
                       int print_textures)
{
    scene s;
    char err[1024];
    if (scene_parse_file(in_dir(scene_name), &s, err, sizeof err)) {
        fprintf(stderr, "bench_texture: %s\n", err);
        return -1;
    }
    render_scene rs;
    if (render_prepare(&s, opt, &rs, err, sizeof err)) {
        fprintf(stderr, "bench_texture: %s\n", err);
        scene_free(&s);
        return -1;
    }
    float *rgb = malloc((size_t)rs.width * rs.height * 3 * sizeof *rgb);
    out->seconds = INFINITY;
    for (int r = 0; r < reps && rgb; ++r) {
        double t0 = cpu_now();
        render_image(&rs, opt, rgb, &out->st);
        double t = cpu_now() - t0;
        if (t < out->seconds) out->seconds = t;
    }
    if (print_textures) render_textures_print(&rs, stdout);
    free(rgb);
    render_release(&rs);
    scene_free(&s);
    return rgb ? 0 : -1;
}

/* ns per filtered lookup of n channels with a footprint of `foot`: at scattered points, or
 * (coherent) in scanline order one footprint apart, as a render's camera samples go. */
static double lookup_ns(texture_system *ts, texture_file *f, int n, double foot, int coherent,
                        int count)
{
    long across = (long)(1.0 / foot);
    texture_thread *th = texture_thread_new(ts);
    float out[4];
    double sum = 0, best = INFINITY;
    for (int rep = 0; rep < 3; ++rep) {
        double t0 = cpu_now();
        for (int k = 0; k < count; ++k) {
            double s = fmod(k * 0.6180339887498949, 1.0), t = fmod(k * 0.7548776662466927, 1.0);
            if (coherent) s = (k % across + 0.5) * foot, t = (k / across % across + 0.5) * foot;
            texture_lookup(ts, th, f, 0, n, s, t, foot, 0, 0, foot, out);
            sum += out[0];
        }
        double dt = cpu_now() - t0;
        if (dt < best) best = dt;
    }
    texture_thread_free(ts, th);
    if (sum < 0) printf("%g\n", sum); /* keeps the loop */
    return 1e9 * best / count;
}

/* ns per abrdf_prepare of lambert_fresnel + disney_specular (a textured hit's lobes). */
static double prepare_ns(int count)
{
    abrdf_pbr q;
    abrdf_pbr_init(&q);
    abrdf_model lobes[2];
    int nl;
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    abrdf_pbr_lobes(&q, lobes, &nl, &p);
    abrdf_prepared prep[2];
    double best = INFINITY, sink = 0;
    for (int rep = 0; rep < 3; ++rep) {
        double t0 = cpu_now();
        for (int k = 0; k < count; ++k) {
            p.r = 0.2 + 0.6 * (k & 255) / 255.0;
            for (int l = 0; l < nl; ++l) abrdf_prepare(lobes[l], &p, &prep[l]);
            sink += prep[0].opaque.align_double;
        }
        double dt = cpu_now() - t0;
        if (dt < best) best = dt;
    }
    if (sink == 12345.678) printf("%g\n", sink);
    return 1e9 * best / count;
}

int main(int argc, char **argv)
{
    int size = 256, spp = 4, tex = 1024, reps = 3;
    for (int i = 1; i + 1 < argc; i += 2) {
        int *slot = !strcmp(argv[i], "--size")           ? &size
                    : !strcmp(argv[i], "--spp")          ? &spp
                    : !strcmp(argv[i], "--texture-size") ? &tex
                    : !strcmp(argv[i], "--reps")         ? &reps
                                                         : NULL;
        if (!slot || (*slot = atoi(argv[i + 1])) < 1) {
            fprintf(stderr, "usage: bench_texture [--size N] [--spp K] [--texture-size S] "
                            "[--reps R]\n");
            return 2;
        }
    }
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/abrdf_bench_texture_XXXXXX", tmp && *tmp ? tmp : P_tmpdir);
    if (!mkdtemp(dir)) {
        perror("bench_texture: mkdtemp");
        return 1;
    }
    int rc = 1;
    const char *quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                       "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
    const char *head = "camera position=0,0,1.2 look_at=0,0,0 fov=90 resolution=64,64\n"
                       "light point position=0.3,0.5,2 intensity=4\n"
                       "light directional direction=-0.4,0.3,1 intensity=1\nambient 0.1\n";
    char text[1024];
    if (write_text("quad.obj", quad) || write_map("bc.exr", tex, 0.05, 0.95, 1) ||
        write_map("mr.exr", tex, 0.1, 0.9, 2))
        goto done;
    snprintf(text, sizeof text,
             "%smaterial m pbr base_color_map=bc.exr metallic_map=mr.exr roughness_map=mr.exr\n"
             "mesh file=quad.obj material=m\n",
             head);
    if (write_text("textured.scene", text)) goto done;
    snprintf(text, sizeof text,
             "%smaterial m pbr base_color=0.25,0.25,0.25 metallic=0.5 roughness=0.5\n"
             "mesh file=quad.obj material=m\n",
             head);
    if (write_text("constant.scene", text)) goto done;

    printf("bench_texture: a %dx%d quad image, %d spp, %dx%d maps (base colour, "
           "metallic-roughness), 2 lights, 1 thread, best of %d (CPU time)\n",
           size, size, spp, tex, tex, reps);
    printf("command: bench_texture --size %d --spp %d --texture-size %d --reps %d\n", size, spp,
           tex, reps);
    printf("%-8s %14s %14s %9s %16s\n", "path", "constant ns", "textured ns", "ratio",
           "extra ns/sample");
    double extra[2] = {0, 0};
    for (int prec = 0; prec < 2; ++prec) {
        render_options opt = {size, size, spp, 0, 1, 0, prec, 0, 0, 0, 0, NULL};
        timing c, t;
        if (render_best("constant.scene", &opt, reps, &c, 0) ||
            render_best("textured.scene", &opt, reps, &t, 0))
            goto done;
        double n = (double)c.st.hits, cns = 1e9 * c.seconds / n, tns = 1e9 * t.seconds / n;
        extra[prec] = tns - cns;
        printf("%-8s %14.1f %14.1f %8.2fx %16.1f\n", render_precision_name(prec), cns, tns,
               tns / cns, tns - cns);
    }
    /* the parts: lookups at the render's footprint (a texel of the finest level per stratum:
     * size * sqrt(spp) strata across tex texels), and the per-hit prepare */
    char err[512];
    texture_system *ts = texture_system_new(TEXTURE_CACHE_MB_DEFAULT, err, sizeof err);
    texture_file *f;
    if (!ts || texture_open(ts, in_dir("bc.exr"), NULL, 0, &f, NULL, err, sizeof err)) {
        fprintf(stderr, "bench_texture: %s\n", err);
        texture_system_free(ts);
        goto done;
    }
    double foot = 1.0 / (size * sqrt((double)spp));
    double l3 = lookup_ns(ts, f, 3, foot, 0, 1000000), l2 = lookup_ns(ts, f, 2, foot, 0, 1000000);
    double c3 = lookup_ns(ts, f, 3, foot, 1, 1000000), c2 = lookup_ns(ts, f, 2, foot, 1, 1000000);
    double prep = prepare_ns(1000000);
    texture_system_free(ts);
    printf("one lookup, scattered: %.1f ns (3 channels), %.1f ns (2 channels); in scanline order: "
           "%.1f ns, %.1f ns\n",
           l3, l2, c3, c2);
    printf("prepare of the 2 lobes per hit: %.1f ns\n", prep);
    printf("a textured sample's 2 lookups (base colour; metallic and roughness from one file) + "
           "prepare, scanline order: %.1f ns of the extra %.1f (float), %.1f (double)\n",
           c3 + c2 + prep, extra[0], extra[1]);
    render_options opt = {size, size, spp, 0, 1, 0, RENDER_FLOAT, 0, 0, 0, 0, NULL};
    timing t;
    if (render_best("textured.scene", &opt, 1, &t, 1)) goto done;
    rc = 0;
done:
    snprintf(text, sizeof text, "rm -rf '%s'", dir);
    if (system(text) != 0) rc = 1;
    return rc;
}
