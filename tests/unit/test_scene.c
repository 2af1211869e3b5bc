/* test_scene.c - the scene parser (values, defaults, errors naming file:line) and the exact
 * intersections and normals of every primitive, against closed forms. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geom.h"
#include "materials.h"
#include "scene_select.h"
#include "test_util.h"

static const char *HEAD = "camera position=0,0,5 look_at=0,0,0\n"
                          "material m model=lambert kd=0.5\n";

/* Parse HEAD + body; returns the parser status, message in err. */
static int parse(const char *body, scene *s, char *err, size_t size)
{
    char text[4096];
    snprintf(text, sizeof text, "%s%s", HEAD, body);
    return scene_parse_text("t.scene", text, strlen(text), s, err, size);
}

START_TEST(parses_values_and_defaults)
{
    const char *text =
        "# a comment\n"
        "camera position=1,2,3 look_at=0,0,0 fov=30 resolution=64,32\n"
        "light point position=0,5,0 color=1,0.5,0.25 intensity=10\n"
        "light directional direction=0,0,2\n"
        "ambient 0.1,0.2,0.3\n"
        "material a diffuse=lambert specular=disney_specular kd=0.2 r=0.3 f0=0.9\n"
        "material b model=disney_specular_aniso anisotropic=0.5   # trailing comment\n"
        "sphere material=a radius=2 translate=1,0,0\n"
        "box material=b size=1,2,3 rotate=0,90,0 scale=2 tangent=0,0,1\n"
        "capsule material=a radius=0.5 height=0 tangent=radial\n";
    scene s;
    char err[256];
    ck_assert_msg(scene_parse_text("x", text, strlen(text), &s, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.camera.width, 64);
    ck_assert_int_eq(s.camera.height, 32);
    ck_assert(s.camera.up[1] == 1.0 && s.camera.fov_deg == 30.0);
    ck_assert_int_eq(s.light_count, 2);
    ck_assert(s.lights[0].kind == SCENE_LIGHT_POINT && s.lights[0].intensity == 10.0 &&
              s.lights[0].color[2] == 0.25);
    ck_assert(s.lights[1].direction[2] == 1.0 &&
              s.lights[1].intensity == 1.0); /* normalised, default */
    ck_assert(s.ambient[2] == 0.3);
    ck_assert_int_eq(s.material_count, 2);
    ck_assert_int_eq(s.materials[0].lobe_count, 2);
    ck_assert(s.materials[0].lobes[1] == ABRDF_DISNEY_SPECULAR && s.materials[0].params.r == 0.3);
    ck_assert(s.materials[0].ka[0] == 0.2); /* ka defaults to kd */
    ck_assert(s.materials[1].ka[0] == 0.0); /* no diffuse albedo: no ambient reflectance */
    ck_assert_int_eq(s.object_count, 3);
    ck_assert(s.objects[1].shape == SCENE_BOX && s.objects[1].scale[2] == 2.0 &&
              s.objects[1].material == 1);
    ck_assert(s.objects[1].tangent == SCENE_TANGENT_AXIS && s.objects[1].tangent_axis[2] == 1.0);
    ck_assert(s.objects[2].tangent == SCENE_TANGENT_RADIAL &&
              s.objects[0].tangent == SCENE_TANGENT_U);
    scene_free(&s);
}
END_TEST

/* Each malformed body must fail with "t.scene:LINE: " and a message containing `what`. */
static const struct {
    const char *body;
    int line;
    const char *what;
} bad[] = {
    {"sphere material=m\n", 3, "radius"},
    {"sphere material=m radius=-1\n", 3, "radius"},
    {"sphere material=nope radius=1\n", 3, "'nope' is not defined"},
    {"sphere material=m radius=1 colour=1\n", 3, "unknown key 'colour'"},
    {"sphere material=m radius=1 radius=2\n", 3, "given twice"},
    {"\n\nteapot material=m\n", 5, "unknown directive 'teapot'"},
    {"box material=m size=1,2\n", 3, "size"},
    {"box material=m size=1,0,1\n", 3, "positive"},
    {"sphere material=m radius=1e400\n", 3, "radius"},
    {"sphere material=m radius=nan\n", 3, "radius"},
    {"sphere material=m radius=1 scale=0\n", 3, "scale"},
    {"sphere material=m radius=1 tangent=w\n", 3, "tangent"},
    {"sphere material=m radius=1 tangent=0,0,0\n", 3, "tangent"},
    {"light spot position=0,0,0\n", 3, "unknown light kind"},
    {"light directional direction=0,0,0\n", 3, "zero"},
    {"light point position=1,1,1 intensity=-2\n", 3, "intensity"},
    {"light sphere center=0,2,0\n", 3, "radius"},
    {"light sphere center=0,2,0 radius=0\n", 3, "radius"},
    {"light rect center=0,2,0 u=1,0,0\n", 3, "v=X,Y,Z"},
    {"light rect center=0,2,0 u=1,0,0 v=1,0,1\n", 3, "orthogonal"},
    {"light rect center=0,2,0 u=0,0,0 v=0,0,1\n", 3, "longer than 1e-9"},
    {"light rect center=0,2,0 u=1,0,0 v=0,0,1 radius=2\n", 3, "unknown key 'radius'"},
    {"light environment\n", 3, "file=PATH"},
    {"light environment file=no_such_map.exr\n", 3, "no_such_map.exr"},
    {"light environment file=x.exr position=1,1,1\n", 3, "unknown key 'position'"},
    {"material m model=lambert\n", 3, "defined twice"},
    {"material q model=lambrt\n", 3, "unknown model 'lambrt'"},
    {"material q model=lambert r=0.3\n", 3, "not used"},
    {"material q model=disney_specular r=2\n", 3, "outside"},
    {"material q model=lambert diffuse=lambert\n", 3, "not both"},
    {"material q adaptive goal=fast\n", 3, "unknown goal"},
    {"material q\n", 3, "needs model="},
    {"camera position=0,0,1 look_at=0,0,0\n", 3, "second camera"},
    {"ambient -1\n", 3, "negative"},
    {"ambient\n", 3, "ambient needs"},
    {"sphere material=m radius=1 stray\n", 3, "unexpected word 'stray'"},
    {"=5\n", 3, "no key"},
    {"material g pbr roughness=1.5\n", 3, "roughness = 1.5 is outside [0, 1]"},
    {"material g pbr metalic=1\n", 3, "unknown key 'metalic'"},
    {"material g pbr goal=photoreal budget=slight\n", 3, "not both"},
    {"material g pbr base_color_map=no_such.png\n", 3, "base_color_map: no_such.png"},
    {"material g pbr normal_channel=1\n", 3, "read as RGB"},
    {"material g pbr roughness_channel=1.5\n", 3, "not a whole number"},
};

START_TEST(errors_name_file_line_and_problem)
{
    scene s;
    char err[512], want[32];
    snprintf(want, sizeof want, "t.scene:%d: ", bad[_i].line);
    ck_assert_msg(parse(bad[_i].body, &s, err, sizeof err) == -1, "accepted: %s", bad[_i].body);
    ck_assert_msg(strncmp(err, want, strlen(want)) == 0, "'%s' does not start with '%s'", err,
                  want);
    ck_assert_msg(strstr(err, bad[_i].what) != NULL, "'%s' does not mention '%s'", err,
                  bad[_i].what);
    ck_assert(s.objects == NULL && s.object_count == 0); /* freed on failure */
}
END_TEST

START_TEST(whole_file_errors)
{
    scene s;
    char err[256];
    ck_assert_int_eq(scene_parse_text("e", "", 0, &s, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "no camera"));
    const char *no_obj = "camera position=0,0,5 look_at=0,0,0\n";
    ck_assert_int_eq(scene_parse_text("e", no_obj, strlen(no_obj), &s, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "no objects"));
    const char nul[] = "camera position=0,0,5 look_at=0,0,0\nsph\0ere\n";
    ck_assert_int_eq(scene_parse_text("e", nul, sizeof nul - 1, &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "e:2: NUL") != NULL, "%s", err);
    ck_assert_int_eq(scene_parse_file("/nonexistent/x.scene", &s, err, sizeof err), -1);
    ck_assert_ptr_nonnull(strstr(err, "cannot open"));
}
END_TEST

/* ---- intersections ----------------------------------------------------------------- */

static scene_object obj(scene_shape shape)
{
    scene_object o;
    memset(&o, 0, sizeof o);
    o.shape = shape;
    o.scale[0] = o.scale[1] = o.scale[2] = 1;
    return o;
}

/* Hit of the world ray o + t d; asserts the t and the unit world normal. */
static void expect_hit(const scene_object *so, const double o[3], const double d[3], double t_want,
                       const double n_want[3])
{
    geom_object g;
    geom_object_make(so, &g);
    double t, n[3];
    ck_assert_msg(geom_intersect(&g, o, d, 0.0, INFINITY, &t, n), "%s: no hit",
                  scene_shape_name(so->shape));
    ck_assert_msg(tu_close(t, t_want, 1e-12, 1e-12), "%s: t %.17g, want %.17g",
                  scene_shape_name(so->shape), t, t_want);
    for (int c = 0; c < 3; ++c)
        ck_assert_msg(tu_close(n[c], n_want[c], 1e-12, 1e-12), "%s: n[%d] %.17g, want %.17g",
                      scene_shape_name(so->shape), c, n[c], n_want[c]);
}

static void expect_miss(const scene_object *so, const double o[3], const double d[3])
{
    geom_object g;
    geom_object_make(so, &g);
    double t, n[3];
    ck_assert_msg(!geom_intersect(&g, o, d, 0.0, INFINITY, &t, n), "%s: unexpected hit at %g",
                  scene_shape_name(so->shape), t);
}

START_TEST(sphere_closed_form)
{
    scene_object s = obj(SCENE_SPHERE);
    s.radius = 2;
    s.translate[0] = 1;
    /* Ray along -z at x offset 1 + 1 from the centre: z = sqrt(4 - 1), normal (1, 0, sqrt3)/2. */
    double o[3] = {2, 0, 10}, d[3] = {0, 0, -2}; /* d not unit: t scales */
    double n[3] = {0.5, 0, sqrt(3.0) / 2};
    expect_hit(&s, o, d, (10 - sqrt(3.0)) / 2, n);
    double o2[3] = {3.5, 0, 10};
    expect_miss(&s, o2, d);
    /* From inside: the exit point, outward normal. */
    double oi[3] = {1, 0, 0}, di[3] = {0, 1, 0}, ni[3] = {0, 1, 0};
    expect_hit(&s, oi, di, 2, ni);
}
END_TEST

START_TEST(cylinder_side_and_caps)
{
    scene_object c = obj(SCENE_CYLINDER);
    c.radius = 1, c.height = 2;
    double o[3] = {0.6, 0, 5}, d[3] = {0, 0, -1}, n[3] = {0.6, 0, 0.8};
    expect_hit(&c, o, d, 5 - 0.8, n);
    double oc[3] = {0.3, 5, 0.4}, dc[3] = {0, -1, 0}, nc[3] = {0, 1, 0};
    expect_hit(&c, oc, dc, 4, nc); /* top cap at y = 1 */
    double ob[3] = {0.3, -5, 0.4}, db[3] = {0, 1, 0}, nb[3] = {0, -1, 0};
    expect_hit(&c, ob, db, 4, nb);
    double om[3] = {0, 1.5, 5};
    expect_miss(&c, om, d); /* above the side, parallel to the caps */
    double oo[3] = {1.2, 5, 0};
    expect_miss(&c, oo, dc); /* outside the cap disc */
}
END_TEST

START_TEST(capsule_side_and_round_caps)
{
    scene_object c = obj(SCENE_CAPSULE);
    c.radius = 1, c.height = 2;
    double o[3] = {0, 0.5, 5}, d[3] = {0, 0, -1}, n[3] = {0, 0, 1};
    expect_hit(&c, o, d, 4, n);
    /* Above the segment end y = 1: the sphere about (0, 1, 0); at y = 1.6, z = 0.8. */
    double o2[3] = {0, 1.6, 5}, n2[3] = {0, 0.6, 0.8};
    expect_hit(&c, o2, d, 5 - 0.8, n2);
    double o3[3] = {0, 10, 0}, d3[3] = {0, -1, 0}, n3[3] = {0, 1, 0};
    expect_hit(&c, o3, d3, 8, n3); /* pole at y = 2 */
    double o4[3] = {0, -1.6, 5}, n4[3] = {0, -0.6, 0.8};
    expect_hit(&c, o4, d, 5 - 0.8, n4);
    double o5[3] = {0, 2.1, 5};
    expect_miss(&c, o5, d);
}
END_TEST

START_TEST(box_faces)
{
    scene_object b = obj(SCENE_BOX);
    b.size[0] = 2, b.size[1] = 4, b.size[2] = 6;
    double o[3] = {0.5, 0.5, 10}, d[3] = {0, 0, -1}, n[3] = {0, 0, 1};
    expect_hit(&b, o, d, 7, n);
    double o2[3] = {-10, 1, 1}, d2[3] = {1, 0, 0}, n2[3] = {-1, 0, 0};
    expect_hit(&b, o2, d2, 9, n2);
    double o3[3] = {0, -10, 0}, d3[3] = {0, 1, 0}, n3[3] = {0, -1, 0};
    expect_hit(&b, o3, d3, 8, n3);
    double o4[3] = {1.5, 0, 10};
    expect_miss(&b, o4, d);
    double oi[3] = {0, 0, 0}, ni[3] = {1, 0, 0};
    expect_hit(&b, oi, d2, 1, ni); /* from inside: exit face */
}
END_TEST

START_TEST(transformed_normals_use_inverse_transpose)
{
    /* Sphere scaled to an ellipsoid x^2/4 + y^2 + z^2 = 1, rotated 90 deg about z (long axis
     * becomes y), moved to (0, 0, -1). Ray along -y from above hits the tip (0, 2, -1). */
    scene_object e = obj(SCENE_SPHERE);
    e.radius = 1;
    e.scale[0] = 2;
    e.rotate_deg[2] = 90;
    e.translate[2] = -1;
    double o[3] = {0, 10, -1}, d[3] = {0, -1, 0}, n[3] = {0, 1, 0};
    expect_hit(&e, o, d, 8, n);
    /* Side point of the unrotated ellipsoid at x = 1: y^2 = 3/4; gradient (x/4, y, 0) ->
     * (0.25, sqrt(.75)) normalised. Here rotated by 90 deg about z: (x, y) -> (-y, x). */
    double o2[3] = {-10, 1, -1}, d2[3] = {1, 0, 0};
    double gx = 0.25, gy = sqrt(0.75), gl = sqrt(gx * gx + gy * gy);
    double n2[3] = {-gy / gl, gx / gl, 0};
    expect_hit(&e, o2, d2, 10 - sqrt(0.75), n2);
}
END_TEST

START_TEST(rotation_order_is_x_then_y_then_z)
{
    /* A box long in x (size 4,1,1), rotated x 90 (x stays) then y 90 (x -> -z): the long
     * axis is z and a ray down the z axis hits at z = 2. The other order would leave it
     * along y. */
    scene_object b = obj(SCENE_BOX);
    b.size[0] = 4, b.size[1] = 1, b.size[2] = 1;
    b.rotate_deg[0] = 90, b.rotate_deg[1] = 90;
    double o[3] = {0, 0, 10}, d[3] = {0, 0, -1}, n[3] = {0, 0, 1};
    expect_hit(&b, o, d, 8, n);
}
END_TEST

START_TEST(tangent_rules)
{
    scene_object s = obj(SCENE_SPHERE);
    s.radius = 1;
    s.translate[1] = 3;
    geom_xform xf;
    geom_xform_make(&s, &xf);
    double p[3] = {1, 3, 0}, t[3];
    s.tangent = SCENE_TANGENT_U;
    geom_tangent(&s, &xf, p, t);
    ck_assert(t[0] == 0 && t[1] == 0 && t[2] == 1);
    s.tangent = SCENE_TANGENT_V;
    geom_tangent(&s, &xf, p, t);
    ck_assert(t[0] == 0 && t[1] == 1 && t[2] == 0);
    s.tangent = SCENE_TANGENT_RADIAL;
    geom_tangent(&s, &xf, p, t);
    ck_assert(t[0] == 1 && t[1] == 0 && t[2] == 0);
}
END_TEST

/* ---- parameters of table materials -------------------------------------------------- */

/* A value of parameter pi that differs from `was`, inside its range (whole for integers). */
static double other_value(const abrdf_param_info *pi, double was)
{
    double v = pi->min + 0.37 * (pi->max - pi->min);
    if (pi->max > 1e3) v = pi->min + 0.5 * (was - pi->min) + 0.25; /* exponents, grids */
    if (pi->kind == ABRDF_PARAM_INT) v = floor(v) == floor(was) ? floor(v) + 1 : floor(v);
    if (v > pi->max) v = pi->min;
    return v;
}

/* Parse "material m table=ENTRY [extra]" and resolve it with the photoreal selection;
 * 0, or -1 with err. */
static int resolve_table(const mat_table *t, const char *entry, const char *extra, scene *s,
                         char *err, size_t size)
{
    char text[512];
    snprintf(text, sizeof text,
             "camera position=0,0,5 look_at=0,0,0\nmaterial m table=%s %s\n"
             "sphere material=m radius=1\n",
             entry, extra);
    if (scene_parse_text("t.scene", text, strlen(text), s, err, size)) return -1;
    scene_selection how = SCENE_SELECTION_INIT;
    if (scene_select(s, "t.scene", &how, t, NULL, err, size)) {
        scene_free(s);
        return -1;
    }
    return 0;
}

/* Every parameter of the models a table entry chooses, set on the scene line, is the value
 * the resolved material renders with (a hair entry's internal_grid=9 used to be dropped), or
 * is refused because it changes nothing (a layer past layer_count); a parameter the chosen
 * models do not read is refused, naming them, and so is a selection input the choice does
 * not depend on. */
START_TEST(table_material_parameters_take_effect)
{
    mat_table t = {NULL, 0, 0};
    char err[1024];
    ck_assert_msg(mat_table_load(&t, ABRDF_TEST_DATA_DIR "/materials.csv", err, sizeof err) == 0,
                  "%s", err);
    int checked = 0, refused = 0;
    for (int e = 0; e < t.count; ++e) {
        scene plain;
        ck_assert_msg(resolve_table(&t, t.items[e].name, "", &plain, err, sizeof err) == 0, "%s",
                      err);
        const scene_material *pm = &plain.materials[0];
        for (int id = 0; id < abrdf_param_count(); ++id) {
            int read = 0;
            for (int l = 0; l < pm->lobe_count; ++l) {
                const abrdf_model_info *mi = abrdf_model_get(pm->lobes[l]);
                for (int k = 0; k < mi->param_count; ++k) read |= mi->params[k].id == id;
            }
            const abrdf_param_info *pi = abrdf_param_get(id);
            double was[3], got[3];
            if (!read || abrdf_param_read(&pm->params, id, was) < 1) continue;
            double v = other_value(pi, was[0]);
            char extra[96];
            snprintf(extra, sizeof extra, "%s=%.17g", pi->name, v);
            scene s;
            if (resolve_table(&t, t.items[e].name, extra, &s, err, sizeof err)) {
                /* refused only where it would change nothing, with the reason */
                ck_assert_msg(strstr(err, "changes nothing") != NULL, "%s %s: %s", t.items[e].name,
                              extra, err);
                ++refused;
                continue;
            }
            abrdf_param_read(&s.materials[0].params, id, got);
            /* description keys (r, kd, ...) reach the models through the selection, which may
             * derive them (n from r); every other parameter is the file's value */
            ck_assert_msg(got[0] == v ||
                              memcmp(&s.materials[0].params, &pm->params, sizeof pm->params) != 0,
                          "%s %s: ignored (resolved %g)", t.items[e].name, extra, got[0]);
            scene_free(&s);
            ++checked;
        }
        scene_free(&plain);
    }
    scene s;
    ck_assert_int_eq(resolve_table(&t, "gold", "internal_grid=9", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "internal_grid is not read by the chosen models") != NULL, "%s", err);
    /* selection inputs the chosen model does not depend on, a layer past layer_count */
    static const char *const nothing[][2] = {{"frosted_plate", "r=0.1"},
                                             {"transparent_plate", "kd=0.1"},
                                             {"velvet", "f0=0.9"},
                                             {"hair_brown", "kd=0.3"},
                                             {"coated_steel", "layer3_kappa=9"}};
    for (size_t k = 0; k < sizeof nothing / sizeof *nothing; ++k) {
        ck_assert_int_eq(resolve_table(&t, nothing[k][0], nothing[k][1], &s, err, sizeof err), -1);
        ck_assert_msg(strstr(err, "changes nothing") != NULL, "%s %s: %s", nothing[k][0],
                      nothing[k][1], err);
    }
    mat_table_free(&t);
    printf("table materials: %d parameters set on a table= line, each used; %d refused as "
           "changing nothing\n",
           checked, refused);
}
END_TEST

/* `material NAME pbr`: glTF's defaults, the mapped lobes, and an adaptive one chosen from
 * abrdf_pbr_material. */
START_TEST(pbr_materials_map_and_select)
{
    scene s;
    char err[512];
    ck_assert_msg(parse("material g pbr base_color=1,0.5,0.25 metallic=1 roughness=0.4\n"
                        "material d pbr\n"
                        "material a pbr metallic=0 roughness=0.01 goal=photoreal\n"
                        "sphere material=g radius=1\n",
                        &s, err, sizeof err) == 0,
                  "%s", err);
    const scene_material *g = &s.materials[1], *d = &s.materials[2];
    ck_assert(g->pbr && g->kind == SCENE_MAT_MODELS && !g->textured);
    ck_assert_int_eq(g->lobe_count, 2);
    ck_assert_int_eq(g->lobes[0], ABRDF_LAMBERT_FRESNEL);
    ck_assert_int_eq(g->lobes[1], ABRDF_DISNEY_SPECULAR);
    ck_assert_double_eq_tol(g->params.f0[1], 0.5, 1e-15);
    ck_assert_double_eq(g->params.kd[0], 0);
    ck_assert_double_eq(g->params.r, 0.4);
    ck_assert(d->pbr_in.metallic == 1 && d->pbr_in.roughness == 1); /* glTF's defaults */
    ck_assert(d->maps[SCENE_MAP_ROUGHNESS].channel == 1 &&
              d->maps[SCENE_MAP_METALLIC].channel == 2);
    ck_assert_int_eq(s.materials[3].kind, SCENE_MAT_ADAPTIVE);
    scene_selection how = SCENE_SELECTION_INIT;
    ck_assert_msg(scene_select(&s, "t.scene", &how, NULL, NULL, err, sizeof err) == 0, "%s", err);
    /* smooth (alpha <= 0.03) photoreal general surface: Lambert (1 - F) + f_2E */
    ck_assert_int_eq(s.materials[3].lobes[0], ABRDF_LAMBERT_FRESNEL);
    ck_assert_int_eq(s.materials[3].lobes[1], ABRDF_F_2E);
    abrdf_pbr q = g->pbr_in;
    q.roughness = 0.8, q.base_color[0] = 0.5;
    abrdf_params at;
    ck_assert_int_eq(scene_pbr_params(g, &q, &at), 0);
    ck_assert_double_eq(at.r, 0.8);
    ck_assert_double_eq_tol(at.f0[0], 0.5, 1e-15);
    q.roughness = -1;
    ck_assert_int_eq(scene_pbr_params(g, &q, &at), -1);
    scene_free(&s);
}
END_TEST

/* A fake roughness map's values: half the texels at r 0.01 (smooth), half at 0.5. */
static int fake_range(void *user, const scene_material *sm, pbr_range *out, char *err,
                      size_t err_size)
{
    (void)user, (void)err, (void)err_size;
    memset(out, 0, sizeof *out);
    out->count = 2;
    out->r[0] = 0.01 * sm->pbr_in.roughness, out->r[1] = 0.5 * sm->pbr_in.roughness;
    out->share[0] = out->share[1] = 0.5;
    out->what = "roughness map";
    return 0;
}

/* An adaptive pbr material with a roughness map is chosen over the map's values (the safe
 * branch when they cross the smooth threshold), and refused when nothing reads the map. */
START_TEST(pbr_textured_selection_reads_the_map)
{
    FILE *f = fopen("test_scene_rough.png", "wb"); /* its bytes are not read here */
    ck_assert(f != NULL);
    fputs("x", f);
    fclose(f);
    scene s;
    char err[512];
    const char *body = "material t pbr metallic=0 roughness=1 roughness_map=test_scene_rough.png "
                       "goal=photoreal\nsphere material=t radius=1\n";
    ck_assert_msg(parse(body, &s, err, sizeof err) == 0, "%s", err);
    ck_assert(s.materials[1].textured);
    scene_selection how = SCENE_SELECTION_INIT;
    ck_assert_int_eq(scene_select(&s, "t.scene", &how, NULL, NULL, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "t.scene:3: material 't'") && strstr(err, "roughness map"), "%s",
                  err);
    scene_free(&s);
    ck_assert_msg(parse(body, &s, err, sizeof err) == 0, "%s", err);
    how.map_range = fake_range;
    ck_assert_msg(scene_select(&s, "t.scene", &how, NULL, NULL, err, sizeof err) == 0, "%s", err);
    ck_assert_int_eq(s.materials[1].lobes[1], ABRDF_DISNEY_SPECULAR); /* GGX covers both */
    ck_assert_int_eq(s.materials[1].kind, SCENE_MAT_MODELS);
    scene_free(&s);
    remove("test_scene_rough.png");
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("scene");
    TCase *tp = tcase_create("parser");
    tcase_add_test(tp, parses_values_and_defaults);
    tcase_add_loop_test(tp, errors_name_file_line_and_problem, 0,
                        (int)(sizeof bad / sizeof bad[0]));
    tcase_add_test(tp, whole_file_errors);
    tcase_add_test(tp, table_material_parameters_take_effect);
    tcase_add_test(tp, pbr_materials_map_and_select);
    tcase_add_test(tp, pbr_textured_selection_reads_the_map);
    suite_add_tcase(s, tp);
    TCase *tg = tcase_create("geometry");
    tcase_add_test(tg, sphere_closed_form);
    tcase_add_test(tg, cylinder_side_and_caps);
    tcase_add_test(tg, capsule_side_and_round_caps);
    tcase_add_test(tg, box_faces);
    tcase_add_test(tg, transformed_normals_use_inverse_transpose);
    tcase_add_test(tg, rotation_order_is_x_then_y_then_z);
    tcase_add_test(tg, tangent_rules);
    suite_add_tcase(s, tg);
    return s;
}

int main(void) { return tu_run(suite()); }
