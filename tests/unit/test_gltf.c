/* test_gltf.c - the glTF reader (tools/gltf/gltf.h) on the fuzz seeds (tests/fuzz/corpus/gltf,
 * written by make_gltf_corpus.py), field by field: textures into scene_map (an embedded
 * image as a blob, texCoord, KHR_texture_transform, metallic-roughness as two maps, normal
 * scale), strips and fans, the node hierarchy baked in (matrix, TRS, a mirroring scale),
 * glTF's default material, the default camera and light, a perspective camera's aspect
 * ratio, KHR_lights_punctual, the KHR material extensions mapped by abrdf_pbr_lobes. */
#include <math.h>
#include <string.h>

#include "gltf.h"
#include "test_util.h"

#define SEEDS FUZZ_CORPUS "/gltf/"
#define TEST_PI 3.14159265358979323846

static void read_seed(const char *name, scene *s)
{
    char err[512];
    char path[1024];
    snprintf(path, sizeof path, SEEDS "%s", name);
    ck_assert_msg(gltf_read_file(path, s, err, sizeof err) == 0, "%s", err);
}

static int mat_by_name(const scene *s, const char *name)
{
    for (int i = 0; i < s->material_count; ++i)
        if (!strcmp(s->materials[i].name, name)) return i;
    return -1;
}

START_TEST(strip_textures_hierarchy_defaults)
{
    scene s;
    read_seed("strip.gltf", &s);
    ck_assert_int_eq(s.object_count, 2);
    /* the textured material: one embedded PNG read by three maps */
    int mi = mat_by_name(&s, "material_0");
    ck_assert_int_ge(mi, 0);
    const scene_material *m = &s.materials[mi];
    ck_assert(m->pbr && m->textured && m->kind == SCENE_MAT_MODELS);
    const scene_map *bc = &m->maps[SCENE_MAP_BASE_COLOR];
    ck_assert_ptr_nonnull(bc->blob);
    ck_assert(bc->blob_size > 8 && !memcmp(bc->blob, "\x89PNG", 4));
    ck_assert_str_eq(bc->mime, "image/png");
    ck_assert(strstr(bc->path, "strip.gltf#image/0") != NULL);
    ck_assert(bc->srgb && bc->uv_set == 0);
    ck_assert(bc->offset[0] == 0.5 && bc->offset[1] == 0 && bc->scale[0] == 2 &&
              bc->scale[1] == 2 && bc->rotation == 0.3);
    ck_assert_ptr_nonnull(m->maps[SCENE_MAP_METALLIC].blob);
    ck_assert_ptr_nonnull(m->maps[SCENE_MAP_ROUGHNESS].blob);
    ck_assert_int_eq(m->maps[SCENE_MAP_METALLIC].channel, 2);
    ck_assert_int_eq(m->maps[SCENE_MAP_ROUGHNESS].channel, 1);
    ck_assert(m->maps[SCENE_MAP_NORMAL].strength == 0.5);
    ck_assert_ptr_null(m->maps[SCENE_MAP_OCCLUSION].path);
    /* the strip: two triangles with uv, moved by its node's matrix (x + 0.5) */
    const scene_object *strip = &s.objects[0], *fan = &s.objects[1];
    ck_assert_int_eq(strip->material, mi);
    const mesh *ms = s.meshes[strip->mesh];
    ck_assert(ms->in_memory && ms->triangle_count == 2 && ms->uv && ms->uv_count == 4);
    ck_assert(ms->uv_origin_top && ms->uv[2 * 3 + 1] == 1); /* as the file has it */
    ck_assert(ms->position[0] == 0.5f && ms->position[3] == 1.5f);
    ck_assert(strstr(ms->path, "strip.gltf#node/1/mesh/0/primitive/0") != NULL);
    /* strip triangles (0 1 2) and (2 1 3): both face +z (computed normals) */
    for (int k = 0; k < ms->normal_count; ++k) ck_assert(ms->normal[3 * k + 2] > 0.999f);
    /* the fan: the child at x + 2 + 0.5, mirrored in y (the winding turned: still +z) */
    const mesh *mf = s.meshes[fan->mesh];
    ck_assert_str_eq(s.materials[fan->material].name, "gltf_default");
    ck_assert(s.materials[fan->material].pbr_in.metallic == 1 &&
              s.materials[fan->material].pbr_in.roughness == 1);
    ck_assert(mf->triangle_count == 2 && mf->position[0] == 2.5f && mf->position[3 * 2 + 1] == -1);
    for (int k = 0; k < mf->normal_count; ++k) ck_assert(mf->normal[3 * k + 2] > 0.999f);
    for (int o = 0; o < 2; ++o)
        ck_assert(s.objects[o].scale[0] == 1 && s.objects[o].translate[0] == 0);
    /* defaults, stated in the notes */
    ck_assert_ptr_nonnull(s.notes);
    ck_assert(strstr(s.notes, "no camera") && strstr(s.notes, "no light"));
    ck_assert_int_eq(s.light_count, 1);
    ck_assert(s.lights[0].kind == SCENE_LIGHT_DIRECTIONAL && s.camera.fov_deg == 40);
    scene_free(&s);
}
END_TEST

START_TEST(cube_camera_lights_extensions)
{
    scene s;
    read_seed("cube.glb", &s);
    ck_assert_int_eq(s.camera.height, 512);
    ck_assert_int_eq(s.camera.width, 768); /* aspectRatio 1.5 */
    ck_assert(fabs(s.camera.fov_deg - 0.7 * 180 / TEST_PI) < 1e-12);
    ck_assert(s.camera.position[1] == 0.5 && s.camera.position[2] == 4);
    ck_assert(s.camera.look_at[2] < s.camera.position[2]); /* looking down -z */
    ck_assert_int_eq(s.light_count, 2);
    ck_assert(s.lights[0].kind == SCENE_LIGHT_POINT && s.lights[0].intensity == 20);
    ck_assert(s.lights[0].position[0] == 2 && s.lights[0].position[1] == 3);
    /* rotated -45 degrees about x: its +z (toward the light) is (0, sin 45, cos 45) */
    ck_assert(s.lights[1].kind == SCENE_LIGHT_DIRECTIONAL && s.lights[1].color[1] == 0.5);
    ck_assert(fabs(s.lights[1].direction[1] - sqrt(0.5)) < 1e-4 &&
              fabs(s.lights[1].direction[2] - sqrt(0.5)) < 1e-4);
    const scene_material *m = &s.materials[s.objects[0].material];
    ck_assert(m->pbr_in.ior == 1.4 && m->pbr_in.specular == 0.7 && m->pbr_in.clearcoat == 0.5);
    ck_assert(m->pbr_in.metallic == 0 && m->pbr_in.roughness == 0.5);
    /* the lobes and parameters are abrdf_pbr_lobes' */
    abrdf_model lobes[2];
    int n;
    abrdf_params p;
    abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
    ck_assert_int_eq(abrdf_pbr_lobes(&m->pbr_in, lobes, &n, &p), ABRDF_OK);
    ck_assert(n == m->lobe_count && lobes[0] == m->lobes[0] && lobes[1] == m->lobes[1]);
    ck_assert(!memcmp(&p, &m->params, sizeof p));
    ck_assert(strstr(s.notes, "clearcoat and sheen have no lobe") != NULL);
    scene_free(&s);
}
END_TEST

START_TEST(refusals_name_the_file)
{
    scene s;
    char err[512];
    ck_assert_int_eq(gltf_read_file(SEEDS "ortho.gltf", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "ortho.gltf: camera 0 is orthographic") != NULL, "%s", err);
    ck_assert_int_eq(gltf_read_file(SEEDS "bad_index.gltf", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "bad_index.gltf: mesh 0 primitive 0: index 7") != NULL, "%s", err);
    ck_assert_int_eq(gltf_read_file(SEEDS "cut.glb", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "cut.glb: ") != NULL && !strchr(err, '\n'), "%s", err);
    ck_assert_int_eq(gltf_read_file(SEEDS "absent.glb", &s, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "absent.glb") != NULL, "%s", err);
    ck_assert_int_eq(
        gltf_read_memory("x.gltf", (const unsigned char *)"{}", 2, &s, err, sizeof err), -1);
    ck_assert_msg(!strncmp(err, "x.gltf: ", 8), "%s", err);
}
END_TEST

int main(void)
{
    Suite *s = suite_create("gltf");
    TCase *tc = tcase_create("read");
    tcase_add_test(tc, strip_textures_hierarchy_defaults);
    tcase_add_test(tc, cube_camera_lights_extensions);
    tcase_add_test(tc, refusals_name_the_file);
    suite_add_tcase(s, tc);
    return tu_run(s);
}
