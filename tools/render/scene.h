/* scene.h - the parsed scene: the one description that the built-in renderer and the exporters
 * (POV-Ray SDL, Cycles bpy) all read. The text format is defined in docs/RENDERER.md, "Scene
 * format"; this header holds only what the file says, with units, and no derived data
 * (matrices, bounds and the effect plan belong to the renderer, render.h).
 *
 * World space is right-handed, y up. Angles in degrees. Colours are linear RGB.
 *
 * PUBLIC FUNCTIONS
 *   scene_parse_file    read and validate a scene file
 *   scene_parse_text    the same for text in memory (name is used in messages)
 *   scene_parse_materials  material lines alone (a material library)
 *   scene_free          release a parsed scene
 *   scene_shape_name, scene_tangent_name   names as the format spells them
 */
#ifndef ABRDF_SCENE_H
#define ABRDF_SCENE_H

#include <stddef.h>
#include "abrdf_pbr.h"
#include "abrdf_select.h"
#include "envmap.h"
#include "measured_table.h"
#include "mesh.h"
#include "pbr_select.h"

#define SCENE_NAME_MAX 64        /* material names, table entries, goals (with the NUL) */
#define SCENE_MAX_OBJECTS 100000 /* keeps a hostile file from exhausting memory */
#define SCENE_MAX_TRIANGLES MESH_MAX_TRIANGLES /* of all mesh objects together */
#define SCENE_MAX_MESH_FILES 1024              /* distinct files (each is read once) */
#define SCENE_MAX_MEASURED_FILES                                                                   \
    64 /* measured-BRDF files (each read once; 17.5 MB
                                                  a MERL table) */
#define SCENE_MAX_LIGHTS 64
#define SCENE_MAX_MATERIALS 256
#define SCENE_MAX_RESOLUTION 16384
#define SCENE_MAX_COORD 1e6 /* |coordinate|, size or scale: far from double trouble */

typedef struct scene_camera {
    double position[3]; /* eye point */
    double look_at[3];  /* point on the optical axis, != position */
    double up[3];       /* not parallel to look_at - position */
    double fov_deg;     /* full vertical field of view, (0, 180) */
    int width, height;  /* resolution in pixels, [1, SCENE_MAX_RESOLUTION] */
} scene_camera;

typedef enum scene_light_kind {
    SCENE_LIGHT_POINT = 0,
    SCENE_LIGHT_DIRECTIONAL,
    SCENE_LIGHT_SPHERE,     /* area light: a sphere of uniform radiance */
    SCENE_LIGHT_RECT,       /* area light: a one-sided rectangle of uniform radiance */
    SCENE_LIGHT_ENVIRONMENT /* radiance from every direction: a lat-long map (envmap.h) */
} scene_light_kind;

/* Point and directional lights are exact; the others are sampled (render.h, light.h). */
#define SCENE_LIGHT_SAMPLED(kind) ((kind) >= SCENE_LIGHT_SPHERE)

typedef struct scene_light {
    scene_light_kind kind;
    double position[3];  /* point light: its position; sphere, rectangle: the centre */
    double direction[3]; /* directional light: unit vector from the scene TOWARD the light */
    double color[3];     /* linear RGB, >= 0 */
    double intensity;    /* >= 0; point: irradiance intensity/d^2 at distance d; directional:
                             irradiance on a surface facing the light; sphere, rectangle,
                             environment: radiance color * intensity (times the map's) */
    double radius;       /* sphere: > 0 */
    double edge_u[3], edge_v[3]; /* rectangle: full edges, orthogonal, non-zero; it lights the
                                    side of edge_u x edge_v */
    envmap *env;                 /* environment: the map read from file= (owned by the scene) */
    int line;                    /* line of the definition, for messages */
} scene_light;

/* What the selection is asked for: the paper's flowchart for a goal, or its budget mode
 * (abrdf_select_budget: the cheapest candidate whose predicted image NMSE is below max_nmse;
 * its reference is the photoreal choice). */
typedef struct select_request {
    int by_budget;   /* 0: the flowchart for `goal`; 1: the budget mode */
    abrdf_goal goal; /* without a budget */
    double max_nmse; /* with a budget: in (0, 1] */
} select_request;

/* How a material chooses its models. */
typedef enum scene_material_kind {
    SCENE_MAT_MODELS = 0, /* explicit: one model, or a diffuse + specular pair */
    SCENE_MAT_TABLE,      /* a material-table entry; models chosen by abrdf_select (photoreal) */
    SCENE_MAT_ADAPTIVE    /* the selection picks the models for a goal (scene_select.h) */
} scene_material_kind;

#define SCENE_MAX_LOBES 2

/* A measured-BRDF file a material names (`measured=FILE`, docs/MEASURED.md): its table. */
typedef struct scene_measured {
    char *path;           /* as resolved from the scene's directory */
    const char *format;   /* the file's format, for messages ("MERL BRDF database") */
    measured_table table; /* owned */
} scene_measured;

/* The textures of a `pbr` material (glTF's, docs/GLTF.md, "In a scene"): what each multiplies. */
typedef enum scene_map_slot {
    SCENE_MAP_BASE_COLOR = 0, /* RGB times base_color; sRGB-encoded unless srgb = 0 (glTF) */
    SCENE_MAP_METALLIC,       /* one channel (glTF's packing: 2, blue) times metallic */
    SCENE_MAP_ROUGHNESS,      /* one channel (glTF's packing: 1, green) times roughness */
    SCENE_MAP_OCCLUSION,      /* one channel (0, red): the ambient term times 1 + s (o - 1) */
    SCENE_MAP_NORMAL,         /* tangent-space normal, RGB [0, 1] -> [-1, 1], xy times s */
    SCENE_MAP_COUNT
} scene_map_slot;

typedef struct scene_map {
    char *path; /* the image file, resolved from the scene's directory; NULL: no map. With a
                   blob: a name for messages only ("FILE.glb#image/N"), not a file to open */
    unsigned char *blob; /* an image embedded in a glTF file (a .glb buffer view or a data:
                            URI): the encoded file's bytes (PNG, JPEG...), owned; NULL: the
                            image is the file at path */
    size_t blob_size;    /* bytes of blob */
    char mime[32];       /* with a blob: its glTF mimeType ("image/png"), or "" if not given */
    int channel;         /* one-channel slots: the channel read, [0, 3] */
    int srgb;            /* base colour: 1 = the file holds sRGB-encoded values */
    double strength;     /* occlusion strength or normal scale (s above); 1 */
    int uv_set;          /* the mesh's texture coordinates it reads (glTF TEXCOORD_n); 0 */
    double offset[2];    /* KHR_texture_transform: uv' = offset + R(rotation) (scale * uv); 0 */
    double scale[2];     /* 1 */
    double rotation;     /* radians; 0 */
} scene_map;

typedef struct scene_material {
    char name[SCENE_NAME_MAX];
    scene_material_kind kind;
    int lobe_count; /* SCENE_MAT_MODELS: 1 (model=) or 2 (diffuse=, specular=) */
    abrdf_model lobes[SCENE_MAX_LOBES]; /* summed: f_r = lobes[0] + lobes[1] */
    abrdf_params params;           /* shared by the lobes; defaults of lobes[0], then lobes[1] */
    unsigned long long params_set; /* bit `id`: parameter id given in the file (ids < 64) */
    double ka[3];                  /* ambient reflectance: ambient term = ka * scene ambient */
    int ka_given;                  /* ka given in the file (else it follows kd) */
    char table[SCENE_NAME_MAX];    /* TABLE / ADAPTIVE: material table entry ("" if none) */
    int measured; /* a lobe is ABRDF_MEASURED: its table, an index into scene.measured; else -1 */
    select_request request; /* ADAPTIVE: its goal= or budget=, parsed */
    int line;
    /* `pbr` materials (glTF metallic-roughness, abrdf_pbr.h): pbr_in holds the factors; an
     * explicit one (SCENE_MAT_MODELS) has abrdf_pbr_lobes(&pbr_in) as lobes and params, an
     * ADAPTIVE one (goal= or budget=) is chosen from abrdf_pbr_material(&pbr_in). Textures
     * (maps) multiply the factors per shading point; textured = some map is given. */
    int pbr;
    abrdf_pbr pbr_in;
    /* A pbr material the budget mode chose over its roughness map (pbr_budget_range): the
     * chosen pair's fitted block at each group's roughness, ascending; scene_pbr_params
     * interpolates them for a shading point (fit_count 0: none). */
    int fit_count;
    double fit_r[PBR_BUDGET_GROUPS];
    abrdf_params fit_params[PBR_BUDGET_GROUPS];
    scene_map maps[SCENE_MAP_COUNT];
    int textured;
    /* Render huang per call even with render_options.hair_tables (abrdf bench --budget's
     * photoreal without tables, beside its tables). */
    int huang_per_call;
} scene_material;

typedef enum scene_shape {
    SCENE_SPHERE = 0, /* radius; centred at the origin */
    SCENE_CYLINDER,   /* radius, height; axis y, y in [-height/2, height/2], flat caps */
    SCENE_CAPSULE,    /* radius, height; segment y in [-height/2, height/2], round caps */
    SCENE_BOX,        /* size X,Y,Z; centred at the origin */
    SCENE_MESH,       /* triangles of a mesh file (scene.meshes), in the file's coordinates */
    SCENE_SHAPE_COUNT
} scene_shape;

/* Tangent field, in object space, projected onto the tangent plane at the hit point. */
typedef enum scene_tangent {
    SCENE_TANGENT_U = 0,  /* around the object's y axis: (-z, 0, x) */
    SCENE_TANGENT_V,      /* along the object's y axis: (0, 1, 0) */
    SCENE_TANGENT_RADIAL, /* away from the object's y axis: (x, 0, z) */
    SCENE_TANGENT_AXIS,   /* a fixed object-space direction (tangent_axis) */
    SCENE_TANGENT_UV      /* meshes with texture coordinates: the direction of increasing u */
} scene_tangent;

typedef struct scene_object {
    scene_shape shape;
    double radius;  /* sphere, cylinder, capsule; > 0 */
    double height;  /* cylinder, capsule; > 0 (capsule: >= 0, 0 is a sphere) */
    double size[3]; /* box: full extents; > 0 */
    /* object -> world: p_world = T * Rz * Ry * Rx * S * p_object (scale first, then rotate
     * about x, y, z in that order, then translate; POV-Ray's and Blender's XYZ order). */
    double scale[3]; /* > 0 */
    double rotate_deg[3];
    double translate[3];
    scene_tangent tangent;
    double tangent_axis[3];       /* SCENE_TANGENT_AXIS: non-zero object-space direction */
    int material;                 /* index into scene.materials */
    int mesh;                     /* SCENE_MESH: index into scene.meshes, else -1 */
    const struct mesh *mesh_data; /* SCENE_MESH: scene.meshes[mesh], else NULL */
    int smooth;                   /* SCENE_MESH: 1 interpolate vertex normals, 0 flat faces */
    int line;
} scene_object;

typedef struct scene {
    scene_camera camera;
    double ambient[3]; /* Ia, linear RGB; the ambient term is ka * Ia */
    scene_light *lights;
    int light_count;
    scene_material *materials;
    int material_count;
    scene_object *objects;
    int object_count;
    mesh **meshes;            /* the mesh files, each read once however many objects use it */
    scene_measured *measured; /* the measured-BRDF files of `measured=`, each read once */
    int measured_count;
    int mesh_count;
    long long triangle_count; /* of all mesh objects, <= SCENE_MAX_TRIANGLES */
    char **buffer_files;      /* the files a glTF file's buffers were read from (.bin), owned */
    int buffer_file_count;
    char *notes; /* what the reader assumed or left out (a glTF file's defaults and ignored
                    features), one line each ending in '\n', owned; NULL: nothing to say */
} scene;

/* Parse; on failure returns -1, frees everything and writes "NAME:LINE: problem" to err; a
 * problem inside a mesh file is "MESHFILE:LINE: problem (mesh at NAME:LINE)". Mesh files
 * (`mesh file=PATH`) are read relative to the directory of NAME. */
int scene_parse_file(const char *path, scene *out, char *err, size_t err_size);
int scene_parse_text(const char *name, const char *text, size_t len, scene *out, char *err,
                     size_t err_size);
/* A list of material lines alone (no camera, light or object; at least one material): the
 * materials of a MaterialX document as `abrdf advise` reads them. Errors as above; paths in
 * the lines are resolved against the directory of name. */
int scene_parse_materials(const char *name, const char *text, size_t len, scene *out, char *err,
                          size_t err_size);
void scene_free(scene *s);
/* The files the scene names - its mesh files, then its environment maps, its measured files,
 * its materials' textures and a glTF file's buffer files, as they were read - with their
 * roles ("mesh file", "environment map", "measured file", "texture", "buffer file"): at most
 * max into paths/roles (NULL roles: not wanted). Returns how many the scene names (it may be
 * more than max). */
int scene_named_files(const scene *s, const char **paths, const char **roles, int max);
/* Refuse outputs that are files the scene names (out_files_distinct: links included):
 * 0, or -1 with one line in err. */
int scene_outputs_distinct(const scene *s, const char *const *outputs,
                           const char *const *output_roles, int nout, char *err, size_t err_size);

/* The parameters of material sm at a shading point whose pbr inputs (its factors times the
 * texels there) are q: sm's block with what abrdf_pbr_lobes maps q to (kd, ks, f0, r,
 * anisotropic), and n from r (abrdf_alpha_g_to_n of r^2) where sm's lobes read n (the
 * performance goal's Blinn-Phong); sm's block itself for sm's own factors where sm has no
 * base colour, metallic or roughness map (a normal or occlusion map only: a budget's fitted
 * stand-in as chosen). A
 * budget choice over a roughness map (fit_count > 0) takes instead the fitted blocks of the
 * two groups around q's roughness, interpolated (linearly; an exponent n geometrically), its
 * kd scaled by the ratio of q's mapped kd to the groups', its ks by the ratio of the mapped
 * f0 (the specular's normal reflectance). 0, or -1 if q is out of its ranges. */
int scene_pbr_params(const scene_material *sm, const abrdf_pbr *q, abrdf_params *out);

/* A `pbr` material's maps with their defaults (no file; glTF's channels, sRGB base colour,
 * strength 1, identity transform), pbr_in at glTF's defaults. */
void scene_pbr_init(scene_material *m);
/* A `pbr` material (pbr_in and maps set) completed as the scene format completes it: kind
 * SCENE_MAT_MODELS unless already ADAPTIVE, lobes and params from abrdf_pbr_lobes, ka from
 * kd unless ka_given, textured from the maps. 0, or -1 with abrdf_pbr_check's message. */
int scene_pbr_finish(scene_material *m, char *msg, size_t msg_size);
/* Free a material's map paths and blobs. */
void scene_material_free(scene_material *m);

const char *scene_shape_name(scene_shape shape);
const char *scene_map_name(scene_map_slot slot); /* "base_color", ... as `KEY_map=` spells it */
const char *scene_tangent_name(scene_tangent tangent);

#endif
