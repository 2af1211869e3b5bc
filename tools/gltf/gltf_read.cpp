// gltf_read.cpp - gltf_read_file / gltf_read_memory (gltf.h): tinygltf parses the JSON (or the
// GLB container) and loads the buffers; everything it hands over is checked here before use -
// indices of every object, accessor and buffer-view ranges, strides, types, counts, index
// bounds, finite numbers - so a malformed file is one line naming the file, never a crash
// (tests/fuzz/fuzz_gltf.c). Failures inside are thrown as gltf_fail and caught at the entry.
#include "gltf.h"
#include "gltf_extras.h"

#include <tiny_gltf.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "in_file.h"
#include "path_msg.h"
}

namespace
{

// Node hierarchies are walked recursively: a depth far above any real file's keeps the stack
// small.
#define GLTF_MAX_DEPTH 1000

struct gltf_fail {
    std::string msg;
};

[[noreturn]] void fail(const std::string &msg) { throw gltf_fail{msg}; }

std::string num(double v)
{
    char b[32];
    snprintf(b, sizeof b, "%g", v);
    return b;
}

// ---- files through tinygltf's callbacks: size-limited, no shell expansion --------------------

bool file_exists(const std::string &path, void *)
{
    char err[16];
    return in_file_check(path.c_str(), err, sizeof err) == 0;
}

std::string expand_path(const std::string &path, void *) { return path; }

// user: the bytes read so far by this load (size_t), all files together (GLTF_MAX_FILES_TOTAL)
bool read_whole(std::vector<unsigned char> *out, std::string *err, const std::string &path,
                void *user)
{
    char msg[512];
    FILE *f = in_file_open(path.c_str(), msg, sizeof msg);
    if (!f) {
        if (err) *err += std::string(msg) + "\n";
        return false;
    }
    out->clear();
    unsigned char buf[65536];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, f)) > 0) {
        if (out->size() + got > GLTF_MAX_FILE) {
            fclose(f);
            if (err) *err += path + ": larger than " + num((double)GLTF_MAX_FILE) + " bytes\n";
            return false;
        }
        out->insert(out->end(), buf, buf + got);
        if (user) {
            size_t *total = static_cast<size_t *>(user);
            *total += got;
            if (*total > GLTF_MAX_FILES_TOTAL) {
                fclose(f);
                if (err)
                    *err += path + ": the files the glTF names hold more than " +
                            num((double)GLTF_MAX_FILES_TOTAL) + " bytes together\n";
                return false;
            }
        }
    }
    bool bad = ferror(f);
    fclose(f);
    if (bad && err) *err += path + ": read error\n";
    return !bad;
}

// The deepest nesting of arrays and objects in JSON text (strings skipped): tinygltf parses
// extras and extensions recursively, so a file nested thousands deep would exhaust the
// stack before any check of ours runs.
size_t json_depth(const unsigned char *p, size_t n)
{
    size_t depth = 0, most = 0;
    bool in_string = false;
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = p[i];
        if (in_string) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            most = std::max(most, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return most;
}

bool write_whole(std::string *err, const std::string &, const std::vector<unsigned char> &, void *)
{
    if (err) *err += "writing is not done while reading\n";
    return false;
}

// Images are not decoded here: an embedded one (no uri) keeps its bytes for the renderer's
// texture reader (scene_map.blob); a file is named by its path.
struct image_store {
    std::vector<std::vector<unsigned char>> bytes;
};

bool keep_image(tinygltf::Image *image, const int index, std::string *, std::string *, int, int,
                const unsigned char *data, int size, void *user)
{
    image_store *st = static_cast<image_store *>(user);
    if (index < 0 || size < 0) return false;
    if ((size_t)index >= st->bytes.size()) st->bytes.resize((size_t)index + 1);
    // A bufferView image is handed over without a check of its range against the buffer (a
    // hostile file reaches past it): its bytes are taken later, after the same range check
    // as an accessor's (texture()). Only a data: URI's decoded bytes are kept here.
    if (image->uri.empty() && image->bufferView < 0)
        st->bytes[(size_t)index].assign(data, data + size);
    return true;
}

// ---- JSON values (tinygltf::Value asserts on a wrong kind: every access checks first) ------

const tinygltf::Value *member(const tinygltf::Value &o, const char *key)
{
    if (!o.IsObject() || !o.Has(key)) return nullptr;
    return &o.Get(key);
}

// o[key] as a number in [lo, hi], or def if absent; what names it in messages.
double number(const tinygltf::Value &o, const char *key, double def, double lo, double hi,
              const std::string &what)
{
    const tinygltf::Value *v = member(o, key);
    if (!v) return def;
    if (!v->IsNumber()) fail(what + "." + key + " is not a number");
    double x = v->GetNumberAsDouble();
    if (!(x >= lo && x <= hi))
        fail(what + "." + key + " = " + num(x) + " is outside [" + num(lo) + ", " + num(hi) + "]");
    return x;
}

void numbers(const tinygltf::Value &o, const char *key, double *out, int n, double lo, double hi,
             const std::string &what)
{
    const tinygltf::Value *v = member(o, key);
    if (!v) return;
    if (!v->IsArray() || (int)v->ArrayLen() != n)
        fail(what + "." + key + " needs " + std::to_string(n) + " numbers");
    for (int i = 0; i < n; ++i) {
        const tinygltf::Value &e = v->Get(i);
        if (!e.IsNumber()) fail(what + "." + key + " needs numbers");
        double x = e.GetNumberAsDouble();
        if (!(x >= lo && x <= hi))
            fail(what + "." + key + "[" + std::to_string(i) + "] = " + num(x) + " is outside [" +
                 num(lo) + ", " + num(hi) + "]");
        out[i] = x;
    }
}

// ---- transforms: column-major 4x4 as glTF stores them ----------------------------------------

struct mat4 {
    double m[16]; // m[col * 4 + row]
};

mat4 identity()
{
    mat4 r{};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1;
    return r;
}

mat4 mul(const mat4 &a, const mat4 &b)
{
    mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a.m[k * 4 + row] * b.m[c * 4 + k];
            r.m[c * 4 + row] = s;
        }
    return r;
}

void apply_point(const mat4 &a, const double p[3], double out[3])
{
    for (int r = 0; r < 3; ++r)
        out[r] = a.m[r] * p[0] + a.m[4 + r] * p[1] + a.m[8 + r] * p[2] + a.m[12 + r];
}

void apply_dir(const mat4 &a, const double d[3], double out[3])
{
    for (int r = 0; r < 3; ++r) out[r] = a.m[r] * d[0] + a.m[4 + r] * d[1] + a.m[8 + r] * d[2];
}

double det3(const mat4 &a)
{
    const double *m = a.m;
    return m[0] * (m[5] * m[10] - m[9] * m[6]) - m[4] * (m[1] * m[10] - m[9] * m[2]) +
           m[8] * (m[1] * m[6] - m[5] * m[2]);
}

// Inverse transpose of the upper 3x3 (normals), up to the determinant's factor, which the
// normalisation after it removes: the cofactor matrix.
void cofactor3(const mat4 &a, double c[9])
{
    const double *m = a.m; // a(r, col) = m[col * 4 + r]
#define GLTF_A(r, k) m[(k)*4 + (r)]
    for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 3; ++k) {
            int r1 = (r + 1) % 3, r2 = (r + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
            c[r * 3 + k] = GLTF_A(r1, k1) * GLTF_A(r2, k2) - GLTF_A(r1, k2) * GLTF_A(r2, k1);
        }
#undef GLTF_A
}

void normalize(double v[3])
{
    double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0)
        for (int i = 0; i < 3; ++i) v[i] /= l;
}

// ---- the reader ------------------------------------------------------------------------------

struct reader {
    std::string name; // the file, for messages and mesh names
    std::string dir;  // its directory with the trailing '/', or ""
    const tinygltf::Model *m;
    image_store images;
    scene *s;
    std::string notes;
    std::vector<int> material_of; // glTF material -> scene material, -1 not made yet
    int default_material = -1;
    std::vector<char> node_seen;
    int camera_node = -1;
    mat4 camera_world;
    long long vertices = 0; // of every mesh, against SCENE_MAX_TRIANGLES * 3
    int mesh_cap = 0, object_cap = 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};

    void note(const std::string &line)
    {
        std::string l = line + "\n";
        if (notes.find(l) == std::string::npos) notes += l;
    }

    std::string where(const char *kind, size_t i) const
    {
        return std::string(kind) + " " + std::to_string(i);
    }

    // ---- accessors ----

    struct view {
        const unsigned char *base; // the first element
        size_t stride, count;
        int comp_type, ncomp;
        bool normalized;
    };

    static int comp_size(int t)
    {
        switch (t) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
        }
    }

    // Accessor idx of `ncomp` components (1 SCALAR, 2 VEC2, 3 VEC3), every byte it reads
    // inside its buffer view and the view inside its buffer.
    view accessor(int idx, int ncomp, const std::string &what) const
    {
        if (idx < 0 || (size_t)idx >= m->accessors.size())
            fail(what + ": accessor " + std::to_string(idx) + " does not exist (" +
                 std::to_string(m->accessors.size()) + " accessors)");
        const tinygltf::Accessor &a = m->accessors[(size_t)idx];
        std::string an = what + ": accessor " + std::to_string(idx);
        if (a.sparse.isSparse) fail(an + " is sparse (not supported)");
        int want = ncomp == 1   ? TINYGLTF_TYPE_SCALAR
                   : ncomp == 2 ? TINYGLTF_TYPE_VEC2
                                : TINYGLTF_TYPE_VEC3;
        if (a.type != want)
            fail(an + " has type " + std::to_string(a.type) + ", not " +
                 (ncomp == 1   ? "SCALAR"
                  : ncomp == 2 ? "VEC2"
                               : "VEC3"));
        int cs = comp_size(a.componentType);
        if (!cs) fail(an + ": unknown componentType " + std::to_string(a.componentType));
        if (a.count < 1 || a.count > (size_t)MESH_MAX_ELEMENTS)
            fail(an + ": count " + std::to_string(a.count) + " is outside [1, " +
                 std::to_string(MESH_MAX_ELEMENTS) + "]");
        if (a.bufferView < 0 || (size_t)a.bufferView >= m->bufferViews.size())
            fail(an + ": bufferView " + std::to_string(a.bufferView) + " does not exist");
        const tinygltf::BufferView &bv = m->bufferViews[(size_t)a.bufferView];
        std::string bn = an + ", bufferView " + std::to_string(a.bufferView);
        if (bv.buffer < 0 || (size_t)bv.buffer >= m->buffers.size())
            fail(bn + ": buffer " + std::to_string(bv.buffer) + " does not exist");
        size_t blen = m->buffers[(size_t)bv.buffer].data.size();
        if (bv.byteOffset > blen || bv.byteLength > blen - bv.byteOffset)
            fail(bn + ": bytes " + std::to_string(bv.byteOffset) + " + " +
                 std::to_string(bv.byteLength) + " reach past the buffer's " +
                 std::to_string(blen));
        size_t elem = (size_t)cs * (size_t)ncomp;
        size_t stride = bv.byteStride ? bv.byteStride : elem;
        if (bv.byteStride && (bv.byteStride < elem || bv.byteStride > 252 || bv.byteStride % 4))
            fail(bn + ": byteStride " + std::to_string(bv.byteStride) + " (a multiple of 4 in [" +
                 std::to_string(elem) + ", 252])");
        // count <= 2^26 and stride <= 252: no overflow in size_t
        if (a.byteOffset > bv.byteLength ||
            (a.count - 1) * stride + elem > bv.byteLength - a.byteOffset)
            fail(an + ": " + std::to_string(a.count) + " elements from byte " +
                 std::to_string(a.byteOffset) + " reach past its bufferView's " +
                 std::to_string(bv.byteLength) + " bytes");
        view v;
        v.base = m->buffers[(size_t)bv.buffer].data.data() + bv.byteOffset + a.byteOffset;
        v.stride = stride;
        v.count = a.count;
        v.comp_type = a.componentType;
        v.ncomp = ncomp;
        v.normalized = a.normalized;
        return v;
    }

    // Component c of element i as a double (normalized integers mapped as glTF says).
    static double get(const view &v, size_t i, int c)
    {
        const unsigned char *p = v.base + i * v.stride + (size_t)c * (size_t)comp_size(v.comp_type);
        switch (v.comp_type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return v.normalized ? p[0] / 255.0 : p[0];
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            double x = (signed char)p[0];
            return v.normalized ? std::fmax(x / 127.0, -1.0) : x;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            unsigned short u;
            memcpy(&u, p, 2);
            return v.normalized ? u / 65535.0 : u;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            short x;
            memcpy(&x, p, 2);
            return v.normalized ? std::fmax(x / 32767.0, -1.0) : x;
        }
        default: {
            unsigned int u;
            memcpy(&u, p, 4);
            return u;
        }
        }
    }

    // ---- materials ----

    // A texture reference into map k of material sm: the image file or its embedded bytes,
    // texCoord and KHR_texture_transform.
    void texture(const tinygltf::ExtensionMap &info_ext, int index, int tex_coord, scene_map *map,
                 const std::string &what)
    {
        if (index < 0 || (size_t)index >= m->textures.size())
            fail(what + ": texture " + std::to_string(index) + " does not exist");
        const tinygltf::Texture &t = m->textures[(size_t)index];
        if (t.source < 0) {
            note(what + ": texture " + std::to_string(index) +
                 " has no source image abrdf reads (left out)");
            return;
        }
        if ((size_t)t.source >= m->images.size())
            fail(what + ": texture " + std::to_string(index) + ": image " +
                 std::to_string(t.source) + " does not exist");
        if (tex_coord < 0 || tex_coord > 7)
            fail(what + ": texCoord " + std::to_string(tex_coord) + " is outside [0, 7]");
        map->uv_set = tex_coord;
        const tinygltf::Value *tt = ext(info_ext, "KHR_texture_transform");
        if (tt) {
            std::string tn = what + " KHR_texture_transform";
            numbers(*tt, "offset", map->offset, 2, -SCENE_MAX_COORD, SCENE_MAX_COORD, tn);
            numbers(*tt, "scale", map->scale, 2, -SCENE_MAX_COORD, SCENE_MAX_COORD, tn);
            map->rotation = number(*tt, "rotation", 0, -1e3, 1e3, tn);
            map->uv_set = (int)number(*tt, "texCoord", map->uv_set, 0, 7, tn);
        }
        size_t img = (size_t)t.source;
        const tinygltf::Image &im = m->images[img];
        std::string path;
        if (!im.uri.empty()) {
            if (im.uri.compare(0, 5, "data:") == 0)
                fail(what + ": image " + num((double)img) +
                     ": a data: URI tinygltf did not decode");
            path = uri_path(im.uri);
            char err[600];
            if (in_file_check(path.c_str(), err, sizeof err))
                fail(what + ": image " + std::to_string(img) + ": " + err);
        } else {
            const unsigned char *src = nullptr;
            size_t len = 0;
            if (im.bufferView >= 0) { // its range within its buffer, checked before reading
                if ((size_t)im.bufferView >= m->bufferViews.size())
                    fail(what + ": image " + std::to_string(img) + ": bufferView " +
                         std::to_string(im.bufferView) + " does not exist");
                const tinygltf::BufferView &bv = m->bufferViews[(size_t)im.bufferView];
                if (bv.buffer < 0 || (size_t)bv.buffer >= m->buffers.size())
                    fail(what + ": image " + std::to_string(img) + ": its bufferView's buffer " +
                         std::to_string(bv.buffer) + " does not exist");
                const std::vector<unsigned char> &data = m->buffers[(size_t)bv.buffer].data;
                if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
                    fail(what + ": image " + std::to_string(img) + ": bufferView " +
                         std::to_string(im.bufferView) + " (offset " + num((double)bv.byteOffset) +
                         ", length " + num((double)bv.byteLength) + ") reaches past its buffer's " +
                         num((double)data.size()) + " bytes");
                src = data.data() + bv.byteOffset, len = bv.byteLength;
            } else if (img < images.bytes.size()) {
                src = images.bytes[img].data(), len = images.bytes[img].size();
            }
            if (!src || len == 0) fail(what + ": image " + std::to_string(img) + " has no data");
            path = name + "#image/" + std::to_string(img);
            map->blob = static_cast<unsigned char *>(malloc(len));
            if (!map->blob) throw std::bad_alloc();
            memcpy(map->blob, src, len);
            map->blob_size = len;
            snprintf(map->mime, sizeof map->mime, "%s", im.mimeType.c_str());
        }
        map->path = strdup(path.c_str());
        if (!map->path) throw std::bad_alloc();
    }

    // A relative URI resolved from the file's directory, %XX decoded.
    std::string uri_path(const std::string &uri) const
    {
        std::string d;
        for (size_t i = 0; i < uri.size(); ++i) {
            auto hex = [](char c) {
                return c >= '0' && c <= '9'   ? c - '0'
                       : c >= 'a' && c <= 'f' ? c - 'a' + 10
                       : c >= 'A' && c <= 'F' ? c - 'A' + 10
                                              : -1;
            };
            if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 &&
                hex(uri[i + 2]) >= 0) {
                d += (char)(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
                i += 2;
            } else {
                d += uri[i];
            }
        }
        if (d.find('\0') != std::string::npos) fail("a URI holds a NUL byte");
        return d[0] == '/' ? d : dir + d;
    }

    static const tinygltf::Value *ext(const tinygltf::ExtensionMap &e, const char *key)
    {
        auto it = e.find(key);
        return it == e.end() ? nullptr : &it->second;
    }

    // A texture info object inside an extension (e.g. clearcoatTexture) is not read: noted.
    void note_ext_textures(const tinygltf::Value &e, const std::string &what)
    {
        for (const std::string &k : e.Keys())
            if (k.size() > 7 && k.compare(k.size() - 7, 7, "Texture") == 0)
                note(what + ": " + k + " left out (its factor is used)");
    }

    int make_material(int gi)
    {
        scene_material sm;
        memset(&sm, 0, sizeof sm);
        sm.measured = -1;
        scene_pbr_init(&sm);
        abrdf_pbr *q = &sm.pbr_in;
        std::string what;
        if (gi < 0) {
            snprintf(sm.name, sizeof sm.name, "gltf_default");
            what = "default material";
        } else {
            const tinygltf::Material &gm = m->materials[(size_t)gi];
            what = "material " + std::to_string(gi);
            // its name where it is one the scene format could spell (printable, no space,
            // unique), else material_N
            bool ok = !gm.name.empty() && gm.name.size() < SCENE_NAME_MAX;
            for (char c : gm.name) ok = ok && c > ' ' && c < 0x7f;
            for (int k = 0; ok && k < s->material_count; ++k) ok = gm.name != s->materials[k].name;
            if (ok)
                snprintf(sm.name, sizeof sm.name, "%s", gm.name.c_str());
            else
                snprintf(sm.name, sizeof sm.name, "material_%d", gi);
            int models = 0;
            try {
                read_material(gm, &sm, what);
                const tinygltf::Value *ab = member(gm.extras, "abrdf");
                if (ab) models = gltf_extras_material(*ab, &sm);
            } catch (const std::runtime_error &e) {
                scene_material_free(&sm);
                fail(what + ": " + e.what());
            } catch (...) {
                scene_material_free(&sm);
                throw;
            }
            if (models) {
                scene_material_free(&sm); /* its own models: no maps */
                return add_material(sm);
            }
        }
        (void)q;
        char msg[256];
        if (scene_pbr_finish(&sm, msg, sizeof msg)) {
            scene_material_free(&sm);
            fail(what + ": " + msg);
        }
        return add_material(sm);
    }

    int add_material(scene_material &sm)
    {
        if (s->material_count == SCENE_MAX_MATERIALS) {
            scene_material_free(&sm);
            fail("more than " + std::to_string(SCENE_MAX_MATERIALS) + " materials");
        }
        scene_material *g = static_cast<scene_material *>(
            realloc(s->materials, (size_t)(s->material_count + 1) * sizeof *g));
        if (!g) {
            scene_material_free(&sm);
            throw std::bad_alloc();
        }
        s->materials = g;
        g[s->material_count] = sm;
        return s->material_count++;
    }

    void read_material(const tinygltf::Material &gm, scene_material *sm, const std::string &what)
    {
        abrdf_pbr *q = &sm->pbr_in;
        const tinygltf::PbrMetallicRoughness &pm = gm.pbrMetallicRoughness;
        if (pm.baseColorFactor.size() != 4) fail(what + ": baseColorFactor needs 4 numbers");
        for (int c = 0; c < 3; ++c) q->base_color[c] = pm.baseColorFactor[(size_t)c];
        if (pm.baseColorFactor[3] != 1) note(what + ": base colour alpha left out (opaque)");
        q->metallic = pm.metallicFactor;
        q->roughness = pm.roughnessFactor;
        if (gm.alphaMode != "OPAQUE") note(what + ": alphaMode " + gm.alphaMode + " left out");
        for (double e : gm.emissiveFactor)
            if (e != 0) {
                note(what + ": emission left out (abrdf renders reflection)");
                break;
            }
        if (gm.emissiveTexture.index >= 0) note(what + ": emissiveTexture left out");
        // maps
        if (pm.baseColorTexture.index >= 0)
            texture(pm.baseColorTexture.extensions, pm.baseColorTexture.index,
                    pm.baseColorTexture.texCoord, &sm->maps[SCENE_MAP_BASE_COLOR],
                    what + " baseColorTexture");
        if (pm.metallicRoughnessTexture.index >= 0) {
            const tinygltf::TextureInfo &ti = pm.metallicRoughnessTexture;
            texture(ti.extensions, ti.index, ti.texCoord, &sm->maps[SCENE_MAP_METALLIC],
                    what + " metallicRoughnessTexture");
            texture(ti.extensions, ti.index, ti.texCoord, &sm->maps[SCENE_MAP_ROUGHNESS],
                    what + " metallicRoughnessTexture");
        }
        if (gm.occlusionTexture.index >= 0) {
            const tinygltf::OcclusionTextureInfo &ti = gm.occlusionTexture;
            if (!(ti.strength >= 0 && ti.strength <= 1))
                fail(what + ": occlusionTexture.strength = " + num(ti.strength) +
                     " is outside [0, 1]");
            texture(ti.extensions, ti.index, ti.texCoord, &sm->maps[SCENE_MAP_OCCLUSION],
                    what + " occlusionTexture");
            sm->maps[SCENE_MAP_OCCLUSION].strength = ti.strength;
        }
        if (gm.normalTexture.index >= 0) {
            const tinygltf::NormalTextureInfo &ti = gm.normalTexture;
            if (!(std::fabs(ti.scale) <= 100))
                fail(what + ": normalTexture.scale = " + num(ti.scale) + " is outside [-100, 100]");
            texture(ti.extensions, ti.index, ti.texCoord, &sm->maps[SCENE_MAP_NORMAL],
                    what + " normalTexture");
            sm->maps[SCENE_MAP_NORMAL].strength = ti.scale;
        }
        // extensions
        for (const auto &kv : gm.extensions) {
            const std::string &k = kv.first;
            const tinygltf::Value &e = kv.second;
            std::string en = what + " " + k;
            if (k == "KHR_materials_ior") {
                q->ior = number(e, "ior", 1.5, 1, 4, en);
            } else if (k == "KHR_materials_specular") {
                q->specular = number(e, "specularFactor", 1, 0, 1, en);
                numbers(e, "specularColorFactor", q->specular_color, 3, 0, 100, en);
            } else if (k == "KHR_materials_clearcoat") {
                q->clearcoat = number(e, "clearcoatFactor", 0, 0, 1, en);
                q->clearcoat_roughness = number(e, "clearcoatRoughnessFactor", 0, 0, 1, en);
            } else if (k == "KHR_materials_sheen") {
                numbers(e, "sheenColorFactor", q->sheen_color, 3, 0, 1, en);
                q->sheen_roughness = number(e, "sheenRoughnessFactor", 0, 0, 1, en);
            } else if (k == "KHR_materials_anisotropy") {
                q->anisotropy = number(e, "anisotropyStrength", 0, 0, 1, en);
                q->anisotropy_rotation = number(e, "anisotropyRotation", 0, -1e3, 1e3, en);
            } else if (k == "KHR_materials_transmission") {
                q->transmission = number(e, "transmissionFactor", 0, 0, 1, en);
            } else {
                note(what + ": extension " + k + " left out");
                continue;
            }
            note_ext_textures(e, en);
        }
        if (q->clearcoat > 0 || q->sheen_color[0] + q->sheen_color[1] + q->sheen_color[2] > 0)
            note(what + ": clearcoat and sheen have no lobe of their own in the explicit lobes " +
                 "(abrdf_pbr_lobes); with goal= or budget= they choose the surface class");
    }

    int material(int gi, const std::string &what)
    {
        if (gi < 0) {
            if (default_material < 0) {
                default_material = make_material(-1);
                note("primitives without a material: glTF's default material (base colour 1, "
                     "metallic 1, roughness 1)");
            }
            return default_material;
        }
        if ((size_t)gi >= m->materials.size())
            fail(what + ": material " + std::to_string(gi) + " does not exist");
        if (material_of[(size_t)gi] < 0) material_of[(size_t)gi] = make_material(gi);
        return material_of[(size_t)gi];
    }

    // ---- meshes ----

    // The texture coordinate set a material's maps read: the first map's (notes a mix).
    int uv_set_of(int mat)
    {
        const scene_material &sm = s->materials[mat];
        int set = -1;
        for (int k = 0; k < SCENE_MAP_COUNT; ++k)
            if (sm.maps[k].path) {
                if (set < 0)
                    set = sm.maps[k].uv_set;
                else if (sm.maps[k].uv_set != set)
                    note(std::string("material '") + sm.name + "': its maps read different " +
                         "TEXCOORD sets; the mesh carries TEXCOORD_" + std::to_string(set));
            }
        return set < 0 ? 0 : set;
    }

    // tmpl: the object's transform, tangent and smooth from extras.abrdf (positions kept in
    // object space), or null (the node's world transform baked in).
    void primitive(size_t node, size_t mi, size_t pi, const mat4 &world, const scene_object *tmpl)
    {
        const tinygltf::Primitive &p = m->meshes[mi].primitives[pi];
        std::string what = "mesh " + std::to_string(mi) + " primitive " + std::to_string(pi);
        int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode < TINYGLTF_MODE_TRIANGLES) {
            note(what + ": points or lines left out (no surface)");
            return;
        }
        if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
            fail(what + ": unknown mode " + std::to_string(mode));
        if (!p.targets.empty()) note(what + ": morph targets left out (the base shape is read)");
        auto attr = [&](const char *key) {
            auto it = p.attributes.find(key);
            return it == p.attributes.end() ? -1 : it->second;
        };
        int pos = attr("POSITION");
        if (pos < 0) fail(what + " has no POSITION");
        view pv = accessor(pos, 3, what + " POSITION");
        if (pv.comp_type != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(what + " POSITION is not float");
        size_t nv = pv.count;
        // the corners, as indices into the vertices
        std::vector<unsigned int> corner;
        if (p.indices >= 0) {
            view iv = accessor(p.indices, 1, what + " indices");
            if (iv.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                iv.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                iv.comp_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail(what + " indices are not unsigned byte, short or int");
            corner.resize(iv.count);
            for (size_t i = 0; i < iv.count; ++i) {
                double x = get(iv, i, 0);
                if (!(x < (double)nv))
                    fail(what + ": index " + num(x) + " (at " + std::to_string(i) + ") but " +
                         std::to_string(nv) + " vertices");
                corner[i] = (unsigned int)x;
            }
        } else {
            corner.resize(nv);
            for (size_t i = 0; i < nv; ++i) corner[i] = (unsigned int)i;
        }
        std::vector<unsigned int> tri;
        size_t nc = corner.size();
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (nc % 3) fail(what + ": " + std::to_string(nc) + " corners, not a multiple of 3");
            tri = corner;
        } else {
            for (size_t i = 0; i + 2 < nc; ++i) {
                unsigned int a, b, c = corner[i + 2];
                if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
                    a = corner[0], b = corner[i + 1];
                else if (i % 2 == 0)
                    a = corner[i], b = corner[i + 1];
                else
                    a = corner[i + 1], b = corner[i]; // every other strip triangle turned
                tri.push_back(a), tri.push_back(b), tri.push_back(c);
            }
        }
        size_t nt = tri.size() / 3;
        if (nt == 0) {
            note(what + ": no triangles (left out)");
            return;
        }
        if (s->triangle_count + (long long)nt > SCENE_MAX_TRIANGLES)
            fail(what + " brings the scene to more than " + std::to_string(SCENE_MAX_TRIANGLES) +
                 " triangles");
        vertices += (long long)nv;
        if (vertices > 3LL * SCENE_MAX_TRIANGLES)
            fail(what + " brings the scene to more than " +
                 std::to_string(3LL * SCENE_MAX_TRIANGLES) + " vertices");
        int mat = material(p.material, what);
        bool mirror = det3(world) < 0; // a mirroring node turns the winding (glTF 3.7.4)
        if (!(std::fabs(det3(world)) > 0)) {
            note(what + " (node " + std::to_string(node) + "): a singular transform (left out)");
            return;
        }
        mesh *me = static_cast<mesh *>(calloc(1, sizeof(mesh)));
        if (!me) throw std::bad_alloc();
        // into the scene first: scene_free releases it whatever happens below
        add_mesh(me);
        std::string mname = name + "#node/" + std::to_string(node) + "/mesh/" + std::to_string(mi) +
                            "/primitive/" + std::to_string(pi);
        me->path = strdup(mname.c_str());
        me->in_memory = 1;
        me->uv_origin_top = 1;
        me->vertex_count = (int)nv;
        me->triangle_count = (int)nt;
        me->position = static_cast<float *>(malloc(3 * nv * sizeof(float)));
        me->tri = static_cast<int *>(malloc((3 * nt + 4) * sizeof(int)));
        if (!me->path || !me->position || !me->tri) throw std::bad_alloc();
        for (size_t v = 0; v < nv; ++v) {
            double p3[3] = {get(pv, v, 0), get(pv, v, 1), get(pv, v, 2)}, w[3];
            apply_point(world, p3, w);
            for (int a = 0; a < 3; ++a) {
                if (!(std::fabs(w[a]) <= SCENE_MAX_COORD))
                    fail(what + ": vertex " + std::to_string(v) + " is not finite or beyond " +
                         num(SCENE_MAX_COORD) + " in world space");
                me->position[3 * v + (size_t)a] = (float)w[a];
                lo[a] = std::fmin(lo[a], w[a]), hi[a] = std::fmax(hi[a], w[a]);
            }
        }
        for (size_t t = 0; t < nt; ++t) {
            me->tri[3 * t] = (int)tri[3 * t];
            me->tri[3 * t + 1] = (int)tri[3 * t + (mirror ? 2 : 1)];
            me->tri[3 * t + 2] = (int)tri[3 * t + (mirror ? 1 : 2)];
        }
        for (int k = 0; k < 4; ++k) me->tri[3 * nt + (size_t)k] = 0;
        int nrm = attr("NORMAL");
        bool have_normals = false;
        if (nrm >= 0) {
            view nv3 = accessor(nrm, 3, what + " NORMAL");
            if (nv3.comp_type != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(what + " NORMAL is not float");
            if (nv3.count != nv) fail(what + ": NORMAL and POSITION counts differ");
            me->normal = static_cast<float *>(malloc(3 * nv * sizeof(float)));
            me->tri_normal = static_cast<int *>(malloc(3 * nt * sizeof(int)));
            if (!me->normal || !me->tri_normal) throw std::bad_alloc();
            double c[9];
            cofactor3(world, c); // det(M) M^-T: its sign flips normals under a mirror
            double sign = det3(world) < 0 ? -1.0 : 1.0;
            for (int k = 0; k < 9; ++k) c[k] *= sign;
            have_normals = true;
            for (size_t v = 0; v < nv && have_normals; ++v) {
                double n[3] = {get(nv3, v, 0), get(nv3, v, 1), get(nv3, v, 2)}, w[3];
                for (int r = 0; r < 3; ++r)
                    w[r] = c[r * 3] * n[0] + c[r * 3 + 1] * n[1] + c[r * 3 + 2] * n[2];
                double l = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
                // 1e-30: as mesh.c, a normal must have a direction
                if (!(l > 1e-30 && std::isfinite(l))) have_normals = false;
                for (int a = 0; a < 3; ++a) me->normal[3 * v + (size_t)a] = (float)(w[a] / l);
            }
            if (!have_normals) {
                note(what + ": a NORMAL of zero length or not finite; normals computed");
                free(me->normal), free(me->tri_normal);
                me->normal = nullptr, me->tri_normal = nullptr;
            } else {
                me->normal_count = (int)nv;
                memcpy(me->tri_normal, me->tri, 3 * nt * sizeof(int));
                me->normals_from_file = 1;
            }
        }
        if (!have_normals && mesh_compute_normals(me)) throw std::bad_alloc();
        int set = uv_set_of(mat);
        std::string key = "TEXCOORD_" + std::to_string(set);
        int uv = attr(key.c_str());
        if (uv >= 0) {
            view tv = accessor(uv, 2, what + " " + key);
            if (tv.comp_type != TINYGLTF_COMPONENT_TYPE_FLOAT && !tv.normalized)
                fail(what + " " + key + " is neither float nor normalized");
            if (tv.count != nv) fail(what + ": " + key + " and POSITION counts differ");
            me->uv = static_cast<float *>(malloc(2 * nv * sizeof(float)));
            me->tri_uv = static_cast<int *>(malloc(3 * nt * sizeof(int)));
            if (!me->uv || !me->tri_uv) throw std::bad_alloc();
            for (size_t v = 0; v < nv; ++v)
                for (int a = 0; a < 2; ++a) {
                    double x = get(tv, v, a);
                    if (!(std::fabs(x) <= MESH_MAX_COORD))
                        fail(what + " " + key + ": value " + std::to_string(v) +
                             " is not finite or beyond " + num(MESH_MAX_COORD));
                    me->uv[2 * v + (size_t)a] = (float)x;
                }
            me->uv_count = (int)nv;
            memcpy(me->tri_uv, me->tri, 3 * nt * sizeof(int));
        } else if (s->materials[mat].textured) {
            note(what + ": its material has maps but the primitive no " + key +
                 " (the maps read uv 0)");
        }
        mesh_bounding_sphere(me);
        s->triangle_count += (long long)nt;
        scene_object o;
        memset(&o, 0, sizeof o);
        if (tmpl) o = *tmpl;
        o.shape = SCENE_MESH;
        if (!tmpl) o.scale[0] = o.scale[1] = o.scale[2] = 1;
        o.material = mat;
        o.mesh = s->mesh_count - 1;
        o.mesh_data = me;
        if (!tmpl) {
            o.smooth = 1;
            o.tangent = me->uv && s->materials[mat].pbr_in.anisotropy > 0 ? SCENE_TANGENT_UV
                                                                          : SCENE_TANGENT_U;
        } else if (o.tangent == SCENE_TANGENT_UV && !me->uv) {
            fail(what + ": tangent uv without texture coordinates");
        }
        add_object(o);
    }

    void add_mesh(mesh *me)
    {
        if (s->mesh_count == SCENE_MAX_OBJECTS) {
            free(me);
            fail("more than " + std::to_string(SCENE_MAX_OBJECTS) + " primitives");
        }
        if (s->mesh_count == mesh_cap) {
            int c = mesh_cap ? 2 * mesh_cap : 16;
            mesh **g = static_cast<mesh **>(realloc(s->meshes, (size_t)c * sizeof *g));
            if (!g) {
                free(me);
                throw std::bad_alloc();
            }
            s->meshes = g;
            mesh_cap = c;
        }
        s->meshes[s->mesh_count++] = me;
    }

    void add_object(const scene_object &o)
    {
        if (s->object_count >= SCENE_MAX_OBJECTS)
            fail("more than " + std::to_string(SCENE_MAX_OBJECTS) + " objects");
        if (s->object_count == object_cap) {
            int c = object_cap ? 2 * object_cap : 16;
            scene_object *g =
                static_cast<scene_object *>(realloc(s->objects, (size_t)c * sizeof *g));
            if (!g) throw std::bad_alloc();
            s->objects = g;
            object_cap = c;
        }
        s->objects[s->object_count++] = o;
    }

    // ---- nodes ----

    mat4 local(const tinygltf::Node &n, size_t i)
    {
        std::string what = "node " + std::to_string(i);
        auto finite = [&](const std::vector<double> &v, size_t len, const char *key) {
            if (v.empty()) return false;
            if (v.size() != len)
                fail(what + ": " + key + " needs " + std::to_string(len) + " numbers");
            for (double x : v)
                if (!(std::fabs(x) <= SCENE_MAX_COORD))
                    fail(what + ": " + key + " holds " + num(x) +
                         " (|x| <= " + num(SCENE_MAX_COORD) + ")");
            return true;
        };
        mat4 r = identity();
        if (finite(n.matrix, 16, "matrix")) {
            for (int k = 0; k < 16; ++k) r.m[k] = n.matrix[(size_t)k];
            return r;
        }
        mat4 t = identity(), rot = identity(), sc = identity();
        if (finite(n.translation, 3, "translation"))
            for (int a = 0; a < 3; ++a) t.m[12 + a] = n.translation[(size_t)a];
        if (finite(n.rotation, 4, "rotation")) {
            double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
            double l = std::sqrt(x * x + y * y + z * z + w * w);
            if (!(l > 0)) fail(what + ": rotation is a zero quaternion");
            x /= l, y /= l, z /= l, w /= l;
            double c[9] = {
                1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
                2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
                2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y)};
            for (int col = 0; col < 3; ++col)
                for (int row = 0; row < 3; ++row) rot.m[col * 4 + row] = c[col * 3 + row];
        }
        if (finite(n.scale, 3, "scale"))
            for (int a = 0; a < 3; ++a) sc.m[a * 5] = n.scale[(size_t)a];
        return mul(t, mul(rot, sc));
    }

    std::vector<std::pair<int, mat4>> light_nodes;

    void visit(int i, const mat4 &parent, int depth)
    {
        if (i < 0 || (size_t)i >= m->nodes.size())
            fail("node " + std::to_string(i) + " does not exist (" +
                 std::to_string(m->nodes.size()) + " nodes)");
        if (node_seen[(size_t)i])
            fail("node " + std::to_string(i) + " is reached twice (nodes form trees)");
        node_seen[(size_t)i] = 1;
        if (depth > GLTF_MAX_DEPTH)
            fail("node " + std::to_string(i) + " is deeper than " + std::to_string(GLTF_MAX_DEPTH) +
                 " levels");
        const tinygltf::Node &n = m->nodes[(size_t)i];
        mat4 world = mul(parent, local(n, (size_t)i));
        if (n.mesh >= 0) {
            if ((size_t)n.mesh >= m->meshes.size())
                fail("node " + std::to_string(i) + ": mesh " + std::to_string(n.mesh) +
                     " does not exist");
            if (n.skin >= 0) note("node " + std::to_string(i) + ": skin left out (bind pose)");
            // abrdf's own object (extras.abrdf, gltf_extras.h): its exact shape and transform
            const tinygltf::Value *ab = member(n.extras, "abrdf");
            scene_object tmpl;
            memset(&tmpl, 0, sizeof tmpl);
            tmpl.scale[0] = tmpl.scale[1] = tmpl.scale[2] = 1;
            tmpl.smooth = 1;
            tmpl.mesh = -1;
            int analytic = 0;
            if (ab) try {
                    analytic = gltf_extras_read_object(*ab, &tmpl);
                } catch (const std::runtime_error &e) {
                    fail("node " + std::to_string(i) + ": " + e.what());
                }
            const tinygltf::Mesh &gm = m->meshes[(size_t)n.mesh];
            if (analytic) {
                if (gm.primitives.empty())
                    fail("node " + std::to_string(i) + ": mesh without primitives");
                tmpl.material = material(gm.primitives[0].material, "node " + std::to_string(i));
                add_object(tmpl);
            } else {
                for (size_t p = 0; p < gm.primitives.size(); ++p)
                    primitive((size_t)i, (size_t)n.mesh, p, ab ? identity() : world,
                              ab ? &tmpl : nullptr);
            }
        }
        if (n.camera >= 0 && camera_node < 0) {
            camera_node = i;
            camera_world = world;
        }
        const tinygltf::Value *lp = ext(n.extensions, "KHR_lights_punctual");
        if (lp) light_nodes.emplace_back(i, world);
        for (int c : n.children) visit(c, world, depth + 1);
    }

    // ---- camera and lights ----

    void camera()
    {
        scene_camera *c = &s->camera;
        double radius = 1, center[3] = {0, 0, 0};
        if (lo[0] <= hi[0]) {
            double r2 = 0;
            for (int a = 0; a < 3; ++a) {
                center[a] = 0.5 * (lo[a] + hi[a]);
                r2 += 0.25 * (hi[a] - lo[a]) * (hi[a] - lo[a]);
            }
            radius = std::fmax(std::sqrt(r2), 1e-3);
        }
        c->up[0] = 0, c->up[1] = 1, c->up[2] = 0;
        c->width = c->height = 512;
        if (camera_node < 0) {
            c->fov_deg = 40;
            // the bounding sphere fills the height: distance r / sin(fov / 2), 10% margin
            double d = 1.1 * radius / std::sin(0.5 * 40 * M_PI / 180);
            for (int a = 0; a < 3; ++a) c->look_at[a] = center[a];
            c->position[0] = center[0], c->position[1] = center[1], c->position[2] = center[2] + d;
            note("no camera: one on +z framing the bounding sphere (centre " + num(center[0]) +
                 "," + num(center[1]) + "," + num(center[2]) + ", radius " + num(radius) +
                 "), fov 40, 512x512");
            return;
        }
        const tinygltf::Node &n = m->nodes[(size_t)camera_node];
        if ((size_t)n.camera >= m->cameras.size())
            fail("node " + std::to_string(camera_node) + ": camera " + std::to_string(n.camera) +
                 " does not exist");
        const tinygltf::Camera &gc = m->cameras[(size_t)n.camera];
        std::string what = "camera " + std::to_string(n.camera);
        if (gc.type != "perspective")
            fail(what + " is " + gc.type + "; abrdf renders with a pinhole (perspective) camera");
        double yfov = gc.perspective.yfov * 180 / M_PI;
        if (!(yfov > 0 && yfov <= 179))
            fail(what + ": yfov " + num(gc.perspective.yfov) + " rad is outside (0, 179] degrees");
        c->fov_deg = yfov;
        double aspect = gc.perspective.aspectRatio;
        if (aspect > 0) {
            double w = std::floor(512 * aspect + 0.5);
            if (!(w >= 1 && w <= SCENE_MAX_RESOLUTION))
                fail(what + ": aspectRatio " + num(aspect) + " gives a width outside [1, " +
                     std::to_string(SCENE_MAX_RESOLUTION) + "] at 512 rows");
            c->width = (int)w;
        } else {
            note(what + ": no aspectRatio; 512x512");
        }
        double o[3] = {0, 0, 0}, fwd[3] = {0, 0, -1}, up[3] = {0, 1, 0}, f[3], u[3];
        apply_point(camera_world, o, c->position);
        apply_dir(camera_world, fwd, f);
        apply_dir(camera_world, up, u);
        normalize(f), normalize(u);
        double x[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2],
                       f[0] * u[1] - f[1] * u[0]};
        if (!(std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) > 1e-9))
            fail("node " + std::to_string(camera_node) + ": the camera's transform is singular");
        for (int a = 0; a < 3; ++a) {
            if (!(std::fabs(c->position[a]) <= SCENE_MAX_COORD))
                fail("node " + std::to_string(camera_node) + ": camera beyond " +
                     num(SCENE_MAX_COORD));
            // look_at one bounding radius ahead: any point on the axis is the same view
            c->look_at[a] = c->position[a] + f[a];
            c->up[a] = u[a];
        }
    }

    void lights()
    {
        for (const auto &ln : light_nodes) {
            const tinygltf::Node &n = m->nodes[(size_t)ln.first];
            const tinygltf::Value *lp = ext(n.extensions, "KHR_lights_punctual");
            std::string what = "node " + std::to_string(ln.first) + " KHR_lights_punctual";
            double li = number(*lp, "light", -1, -1, 1e9, what);
            if (li < 0 || li != std::floor(li) || li >= (double)m->lights.size())
                fail(what + ": light " + num(li) + " does not exist");
            const tinygltf::Light &gl = m->lights[(size_t)li];
            std::string lw = "light " + num(li);
            if (s->light_count == SCENE_MAX_LIGHTS)
                fail("more than " + std::to_string(SCENE_MAX_LIGHTS) + " lights");
            scene_light l;
            memset(&l, 0, sizeof l);
            l.color[0] = l.color[1] = l.color[2] = 1;
            if (!gl.color.empty()) {
                if (gl.color.size() != 3) fail(lw + ": color needs 3 numbers");
                for (int c = 0; c < 3; ++c) {
                    if (!(gl.color[(size_t)c] >= 0 && gl.color[(size_t)c] <= SCENE_MAX_COORD))
                        fail(lw + ": color " + num(gl.color[(size_t)c]) + " is outside [0, " +
                             num(SCENE_MAX_COORD) + "]");
                    l.color[c] = gl.color[(size_t)c];
                }
            }
            if (!(gl.intensity >= 0 && gl.intensity <= SCENE_MAX_COORD))
                fail(lw + ": intensity " + num(gl.intensity) + " is outside [0, " +
                     num(SCENE_MAX_COORD) + "]");
            l.intensity = gl.intensity;
            double o[3] = {0, 0, 0}, back[3] = {0, 0, 1};
            if (gl.type == "directional") {
                l.kind = SCENE_LIGHT_DIRECTIONAL;
                apply_dir(ln.second, back, l.direction); // toward the light: its +z
                normalize(l.direction);
                if (!(l.direction[0] * l.direction[0] + l.direction[1] * l.direction[1] +
                          l.direction[2] * l.direction[2] >
                      0.5))
                    fail(what + ": the light's transform is singular");
            } else if (gl.type == "point" || gl.type == "spot") {
                l.kind = SCENE_LIGHT_POINT;
                apply_point(ln.second, o, l.position);
                for (int a = 0; a < 3; ++a)
                    if (!(std::fabs(l.position[a]) <= SCENE_MAX_COORD))
                        fail(what + ": light beyond " + num(SCENE_MAX_COORD));
                if (gl.type == "spot")
                    note(lw + ": a spot light, rendered as a point light (no cone)");
            } else {
                fail(lw + ": unknown type '" + gl.type + "'");
            }
            if (gl.range > 0) note(lw + ": range left out (inverse-square to any distance)");
            s->lights[s->light_count++] = l;
        }
        if (s->light_count == 0) {
            scene_light l;
            memset(&l, 0, sizeof l);
            l.kind = SCENE_LIGHT_DIRECTIONAL;
            l.color[0] = l.color[1] = l.color[2] = 1;
            l.intensity = M_PI;
            const scene_camera *c = &s->camera;
            // from behind the camera and above it
            double b[3], u[3] = {c->up[0], c->up[1], c->up[2]};
            for (int a = 0; a < 3; ++a) b[a] = c->position[a] - c->look_at[a];
            normalize(b), normalize(u);
            for (int a = 0; a < 3; ++a) l.direction[a] = b[a] + u[a];
            normalize(l.direction);
            s->lights[s->light_count++] = l;
            note("no light: one directional light of irradiance pi (a white Lambertian surface "
                 "facing it is 1) from behind the camera and above, direction " +
                 num(l.direction[0]) + "," + num(l.direction[1]) + "," + num(l.direction[2]));
        }
    }

    // The files the buffers came from, so that no output replaces one (scene_named_files).
    void buffer_files()
    {
        for (const tinygltf::Buffer &b : m->buffers) {
            if (b.uri.empty() || b.uri.compare(0, 5, "data:") == 0) continue;
            char **g = static_cast<char **>(
                realloc(s->buffer_files, (size_t)(s->buffer_file_count + 1) * sizeof *g));
            if (!g) throw std::bad_alloc();
            s->buffer_files = g;
            if (!(g[s->buffer_file_count] = strdup(uri_path(b.uri).c_str())))
                throw std::bad_alloc();
            ++s->buffer_file_count;
        }
    }

    void read()
    {
        material_of.assign(m->materials.size(), -1);
        node_seen.assign(m->nodes.size(), 0);
        s->lights = static_cast<scene_light *>(calloc(SCENE_MAX_LIGHTS, sizeof(scene_light)));
        if (!s->lights) throw std::bad_alloc();
        std::vector<int> roots;
        if (!m->scenes.empty()) {
            int si = m->defaultScene >= 0 ? m->defaultScene : 0;
            if ((size_t)si >= m->scenes.size())
                fail("scene " + std::to_string(si) + " does not exist");
            roots = m->scenes[(size_t)si].nodes;
            if (m->scenes.size() > 1)
                note("scene " + std::to_string(si) + " of " + std::to_string(m->scenes.size()) +
                     " read");
        } else {
            std::vector<char> child(m->nodes.size(), 0);
            for (const tinygltf::Node &n : m->nodes)
                for (int c : n.children)
                    if (c >= 0 && (size_t)c < child.size()) child[(size_t)c] = 1;
            for (size_t i = 0; i < m->nodes.size(); ++i)
                if (!child[i]) roots.push_back((int)i);
            note("no scenes: every root node read");
        }
        for (int r : roots) visit(r, identity(), 0);
        if (s->object_count == 0) fail("no triangles in the scene's nodes");
        if (!m->animations.empty()) note("animations left out (the rest pose)");
        camera();
        if (!m->scenes.empty()) {
            const tinygltf::Value *ab = member(
                m->scenes[(size_t)(m->defaultScene >= 0 ? m->defaultScene : 0)].extras, "abrdf");
            if (ab) try {
                    gltf_extras_read_scene(*ab, s);
                } catch (const std::runtime_error &e) {
                    fail(std::string("scene: ") + e.what());
                }
        }
        lights();
        for (const std::string &e : m->extensionsUsed) {
            static const char *const known[] = {
                "KHR_materials_ior",     "KHR_materials_specular",   "KHR_materials_clearcoat",
                "KHR_materials_sheen",   "KHR_materials_anisotropy", "KHR_materials_transmission",
                "KHR_texture_transform", "KHR_lights_punctual"};
            bool k = false;
            for (const char *x : known) k |= e == x;
            if (!k) note("extension " + e + " left out");
        }
    }
};

// One line: tinygltf's messages end in newlines and may hold several.
std::string one_line(std::string t)
{
    while (!t.empty() && (t.back() == '\n' || t.back() == '\r' || t.back() == ' ')) t.pop_back();
    for (char &c : t)
        if (c == '\n' || c == '\r') c = ' ';
    if (t.size() > 400) t = t.substr(0, 400) + "...";
    return t;
}

void say(char *err, size_t err_size, const std::string &name, const std::string &msg)
{
    if (err && err_size) path_msg(err, err_size, name.c_str(), ": %s", one_line(msg).c_str());
}

} // namespace

extern "C" int gltf_read_memory(const char *name, const unsigned char *bytes, size_t size,
                                scene *out, char *err, size_t err_size)
{
    if (err && err_size) err[0] = '\0';
    if (!out) return -1;
    memset(out, 0, sizeof *out);
    std::string nm = name ? name : "<gltf>";
    if (!bytes || size == 0) {
        say(err, err_size, nm, "empty file");
        return -1;
    }
    if (size > GLTF_MAX_FILE || size > 0xffffffffu) {
        say(err, err_size, nm, "larger than " + num((double)GLTF_MAX_FILE) + " bytes");
        return -1;
    }
    try {
        tinygltf::Model model;
        tinygltf::TinyGLTF loader;
        reader r;
        r.name = nm;
        size_t slash = nm.rfind('/');
        r.dir = slash == std::string::npos ? "" : nm.substr(0, slash + 1);
        size_t named_bytes = 0; // all the files it names, together
        tinygltf::FsCallbacks fs = {file_exists, expand_path, read_whole, write_whole,
                                    &named_bytes};
        loader.SetFsCallbacks(fs);
        loader.SetImageLoader(keep_image, &r.images);
        std::string lerr, lwarn;
        bool ok;
        { // the JSON's nesting, before tinygltf recurses into it (json_depth)
            const unsigned char *js = bytes;
            size_t jn = size;
            if (size >= 20 && !memcmp(bytes, "glTF", 4)) { // GLB: the first chunk is the JSON
                uint32_t len;
                memcpy(&len, bytes + 12, 4);
                js = bytes + 20, jn = std::min<size_t>(len, size - 20);
            }
            if (json_depth(js, jn) > GLTF_MAX_JSON_DEPTH) {
                say(err, err_size, nm,
                    "JSON nested more than " + std::to_string(GLTF_MAX_JSON_DEPTH) + " deep");
                return -1;
            }
        }
        if (size >= 4 && !memcmp(bytes, "glTF", 4))
            ok = loader.LoadBinaryFromMemory(&model, &lerr, &lwarn, bytes, (unsigned int)size,
                                             r.dir);
        else
            ok = loader.LoadASCIIFromString(&model, &lerr, &lwarn,
                                            reinterpret_cast<const char *>(bytes),
                                            (unsigned int)size, r.dir);
        if (!ok) {
            say(err, err_size, nm, lerr.empty() ? "not a glTF file" : lerr);
            return -1;
        }
        r.m = &model;
        r.s = out;
        r.buffer_files();
        if (!lwarn.empty()) r.note("tinygltf: " + one_line(lwarn));
        r.read();
        if (!r.notes.empty()) {
            out->notes = strdup(r.notes.c_str());
            if (!out->notes) throw std::bad_alloc();
        }
        return 0;
    } catch (const gltf_fail &f) {
        say(err, err_size, nm, f.msg);
    } catch (const std::bad_alloc &) {
        say(err, err_size, nm, "out of memory");
    } catch (const std::exception &e) {
        say(err, err_size, nm, e.what());
    } catch (...) {
        say(err, err_size, nm, "unreadable glTF");
    }
    scene_free(out);
    return -1;
}

extern "C" int gltf_read_file(const char *path, scene *out, char *err, size_t err_size)
{
    if (out) memset(out, 0, sizeof *out);
    std::vector<unsigned char> bytes;
    std::string lerr;
    try {
        if (!read_whole(&bytes, &lerr, path, nullptr)) {
            if (err && err_size) snprintf(err, err_size, "%s", one_line(lerr).c_str());
            return -1;
        }
    } catch (const std::bad_alloc &) {
        say(err, err_size, path, "out of memory");
        return -1;
    }
    return gltf_read_memory(path, bytes.data(), bytes.size(), out, err, err_size);
}
