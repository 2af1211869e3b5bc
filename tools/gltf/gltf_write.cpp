// gltf_write.cpp - gltf_write_memory (gltf.h): a parsed scene as a glTF 2.0 model, serialised
// by tinygltf. What other viewers need is glTF proper (meshes, metallic-roughness materials
// with their KHR extensions, a perspective camera, KHR_lights_punctual); what only abrdf
// reads back exactly rides in `extras.abrdf` (gltf_extras.h): an analytic shape and its
// transform on its node, explicit models and their parameters on their material, the
// resolution and ambient light on the scene.
#include "gltf.h"
#include "gltf_extras.h"

#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cctype>
#include <strings.h>
#include <exception>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace
{

using tinygltf::Value;

struct write_fail {
    std::string msg;
};

[[noreturn]] void fail(const std::string &msg) { throw write_fail{msg}; }

Value vec(const double *v, int n)
{
    Value::Array a;
    for (int i = 0; i < n; ++i) a.push_back(Value(v[i]));
    return Value(a);
}

struct writer {
    const scene *s;
    tinygltf::Model m;
    std::vector<unsigned char> bin;
    FILE *warn;

    // A float accessor over new bytes of the buffer (min/max for POSITION).
    int floats(const std::vector<float> &v, int ncomp, bool bounds)
    {
        while (bin.size() % 4) bin.push_back(0);
        size_t off = bin.size();
        bin.resize(off + v.size() * 4);
        memcpy(bin.data() + off, v.data(), v.size() * 4);
        tinygltf::BufferView bv;
        bv.buffer = 0;
        bv.byteOffset = off;
        bv.byteLength = v.size() * 4;
        bv.target = TINYGLTF_TARGET_ARRAY_BUFFER;
        m.bufferViews.push_back(bv);
        tinygltf::Accessor a;
        a.bufferView = (int)m.bufferViews.size() - 1;
        a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
        a.count = v.size() / (size_t)ncomp;
        a.type = ncomp == 2 ? TINYGLTF_TYPE_VEC2 : TINYGLTF_TYPE_VEC3;
        if (bounds) {
            a.minValues.assign(3, INFINITY), a.maxValues.assign(3, -INFINITY);
            for (size_t i = 0; i < v.size(); ++i) {
                a.minValues[i % 3] = std::fmin(a.minValues[i % 3], v[i]);
                a.maxValues[i % 3] = std::fmax(a.maxValues[i % 3], v[i]);
            }
        }
        m.accessors.push_back(a);
        return (int)m.accessors.size() - 1;
    }

    // A mesh of corner-expanded triangles (positions, normals, uv per corner: the scene's
    // separate index lists become glTF's one).
    int add_mesh(const std::vector<float> &pos, const std::vector<float> &nrm,
                 const std::vector<float> &uv, int material)
    {
        tinygltf::Primitive p;
        p.mode = TINYGLTF_MODE_TRIANGLES;
        p.material = material;
        p.attributes["POSITION"] = floats(pos, 3, true);
        p.attributes["NORMAL"] = floats(nrm, 3, false);
        if (!uv.empty()) p.attributes["TEXCOORD_0"] = floats(uv, 2, false);
        tinygltf::Mesh me;
        me.primitives.push_back(p);
        m.meshes.push_back(me);
        return (int)m.meshes.size() - 1;
    }

    int scene_mesh(const mesh *me, int smooth, int material)
    {
        std::vector<float> pos, nrm, uv;
        for (int t = 0; t < me->triangle_count; ++t) {
            const int *c = me->tri + 3 * t;
            double fn[3] = {0, 0, 1};
            if (!smooth) { // flat: the face's normal at every corner
                const float *a = me->position + 3 * c[0], *b = me->position + 3 * c[1],
                            *d = me->position + 3 * c[2];
                double e1[3], e2[3];
                for (int k = 0; k < 3; ++k) e1[k] = b[k] - a[k], e2[k] = d[k] - a[k];
                fn[0] = e1[1] * e2[2] - e1[2] * e2[1];
                fn[1] = e1[2] * e2[0] - e1[0] * e2[2];
                fn[2] = e1[0] * e2[1] - e1[1] * e2[0];
                double l = std::sqrt(fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2]);
                if (l > 0)
                    for (double &x : fn) x /= l;
                else
                    fn[0] = 0, fn[1] = 0, fn[2] = 1;
            }
            for (int k = 0; k < 3; ++k) {
                for (int a = 0; a < 3; ++a) {
                    pos.push_back(me->position[3 * c[k] + a]);
                    nrm.push_back(smooth ? me->normal[3 * me->tri_normal[3 * t + k] + a]
                                         : (float)fn[a]);
                }
                if (me->uv) { // glTF's v runs down the image (mesh.h, uv_origin_top)
                    const float *q = me->uv + 2 * me->tri_uv[3 * t + k];
                    uv.push_back(q[0]);
                    uv.push_back(me->uv_origin_top ? q[1] : 1 - q[1]);
                }
            }
        }
        return add_mesh(pos, nrm, uv, material);
    }

    // ---- analytic shapes, tessellated for other viewers ----

    static void push3(std::vector<float> &v, double x, double y, double z)
    {
        v.push_back((float)x), v.push_back((float)y), v.push_back((float)z);
    }

    // A sphere or a capsule (the halves moved apart by h) of radius r: rings of latitude.
    int round_shape(double r, double h, int material)
    {
        const int nu = 48, nv = 24;
        std::vector<float> pos, nrm, none;
        auto corner = [&](int i, int j, bool upper) {
            double th = M_PI * i / nv, ph = 2 * M_PI * j / nu;
            double n[3] = {std::sin(th) * std::cos(ph), std::cos(th), -std::sin(th) * std::sin(ph)};
            push3(pos, r * n[0], r * n[1] + (upper ? 0.5 : -0.5) * h, r * n[2]);
            push3(nrm, n[0], n[1], n[2]);
        };
        for (int i = 0; i < nv; ++i)
            for (int j = 0; j < nu; ++j) {
                bool up = i < nv / 2;
                corner(i, j, up), corner(i + 1, j, up), corner(i + 1, j + 1, up);
                corner(i, j, up), corner(i + 1, j + 1, up), corner(i, j + 1, up);
            }
        if (h > 0) // the capsule's side: a cylinder between the halves
            for (int j = 0; j < nu; ++j) {
                double p0 = 2 * M_PI * j / nu, p1 = 2 * M_PI * (j + 1) / nu;
                double x0 = std::cos(p0), z0 = -std::sin(p0), x1 = std::cos(p1), z1 = -std::sin(p1);
                double q[6][3] = {{x0, 0.5, z0}, {x0, -0.5, z0}, {x1, -0.5, z1},
                                  {x0, 0.5, z0}, {x1, -0.5, z1}, {x1, 0.5, z1}};
                for (auto &c : q) {
                    push3(pos, r * c[0], h * c[1], r * c[2]);
                    push3(nrm, c[0], 0, c[2]);
                }
            }
        return add_mesh(pos, nrm, none, material);
    }

    int cylinder(double r, double h, int material)
    {
        const int nu = 48;
        std::vector<float> pos, nrm, none;
        for (int j = 0; j < nu; ++j) {
            double p0 = 2 * M_PI * j / nu, p1 = 2 * M_PI * (j + 1) / nu;
            double x0 = std::cos(p0), z0 = -std::sin(p0), x1 = std::cos(p1), z1 = -std::sin(p1);
            double q[6][3] = {{x0, 0.5, z0}, {x0, -0.5, z0}, {x1, -0.5, z1},
                              {x0, 0.5, z0}, {x1, -0.5, z1}, {x1, 0.5, z1}};
            for (auto &c : q) {
                push3(pos, r * c[0], h * c[1], r * c[2]);
                push3(nrm, c[0], 0, c[2]);
            }
            for (int cap = 0; cap < 2; ++cap) { // top (+y), then bottom (-y)
                double y = cap ? -0.5 * h : 0.5 * h, ny = cap ? -1 : 1;
                double t[3][2] = {{0, 0}, {x0, z0}, {x1, z1}};
                int order[3] = {0, cap ? 2 : 1, cap ? 1 : 2};
                for (int k : order) {
                    push3(pos, r * t[k][0], y, r * t[k][1]);
                    push3(nrm, 0, ny, 0);
                }
            }
        }
        return add_mesh(pos, nrm, none, material);
    }

    int box(const double size[3], int material)
    {
        std::vector<float> pos, nrm, none;
        for (int axis = 0; axis < 3; ++axis)
            for (int sign = 1; sign >= -1; sign -= 2) {
                double n[3] = {0, 0, 0}, u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
                n[axis] = sign, u[(axis + 1) % 3] = 1, v[(axis + 2) % 3] = 1;
                double q[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
                int tri[6] = {0, 1, 2, 0, 2, 3};
                if (sign < 0) tri[1] = 2, tri[2] = 1, tri[4] = 3, tri[5] = 2;
                for (int k : tri) {
                    double p[3];
                    for (int a = 0; a < 3; ++a)
                        p[a] = 0.5 * size[a] * (n[a] + q[k][0] * u[a] + q[k][1] * v[a]);
                    push3(pos, p[0], p[1], p[2]);
                    push3(nrm, n[0], n[1], n[2]);
                }
            }
        return add_mesh(pos, nrm, none, material);
    }

    // ---- transforms ----

    // The object's T * Rz * Ry * Rx * S (scene.h) as a column-major matrix.
    static std::vector<double> object_matrix(const scene_object *o)
    {
        double r[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
        for (int ax = 0; ax < 3; ++ax) { // x first: r = R_ax * r
            double c = std::cos(o->rotate_deg[ax] * M_PI / 180),
                   sn = std::sin(o->rotate_deg[ax] * M_PI / 180);
            double q[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
            int a = (ax + 1) % 3, b = (ax + 2) % 3;
            q[ax][ax] = 1, q[a][a] = c, q[a][b] = -sn, q[b][a] = sn, q[b][b] = c;
            double t[3][3];
            for (int i = 0; i < 3; ++i)
                for (int j = 0; j < 3; ++j)
                    t[i][j] = q[i][0] * r[0][j] + q[i][1] * r[1][j] + q[i][2] * r[2][j];
            memcpy(r, t, sizeof r);
        }
        std::vector<double> mm(16, 0.0);
        for (int col = 0; col < 3; ++col)
            for (int row = 0; row < 3; ++row)
                mm[(size_t)(col * 4 + row)] = r[row][col] * o->scale[col];
        for (int row = 0; row < 3; ++row) mm[(size_t)(12 + row)] = o->translate[row];
        mm[15] = 1;
        return mm;
    }

    // A node whose local -z is `forward` and +y is in the plane of `up` (camera, light).
    static std::vector<double> frame_matrix(const double pos[3], const double forward[3],
                                            const double up[3])
    {
        double z[3] = {-forward[0], -forward[1], -forward[2]}, x[3], y[3];
        double l = std::sqrt(z[0] * z[0] + z[1] * z[1] + z[2] * z[2]);
        for (double &c : z) c /= l;
        x[0] = up[1] * z[2] - up[2] * z[1], x[1] = up[2] * z[0] - up[0] * z[2],
        x[2] = up[0] * z[1] - up[1] * z[0];
        l = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(l > 1e-12)) { // up parallel to the axis: any perpendicular
            double a[3] = {std::fabs(z[0]) < 0.9 ? 1.0 : 0.0, std::fabs(z[0]) < 0.9 ? 0.0 : 1.0, 0};
            x[0] = a[1] * z[2] - a[2] * z[1], x[1] = a[2] * z[0] - a[0] * z[2],
            x[2] = a[0] * z[1] - a[1] * z[0];
            l = std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        }
        for (double &c : x) c /= l;
        y[0] = z[1] * x[2] - z[2] * x[1], y[1] = z[2] * x[0] - z[0] * x[2],
        y[2] = z[0] * x[1] - z[1] * x[0];
        return {x[0], x[1], x[2], 0, y[0],   y[1],   y[2],   0,
                z[0], z[1], z[2], 0, pos[0], pos[1], pos[2], 1};
    }

    // ---- materials ----

    // ---- textures ----

    std::string out_dir; // the output's directory, resolved ("" if unknown)
    std::vector<std::pair<const scene_map *, int>> image_of; // map -> glTF image

    // A URI for file `path` relative to the output's directory (percent-encoded), so the
    // output and the image may move together.
    std::string uri_for(const char *path) const
    {
        char *abs = realpath(path, nullptr);
        std::string a = abs ? abs : path, rel;
        free(abs);
        if (!out_dir.empty() && a[0] == '/') { // out_dir: absolute, ending in '/'
            size_t common = 0;                 // the shared directories, through their last '/'
            for (size_t k = 0; k < a.size() && k < out_dir.size() && a[k] == out_dir[k]; ++k)
                if (a[k] == '/') common = k + 1;
            for (size_t k = common; k < out_dir.size(); ++k)
                if (out_dir[k] == '/') rel += "../";
            a = rel + a.substr(common);
        }
        std::string u;
        for (unsigned char c : a) {
            if (isalnum(c) || strchr("-._~/", c)) {
                u += (char)c;
            } else {
                char h[4];
                snprintf(h, sizeof h, "%%%02X", c);
                u += h;
            }
        }
        return u;
    }

    // The glTF texture of map mp: its image once per file or blob (a blob into the buffer).
    int texture(const scene_map *mp)
    {
        for (const auto &e : image_of)
            if ((mp->blob && e.first->blob && e.first->blob_size == mp->blob_size &&
                 !memcmp(e.first->blob, mp->blob, mp->blob_size)) ||
                (!mp->blob && !e.first->blob && !strcmp(e.first->path, mp->path)))
                return e.second;
        tinygltf::Image im;
        if (mp->blob) {
            while (bin.size() % 4) bin.push_back(0);
            tinygltf::BufferView bv;
            bv.buffer = 0;
            bv.byteOffset = bin.size();
            bv.byteLength = mp->blob_size;
            bin.insert(bin.end(), mp->blob, mp->blob + mp->blob_size);
            m.bufferViews.push_back(bv);
            im.bufferView = (int)m.bufferViews.size() - 1;
            im.mimeType = mp->mime[0] ? mp->mime : "image/png";
        } else {
            im.uri = uri_for(mp->path);
        }
        m.images.push_back(im);
        tinygltf::Texture t;
        t.source = (int)m.images.size() - 1;
        m.textures.push_back(t);
        image_of.emplace_back(mp, (int)m.textures.size() - 1);
        return (int)m.textures.size() - 1;
    }

    void transform(const scene_map *mp, tinygltf::ExtensionMap &e)
    {
        if (mp->offset[0] == 0 && mp->offset[1] == 0 && mp->scale[0] == 1 && mp->scale[1] == 1 &&
            mp->rotation == 0)
            return;
        Value::Object t;
        t["offset"] = vec(mp->offset, 2);
        t["scale"] = vec(mp->scale, 2);
        t["rotation"] = Value(mp->rotation);
        e["KHR_texture_transform"] = Value(t);
        if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), "KHR_texture_transform") ==
            m.extensionsUsed.end())
            m.extensionsUsed.push_back("KHR_texture_transform");
    }

    void skipped(const scene_material &sm, const char *why)
    {
        if (warn) fprintf(warn, "abrdf export: material '%s': %s\n", sm.name, why);
    }

    // A pbr material's maps as glTF textures (the mesh's uv is written as TEXCOORD_0).
    void maps(const scene_material &sm, tinygltf::Material &gm)
    {
        const scene_map *mp = sm.maps;
        tinygltf::PbrMetallicRoughness &pm = gm.pbrMetallicRoughness;
        if (mp[SCENE_MAP_BASE_COLOR].path) {
            if (!mp[SCENE_MAP_BASE_COLOR].srgb)
                skipped(sm, "base_color_srgb=off has no glTF form (the map is written as sRGB)");
            pm.baseColorTexture.index = texture(&mp[SCENE_MAP_BASE_COLOR]);
            transform(&mp[SCENE_MAP_BASE_COLOR], pm.baseColorTexture.extensions);
        }
        const scene_map *me = &mp[SCENE_MAP_METALLIC], *ro = &mp[SCENE_MAP_ROUGHNESS];
        if (me->path || ro->path) {
            // glTF has one file: metallic in blue, roughness in green
            bool one = me->path && ro->path && !strcmp(me->path, ro->path) &&
                       me->blob_size == ro->blob_size && me->channel == 2 && ro->channel == 1;
            if (one) {
                pm.metallicRoughnessTexture.index = texture(me);
                transform(me, pm.metallicRoughnessTexture.extensions);
            } else {
                skipped(sm, "metallic and roughness maps that are not one file's blue and green "
                            "channels have no glTF form (not written)");
            }
        }
        if (mp[SCENE_MAP_OCCLUSION].path) {
            if (mp[SCENE_MAP_OCCLUSION].channel != 0) {
                skipped(sm, "an occlusion map not in the red channel has no glTF form (not "
                            "written)");
            } else {
                gm.occlusionTexture.index = texture(&mp[SCENE_MAP_OCCLUSION]);
                gm.occlusionTexture.strength = mp[SCENE_MAP_OCCLUSION].strength;
                transform(&mp[SCENE_MAP_OCCLUSION], gm.occlusionTexture.extensions);
            }
        }
        if (mp[SCENE_MAP_NORMAL].path) {
            gm.normalTexture.index = texture(&mp[SCENE_MAP_NORMAL]);
            gm.normalTexture.scale = mp[SCENE_MAP_NORMAL].strength;
            transform(&mp[SCENE_MAP_NORMAL], gm.normalTexture.extensions);
        }
    }

    int material(int i)
    {
        const scene_material &sm = s->materials[i];
        tinygltf::Material gm;
        gm.name = sm.name;
        Value::Object ab;
        if (sm.kind != SCENE_MAT_MODELS)
            fail(std::string("material '") + sm.name +
                 "': a table= or adaptive material is written once chosen (abrdf export --gltf "
                 "chooses it as abrdf render does)");
        for (int l = 0; l < sm.lobe_count; ++l)
            if (sm.lobes[l] == ABRDF_MEASURED)
                fail(std::string("material '") + sm.name + "': a measured table has no glTF form");
        const abrdf_pbr *q = &sm.pbr_in;
        abrdf_pbr near;
        bool chosen = false; // a pbr material whose models the selection chose
        if (sm.pbr) {
            near = *q;
            abrdf_model lobes[ABRDF_PBR_MAX_LOBES];
            int count = 0;
            abrdf_params p;
            abrdf_params_init(ABRDF_DISNEY_SPECULAR, &p);
            chosen = abrdf_pbr_lobes(q, lobes, &count, &p) != ABRDF_OK || count != sm.lobe_count ||
                     memcmp(lobes, sm.lobes, (size_t)count * sizeof *lobes) ||
                     memcmp(&p, &sm.params, sizeof p);
            if (chosen) gltf_extras_models(&sm, ab); // the factors for viewers, models for abrdf
        } else {
            // the closest metallic-roughness material for other viewers; abrdf reads extras
            abrdf_pbr_init(&near);
            near.metallic = 0;
            for (int c = 0; c < 3; ++c)
                near.base_color[c] = std::fmin(1, std::fmax(0, sm.params.kd[c]));
            near.roughness = std::fmin(1, std::fmax(0, sm.params.r));
            gltf_extras_models(&sm, ab);
        }
        if (sm.ka_given || !sm.pbr || chosen) ab["ka"] = vec(sm.ka, 3);
        tinygltf::PbrMetallicRoughness &pm = gm.pbrMetallicRoughness;
        pm.baseColorFactor = {near.base_color[0], near.base_color[1], near.base_color[2], 1.0};
        pm.metallicFactor = near.metallic;
        pm.roughnessFactor = near.roughness;
        auto ext = [&](const char *name, Value::Object o) {
            gm.extensions[name] = Value(o);
            if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), name) ==
                m.extensionsUsed.end())
                m.extensionsUsed.push_back(name);
        };
        if (near.ior != 1.5) ext("KHR_materials_ior", {{"ior", Value(near.ior)}});
        if (near.specular != 1 || near.specular_color[0] != 1 || near.specular_color[1] != 1 ||
            near.specular_color[2] != 1)
            ext("KHR_materials_specular", {{"specularFactor", Value(near.specular)},
                                           {"specularColorFactor", vec(near.specular_color, 3)}});
        if (near.clearcoat > 0)
            ext("KHR_materials_clearcoat",
                {{"clearcoatFactor", Value(near.clearcoat)},
                 {"clearcoatRoughnessFactor", Value(near.clearcoat_roughness)}});
        if (near.sheen_color[0] > 0 || near.sheen_color[1] > 0 || near.sheen_color[2] > 0)
            ext("KHR_materials_sheen", {{"sheenColorFactor", vec(near.sheen_color, 3)},
                                        {"sheenRoughnessFactor", Value(near.sheen_roughness)}});
        if (near.anisotropy > 0 || near.anisotropy_rotation != 0)
            ext("KHR_materials_anisotropy",
                {{"anisotropyStrength", Value(near.anisotropy)},
                 {"anisotropyRotation", Value(near.anisotropy_rotation)}});
        if (near.transmission > 0)
            ext("KHR_materials_transmission", {{"transmissionFactor", Value(near.transmission)}});
        if (sm.pbr) maps(sm, gm);
        if (!ab.empty()) {
            Value::Object extras;
            extras["abrdf"] = Value(ab);
            gm.extras = Value(extras);
        }
        m.materials.push_back(gm);
        return (int)m.materials.size() - 1;
    }

    // ---- the scene ----

    void write()
    {
        m.asset.version = "2.0";
        m.asset.generator = "abrdf";
        for (int i = 0; i < s->material_count; ++i) material(i);
        tinygltf::Scene sc;
        for (int i = 0; i < s->object_count; ++i) {
            const scene_object *o = &s->objects[i];
            tinygltf::Node n;
            n.name = std::string(scene_shape_name(o->shape)) + " " + std::to_string(i);
            switch (o->shape) {
            case SCENE_SPHERE: n.mesh = round_shape(o->radius, 0, o->material); break;
            case SCENE_CAPSULE: n.mesh = round_shape(o->radius, o->height, o->material); break;
            case SCENE_CYLINDER: n.mesh = cylinder(o->radius, o->height, o->material); break;
            case SCENE_BOX: n.mesh = box(o->size, o->material); break;
            default: n.mesh = scene_mesh(o->mesh_data, o->smooth, o->material); break;
            }
            n.matrix = object_matrix(o);
            Value::Object ab;
            gltf_extras_object(o, ab);
            Value::Object extras;
            extras["abrdf"] = Value(ab);
            n.extras = Value(extras);
            m.nodes.push_back(n);
            sc.nodes.push_back((int)m.nodes.size() - 1);
        }
        // camera
        const scene_camera *c = &s->camera;
        tinygltf::Camera cam;
        cam.type = "perspective";
        cam.perspective.yfov = c->fov_deg * M_PI / 180;
        cam.perspective.aspectRatio = (double)c->width / c->height;
        cam.perspective.znear = 1e-3;
        m.cameras.push_back(cam);
        tinygltf::Node cn;
        cn.name = "camera";
        cn.camera = 0;
        double f[3] = {c->look_at[0] - c->position[0], c->look_at[1] - c->position[1],
                       c->look_at[2] - c->position[2]};
        cn.matrix = frame_matrix(c->position, f, c->up);
        m.nodes.push_back(cn);
        sc.nodes.push_back((int)m.nodes.size() - 1);
        // lights
        for (int i = 0; i < s->light_count; ++i) {
            const scene_light *l = &s->lights[i];
            tinygltf::Light gl;
            gl.color = {l->color[0], l->color[1], l->color[2]};
            gl.intensity = l->intensity;
            tinygltf::Node ln;
            ln.name = "light " + std::to_string(i);
            double up[3] = {0, 1, 0};
            if (l->kind == SCENE_LIGHT_POINT) {
                gl.type = "point";
                ln.translation = {l->position[0], l->position[1], l->position[2]};
            } else if (l->kind == SCENE_LIGHT_DIRECTIONAL) {
                gl.type = "directional";
                double o[3] = {0, 0, 0},
                       fwd[3] = {-l->direction[0], -l->direction[1], -l->direction[2]};
                ln.matrix = frame_matrix(o, fwd, up);
            } else {
                fail("light " + std::to_string(i) +
                     ": glTF has point and directional lights only (KHR_lights_punctual), not "
                     "area or environment lights");
            }
            m.lights.push_back(gl);
            Value::Object lp;
            lp["light"] = Value((int)m.lights.size() - 1);
            ln.extensions["KHR_lights_punctual"] = Value(lp);
            m.nodes.push_back(ln);
            sc.nodes.push_back((int)m.nodes.size() - 1);
        }
        if (!m.lights.empty()) m.extensionsUsed.push_back("KHR_lights_punctual");
        Value::Object ab;
        gltf_extras_scene_write(s, ab);
        Value::Object extras;
        extras["abrdf"] = Value(ab);
        sc.extras = Value(extras);
        m.scenes.push_back(sc);
        m.defaultScene = 0;
        tinygltf::Buffer b;
        b.data = bin;
        m.buffers.push_back(b);
    }
};

} // namespace

// A write callback that writes nothing: an image keeps the uri set above.
bool keep_uri(const std::string *, const std::string *, const tinygltf::Image *, bool,
              std::string *, void *)
{
    return false;
}

extern "C" int gltf_write_memory(const scene *s, const char *out_path, FILE *warn,
                                 unsigned char **bytes, size_t *size, char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    *bytes = nullptr;
    *size = 0;
    try {
        const char *dot = strrchr(out_path, '.'), *slash = strrchr(out_path, '/');
        int binary = dot && (!slash || dot > slash) && !strcasecmp(dot, ".glb");
        writer w;
        w.s = s;
        w.warn = warn;
        std::string dir = slash ? std::string(out_path, (size_t)(slash - out_path) + 1) : "./";
        char *d = realpath(dir.c_str(), nullptr);
        if (d) w.out_dir = std::string(d) + (strcmp(d, "/") ? "/" : ""), free(d);
        w.write();
        // .gltf: tinygltf writes the buffer as a data: URI; .glb: as the BIN chunk
        tinygltf::TinyGLTF t;
        t.SetImageWriter(keep_uri, nullptr);
        std::ostringstream os;
        if (!t.WriteGltfSceneToStream(&w.m, os, !binary, binary != 0))
            fail("tinygltf could not serialise the model");
        std::string out = os.str();
        *bytes = static_cast<unsigned char *>(malloc(out.size() ? out.size() : 1));
        if (!*bytes) throw std::bad_alloc();
        memcpy(*bytes, out.data(), out.size());
        *size = out.size();
        return 0;
    } catch (const write_fail &f) {
        if (err && err_size) snprintf(err, err_size, "%s", f.msg.c_str());
    } catch (const std::bad_alloc &) {
        if (err && err_size) snprintf(err, err_size, "out of memory");
    } catch (const std::exception &e) {
        if (err && err_size) snprintf(err, err_size, "%s", e.what());
    }
    return -1;
}
