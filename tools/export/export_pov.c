/* export_pov.c - the scene as POV-Ray SDL through abrdf.inc (export_pov.h). */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "export_pov.h"
#include "export_text.h"

/* POV-Ray's left-handed world: z negated. */
static void vec(FILE *f, const double v[3], double scale)
{
    fprintf(f, "<%.17g, %.17g, %.17g>", scale * v[0], scale * v[1], -scale * v[2]);
}

static void upper(char *dst, const char *src, size_t size)
{
    size_t i = 0;
    for (; src[i] && i + 1 < size; ++i) dst[i] = (char)toupper((unsigned char)src[i]);
    dst[i] = '\0';
}

static int material(FILE *f, int index, const scene_material *sm, const render_material *m,
                    char *err, size_t err_size)
{
    char id[64];
    upper(id, abrdf_model_get(m->lobes[0])->name, sizeof id);
    fputs("// material '", f);
    pov_comment(f, sm->name);
    fprintf(f, "'\n#declare Abrdf_Mat_%d = Abrdf_Default(ABRDF_ID_%s);\n", index, id);
    if (m->lobe_count > 1) {
        upper(id, abrdf_model_get(m->lobes[1])->name, sizeof id);
        fprintf(f, "#declare Abrdf_Mat_%d[1] = ABRDF_ID_%s;\n", index, id);
    }
    /* every parameter a lobe reads, by its symbolic slot */
    for (int l = 0; l < m->lobe_count; ++l) {
        const abrdf_model_info *mi = abrdf_model_get(m->lobes[l]);
        for (int k = 0; k < mi->param_count; ++k) {
            const abrdf_param_info *pi = abrdf_param_get(mi->params[k].id);
            double v[3];
            int n = abrdf_param_read(&m->params, mi->params[k].id, v);
            upper(id, pi->name, sizeof id);
            for (int c = 0; c < n; ++c)
                fprintf(f, "#declare Abrdf_Mat_%d[ABRDF_SLOT_%s + %d] = %.17g;\n", index, id, c,
                        v[c]);
        }
    }
    /* The name reaches POV-Ray's messages as a string: escaped, or refused. */
    char what[SCENE_NAME_MAX + 16];
    snprintf(what, sizeof what, "material '%s'", sm->name);
    fprintf(f, "Abrdf__Check(Abrdf_Mat_%d, ", index);
    if (pov_string(f, what)) {
        snprintf(err, err_size,
                 "material name '%s' (line %d) cannot be a POV-Ray string: printable ASCII only",
                 sm->name, sm->line);
        return -1;
    }
    fputs(")\n", f);
    return 0;
}

/* A scene's materials each have at most one table, and the macros hold this many. */
typedef char export_pov_tables_fit[EXPORT_POV_HUANG_TABLES_MAX >= SCENE_MAX_MATERIALS ? 1 : -1];

/* A tabulated material reads its table (abrdf_huang.inc, Abrdf_Huang_Table), which refuses
 * it for a material edited since the table was built: the parameters it was built for. */
static int material_table(FILE *f, int index, const render_material *m,
                          const export_pov_options *opt, char *err, size_t err_size)
{
    const double *v = opt->hair_tables ? hair_store_table(opt->hair_tables, &m->params) : NULL;
    const char *name = opt->table_files ? opt->table_files[index] : NULL;
    if (!v || !name) {
        snprintf(err, err_size, "material %d: no huang table to export", index);
        return -1;
    }
    const abrdf_params *p = &m->params;
    const int *sz = opt->hair_tables->sizes;
    fprintf(f,
            "#declare Abrdf_Mat_%d_Built = array[8] {%.17g, %.17g, %.17g, %.17g, %.17g, %.17g, "
            "%d, %d}\n#declare Abrdf_Mat_%d = Abrdf_Huang_Table(Abrdf_Mat_%d, ",
            index, p->eta, p->melanin, p->redness, p->cuticle_tilt, p->aspect_ratio, p->r,
            p->entry_grid, p->internal_grid, index, index);
    if (pov_string(f, name)) {
        snprintf(err, err_size, "huang table '%s' cannot be a POV-Ray string: printable ASCII only",
                 name);
        return -1;
    }
    fprintf(f, ", %d, %d, %d, %.17g, Abrdf_Mat_%d_Built)\n", sz[0], sz[1], sz[2],
            export_pov_table_scale(v, sz), index);
    return 0;
}

/* The half float nearest x (|x| below 65504): 11 significant bits, or multiples of 2^-24
 * below 2^-14; ties to even, as rint rounds. */
static double half_nearest(double x)
{
    int e;
    frexp(x, &e); /* |x| in [2^(e-1), 2^e) */
    double q = ldexp(1.0, (e - 1 >= -14 ? e : -13) - 11);
    return q * rint(x / q);
}

double export_pov_table_scale(const double *values, const int sizes[4])
{
    const long n = 3L * sizes[0] * sizes[1] * sizes[0] * sizes[2];
    double top = 0.0;
    for (long i = 0; i < n; ++i) top = fmax(top, values[HAIR_STORE_HEADER + i]);
    int e = 0;
    if (top > 0.0) frexp(32768.0 / top, &e); /* 32768 / top in [2^(e-1), 2^e) */
    return ldexp(1.0, top > 0.0 ? e - 1 : 0);
}

int export_pov_table_image(const double *values, const int sizes[4], float **rgb, int *width,
                           int *height)
{
    const int nt = sizes[0], nv = sizes[1], np = sizes[2];
    const long n = (long)nt * nv * nt * np;
    const double *v = values + HAIR_STORE_HEADER, scale = export_pov_table_scale(values, sizes);
    *width = nt * np, *height = 3 * nt * nv;
    float *x = malloc((size_t)n * 9 * sizeof *x);
    if (!(*rgb = x)) return -1;
    /* node (row r = iv nv + jv, column il np + kd) at r * width + column: the table's order */
    for (int c = 0; c < 3; ++c)
        for (long i = 0; i < n; ++i) {
            double s = v[3 * i + c] * scale, hi = half_nearest(s);
            float *t = x + 3 * ((long)c * n + i);
            t[0] = (float)hi, t[1] = (float)half_nearest(s - hi), t[2] = 0.0f;
        }
    return 0;
}

/* ---- meshes ----------------------------------------------------------------------- */

/* 9 significant digits: the float a mesh holds survives the text exactly. */
static void fvec(FILE *f, const float *v) { fprintf(f, "<%.9g, %.9g, %.9g>", v[0], v[1], v[2]); }

/* The mesh2 of mesh file `index` in object space (the object's matrix mirrors z, as for the
 * analytic shapes): with its corner normals (smooth) or without (flat faces); with `eval`,
 * uv coordinates that tell the uv-mapped pigment of Abrdf_Mesh_Texture the triangle k and
 * the barycentric weights (abrdf_shading.inc). */
static void pov_mesh2(FILE *f, const mesh *m, int index, int smooth, int eval)
{
    int nt = m->triangle_count;
    fputs("// ", f);
    pov_comment(f, m->path); /* a file name is data: escaped (export_text.h) */
    fprintf(f, ": %d triangles\n#declare Abrdf_Mesh_%d_%s = mesh2 {\n  vertex_vectors { %d", nt,
            index, smooth ? "Smooth" : "Flat", m->vertex_count);
    for (int i = 0; i < m->vertex_count; ++i) fputs(",\n    ", f), fvec(f, m->position + 3 * i);
    fputs(" }\n", f);
    if (smooth) {
        fprintf(f, "  normal_vectors { %d", m->normal_count);
        for (int i = 0; i < m->normal_count; ++i) fputs(",\n    ", f), fvec(f, m->normal + 3 * i);
        fputs(" }\n", f);
    }
    if (eval) {
        fprintf(f, "  uv_vectors { %d", 3 * nt);
        for (int k = 0; k < nt; ++k)
            fprintf(f, ",\n    <0, %d.5>, <1, %d.5>, <0, %d.5>", 2 * k, 2 * k, 2 * k + 1);
        fputs(" }\n", f);
    }
    fprintf(f, "  face_indices { %d", nt);
    for (int k = 0; k < nt; ++k)
        fprintf(f, ",\n    <%d, %d, %d>", m->tri[3 * k], m->tri[3 * k + 1], m->tri[3 * k + 2]);
    fputs(" }\n", f);
    if (eval) {
        fprintf(f, "  uv_indices { %d", nt);
        for (int k = 0; k < nt; ++k) fprintf(f, ",\n    <%d, %d, %d>", 3 * k, 3 * k + 1, 3 * k + 2);
        fputs(" }\n", f);
    }
    if (smooth) {
        fprintf(f, "  normal_indices { %d", nt);
        for (int k = 0; k < nt; ++k)
            fprintf(f, ",\n    <%d, %d, %d>", m->tri_normal[3 * k], m->tri_normal[3 * k + 1],
                    m->tri_normal[3 * k + 2]);
        fputs(" }\n", f);
    }
    fputs("}\n", f);
}

/* The per-triangle data Abrdf_Mesh_Texture reads: spline functions of the triangle index
 * (corners, corner normals, uv tangent), knots at 0 .. n-1 and a copy of the last at n. */
static void pov_mesh_data(FILE *f, const mesh *m, int index)
{
    static const char *const names[7] = {"P0", "P1", "P2", "N0", "N1", "N2", "T"};
    int nt = m->triangle_count;
    for (int q = 0; q < 7; ++q) {
        fprintf(f, "#declare Abrdf_Mesh_%d_%s = function { spline { linear_spline", index,
                names[q]);
        for (int k = 0; k <= nt; ++k) {
            int t = k < nt ? k : nt - 1;
            float v[3] = {0, 0, 0};
            if (q < 3) {
                memcpy(v, m->position + 3 * m->tri[3 * t + q], sizeof v);
            } else if (q < 6) {
                memcpy(v, m->normal + 3 * m->tri_normal[3 * t + q - 3], sizeof v);
            } else if (m->tri_uv) { /* dP/du of the triangle, as geom_tangent_uv */
                const float *p[3], *uv[3];
                for (int c = 0; c < 3; ++c)
                    p[c] = m->position + 3 * m->tri[3 * t + c],
                    uv[c] = m->uv + 2 * m->tri_uv[3 * t + c];
                double du1 = (double)uv[1][0] - uv[0][0], dv1 = (double)uv[1][1] - uv[0][1];
                double du2 = (double)uv[2][0] - uv[0][0], dv2 = (double)uv[2][1] - uv[0][1];
                double det = du1 * dv2 - du2 * dv1;
                for (int i = 0; i < 3 && det != 0; ++i)
                    v[i] = (float)((dv2 * ((double)p[1][i] - p[0][i]) -
                                    dv1 * ((double)p[2][i] - p[0][i])) /
                                   det);
            }
            fprintf(f, "%s%d, ", k % 4 ? " " : "\n  ", k);
            fvec(f, v);
            fputc(k < nt ? ',' : ' ', f);
        }
        fputs("} }\n", f);
    }
    fprintf(f, "#declare Abrdf_Mesh_%d_Data = array[7] {", index);
    for (int q = 0; q < 7; ++q) fprintf(f, "%sAbrdf_Mesh_%d_%s", q ? ", " : "", index, names[q]);
    fputs("}\n", f);
}

/* The arguments after M of Abrdf_Shaded_Texture and Abrdf_Mesh_Texture: tangent rule, eye,
 * lights, ambient and Lit; with passes, those of the pass povray was given (pov_passes). */
static void eval_args(FILE *f, const scene_object *o, const double a[3],
                      const export_pov_options *opt)
{
    fprintf(f, "    array[4] {%d, %.17g, %.17g, %.17g}, Abrdf_Eye, %s,\n", (int)o->tangent,
            o->tangent_axis[0], o->tangent_axis[1], o->tangent_axis[2],
            opt->passes ? "Abrdf_Pass_Lights" : "Abrdf_Lights");
    fprintf(f, "    <%.17g, %.17g, %.17g>%s, %s)\n", a[0], a[1], a[2],
            opt->passes ? " * Abrdf_Ambient_On" : "",
            opt->passes ? "Abrdf_Lit"
            : opt->lit  ? "true"
                        : "false");
}

/* A mesh object: its mesh2 under the texture (evaluation or native) and the transform. */
static void pov_mesh_object(FILE *f, const scene_object *o, const render_material *m,
                            const export_pov_options *opt)
{
    double a[3] = {0, 0, 0};
    if (m->use_ambient) memcpy(a, m->ambient, sizeof a);
    fprintf(f, "object { Abrdf_Mesh_%d_%s\n", o->mesh, o->smooth ? "Smooth" : "Flat");
    if (opt->native) {
        fprintf(f, "  Abrdf_Native_Texture(Abrdf_Mat_%d, <%.17g, %.17g, %.17g>)\n", o->material,
                a[0], a[1], a[2]);
    } else {
        fprintf(f, "  Abrdf_Mesh_Texture(Abrdf_Mat_%d, Abrdf_Mesh_%d_Data, %s, Abrdf_M,\n",
                o->material, o->mesh, o->smooth ? "true" : "false");
        eval_args(f, o, a, opt);
    }
    fputs("  Abrdf_Xform_Matrix(Abrdf_M) }\n", f);
}

/* Every mesh file some object uses, in the variants the objects need. */
static void pov_meshes(FILE *f, const scene *s, int eval)
{
    for (int i = 0; i < s->mesh_count; ++i) {
        int smooth = 0, flat = 0;
        for (int k = 0; k < s->object_count; ++k)
            if (s->objects[k].shape == SCENE_MESH && s->objects[k].mesh == i)
                smooth |= s->objects[k].smooth, flat |= !s->objects[k].smooth;
        if (smooth) pov_mesh2(f, s->meshes[i], i, 1, eval);
        if (flat) pov_mesh2(f, s->meshes[i], i, 0, eval);
        if ((smooth || flat) && eval) pov_mesh_data(f, s->meshes[i], i);
    }
}

/* One light as POV-Ray's light_source: white (the pigment holds E), or carrying E (native). */
static void light_source(FILE *f, const render_light *lt, int native, double extent)
{
    double e[3] = {1, 1, 1};
    if (native) memcpy(e, lt->e, sizeof e);
    fprintf(f, "light_source { ");
    if (lt->kind == SCENE_LIGHT_POINT) {
        vec(f, lt->position, 1);
        fprintf(f, " color rgb <%.17g, %.17g, %.17g> }\n", e[0], e[1], e[2]);
    } else {
        /* far beyond the scene: POV-Ray's parallel light shadows up to its location */
        vec(f, lt->direction, 1e6 * fmax(extent, 1.0));
        fprintf(f, " color rgb <%.17g, %.17g, %.17g> parallel point_at <0, 0, 0> }\n", e[0], e[1],
                e[2]);
    }
}

/* The row of Abrdf_Lights for one light: {kind, position or direction, E}. */
static void light_row(FILE *f, const render_light *lt)
{
    const double *p = lt->kind == SCENE_LIGHT_POINT ? lt->position : lt->direction;
    fprintf(f, "{%d, %.17g, %.17g, %.17g, %.17g, %.17g, %.17g}",
            lt->kind == SCENE_LIGHT_POINT ? 0 : 1, p[0], p[1], -p[2], lt->e[0], lt->e[1], lt->e[2]);
}

/* Passes: povray given Declare=Abrdf_Pass=k renders light k alone through its light_source (shadows)
 * and the ambient term in pass 0 only, so the passes' images sum to the scene's; without
 * Abrdf_Pass every light is summed in the pigment without shadows. The objects read
 * Abrdf_Pass_Lights, Abrdf_Lit and Abrdf_Ambient_On. */
static void pov_passes(FILE *f, const render_scene *rs, double extent)
{
    int n = rs->light_count;
    fprintf(f,
            "#declare Abrdf_Pass_Count = %d;\n"
            "#ifdef (Abrdf_Pass)\n"
            "  #if (Abrdf_Pass != int(Abrdf_Pass) | Abrdf_Pass < 0 | Abrdf_Pass >= "
            "Abrdf_Pass_Count)\n"
            "    #error concat(\"Abrdf_Pass = \", str(Abrdf_Pass, 0, -1), \" is not a light: "
            "render with Declare=Abrdf_Pass=k, k = 0 .. %d\\n\")\n"
            "  #end\n"
            "  #declare Abrdf_Lit = true;\n"
            "  #declare Abrdf_Ambient_On = (Abrdf_Pass = 0);\n"
            "  #switch (Abrdf_Pass)\n",
            n, n - 1);
    for (int l = 0; l < n; ++l) {
        fprintf(f, "  #case (%d)\n    #declare Abrdf_Pass_Lights = array[1][7] {", l);
        light_row(f, &rs->lights[l]);
        fputs("}\n    ", f);
        light_source(f, &rs->lights[l], 0, extent);
        fputs("  #break\n", f);
    }
    fprintf(f, "  #end\n"
               "#else\n"
               "  #warning \"no Abrdf_Pass: every light without shadows; for shadows render "
               "once per light with Declare=Abrdf_Pass=k and sum the images (docs/POVRAY.md)\\n\"\n"
               "  #declare Abrdf_Lit = false;\n"
               "  #declare Abrdf_Ambient_On = 1;\n"
               "  #declare Abrdf_Pass_Lights = Abrdf_Lights;\n"
               "#end\n");
}

/* What POV-Ray cannot render as the built-in renderer does, or options that do not fit the
 * scene: 0, or -1 with the reason in err. */
static int pov_refuse(const render_scene *rs, const export_pov_options *opt, char *err,
                      size_t err_size)
{
    const scene *s = rs->src;
    for (int l = 0; l < s->light_count; ++l)
        if (SCENE_LIGHT_SAMPLED(s->lights[l].kind)) {
            snprintf(err, err_size,
                     "light at line %d: sphere, rect and environment lights are not exported to "
                     "POV-Ray (its area_light is a grid of point lights, not a surface of "
                     "uniform radiance); render them with abrdf render or export to Cycles",
                     s->lights[l].line);
            return -1;
        }
    if (opt->lit && rs->light_count != 1) {
        snprintf(err, err_size,
                 "POV-Ray's own shadows need exactly one light (the scene has %d); "
                 "export without them",
                 rs->light_count);
        return -1;
    }
    if (opt->passes && (opt->lit || opt->native || rs->light_count < 2)) {
        snprintf(err, err_size,
                 "passes render one light each: they need two lights or more (the scene has "
                 "%d) and function pigments (not --native)",
                 rs->light_count);
        return -1;
    }
    for (int l = 0; opt->native && l < rs->light_count; ++l)
        if (rs->lights[l].kind == SCENE_LIGHT_POINT) {
            snprintf(err, err_size,
                     "--native: POV-Ray's light fading is 2 / (1 + (d/D)^p), never the "
                     "1/d^2 of a point light; export without --native");
            return -1;
        }
    return 0;
}

/* The file's opening comments (how to render it, the shading, the notes), the settings,
 * includes and the camera. */
static void pov_head(FILE *f, const render_scene *rs, const export_pov_options *opt)
{
    fputs("// ", f);
    pov_comment(f, opt->source);
    fputs(" - exported by `abrdf export --pov` (docs/POVRAY.md).\n", f);
    fprintf(f,
            "// Render linear HDR without antialiasing, e.g. with k x k supersampling:\n"
            "//   povray +I<this file> +O<out>.exr +FE +W%d +H%d -A +L<abrdf>/povray_macros\n"
            "// and average k x k pixel blocks (k = 1 here): the samples are those of\n"
            "// `abrdf render --spp k*k` (stratum centres).\n",
            rs->width, rs->height);
    fprintf(
        f, "// Shading: %s\n",
        opt->native ? "POV-Ray's own finishes (abrdf_native.inc), its lights and shadows."
        : opt->lit  ? "function pigments; POV-Ray's light_source and shadow test (one light)."
        : opt->passes
            ? "function pigments; one pass per light with POV-Ray's light_source and\n"
              "// shadow test. Render each pass k = 0 .. N-1 (N lights) with\n"
              "//   povray ... Declare=Abrdf_Pass=k +O<out>_k.exr\n"
              "// and sum them: oiiotool <out>_0.exr <out>_1.exr --add ... -o <out>.exr\n"
              "// (pass 0 holds the ambient term). Without Declare=Abrdf_Pass the file renders\n"
              "// every light emissively, without shadows."
            : "function pigments, emissive: each pigment sums every light unoccluded "
              "(no shadows).");
    if (opt->passes)
        fprintf(f, "// Passes: k = 0 .. %d (%d lights).\n", rs->light_count - 1, rs->light_count);
    int tables = 0;
    for (int i = 0; opt->table_files && i < rs->material_count; ++i)
        tables |= !!opt->table_files[i];
    if (tables)
        fputs(
            "// huang tables: the .exr files this file names (Abrdf_Huang_Table), written beside\n"
            "// it: render from its directory, or add +L<its directory>.\n",
            f);
    if (opt->notes) pov_comment_lines(f, opt->notes);
    fprintf(
        f,
        "#version 3.7;\nglobal_settings { assumed_gamma 1 ambient_light %d max_trace_level 1 }\n",
        opt->native ? 1 : 0);
    fprintf(f,
            "#include \"abrdf.inc\"\n#include \"abrdf_shading.inc\"  // shapes, transforms\n%s\n",
            opt->native ? "#include \"abrdf_native.inc\"\n" : "");
    fprintf(f, "#declare Abrdf_Eye = ");
    vec(f, rs->eye, 1);
    fprintf(f, ";\ncamera { perspective location Abrdf_Eye\n  direction ");
    vec(f, rs->forward, 1);
    fprintf(f, "\n  right ");
    vec(f, rs->right, 2); /* render.h: right/up span half the image plane */
    fprintf(f, "\n  up ");
    vec(f, rs->up, 2);
    fprintf(f, " }\n\n");
}

/* The lights' table the pigments read, and POV-Ray's light_source (lit, native) or the
 * passes. */
static void pov_lights(FILE *f, const render_scene *rs, const export_pov_options *opt)
{
    double extent = rs->eps / 1e-9; /* render.c: eps = 1e-9 * scene size */
    fprintf(f, "#declare Abrdf_Lights = array[%d][7] {\n",
            rs->light_count > 0 ? rs->light_count : 1);
    for (int l = 0; l < rs->light_count; ++l) {
        fputs("  ", f);
        light_row(f, &rs->lights[l]);
        fputs(l + 1 < rs->light_count ? ",\n" : "\n", f);
    }
    if (rs->light_count == 0) fprintf(f, "  {1, 0, 1, 0, 0, 0, 0}  // no light: a black one\n");
    fprintf(f, "}\n");
    /* Lit: the pigment holds E, the light is white; native: the light carries E. */
    for (int l = 0; (opt->lit || opt->native) && l < rs->light_count; ++l)
        light_source(f, &rs->lights[l], opt->native, extent);
    if (opt->passes) pov_passes(f, rs, extent);
}

/* Object i: its transform, then its shape with the native finish or the function pigment
 * (a mesh by pov_mesh_object). */
static void pov_object(FILE *f, const render_scene *rs, int i, const export_pov_options *opt)
{
    static const char *shapes[] = {"sphere", "cylinder", "capsule", "box", "mesh"};
    const scene_object *o = &rs->src->objects[i];
    const geom_object *g = &rs->objects[i];
    const render_material *m = &rs->materials[o->material];
    fprintf(f, "// %s, scene line %d\n#declare Abrdf_M = array[12] {", shapes[o->shape], o->line);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c)
            fprintf(f, "%.17g%s", r == 2 ? -g->xf.m[r][c] : g->xf.m[r][c],
                    r == 2 && c == 3 ? "" : ", ");
    fprintf(f, "}\n");
    if (o->shape == SCENE_MESH) {
        pov_mesh_object(f, o, m, opt);
        return;
    }
    double dims[3] = {o->radius, o->height, 0};
    if (o->shape == SCENE_BOX) memcpy(dims, o->size, sizeof dims);
    fprintf(f, "object { Abrdf_Shape(\"%s\", <%.17g, %.17g, %.17g>)\n", shapes[o->shape], dims[0],
            dims[1], dims[2]);
    if (opt->native) {
        fprintf(f, "  Abrdf_Native_Texture(Abrdf_Mat_%d, <%.17g, %.17g, %.17g>)\n", o->material,
                m->use_ambient ? m->ambient[0] : 0.0, m->use_ambient ? m->ambient[1] : 0.0,
                m->use_ambient ? m->ambient[2] : 0.0);
        fprintf(f, "  Abrdf_Xform_Matrix(Abrdf_M) }\n");
        return;
    }
    fprintf(f, "  Abrdf_Shaded_Texture(Abrdf_Mat_%d, \"%s\", <%.17g, %.17g, %.17g>, Abrdf_M,\n",
            o->material, shapes[o->shape], dims[0], dims[1], dims[2]);
    double a[3] = {0, 0, 0};
    if (m->use_ambient) memcpy(a, m->ambient, sizeof a);
    eval_args(f, o, a, opt);
    fprintf(f, "  Abrdf_Xform_Matrix(Abrdf_M) }\n");
}

int export_pov_write(const render_scene *rs, const export_pov_options *opt, FILE *f, char *err,
                     size_t err_size)
{
    const scene *s = rs->src;
    if (pov_refuse(rs, opt, err, err_size)) return -1;
    pov_head(f, rs, opt);
    pov_lights(f, rs, opt);
    fprintf(f, "\n");
    for (int i = 0; i < rs->material_count; ++i)
        if (rs->materials[i].used &&
            (material(f, i, &s->materials[i], &rs->materials[i], err, err_size) ||
             (rs->materials[i].tabulated &&
              material_table(f, i, &rs->materials[i], opt, err, err_size))))
            return -1;
    fprintf(f, "\n");
    pov_meshes(f, s, !opt->native);
    for (int i = 0; i < rs->object_count; ++i) pov_object(f, rs, i, opt);
    return ferror(f) ? (snprintf(err, err_size, "write error"), -1) : 0;
}
