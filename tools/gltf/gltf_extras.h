// gltf_extras.h - what abrdf writes into glTF `extras.abrdf` and reads back exactly
// (docs/GLTF.md, "Writing glTF"): on a material its explicit models with the parameters they
// read (the rest at the first model's defaults) and its ambient reflectance ka; on a node the
// analytic shape or a mesh's shading, its transform and tangent field; on the scene the
// resolution and the ambient light. Other viewers ignore extras and see the glTF proper
// beside them. C++ only (between gltf_read.cpp and gltf_write.cpp); a malformed value throws
// std::runtime_error naming it.
#ifndef ABRDF_GLTF_EXTRAS_H
#define ABRDF_GLTF_EXTRAS_H

#include <tiny_gltf.h>

extern "C" {
#include "scene.h"
}

// writing
void gltf_extras_models(const scene_material *sm, tinygltf::Value::Object &ab);
void gltf_extras_object(const scene_object *o, tinygltf::Value::Object &ab);
void gltf_extras_scene_write(const scene *s, tinygltf::Value::Object &ab);

// reading: a material's models (returns 1 if it has them: sm is then explicit, not pbr) and
// ka; a node's object (returns 1 for an analytic shape, 0 for a mesh; sets the transform,
// tangent field and the shape's fields or smooth); the scene's resolution and ambient.
int gltf_extras_material(const tinygltf::Value &ab, scene_material *sm);
int gltf_extras_read_object(const tinygltf::Value &ab, scene_object *o);
void gltf_extras_read_scene(const tinygltf::Value &ab, scene *s);

#endif
