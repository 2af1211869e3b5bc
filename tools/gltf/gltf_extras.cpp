// gltf_extras.cpp - extras.abrdf written and read back (gltf_extras.h).
#include "gltf_extras.h"

extern "C" {
#include "cli_args.h"
}

#include <cmath>
#include <stdexcept>
#include <string>

using tinygltf::Value;

namespace
{

[[noreturn]] void bad(const std::string &msg) { throw std::runtime_error("extras.abrdf: " + msg); }

Value vec(const double *v, int n)
{
    Value::Array a;
    for (int i = 0; i < n; ++i) a.push_back(Value(v[i]));
    return Value(a);
}

const Value *member(const Value &o, const char *key)
{
    return o.IsObject() && o.Has(key) ? &o.Get(key) : nullptr;
}

// o[key]: one number or n of them, each finite with |x| <= limit; 0 if absent, else the count.
int nums(const Value &o, const char *key, double *out, int n, double limit)
{
    const Value *v = member(o, key);
    if (!v) return 0;
    if (v->IsNumber()) {
        out[0] = v->GetNumberAsDouble();
        if (!(std::fabs(out[0]) <= limit)) bad(std::string(key) + " is out of range");
        return 1;
    }
    if (!v->IsArray() || (int)v->ArrayLen() != n) bad(std::string(key) + " has the wrong length");
    for (int i = 0; i < n; ++i) {
        if (!v->Get(i).IsNumber()) bad(std::string(key) + " holds a non-number");
        out[i] = v->Get(i).GetNumberAsDouble();
        if (!(std::fabs(out[i]) <= limit)) bad(std::string(key) + " is out of range");
    }
    return n;
}

std::string str(const Value &o, const char *key)
{
    const Value *v = member(o, key);
    if (!v) return "";
    if (!v->IsString()) bad(std::string(key) + " is not a string");
    return v->Get<std::string>();
}

} // namespace

void gltf_extras_models(const scene_material *sm, Value::Object &ab)
{
    Value::Array models;
    for (int l = 0; l < sm->lobe_count; ++l)
        models.push_back(Value(std::string(abrdf_model_get(sm->lobes[l])->name)));
    ab["models"] = Value(models);
    Value::Object params;
    for (int id = 0; id < abrdf_param_count(); ++id) {
        int read = 0;
        for (int l = 0; l < sm->lobe_count; ++l) read |= cli_model_reads(sm->lobes[l], id);
        if (!read) continue;
        double v[3];
        int n = abrdf_param_read(&sm->params, id, v);
        if (n == 1) params[abrdf_param_get(id)->name] = Value(v[0]);
        if (n == 3) params[abrdf_param_get(id)->name] = vec(v, 3);
    }
    ab["params"] = Value(params);
}

int gltf_extras_material(const Value &ab, scene_material *sm)
{
    double ka[3];
    int n = nums(ab, "ka", ka, 3, SCENE_MAX_COORD);
    if (n == 1) ka[1] = ka[2] = ka[0];
    if (n) {
        for (int c = 0; c < 3; ++c) {
            if (!(ka[c] >= 0)) bad("ka is negative");
            sm->ka[c] = ka[c];
        }
        sm->ka_given = 1;
    }
    const Value *models = member(ab, "models");
    if (!models) return 0;
    if (!models->IsArray() || models->ArrayLen() < 1 || models->ArrayLen() > SCENE_MAX_LOBES)
        bad("models needs 1 or 2 model names");
    sm->lobe_count = (int)models->ArrayLen();
    for (int l = 0; l < sm->lobe_count; ++l) {
        const Value &v = models->Get(l);
        if (!v.IsString() ||
            abrdf_model_find(v.Get<std::string>().c_str(), &sm->lobes[l]) != ABRDF_OK)
            bad("models: unknown model");
        if (abrdf_model_get(sm->lobes[l])->needs & ABRDF_NEEDS_TABLE)
            bad("models: a measured model needs its table");
    }
    abrdf_params_init(sm->lobes[0], &sm->params);
    const Value *params = member(ab, "params");
    if (params) {
        if (!params->IsObject()) bad("params is not an object");
        for (const std::string &k : params->Keys()) {
            int id;
            if (abrdf_param_find(k.c_str(), &id) != ABRDF_OK) bad("params: unknown parameter " + k);
            double v[3];
            int cnt = nums(*params, k.c_str(), v, 3, 1e300);
            if (abrdf_param_set(&sm->params, id, v, cnt) != ABRDF_OK)
                bad("params: " + k + " is out of its range");
        }
    }
    for (int l = 0; l < sm->lobe_count; ++l) {
        char msg[256];
        if (abrdf_params_check(sm->lobes[l], &sm->params, msg, sizeof msg) != ABRDF_OK) bad(msg);
    }
    sm->pbr = 0;
    sm->kind = SCENE_MAT_MODELS;
    if (!sm->ka_given) {
        for (int c = 0; c < 3; ++c) sm->ka[c] = 0;
    }
    return 1;
}

static const char *const tangents[] = {"u", "v", "radial", "axis", "uv"};

void gltf_extras_object(const scene_object *o, Value::Object &ab)
{
    ab["shape"] = Value(std::string(scene_shape_name(o->shape)));
    if (o->shape == SCENE_SPHERE || o->shape == SCENE_CYLINDER || o->shape == SCENE_CAPSULE)
        ab["radius"] = Value(o->radius);
    if (o->shape == SCENE_CYLINDER || o->shape == SCENE_CAPSULE) ab["height"] = Value(o->height);
    if (o->shape == SCENE_BOX) ab["size"] = vec(o->size, 3);
    if (o->shape == SCENE_MESH) ab["smooth"] = Value(o->smooth != 0);
    ab["translate"] = vec(o->translate, 3);
    ab["rotate"] = vec(o->rotate_deg, 3);
    ab["scale"] = vec(o->scale, 3);
    ab["tangent"] = Value(std::string(tangents[o->tangent]));
    if (o->tangent == SCENE_TANGENT_AXIS) ab["tangent_axis"] = vec(o->tangent_axis, 3);
}

int gltf_extras_read_object(const Value &ab, scene_object *o)
{
    std::string t = str(ab, "tangent");
    if (!t.empty()) {
        int k = 0;
        while (k < 5 && t != tangents[k]) ++k;
        if (k == 5) bad("unknown tangent '" + t + "'");
        o->tangent = (scene_tangent)k;
        if (k == SCENE_TANGENT_AXIS) {
            if (nums(ab, "tangent_axis", o->tangent_axis, 3, SCENE_MAX_COORD) != 3 ||
                !(o->tangent_axis[0] != 0 || o->tangent_axis[1] != 0 || o->tangent_axis[2] != 0))
                bad("tangent axis needs tangent_axis, three numbers not all zero");
        }
    }
    const Value *sm = member(ab, "smooth");
    if (sm) {
        if (!sm->IsBool()) bad("smooth is not true or false");
        o->smooth = sm->Get<bool>();
    }
    std::string shape = str(ab, "shape");
    if (shape.empty() || shape == "mesh") {
        nums(ab, "translate", o->translate, 3, SCENE_MAX_COORD);
        nums(ab, "rotate", o->rotate_deg, 3, SCENE_MAX_COORD);
        if (nums(ab, "scale", o->scale, 3, SCENE_MAX_COORD))
            for (double x : o->scale)
                if (!(x >= 1e-6)) bad("scale below 1e-6");
        return 0;
    }
    int k = 0;
    while (k < SCENE_MESH && shape != scene_shape_name((scene_shape)k)) ++k;
    if (k == SCENE_MESH) bad("unknown shape '" + shape + "'");
    o->shape = (scene_shape)k;
    auto positive = [&](const char *key, double *v, int n, bool zero_ok) {
        if (nums(ab, key, v, n, SCENE_MAX_COORD) != n) bad(shape + " needs " + key);
        for (int i = 0; i < n; ++i)
            if (!(v[i] > 0 || (zero_ok && v[i] == 0))) bad(std::string(key) + " must be positive");
    };
    if (k != SCENE_BOX) positive("radius", &o->radius, 1, false);
    if (k == SCENE_CYLINDER || k == SCENE_CAPSULE)
        positive("height", &o->height, 1, k == SCENE_CAPSULE);
    if (k == SCENE_BOX) positive("size", o->size, 3, false);
    nums(ab, "translate", o->translate, 3, SCENE_MAX_COORD);
    nums(ab, "rotate", o->rotate_deg, 3, SCENE_MAX_COORD);
    if (nums(ab, "scale", o->scale, 3, SCENE_MAX_COORD))
        for (double x : o->scale)
            if (!(x >= 1e-6)) bad("scale below 1e-6");
    if (o->tangent == SCENE_TANGENT_UV) bad("tangent uv needs a mesh");
    return 1;
}

void gltf_extras_scene_write(const scene *s, Value::Object &ab)
{
    Value::Array res;
    res.push_back(Value(s->camera.width));
    res.push_back(Value(s->camera.height));
    ab["resolution"] = Value(res);
    ab["ambient"] = vec(s->ambient, 3);
}

void gltf_extras_read_scene(const Value &ab, scene *s)
{
    double r[2];
    if (nums(ab, "resolution", r, 2, SCENE_MAX_RESOLUTION) == 2) {
        for (double x : r)
            if (!(x >= 1 && x == std::floor(x))) bad("resolution needs two whole numbers >= 1");
        s->camera.width = (int)r[0], s->camera.height = (int)r[1];
    }
    double a[3];
    int n = nums(ab, "ambient", a, 3, SCENE_MAX_COORD);
    if (n == 1) a[1] = a[2] = a[0];
    if (n)
        for (int c = 0; c < 3; ++c) {
            if (!(a[c] >= 0)) bad("ambient is negative");
            s->ambient[c] = a[c];
        }
}
