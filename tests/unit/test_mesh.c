/* test_mesh.c - triangle meshes: the OBJ reader (counts, polygons, indices, computed normals,
 * every kind of malformed line named by FILE:LINE), the `mesh` directive of the scene format
 * (paths, limits, errors) and the mesh geometry of geom.c (triangle hits, interpolated
 * normals against POV-Ray's formulation, two-sided normals, uv tangents) in closed form, and
 * the renderer's frames from uv tangents. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "render.h"
#include "test_util.h"

#define ABRDF_TEST_PI 3.14159265358979323846

static int load(const char *text, mesh *m, char *err, size_t size)
{
    return mesh_load_text("t.obj", text, strlen(text), MESH_MAX_TRIANGLES, m, err, size);
}

START_TEST(teapot_obj_reads)
{
    mesh m;
    char err[512];
    ck_assert_msg(
        mesh_load_file(SCENES_DIR "/teapot.obj", MESH_MAX_TRIANGLES, &m, err, sizeof err) == 0,
        "%s", err);
    /* gen_teapot --segments 8: 64 N^2 - 8 N triangles, welded vertices */
    ck_assert_int_eq(m.triangle_count, 64 * 64 - 64);
    ck_assert_int_eq(m.vertex_count, 2081);
    ck_assert(m.normals_from_file && m.uv && m.tri_uv && !m.polygons_split);
    for (int i = 0; i < m.normal_count; ++i) {
        const float *n = m.normal + 3 * i;
        ck_assert(fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) < 1e-6);
    }
    /* Newell's teapot: base at y = 0, lid knob at y = 3.15 */
    double lo = 1e9, hi = -1e9;
    for (int i = 0; i < m.vertex_count; ++i)
        lo = fmin(lo, m.position[3 * i + 1]), hi = fmax(hi, m.position[3 * i + 1]);
    ck_assert(lo == 0.0 && fabs(hi - 3.15) < 1e-6);
    mesh_free(&m);
}
END_TEST

START_TEST(polygons_indices_and_counts)
{
    /* a quad (fan: 2 triangles), a pentagon written with negative indices (3 triangles),
     * a triangle referring forward to a vertex defined after it */
    const char *text = "# comment\n"
                       "o thing\ng group\ns 1\nusemtl red\nmtllib x.mtl\n"
                       "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                       "f 1 2 3 4\n"
                       "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2.5 2 0\nv 2 1 0\n"
                       "f -5 -4 -3 -2 -1\n"
                       "f 1 2 10\n"
                       "v 0 0 1\n"
                       "l 1 2\n";
    mesh m;
    char err[512];
    ck_assert_msg(load(text, &m, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(m.vertex_count, 10);
    ck_assert_int_eq(m.triangle_count, 6);
    ck_assert(m.polygons_split && !m.normals_from_file && !m.uv);
    static const int want[6][3] = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6},
                                   {4, 6, 7}, {4, 7, 8}, {0, 1, 9}};
    for (int t = 0; t < 6; ++t)
        for (int c = 0; c < 3; ++c) ck_assert_int_eq(m.tri[3 * t + c], want[t][c]);
    mesh_free(&m);
    /* CRLF and lone CR end lines too */
    const char *crlf = "v 0 0 0\r\nv 1 0 0\rv 0 1 0\r\nf 1 2 3\r\n";
    ck_assert_msg(load(crlf, &m, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(m.vertex_count, 3);
    mesh_free(&m);
}
END_TEST

/* Normalised sum of unit face normals weighted by the corner angle (Blender's rule). */
START_TEST(computed_normals_are_angle_weighted)
{
    /* vertex 1 (the origin) is a corner of a triangle in the xy plane (angle 90 degrees,
     * normal +z) and of a triangle in the xz plane (angle 30 degrees, normal -y) */
    double s = sqrt(3.0);
    char text[512];
    snprintf(text, sizeof text, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv %.17g 0 -1\nf 1 2 3\nf 1 4 2\n", s);
    mesh m;
    char err[512];
    ck_assert_msg(load(text, &m, err, sizeof err) == 0, "%s", err);
    const float *n = m.normal + 3 * m.tri_normal[0];
    double w1 = ABRDF_TEST_PI / 2, w2 = ABRDF_TEST_PI / 6, e[3] = {0, -w2, w1};
    double l = sqrt(e[1] * e[1] + e[2] * e[2]);
    for (int c = 0; c < 3; ++c) ck_assert_msg(fabs(n[c] - e[c] / l) < 1e-6, "%g", n[c]);
    /* area weighting would give (0, -0.866/2, 1/2) normalised: different */
    ck_assert(fabs(n[1] - (-0.866 / 2) / sqrt(0.433 * 0.433 + 0.25)) > 0.05);
    /* a corner of one triangle only gets that triangle's normal */
    n = m.normal + 3 * m.tri_normal[2];
    ck_assert(n[0] == 0 && n[1] == 0 && n[2] == 1);
    mesh_free(&m);
}
END_TEST

/* Malformed files: each message names the file and the line. */
START_TEST(errors_name_file_and_line)
{
    static const struct {
        const char *text, *want;
    } cases[] = {
        {"v 1 2\nf 1 1 1\n", "t.obj:1: v needs 3 to 6 numbers, got 2"},
        {"v 0 0 0\nv 1 abc 3\n", "t.obj:2: v: 'abc' is not a finite decimal number"},
        {"v nan 0 0\n", "t.obj:1: v: 'nan' is not"},
        {"v 0x10 0 0\n", "t.obj:1: v: '0x10' is not"},
        {"v 1e7 0 0\n", "t.obj:1: v: 1e7 is outside"},
        {"v 1 2 3 4 5\n", "t.obj:1: v needs 3, 4 or 6 numbers, got 5"},
        {"vn 0 0 0\n", "t.obj:1: vn has zero length"},
        {"vt\n", "t.obj:1: 'vt' without values"},
        {"v 0 0 0\nv 1 0 0\nf 1 2\n", "t.obj:3: a face needs at least 3 corners, got 2"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "t.obj:5: vertex index 4 but the file has 3"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "t.obj:4: vertex index 0 (OBJ counts from 1)"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n", "t.obj:4: vertex index -5 reaches before"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n", "t.obj:5: corners of one face differ"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 1 2 3\n",
         "t.obj:6: every face gives normals or none does: this face does not, the first (line 5) "
         "does"},
        {"v 0 0 0\nf 1/2/3/4 1 1\n", "t.obj:2: face corner '1/2/3/4' is not"},
        {"v 0 0 0\nf 1/ 1 1\n", "t.obj:2: face corner '1/' is not"},
        {"v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//2 2//1 3//1\n",
         "t.obj:5: normal index 2 but the file has 1"},
        {"curv 0 1 1 2\n", "t.obj:1: free-form geometry ('curv') is not supported"},
        {"v 0 0 0\nhello world\n", "t.obj:2: unknown OBJ statement 'hello'"},
        {"v 0 0 0\nv 1 0 0\x01\n", "t.obj:2: v: '0\x01' is not"},
        {"v 0 0 0\r\nv 1 0 0\rbad\n", "t.obj:3: unknown OBJ statement 'bad'"},
        {"# nothing\n", "t.obj:0: no faces (f statements)"},
        {"", "t.obj:0: no faces"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        mesh m;
        char err[512];
        ck_assert_msg(load(cases[i].text, &m, err, sizeof err) == -1, "case %zu accepted", i);
        ck_assert_msg(strstr(err, cases[i].want) == err, "case %zu: got '%s', want '%s'", i, err,
                      cases[i].want);
    }
    /* a NUL byte: not text */
    static const char nul[] = "v 0 0 0\nv 1\0 0 0\n";
    mesh m;
    char err[512];
    ck_assert(mesh_load_text("t.obj", nul, sizeof nul - 1, 100, &m, err, sizeof err) == -1);
    ck_assert_str_eq(err, "t.obj:2: NUL byte (not a text OBJ file)");
    /* the caller's triangle limit */
    const char *quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 2 3 4\n";
    ck_assert(mesh_load_text("t.obj", quad, strlen(quad), 2, &m, err, sizeof err) == -1);
    ck_assert_str_eq(err, "t.obj:6: more than 2 triangles");
    ck_assert(mesh_load_text("t.obj", quad, strlen(quad), 3, &m, err, sizeof err) == 0);
    mesh_free(&m);
    ck_assert_int_eq(mesh_load_file("/nonexistent/x.obj", 10, &m, err, sizeof err), -2);
    ck_assert(strstr(err, "/nonexistent/x.obj: cannot open") == err);
}
END_TEST

/* ---- the scene's mesh directive ------------------------------------------------------ */

static char dir[256];

static void write_file(const char *name, const char *text)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    ck_assert(f != NULL);
    fputs(text, f);
    fclose(f);
}

static int parse_scene(const char *body, scene *s, char *err, size_t size)
{
    char path[512];
    snprintf(path, sizeof path, "%s/t.scene", dir);
    FILE *f = fopen(path, "w");
    ck_assert(f != NULL);
    fprintf(f, "camera position=0,0,5 look_at=0,0,0\nmaterial m model=lambert kd=0.5\n%s", body);
    fclose(f);
    return scene_parse_file(path, s, err, size);
}

static void setup_dir(void)
{
    snprintf(dir, sizeof dir, "/tmp/abrdf_test_mesh_%ld", (long)getpid());
    char cmd[300];
    snprintf(cmd, sizeof cmd, "mkdir -p %s/sub", dir);
    ck_assert(system(cmd) == 0);
    write_file("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    write_file("sub/uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/3\n");
    write_file("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
}

static void teardown_dir(void)
{
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", dir);
}

START_TEST(scene_mesh_directive)
{
    setup_dir();
    scene s;
    char err[1024];
    ck_assert_msg(parse_scene("mesh file=tri.obj material=m\n"
                              "mesh file=sub/uv.obj material=m smooth=off tangent=uv scale=2\n"
                              "mesh file=tri.obj material=m translate=1,0,0\n",
                              &s, err, sizeof err) == 0,
                  "%s", err);
    ck_assert_int_eq(s.object_count, 3);
    ck_assert_int_eq(s.mesh_count, 2); /* tri.obj is read once */
    ck_assert(s.objects[0].shape == SCENE_MESH && s.objects[0].smooth == 1 &&
              s.objects[0].mesh == 0 && s.objects[2].mesh_data == s.meshes[0]);
    ck_assert(s.objects[1].smooth == 0 && s.objects[1].tangent == SCENE_TANGENT_UV &&
              s.objects[1].scale[1] == 2.0);
    ck_assert_int_eq(s.triangle_count, 3);
    scene_free(&s);

    static const struct {
        const char *body, *want;
    } cases[] = {
        {"mesh material=m\n", "t.scene:3: mesh needs file=PATH"},
        {"mesh file=tri.obj\n", "t.scene:3: mesh needs material=NAME"},
        {"mesh file=tri.obj material=m smooth=yes\n", "t.scene:3: smooth must be on or off"},
        {"mesh file=tri.obj material=m tangent=uv\n",
         "t.scene:3: tangent=uv: "}, /* ... has no texture coordinates */
        {"sphere material=m radius=1 tangent=uv\n", "t.scene:3: tangent=uv needs a mesh"},
        {"mesh file=none.obj material=m\n", "t.scene:3: "},
        {"mesh file=tri.obj material=m radius=2\n", "t.scene:3: unknown key 'radius'"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        ck_assert_msg(parse_scene(cases[i].body, &s, err, sizeof err) == -1, "case %zu", i);
        char want[600];
        snprintf(want, sizeof want, "%s/%s", dir, cases[i].want);
        ck_assert_msg(strstr(err, want) == err, "case %zu: got '%s', want '%s'", i, err, want);
    }
    /* a missing file names the scene line and the file */
    ck_assert(parse_scene("\nmesh file=none.obj material=m\n", &s, err, sizeof err) == -1);
    ck_assert_msg(strstr(err, "t.scene:4: ") && strstr(err, "/none.obj: cannot open"), "%s", err);
    /* a problem inside the OBJ: its own FILE:LINE first, then the scene line */
    ck_assert(parse_scene("mesh file=bad.obj material=m\n", &s, err, sizeof err) == -1);
    char want[600];
    snprintf(want, sizeof want,
             "%s/bad.obj:4: vertex index 9 but the file has 3 (mesh at %s/t.scene:3)", dir, dir);
    ck_assert_str_eq(err, want);
    teardown_dir();
}
END_TEST

/* The limits: 10^5 objects and 2^24 triangles per scene, each with a clear message. */
START_TEST(scene_limits)
{
    setup_dir();
    size_t cap = 8u << 20, len = 0;
    char *body = malloc(cap);
    ck_assert(body != NULL);
    for (int i = 0; i < SCENE_MAX_OBJECTS; ++i)
        len += (size_t)snprintf(body + len, cap - len, "sphere material=m radius=1\n");
    scene s;
    char err[1024];
    ck_assert_msg(parse_scene(body, &s, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.object_count, SCENE_MAX_OBJECTS);
    scene_free(&s);
    len += (size_t)snprintf(body + len, cap - len, "sphere material=m radius=1\n");
    ck_assert(parse_scene(body, &s, err, sizeof err) == -1);
    char want[600];
    snprintf(want, sizeof want, "%s/t.scene:%d: more than %d objects", dir, SCENE_MAX_OBJECTS + 3,
             SCENE_MAX_OBJECTS);
    ck_assert_str_eq(err, want);
    /* triangles: a 4096-triangle strip used 4097 times passes 2^24 */
    FILE *f;
    char path[512];
    snprintf(path, sizeof path, "%s/strip.obj", dir);
    ck_assert((f = fopen(path, "w")) != NULL);
    for (int i = 0; i < 2050; ++i) fprintf(f, "v %d 0 0\nv %d 1 0\n", i, i);
    for (int i = 0; i < 2048; ++i)
        fprintf(f, "f %d %d %d\nf %d %d %d\n", 2 * i + 1, 2 * i + 3, 2 * i + 2, 2 * i + 2,
                2 * i + 3, 2 * i + 4);
    fclose(f);
    len = 0;
    for (int i = 0; i < 4097; ++i)
        len += (size_t)snprintf(body + len, cap - len, "mesh file=strip.obj material=m\n");
    ck_assert(parse_scene(body, &s, err, sizeof err) == -1);
    snprintf(want, sizeof want,
             "%s/t.scene:%d: this mesh brings the scene to %lld triangles, more than %d", dir,
             4097 + 2, 4097LL * 4096, SCENE_MAX_TRIANGLES);
    ck_assert_str_eq(err, want);
    free(body);
    teardown_dir();
}
END_TEST

/* ---- mesh geometry ------------------------------------------------------------------- */

/* One triangle (0,0,0), (2,0,0), (0,3,0) with corner normals and texture coordinates. */
static const char *TRI = "v 0 0 0\nv 2 0 0\nv 0 3 0\n"
                         "vn 0 0 1\nvn 1 0 1\nvn 0 1 1\n"
                         "vt 0 0\nvt 1 0\nvt 0 1\n"
                         "f 1/1/1 2/2/2 3/3/3\n";

static void object_of(const mesh *m, int smooth, geom_object *g)
{
    scene_object o;
    memset(&o, 0, sizeof o);
    o.shape = SCENE_MESH;
    o.mesh_data = m;
    o.smooth = smooth;
    o.scale[0] = o.scale[1] = o.scale[2] = 1;
    geom_object_make(&o, g);
}

START_TEST(triangle_hit_normals_tangent)
{
    mesh m;
    char err[256];
    ck_assert_msg(load(TRI, &m, err, sizeof err) == 0, "%s", err);
    geom_object g;
    object_of(&m, 1, &g);
    double o[3] = {0.5, 0.75, 2}, d[3] = {0, 0, -1}, t, b1, b2;
    ck_assert(geom_triangle_intersect(&g, 0, o, d, 0, INFINITY, &t, &b1, &b2));
    ck_assert(t == 2 && b1 == 0.25 && b2 == 0.25);
    ck_assert(!geom_triangle_intersect(&g, 0, o, d, 0, 2, &t, &b1, &b2)); /* (tmin, tmax) open */
    double miss[3] = {1.5, 1.5, 2};
    ck_assert(!geom_triangle_intersect(&g, 0, miss, d, 0, INFINITY, &t, &b1, &b2));
    /* smooth: the barycentric mix of the corner normals (each normalised on reading) */
    geom_mesh_hit h;
    geom_triangle_normals(&g, 0, 0.25, 0.25, d, &h);
    double r2 = sqrt(0.5), e[3] = {0.25 * r2, 0.25 * r2, 0.5 + 0.5 * r2};
    for (int c = 0; c < 3; ++c) ck_assert(fabs(h.n[c] - e[c]) < 1e-7);
    ck_assert(h.ng[0] == 0 && h.ng[1] == 0 && h.ng[2] > 0);
    /* seen from behind: both normals turn toward the viewer */
    double up[3] = {0, 0, 1};
    geom_mesh_hit back;
    geom_triangle_normals(&g, 0, 0.25, 0.25, up, &back);
    for (int c = 0; c < 3; ++c) ck_assert(back.n[c] == -h.n[c] && back.ng[c] == -h.ng[c]);
    /* flat: the face normal */
    geom_object gf;
    object_of(&m, 0, &gf);
    geom_triangle_normals(&gf, 0, 0.25, 0.25, d, &h);
    ck_assert(h.n[0] == 0 && h.n[1] == 0 && h.n[2] > 0);
    /* uv tangent: u runs along the edge to (2, 0, 0), dP/du = (2, 0, 0) */
    double tg[3];
    geom_tangent_uv(&g, 0, tg);
    ck_assert(tg[0] == 2 && tg[1] == 0 && tg[2] == 0);
    /* world space: the object's rotation turns it */
    scene_object o2;
    memset(&o2, 0, sizeof o2);
    o2.shape = SCENE_MESH, o2.mesh_data = &m, o2.smooth = 1;
    o2.scale[0] = o2.scale[1] = o2.scale[2] = 1;
    o2.rotate_deg[2] = 90;
    geom_object_make(&o2, &g);
    geom_tangent_uv(&g, 0, tg);
    ck_assert(fabs(tg[0]) < 1e-12 && fabs(tg[1] - 2) < 1e-12);
    mesh_free(&m);
}
END_TEST

/* POV-Ray's mesh2 smooth normal (Smooth_Mesh_Normal): u = the fraction of the way from
 * corner 1 to the opposite edge, v the position along that edge, N = N1 + u (N2 - N1 +
 * v (N3 - N2)); the same barycentric mix in another form. */
START_TEST(interpolation_matches_povray_form)
{
    mesh m;
    char err[256];
    ck_assert_msg(load(TRI, &m, err, sizeof err) == 0, "%s", err);
    geom_object g;
    object_of(&m, 1, &g);
    const float *N[3];
    for (int c = 0; c < 3; ++c) N[c] = m.normal + 3 * m.tri_normal[c];
    for (int i = 1; i < 20; ++i)
        for (int j = 1; i + j < 20; ++j) {
            double b1 = i / 20.0, b2 = j / 20.0;
            geom_mesh_hit h;
            double d[3] = {0, 0, -1};
            geom_triangle_normals(&g, 0, b1, b2, d, &h);
            double u = b1 + b2, v = b2 / u, pov[3];
            for (int c = 0; c < 3; ++c)
                pov[c] = N[0][c] + u * (N[1][c] - N[0][c] + v * (N[2][c] - N[1][c]));
            for (int c = 0; c < 3; ++c) ck_assert(fabs(pov[c] - h.n[c]) < 1e-12);
        }
    mesh_free(&m);
}
END_TEST

/* The teapot: a ray down the axis meets the lid knob's top at y = 3.15 (the vertex where 32
 * triangles meet), normal +y; the
 * brute-force closest hit agrees with the single-triangle test on the triangle it names. */
START_TEST(teapot_axis_hit)
{
    mesh m;
    char err[512];
    ck_assert(mesh_load_file(SCENES_DIR "/teapot.obj", MESH_MAX_TRIANGLES, &m, err, sizeof err) ==
              0);
    geom_object g;
    object_of(&m, 1, &g);
    double o[3] = {0, 10, 0}, d[3] = {0, -1, 0};
    geom_mesh_hit h;
    ck_assert(geom_mesh_intersect_local(&g, o, d, 0, INFINITY, &h));
    /* through the vertex where the lid's patches meet (3.15 rounded to float) */
    ck_assert_msg(fabs(h.t - (10 - (double)3.15f)) < 1e-12, "%.17g", h.t);
    double l = sqrt(geom_dot(h.n, h.n));
    ck_assert(h.n[1] / l > 0.9999);
    double t, b1, b2;
    ck_assert(geom_triangle_intersect(&g, h.triangle, o, d, 0, INFINITY, &t, &b1, &b2) && t == h.t);
    /* from below: the centre of the base (y = 0), whose normal faces the ray */
    double ob[3] = {0, -5, 0}, db[3] = {0, 1, 0};
    ck_assert(geom_mesh_intersect_local(&g, ob, db, 0, INFINITY, &h));
    ck_assert(fabs(h.t - 5) < 1e-12 && h.n[1] < 0);
    mesh_free(&m);
}
END_TEST

/* A square in the xy plane (two triangles) whose u runs along (1, 1, 0), under an anisotropic
 * lobe, 24x24 pixels; TANGENT is the object's tangent rule. */
static float *render_square(const char *tangent, render_stats *st)
{
    write_file("square.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n"
                             "vt 0 0.5\nvt 0.5 0\nvt 1 0.5\nvt 0.5 1\n"
                             "f 1/1 2/2 3/3 4/4\n");
    char body[256];
    snprintf(body, sizeof body,
             "light directional direction=0.3,0.5,1\n"
             "material a model=disney_specular_aniso r=0.4 anisotropic=0.9\n"
             "mesh file=square.obj material=a tangent=%s\n",
             tangent);
    scene s;
    char err[512];
    ck_assert_msg(parse_scene(body, &s, err, sizeof err) == 0, "%s", err);
    render_options opt = {24, 24, 1, 0, 1, 0, RENDER_DOUBLE, 0, 0, 0, 0, NULL};
    render_scene rs;
    ck_assert_msg(render_prepare(&s, &opt, &rs, err, sizeof err) == 0, "%s", err);
    float *rgb = malloc(24 * 24 * 3 * sizeof *rgb);
    ck_assert(rgb && render_image(&rs, &opt, rgb, st) == 0);
    render_release(&rs);
    scene_free(&s);
    return rgb;
}

/* tangent=uv gives the frame of the fixed rule along dP/du, and not the one across it. */
START_TEST(uv_tangent_frames_render)
{
    setup_dir();
    render_stats st;
    float *uv = render_square("uv", &st), *along = render_square("1,1,0", NULL),
          *across = render_square("1,-1,0", NULL);
    ck_assert(st.tangent_frames == st.hits && st.hits > 0);
    double same = 0, other = 0;
    for (int k = 0; k < 24 * 24 * 3; ++k) {
        same = fmax(same, fabs(uv[k] - along[k]) / fmax(1e-3, fabs(along[k])));
        other = fmax(other, fabs(uv[k] - across[k]) / fmax(1e-3, fabs(across[k])));
    }
    ck_assert_msg(same < 1e-9, "uv vs the rule along dP/du: rel diff %g", same);
    ck_assert_msg(other > 0.1, "uv vs the rule across dP/du: rel diff %g", other);
    free(uv), free(along), free(across);
    teardown_dir();
}
END_TEST

int main(void)
{
    Suite *s = suite_create("mesh");
    TCase *tc = tcase_create("core");
    tcase_set_timeout(tc, 120);
    tcase_add_test(tc, teapot_obj_reads);
    tcase_add_test(tc, polygons_indices_and_counts);
    tcase_add_test(tc, computed_normals_are_angle_weighted);
    tcase_add_test(tc, errors_name_file_and_line);
    tcase_add_test(tc, scene_mesh_directive);
    tcase_add_test(tc, scene_limits);
    tcase_add_test(tc, triangle_hit_normals_tangent);
    tcase_add_test(tc, interpolation_matches_povray_form);
    tcase_add_test(tc, teapot_axis_hit);
    tcase_add_test(tc, uv_tangent_frames_render);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
