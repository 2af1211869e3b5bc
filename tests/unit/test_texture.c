/* test_texture.c - textures (texture.h) and textured shading (render.c): a texel's pixel
 * equals the same quad with the texel's values as constant factors; the occlusion and normal
 * maps against closed forms; in-memory images; whole-image channel statistics; the refusals.
 * The images are written by the test (OpenImageIO through image_io.h) into a fresh directory. */
#define _DEFAULT_SOURCE /* mkdtemp, P_tmpdir */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "abrdf_fit.h"
#include "image_io.h"
#include "render.h"
#include "scene_points.h"
#include "test_util.h"

static char dir[512]; /* the test's directory, made by setup() */

static void setup(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, sizeof dir, "%s/abrdf_texture_XXXXXX", tmp && *tmp ? tmp : P_tmpdir);
    ck_assert_ptr_nonnull(mkdtemp(dir));
}

static void teardown(void)
{
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    ck_assert_int_eq(system(cmd), 0);
}

static const char *in_dir(const char *name)
{
    static char path[4][700];
    static int next;
    char *p = path[next++ % 4];
    snprintf(p, sizeof path[0], "%s/%s", dir, name);
    return p;
}

static void write_bytes(const char *name, const void *data, size_t size)
{
    FILE *f = fopen(in_dir(name), "wb");
    ck_assert_ptr_nonnull(f);
    ck_assert_uint_eq(fwrite(data, 1, size, f), size);
    ck_assert_int_eq(fclose(f), 0);
}

static void write_text(const char *name, const char *text)
{
    write_bytes(name, text, strlen(text));
}

/* A float RGB EXR of w x h pixels (top row first). */
static void write_exr(const char *name, int w, int h, const float *rgb)
{
    abrdf_bytes b;
    char err[512];
    ck_assert_msg(abrdf_image_encode_linear(name, w, h, rgb, &b, err, sizeof err) == 0, "%s", err);
    write_bytes(name, b.data, b.size);
    abrdf_bytes_free(&b);
}

/* The square [-1, 1]^2 at z = 0 facing +z, u along x and v along y (OBJ: v up); vn: its
 * normal, "" for none. */
static void write_quad(const char *name, const char *vn)
{
    char text[1024];
    snprintf(text, sizeof text,
             "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n%s%s%s",
             *vn ? "vn " : "", vn,
             *vn ? "\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"
                 : "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    write_text(name, text);
}

typedef struct result {
    int w, h;
    float *rgb;
    render_stats st;
} result;

/* Render the scene file `name` of the test's directory. */
static result render_file(const char *name, int precision, int threads)
{
    scene s;
    char err[1024];
    ck_assert_msg(scene_parse_file(in_dir(name), &s, err, sizeof err) == 0, "%s", err);
    render_options opt = {0, 0, 1, 0, threads, 0, precision, 0, 0, 0, 8, NULL};
    render_scene rs;
    ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
    result r = {rs.width, rs.height, malloc((size_t)rs.width * rs.height * 3 * sizeof(float)), {0}};
    ck_assert_ptr_nonnull(r.rgb);
    ck_assert_int_eq(render_image(&rs, &opt, r.rgb, &r.st), 0);
    render_release(&rs);
    scene_free(&s);
    return r;
}

static const float *pixel(const result *r, int i, int j)
{
    return r->rgb + 3 * ((size_t)j * r->w + i);
}

/* The camera sees the quad filling a 9N x 9N image (fov 90 from z = 1): texel (i, j) of an
 * N x N map (column i, row j from the top) has its centre at the centre of pixel
 * (9i + 4, 9j + 4), so one sample there looks the map up at the texel's centre. */
#define TX_N 4
#define TX_PIX (9 * TX_N)
#define TX_CAMERA "camera position=0,0,1 look_at=0,0,0 fov=90 resolution=36,36\n"
#define TX_LIGHTS "light point position=0.3,0.5,2 intensity=4\nambient 0.1\n"

/* Pseudo-random values in [lo, hi] (a fixed sequence: the test is deterministic). */
static float value(unsigned k, float lo, float hi)
{
    k = k * 2654435761u + 12345u;
    return lo + (hi - lo) * (float)((k >> 8) & 0xffff) / 65535.0f;
}

/* Per texel: base colour (sRGB-encoded in the file), roughness (green) and metallic (blue)
 * maps against a constant pbr material of the texel's values, in both precisions. The
 * tolerance: the lookup at a texel's centre interpolates its neighbours with float-rounding
 * weights (~1e-7), which the BRDF amplifies well below 1e-5. */
START_TEST(texel_pixel_equals_constant_material)
{
    int precision = _i;
    float bc[TX_N * TX_N * 3], mr[TX_N * TX_N * 3];
    for (unsigned k = 0; k < TX_N * TX_N * 3; ++k) {
        bc[k] = value(k, 0.05f, 0.95f);
        mr[k] = k % 3 == 1 ? value(k + 100, 0.15f, 0.9f) : value(k + 200, 0.0f, 1.0f);
    }
    write_exr("bc.exr", TX_N, TX_N, bc);
    write_exr("mr.exr", TX_N, TX_N, mr);
    write_quad("quad.obj", "");
    write_text("tex.scene", TX_CAMERA TX_LIGHTS
               "material m pbr base_color_map=bc.exr roughness_map=mr.exr metallic_map=mr.exr\n"
               "mesh file=quad.obj material=m\n");
    result t = render_file("tex.scene", precision, 2);
    ck_assert_uint_eq(t.st.textured_hits, TX_PIX * TX_PIX);
    ck_assert_uint_eq(t.st.texture_lookups, 2 * TX_PIX * TX_PIX); /* metallic-roughness: one */
    for (int j = 0; j < TX_N; ++j)
        for (int i = 0; i < TX_N; ++i) {
            const float *b = bc + 3 * (j * TX_N + i), *m = mr + 3 * (j * TX_N + i);
            char text[1024];
            snprintf(text, sizeof text,
                     TX_CAMERA TX_LIGHTS "material m pbr base_color=%.9g,%.9g,%.9g roughness=%.9g "
                                         "metallic=%.9g\nmesh file=quad.obj material=m\n",
                     texture_srgb_decode(b[0]), texture_srgb_decode(b[1]),
                     texture_srgb_decode(b[2]), m[1], m[2]);
            write_text("const.scene", text);
            result c = render_file("const.scene", precision, 1);
            ck_assert_uint_eq(c.st.textured_hits, 0);
            const float *pt = pixel(&t, 9 * i + 4, 9 * j + 4),
                        *pc = pixel(&c, 9 * i + 4, 9 * j + 4);
            for (int k = 0; k < 3; ++k)
                ck_assert_msg(tu_close(pt[k], pc[k], 1e-5, 1e-7),
                              "texel (%d, %d) channel %d: textured %.9g, constant %.9g", i, j, k,
                              pt[k], pc[k]);
            ck_assert(pc[0] > 0); /* lit */
            free(c.rgb);
        }
    free(t.rgb);
}
END_TEST

/* A texture that is the factor's identity (white base colour, linear) changes nothing, and
 * the image does not depend on the thread count. */
START_TEST(white_map_changes_nothing_any_threads)
{
    int precision = _i;
    float white[TX_N * TX_N * 3];
    for (int k = 0; k < TX_N * TX_N * 3; ++k) white[k] = 1.0f;
    write_exr("white.exr", TX_N, TX_N, white);
    write_quad("quad.obj", "");
    const char *base = TX_CAMERA TX_LIGHTS "material m pbr base_color=0.7,0.4,0.2 metallic=0.3 "
                                           "roughness=0.45 %s\nmesh file=quad.obj material=m\n";
    char text[1024];
    snprintf(text, sizeof text, base, "base_color_map=white.exr base_color_srgb=off");
    write_text("tex.scene", text);
    snprintf(text, sizeof text, base, "");
    write_text("plain.scene", text);
    result a = render_file("tex.scene", precision, 1), b = render_file("tex.scene", precision, 2),
           c = render_file("plain.scene", precision, 1);
    ck_assert_mem_eq(a.rgb, b.rgb, (size_t)a.w * a.h * 3 * sizeof(float));
    for (int p = 0; p < a.w * a.h * 3; ++p)
        ck_assert_msg(tu_close(a.rgb[p], c.rgb[p], 1e-6, 1e-9), "%d: %.9g %.9g", p, a.rgb[p],
                      c.rgb[p]);
    free(a.rgb), free(b.rgb), free(c.rgb);
}
END_TEST

/* Occlusion scales the ambient term: with no light, a texel's pixel is
 * base_color * Ia * (1 + s (o - 1)) for metallic 0 (kd = base colour, ka follows kd). */
START_TEST(occlusion_scales_ambient)
{
    int precision = _i;
    float occ[TX_N * TX_N * 3];
    for (unsigned k = 0; k < TX_N * TX_N * 3; ++k) occ[k] = value(k + 7, 0.0f, 1.0f);
    write_exr("occ.exr", TX_N, TX_N, occ);
    write_quad("quad.obj", "");
    write_text("occ.scene", TX_CAMERA "ambient 0.25\n"
                                      "material m pbr base_color=0.6,0.5,0.4 metallic=0 "
                                      "occlusion_map=occ.exr occlusion_strength=0.7\n"
                                      "mesh file=quad.obj material=m\n");
    result r = render_file("occ.scene", precision, 2);
    const double base[3] = {0.6, 0.5, 0.4};
    for (int j = 0; j < TX_N; ++j)
        for (int i = 0; i < TX_N; ++i) {
            double o = occ[3 * (j * TX_N + i)];
            const float *p = pixel(&r, 9 * i + 4, 9 * j + 4);
            for (int k = 0; k < 3; ++k) {
                double want = base[k] * 0.25 * (1 + 0.7 * (o - 1));
                ck_assert_msg(tu_close(p[k], want, 1e-5, 1e-8), "texel (%d, %d): %.9g, want %.9g",
                              i, j, p[k], want);
            }
        }
    free(r.rgb);
}
END_TEST

/* The footprint filters: a 256^2 checker of single texels (0 and 1) seen at 15 x 15 pixels
 * (17 texels a pixel, 1 sample) or 7 x 7 pixels of 2 x 2 samples reads about its mean 0.5 in
 * every pixel, where lookups without a footprint read anything from 0 to 1 (bilinear between
 * texels at these off-grid positions). Occlusion against the closed form base_color * Ia * o. */
START_TEST(footprint_filters_a_fine_checker)
{
    enum { S = 256 };
    float *occ = malloc(S * S * 3 * sizeof *occ);
    ck_assert_ptr_nonnull(occ);
    for (int y = 0; y < S; ++y)
        for (int x = 0; x < S; ++x)
            for (int c = 0; c < 3; ++c) occ[3 * (y * S + x) + c] = (float)((x + y) & 1);
    write_exr("checker.exr", S, S, occ);
    free(occ);
    write_quad("quad.obj", "");
    write_text("occ.scene", TX_CAMERA "ambient 1\n"
                                      "material m pbr base_color=1,1,1 metallic=0 "
                                      "occlusion_map=checker.exr\n"
                                      "mesh file=quad.obj material=m\n");
    for (int spp = 1; spp <= 4; spp += 3) {
        scene s;
        char err[1024];
        ck_assert_msg(scene_parse_file(in_dir("occ.scene"), &s, err, sizeof err) == 0, "%s", err);
        int size = spp == 1 ? 15 : 7;
        render_options opt = {size, size, spp, 0, 1, 0, RENDER_FLOAT, 0, 0, 0, 0, NULL};
        render_scene rs;
        ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
        float rgb[16 * 16 * 3];
        ck_assert_int_eq(render_image(&rs, &opt, rgb, NULL), 0);
        for (int p = 0; p < size * size * 3; ++p)
            ck_assert_msg(fabs(rgb[p] - 0.5) < 0.02, "spp %d, pixel %d: %.6g", spp, p / 3, rgb[p]);
        render_release(&rs);
        scene_free(&s);
    }
}
END_TEST

/* KHR_texture_transform (scene_map offset, rotation, scale; set here as a glTF reader sets
 * them): with rotation pi/2 and offset (0.25, 0), (s, t) -> (0.25 - t, s), so the pixel of
 * texel (i, j) reads texel (4 - j mod 4, i) of the occlusion map (periodic wrap). */
START_TEST(texture_transform_moves_texels)
{
    float occ[TX_N * TX_N * 3];
    for (unsigned k = 0; k < TX_N * TX_N * 3; ++k) occ[k] = value(k + 11, 0.0f, 1.0f);
    write_exr("occ.exr", TX_N, TX_N, occ);
    write_quad("quad.obj", "");
    write_text("occ.scene", TX_CAMERA "ambient 0.5\n"
                                      "material m pbr base_color=1,1,1 metallic=0 "
                                      "occlusion_map=occ.exr\n"
                                      "mesh file=quad.obj material=m\n");
    scene s;
    char err[1024];
    ck_assert_msg(scene_parse_file(in_dir("occ.scene"), &s, err, sizeof err) == 0, "%s", err);
    scene_map *mp = &s.materials[0].maps[SCENE_MAP_OCCLUSION];
    mp->rotation = acos(-1.0) / 2, mp->offset[0] = 0.25;
    render_options opt = {0, 0, 1, 0, 2, 0, RENDER_DOUBLE, 0, 0, 0, 0, NULL};
    render_scene rs;
    ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
    float *rgb = malloc((size_t)rs.width * rs.height * 3 * sizeof *rgb);
    ck_assert_ptr_nonnull(rgb);
    ck_assert_int_eq(render_image(&rs, &opt, rgb, NULL), 0);
    for (int j = 0; j < TX_N; ++j)
        for (int i = 0; i < TX_N; ++i) {
            double o = occ[3 * (i * TX_N + (TX_N - j) % TX_N)];
            double got = rgb[3 * ((size_t)(9 * j + 4) * rs.width + 9 * i + 4)];
            ck_assert_msg(tu_close(got, 0.5 * o, 1e-5, 1e-8), "texel (%d, %d): %.9g, want %.9g", i,
                          j, got, 0.5 * o);
        }
    free(rgb);
    render_release(&rs);
    scene_free(&s);
}
END_TEST

/* A flat normal map (0.5, 0.5, 1) is the surface's normal: the image is the unmapped one's.
 * A constant tilted normal n = (sin a cos b, sin a sin b, cos a) in tangent space is, on this
 * quad (dP/du = +x, dP/dv = +y, N = +z), the world normal n: the same quad with that vertex
 * normal renders the same image (b tilts both tangent axes: their signs are tested). */
START_TEST(normal_map_flat_and_tilted)
{
    int precision = _i;
    const double a = 0.5, b = 1.0, n[3] = {sin(a) * cos(b), sin(a) * sin(b), cos(a)};
    float flat[TX_N * TX_N * 3], tilt[TX_N * TX_N * 3];
    for (int k = 0; k < TX_N * TX_N; ++k) {
        flat[3 * k] = flat[3 * k + 1] = 0.5f, flat[3 * k + 2] = 1.0f;
        for (int c = 0; c < 3; ++c) tilt[3 * k + c] = (float)(0.5 * (n[c] + 1));
    }
    write_exr("flat.exr", TX_N, TX_N, flat);
    write_exr("tilt.exr", TX_N, TX_N, tilt);
    write_quad("quad.obj", "");
    char vn[128];
    snprintf(vn, sizeof vn, "%.17g %.17g %.17g", n[0], n[1], n[2]);
    write_quad("tilted.obj", vn);
    const char *m = TX_CAMERA TX_LIGHTS "material m pbr base_color=0.8,0.5,0.3 metallic=0.2 "
                                        "roughness=0.4 %s\nmesh file=%s material=m\n";
    char text[1024];
    const char *pairs[2][3] = {{"normal_map=flat.exr", "quad.obj", ""},
                               {"normal_map=tilt.exr", "quad.obj", "tilted.obj"}};
    for (int t = 0; t < 2; ++t) {
        snprintf(text, sizeof text, m, pairs[t][0], pairs[t][1]);
        write_text("mapped.scene", text);
        snprintf(text, sizeof text, m, "", t ? pairs[t][2] : "quad.obj");
        write_text("ref.scene", text);
        result r = render_file("mapped.scene", precision, 2),
               q = render_file("ref.scene", precision, 1);
        double diff = 0;
        for (int p = 0; p < r.w * r.h * 3; ++p) {
            ck_assert_msg(tu_close(r.rgb[p], q.rgb[p], 2e-5, 1e-7), "%s pixel %d: %.9g, want %.9g",
                          pairs[t][0], p / 3, r.rgb[p], q.rgb[p]);
            diff += fabs(r.rgb[p] - q.rgb[p]);
        }
        if (t == 1) { /* the tilt changed the image: the test can fail */
            snprintf(text, sizeof text, m, "", "quad.obj");
            write_text("flat.scene", text);
            result f = render_file("flat.scene", precision, 1);
            double change = 0;
            for (int p = 0; p < r.w * r.h * 3; ++p) change += fabs(r.rgb[p] - f.rgb[p]);
            ck_assert(change > 1000 * (diff + 1e-9));
            free(f.rgb);
        }
        free(r.rgb), free(q.rgb);
    }
}
END_TEST

/* The budget's shading points (scene_points.h) see a normal map as the render shades it:
 * on a quad under a strong one (bumps tilting the normal up to ~50 degrees), the prediction
 * on the points of a pbr candidate against a pbr reference is the NMSE of their two renders
 * over the material's pixels, as scene_points_predict_the_render (test_render.c) has it
 * without a map. The points traced with the map left out predict another number: the
 * map matters here, so the test can fail. */
#define NM_SCENE                                                                                   \
    "camera position=0,-1.3,1.5 look_at=0,0,0 fov=60 resolution=32,32\n"                           \
    "ambient 0\n"                                                                                  \
    "light directional direction=-0.5,0.4,1 intensity=2\n"                                         \
    "light point position=0.6,0.8,1.5 intensity=3\n"                                               \
    "material m pbr base_color=0.8,0.5,0.3 metallic=0.2 %s %s\n"                                   \
    "mesh file=quad.obj material=m\n"

/* NMSE of b against a over the pixels whose centre sees material m (budget_points'). */
static double nmse_over(const result *a, const result *b, const scene_points *p, int m)
{
    double num = 0, den = 0;
    for (int q = 0; q < a->w * a->h; ++q) {
        if (p->pixel_material[q] != m) continue;
        for (int c = 0; c < 3; ++c) {
            double d = (double)b->rgb[3 * q + c] - a->rgb[3 * q + c];
            num += d * d, den += (double)a->rgb[3 * q + c] * a->rgb[3 * q + c];
        }
    }
    return num / den;
}

/* Material 0 of scene file `name`: its lobes and the parameters a textured hit shades with. */
static void lobes_params(const char *name, abrdf_model *d, abrdf_model *sp, abrdf_params *p)
{
    scene s;
    char err[1024];
    ck_assert_msg(scene_parse_file(in_dir(name), &s, err, sizeof err) == 0, "%s", err);
    const scene_material *m = &s.materials[0];
    *d = m->lobe_count == 2 ? m->lobes[0] : ABRDF_MODEL_NONE;
    *sp = m->lobes[m->lobe_count - 1];
    ck_assert_int_eq(scene_pbr_params(m, &m->pbr_in, p), 0);
    scene_free(&s);
}

/* The points of scene file `name` at 4 spp and the prediction on them of cand against ref. */
static double points_predict(const char *name, const char *ref, const char *cand, scene_points *p)
{
    scene s;
    char err[1024];
    ck_assert_msg(scene_parse_file(in_dir(name), &s, err, sizeof err) == 0, "%s", err);
    ck_assert_msg(scene_points_trace(&s, 4, p, err, sizeof err) == 0, "%s", err);
    scene_free(&s);
    abrdf_model rd, rsp, cd, csp;
    abrdf_params pr, pc;
    lobes_params(ref, &rd, &rsp, &pr);
    lobes_params(cand, &cd, &csp, &pc);
    abrdf_view v;
    ck_assert(scene_points_view(p, 0, &v));
    size_t size = abrdf_fit_workspace_size(NULL, &v);
    void *work = malloc(size);
    ck_assert_ptr_nonnull(work);
    double nmse = -1;
    ck_assert_int_eq(abrdf_predict_nmse(rd, rsp, &pr, cd, csp, &pc, &v, &nmse, work, size),
                     ABRDF_OK);
    free(work);
    return nmse;
}

START_TEST(scene_points_see_the_normal_map)
{
    enum { N = 16 };
    float bumps[N * N * 3];
    const double pi = 3.14159265358979323846, a = 1.2; /* slope amplitude: tilts up to ~50 deg */
    for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i) { /* the gradient of sin(2 pi 2 u) sin(2 pi 2 v), v up */
            double u = (i + 0.5) / N, v = 1 - (j + 0.5) / N;
            double n[3] = {-a * cos(4 * pi * u) * sin(4 * pi * v),
                           -a * sin(4 * pi * u) * cos(4 * pi * v), 1};
            double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (int c = 0; c < 3; ++c) bumps[3 * (j * N + i) + c] = (float)(0.5 * (n[c] / l + 1));
        }
    write_exr("bumps.exr", N, N, bumps);
    write_quad("quad.obj", "");
    const char *names[4] = {"ref.scene", "cand.scene", "ref_flat.scene", "cand_flat.scene"};
    const char *rough[2] = {"roughness=0.45", "roughness=0.2"};
    for (int k = 0; k < 4; ++k) {
        char text[1024];
        snprintf(text, sizeof text, NM_SCENE, rough[k % 2], k < 2 ? "normal_map=bumps.exr" : "");
        write_text(names[k], text);
    }
    result r[2];
    for (int k = 0; k < 2; ++k) {
        scene s;
        char err[1024];
        ck_assert_msg(scene_parse_file(in_dir(names[k]), &s, err, sizeof err) == 0, "%s", err);
        render_options opt = {0, 0, 4, 0, 2, 0, RENDER_DOUBLE, 0, 0, 0, 8, NULL};
        render_scene rs;
        ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
        r[k] = (result){
            rs.width, rs.height, malloc((size_t)rs.width * rs.height * 3 * sizeof(float)), {0}};
        ck_assert_ptr_nonnull(r[k].rgb);
        ck_assert_int_eq(render_image(&rs, &opt, r[k].rgb, &r[k].st), 0);
        ck_assert(r[k].st.textured_hits > 0);
        render_release(&rs);
        scene_free(&s);
    }
    scene_points p, flat;
    double mapped = points_predict(names[0], names[0], names[1], &p);
    double measured = nmse_over(&r[0], &r[1], &p, 0);
    ck_assert_msg(measured > 1e-3, "the candidate must differ: %g", measured);
    /* the images are stored in float: 1e-5 of relative rounding */
    ck_assert_msg(fabs(mapped - measured) < 1e-5 * measured, "points %.9g, image %.9g", mapped,
                  measured);
    /* the same points with the map left out: the prediction is off by more than 10% */
    double unmapped = points_predict(names[2], names[0], names[1], &flat);
    ck_assert_int_eq(flat.pixels[0], p.pixels[0]);
    ck_assert_msg(fabs(unmapped - measured) > 0.1 * measured, "unmapped %.9g, image %.9g", unmapped,
                  measured);
    scene_points_free(&p);
    scene_points_free(&flat);
    free(r[0].rgb), free(r[1].rgb);
}
END_TEST

/* texture_channel_stats on an image of known values: channel 1 holds k / 3072 at pixel k,
 * so each of 8 bins holds 384 values. */
START_TEST(channel_stats_known_values)
{
    enum { W = 64, H = 48 };
    float *rgb = malloc(W * H * 3 * sizeof(float));
    ck_assert_ptr_nonnull(rgb);
    for (int k = 0; k < W * H; ++k)
        rgb[3 * k] = 0.25f, rgb[3 * k + 1] = (float)k / (W * H), rgb[3 * k + 2] = 2.0f;
    write_exr("stats.exr", W, H, rgb);
    char err[512];
    texture_system *ts = texture_system_new(4, err, sizeof err);
    ck_assert_msg(ts != NULL, "%s", err);
    texture_file *f;
    texture_info info;
    ck_assert_msg(texture_open(ts, in_dir("stats.exr"), NULL, 0, &f, &info, err, sizeof err) == 0,
                  "%s", err);
    ck_assert_int_eq(info.width, W);
    ck_assert_int_eq(info.height, H);
    ck_assert_int_eq(info.channels, 3);
    unsigned long long hist[8];
    double lo, hi;
    ck_assert_int_eq(texture_channel_stats(ts, f, 0, 1, 0, 8, hist, &lo, &hi, err, sizeof err), 0);
    for (int b = 0; b < 8; ++b) ck_assert_uint_eq(hist[b], W * H / 8);
    ck_assert(lo == 0.0 && hi == (double)((float)(W * H - 1) / (W * H)));
    /* sRGB decoding first: the bins of the decoded values */
    unsigned long long want[8] = {0};
    for (int k = 0; k < W * H; ++k) {
        double v = texture_srgb_decode((float)k / (W * H));
        ++want[v >= 1 ? 7 : (int)(v * 8)];
    }
    ck_assert_int_eq(texture_channel_stats(ts, f, 0, 1, 1, 8, hist, &lo, &hi, err, sizeof err), 0);
    for (int b = 0; b < 8; ++b) ck_assert_uint_eq(hist[b], want[b]);
    ck_assert(hi == texture_srgb_decode((float)(W * H - 1) / (W * H)));
    /* out of [0, 1]: the end bins */
    ck_assert_int_eq(texture_channel_stats(ts, f, 0, 2, 0, 4, hist, &lo, &hi, err, sizeof err), 0);
    ck_assert_uint_eq(hist[3], W * H);
    ck_assert(lo == 2.0 && hi == 2.0);
    ck_assert_int_eq(texture_channel_stats(ts, f, 0, 3, 0, 4, hist, &lo, &hi, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "no channel 3") && strstr(err, "stats.exr"), "%s", err);
    texture_system_free(ts);
    free(rgb);
}
END_TEST

/* An image in memory (a .glb's embedded PNG) reads as the same file on disk. */
START_TEST(image_in_memory_reads_as_file)
{
    enum { W = 8, H = 8 };
    float rgb[W * H * 3];
    for (int k = 0; k < W * H * 3; ++k) rgb[k] = value((unsigned)k, 0.0f, 1.0f);
    abrdf_bytes png;
    char err[512];
    ck_assert_msg(abrdf_image_encode_preview("m.png", W, H, rgb, NULL, NULL, NULL, &png, err,
                                             sizeof err) == 0,
                  "%s", err);
    write_bytes("m.png", png.data, png.size);
    texture_system *ts = texture_system_new(4, err, sizeof err);
    ck_assert_msg(ts != NULL, "%s", err);
    texture_thread *th = texture_thread_new(ts);
    texture_file *ff, *fm;
    ck_assert_msg(texture_open(ts, in_dir("m.png"), NULL, 0, &ff, NULL, err, sizeof err) == 0, "%s",
                  err);
    ck_assert_msg(texture_open(ts, "model.glb#image0.png", png.data, png.size, &fm, NULL, err,
                               sizeof err) == 0,
                  "%s", err);
    for (int k = 0; k < 20; ++k) {
        float a[3], b[3];
        double s = value(k, 0, 1), t = value(k + 50, 0, 1);
        ck_assert_int_eq(texture_lookup(ts, th, ff, 0, 3, s, t, 0.01, 0, 0, 0.01, a), 0);
        ck_assert_int_eq(texture_lookup(ts, th, fm, 0, 3, s, t, 0.01, 0, 0, 0.01, b), 0);
        ck_assert_mem_eq(a, b, sizeof a);
    }
    /* bytes of no image format, and a format named by no extension: one line each */
    ck_assert_int_eq(
        texture_open(ts, "model.glb#image1.png", "not a png", 9, &fm, NULL, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "model.glb#image1.png") == err && !strchr(err, '\n'), "%s", err);
    ck_assert_int_eq(
        texture_open(ts, "model.glb#image2", png.data, png.size, &fm, NULL, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "model.glb#image2: ") == err, "%s", err);
    texture_thread_free(ts, th);
    texture_system_free(ts);
    abrdf_bytes_free(&png);
}
END_TEST

/* Bad files and textures on objects without texture coordinates: one line at prepare. */
START_TEST(refusals_at_prepare)
{
    write_quad("quad.obj", "");
    write_text("junk.png", "this is not an image\n");
    const struct {
        const char *lines, *want;
    } cases[] = {
        {"material m pbr roughness_map=junk.png\nmesh file=quad.obj material=m\n", "junk.png: "},
        {"material m pbr roughness_map=junk.png\nsphere material=m radius=1\n",
         "material 'm' (line 4) has textures, but the sphere at line 5 has no texture "
         "coordinates"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof *cases; ++c) {
        char text[1024], err[1024];
        snprintf(text, sizeof text, TX_CAMERA TX_LIGHTS "%s", cases[c].lines);
        write_text("bad.scene", text);
        scene s;
        ck_assert_msg(scene_parse_file(in_dir("bad.scene"), &s, err, sizeof err) == 0, "%s", err);
        render_options opt = {0, 0, 1, 0, 1, 0, RENDER_FLOAT, 0, 0, 0, 0, NULL};
        render_scene rs;
        ck_assert_int_eq(render_prepare(&s, &opt, &rs, err, sizeof err), -1);
        ck_assert_msg(strstr(err, cases[c].want) && !strchr(err, '\n'), "%s", err);
        const char *junk = in_dir("junk.png");
        if (c == 0) ck_assert_msg(!strncmp(err, junk, strlen(junk)), "%s", err);
        scene_free(&s);
    }
}
END_TEST

int main(void)
{
    Suite *s = suite_create("texture");
    TCase *tr = tcase_create("render");
    tcase_add_checked_fixture(tr, setup, teardown);
    tcase_set_timeout(tr, 60);
    tcase_add_loop_test(tr, texel_pixel_equals_constant_material, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tr, white_map_changes_nothing_any_threads, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tr, occlusion_scales_ambient, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_loop_test(tr, normal_map_flat_and_tilted, RENDER_FLOAT, RENDER_DOUBLE + 1);
    tcase_add_test(tr, texture_transform_moves_texels);
    tcase_add_test(tr, footprint_filters_a_fine_checker);
    tcase_add_test(tr, refusals_at_prepare);
    tcase_add_test(tr, scene_points_see_the_normal_map);
    suite_add_tcase(s, tr);
    TCase *tt = tcase_create("texture");
    tcase_add_checked_fixture(tt, setup, teardown);
    tcase_add_test(tt, channel_stats_known_values);
    tcase_add_test(tt, image_in_memory_reads_as_file);
    suite_add_tcase(s, tt);
    return tu_run(s);
}
