/* scene_select.c - material-table and adaptive scene materials -> explicit models through
 * abrdf_select (the paper's Fig. 2) or its budget mode (abrdf_select_budget, predicted on
 * each material's own shading points in the scene, scene_points.h, or on a sphere under the
 * scene's lights and camera). The selection's trace is what --explain prints. */
#include <math.h>
#include <string.h>

#include "scene_select.h"
#include "cli_args.h"
#include "data_path.h"
#include "path_msg.h"
#include "render.h"
#include "budget_run.h"
#include "param_effect.h"
#include "scene_points.h"
#include "select_trace.h"

int scene_needs_table(const scene *s)
{
    for (int i = 0; i < s->material_count; ++i)
        if (s->materials[i].table[0]) return 1;
    return 0;
}

/* Is parameter `name` given in the file, or read by one of the material's lobes (then its
 * value, default or not, describes the material)? */
static int described(const scene_material *m, const char *name)
{
    int id;
    if (abrdf_param_find(name, &id) != ABRDF_OK) return 0;
    if (id < 64 && (m->params_set >> id) & 1u) return 1;
    for (int l = 0; l < m->lobe_count; ++l)
        if (cli_model_reads(m->lobes[l], id)) return 1;
    return 0;
}

static void take_rgb(const scene_material *m, const char *name, const double *src, double dst[3])
{
    if (described(m, name)) memcpy(dst, src, 3 * sizeof *dst);
}

/* ka: the ambient reflectance follows kd when a lobe of `lobes` reads kd (and the file gave
 * none). */
static void ka_from(scene_material *sm, const abrdf_model *lobes, int count, const abrdf_params *p)
{
    if (sm->ka_given) return;
    int kd_id, uses = 0;
    abrdf_param_find("kd", &kd_id);
    for (int l = 0; l < count; ++l) uses |= cli_model_reads(lobes[l], kd_id);
    for (int c = 0; c < 3; ++c) sm->ka[c] = uses ? p->kd[c] : 0.0;
}

/* The parameters that describe the material to the selection (abrdf_material's fields). */
static int describes(const char *name)
{
    static const char *const keys[] = {"r",  "n",           "kd",      "ks",
                                       "f0", "anisotropic", "melanin", "redness"};
    for (size_t k = 0; k < sizeof keys / sizeof *keys; ++k)
        if (!strcmp(name, keys[k])) return 1;
    return 0;
}

/* The material the selection sees: the table entry's (or the defaults), with the values the
 * file gives (or, for an explicit material, its lobes' values) over it. */
static void describe(const scene_material *sm, const abrdf_params *p, abrdf_material *am)
{
    if (described(sm, "r")) am->r = p->r;
    if (described(sm, "n")) am->n = p->n;
    take_rgb(sm, "kd", p->kd, am->kd);
    take_rgb(sm, "ks", p->ks, am->ks);
    if (described(sm, "f0")) memcpy(am->f0, p->f0, sizeof am->f0), am->eta = -1.0;
    if (described(sm, "anisotropic")) am->anisotropy = p->anisotropic;
    if (described(sm, "melanin")) am->melanin = p->melanin;
    if (described(sm, "redness")) am->redness = p->redness;
}

/* The models and block abrdf_select chooses for the material sm describes with block p over
 * the entry (NULL: the defaults); 0, or -1 if it refuses. */
static int select_for(const scene_material *sm, const abrdf_material *entry, const abrdf_params *p,
                      abrdf_goal goal, abrdf_model lobes[2], int *count, abrdf_params *chosen)
{
    abrdf_material am;
    abrdf_material_init(&am);
    if (entry) am = *entry;
    describe(sm, p, &am);
    abrdf_selection sel;
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, chosen);
    if (abrdf_select(&am, goal, NULL, NULL, &sel, chosen, NULL, NULL) != ABRDF_OK) return -1;
    *count = 0;
    if (sel.diffuse != ABRDF_MODEL_NONE) lobes[(*count)++] = sel.diffuse;
    lobes[(*count)++] = sel.specular;
    return 0;
}

/* Each selection input the file gives (r, kd, ...) must change the reflectance the selection
 * chooses (for a budget, its reference: the photoreal choice): the material is selected with
 * the value and with another value, and the two reflectances compared (param_effect.h).
 * 0, or -1 with the reason in msg. */
static int selection_inputs(const scene_material *sm, const abrdf_material *entry, abrdf_goal goal,
                            char *msg, size_t msg_size)
{
    abrdf_model la[2], lb[2];
    abrdf_params pa, pb, nudged;
    int na, nb;
    if (select_for(sm, entry, &sm->params, goal, la, &na, &pa)) return 0; /* reported elsewhere */
    for (int id = 0; id < 64 && id < abrdf_param_count(); ++id) {
        const abrdf_param_info *pi = abrdf_param_get(id);
        if (!((sm->params_set >> id) & 1u) || !describes(pi->name)) continue;
        int matters = 0;
        for (int dir = 1; dir >= -1 && !matters; dir -= 2)
            matters = !param_nudge(&sm->params, id, dir, &nudged) &&
                      (select_for(sm, entry, &nudged, goal, lb, &nb, &pb) || /* it changes that */
                       lobes_differ(la, na, &pa, lb, nb, &pb));
        if (!matters) {
            snprintf(msg, msg_size,
                     "%s changes nothing in what the selection chooses for it (%s%s%s); drop it",
                     pi->name, na > 1 ? abrdf_model_get(la[0])->name : "", na > 1 ? " + " : "",
                     abrdf_model_get(la[na - 1])->name);
            return -1;
        }
    }
    return 0;
}

/* Every other parameter the file gives takes effect on the chosen models: in their block
 * where one of them reads it; where none does, a table or adaptive material refuses it
 * (strict), while an explicit material whose models a forced selection replaced keeps only
 * what the new models read. 0, or -1 with the reason in msg. */
static int file_params(const scene_material *sm, abrdf_params *chosen, int strict, char *msg,
                       size_t msg_size)
{
    for (int id = 0; id < 64 && id < abrdf_param_count(); ++id) {
        if (!((sm->params_set >> id) & 1u)) continue;
        const abrdf_param_info *pi = abrdf_param_get(id);
        if (describes(pi->name)) continue; /* taken into the selection's material */
        int read = 0;
        for (int l = 0; l < sm->lobe_count; ++l) read |= cli_model_reads(sm->lobes[l], id);
        if (read) {
            double v[3];
            int n = abrdf_param_read(&sm->params, id, v);
            if (n > 0) abrdf_param_set(chosen, id, v, n);
            if (strict && !param_matters(sm->lobes, sm->lobe_count, chosen, id)) {
                snprintf(msg, msg_size,
                         "%s changes nothing in the reflectance of the chosen model%s here (e.g. "
                         "a layer past layer_count); drop it",
                         pi->name, sm->lobe_count > 1 ? "s" : "");
                return -1;
            }
        } else if (strict) {
            snprintf(msg, msg_size,
                     "%s is not read by the chosen model%s %s%s%s; give it with a model that "
                     "reads it (model=...)",
                     pi->name, sm->lobe_count > 1 ? "s" : "", abrdf_model_get(sm->lobes[0])->name,
                     sm->lobe_count > 1 ? " + " : "",
                     sm->lobe_count > 1 ? abrdf_model_get(sm->lobes[1])->name : "");
            return -1;
        }
    }
    return 0;
}

/* Whether a and b agree on every parameter model reads. */
static int same_params(abrdf_model model, const abrdf_params *a, const abrdf_params *b)
{
    const abrdf_model_info *mi = abrdf_model_get(model);
    for (int k = 0; k < mi->param_count; ++k) {
        double x[3] = {0, 0, 0}, y[3] = {0, 0, 0};
        int n = abrdf_param_read(a, mi->params[k].id, x);
        abrdf_param_read(b, mi->params[k].id, y);
        for (int c = 0; c < n; ++c)
            if (!(x[c] == y[c])) return 0;
    }
    return 1;
}

void scene_budget_view(const scene *s, int spp, abrdf_view *v, abrdf_light_dir *lights)
{
    abrdf_view_init(v);
    const scene_camera *c = &s->camera;
    double d2c = 0.0;
    for (int k = 0; k < 3; ++k) {
        v->view_dir[k] = c->position[k] - c->look_at[k];
        d2c += v->view_dir[k] * v->view_dir[k];
    }
    memcpy(v->up, c->up, sizeof v->up);
    /* samples across a unit sphere at the camera's target: its diameter 2 over the view's
     * height 2 d tan(fov / 2), times the image's rows and sqrt(spp) */
    double across = c->height * sqrt(spp > 0 ? (double)spp : 1.0) /
                    (sqrt(d2c) * tan(0.5 * c->fov_deg * 3.14159265358979323846 / 180.0));
    v->resolution = (int)fmin(1024.0, fmax(16.0, floor(across + 0.5)));
    int n = 0;
    for (int l = 0; l < s->light_count && n < SCENE_MAX_LIGHTS; ++l) {
        const scene_light *L = &s->lights[l];
        double d[3], d2 = 1.0, area = 1.0; /* area: a sampled light's radiance -> E at d = 1 */
        if (L->kind == SCENE_LIGHT_ENVIRONMENT) continue; /* no direction to stand for it */
        if (L->kind == SCENE_LIGHT_DIRECTIONAL) {
            memcpy(d, L->direction, sizeof d);
        } else { /* point, sphere, rectangle: from its centre, over d^2 */
            for (int k = 0; k < 3; ++k) d[k] = L->position[k] - c->look_at[k];
            d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            if (!(d2 > 0.0)) continue;
        }
        if (L->kind == SCENE_LIGHT_SPHERE) area = 3.14159265358979323846 * L->radius * L->radius;
        if (L->kind == SCENE_LIGHT_RECT) { /* its area seen from the target, one-sided */
            const double *u = L->edge_u, *v = L->edge_v;
            double nrm[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]};
            area = -(nrm[0] * d[0] + nrm[1] * d[1] + nrm[2] * d[2]) / sqrt(d2);
            if (!(area > 0.0)) continue; /* the target is behind it */
        }
        memcpy(lights[n].dir, d, sizeof d);
        for (int k = 0; k < 3; ++k) lights[n].e[k] = L->color[k] * L->intensity * area / d2;
        ++n;
    }
    v->light_count = n;
    v->lights = lights;
}

/* The table entry sm names (NULL if it names none): 0, or -1 with the message, naming the
 * nearest entries, when the table has no such entry. */
static int entry_of(const scene_material *sm, const mat_table *table, const char *scene_name,
                    const mat_entry **out, char *err, size_t err_size)
{
    *out = NULL;
    if (!sm->table[0]) return 0;
    *out = table ? mat_table_find(table, sm->table) : NULL;
    if (*out) return 0;
    const char *near[4];
    int k = table ? mat_table_nearest(table, sm->table, near, 4) : 0;
    char hint[256] = "";
    for (int j = 0; j < k; ++j) strcat(strcat(hint, j ? ", " : ""), near[j]);
    path_msg(err, err_size, scene_name,
             ":%d: material '%s': no entry '%s' in the material table%s%s%s", sm->line, sm->name,
             sm->table, k ? "; did you mean: " : "", hint, k ? "?" : " (abrdf advise --list)");
    return -1;
}

/* The budget mode for am against huang's table when the photoreal choice is huang alone
 * (scene_selection.hair_tables; hair_store_budget) and sm's line sets no parameter of huang's
 * beyond what am describes (file_params would make the rendered block another than the
 * table's), else against the photoreal choice as abrdf_prepare makes it; budget_run's
 * contract. */
static int choose_to_table(const scene_material *sm, const abrdf_material *am,
                           const select_request *rq, const abrdf_view *view, hair_store *tables,
                           budget_result *out, char *msg, size_t msg_size)
{
    abrdf_selection ps;
    abrdf_params pp, with_file;
    abrdf_selection_init(&ps);
    abrdf_params_init(ABRDF_MODEL_NONE, &pp);
    scene_material as_chosen = *sm; /* file_params reads the lobes it is given */
    as_chosen.lobe_count = 1;
    as_chosen.lobes[0] = ABRDF_HUANG;
    int photoreal_ok = abrdf_select(am, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &ps, &pp, NULL, NULL);
    with_file = pp;
    if (photoreal_ok == ABRDF_OK && !file_params(&as_chosen, &with_file, 0, msg, msg_size) &&
        same_params(ABRDF_HUANG, &pp, &with_file)) {
        char what[160];
        snprintf(what, sizeof what, "material '%s' (line %d)", sm->name, sm->line);
        int done =
            hair_store_budget(tables, am, rq->max_nmse, NULL, view, what, out, msg, msg_size);
        if (done) return done > 0 ? 0 : -1;
    }
    return budget_run(am, rq->max_nmse, NULL, view, out, msg, msg_size);
}

/* What the selection chooses for am as rq asks: the flowchart's choice for a goal (its trace
 * kept with keep_trace), the budget mode's, predicted on view, for a budget (its trace always:
 * the reference's step is in it). 0, or -1 with the reason in msg; out is freed by
 * budget_result_free either way. */
static int choose(const scene_material *sm, const abrdf_material *am, const select_request *rq,
                  const abrdf_view *view, int keep_trace, hair_store *tables, budget_result *out,
                  char *msg, size_t msg_size)
{
    if (rq->by_budget && tables)
        return choose_to_table(sm, am, rq, view, tables, out, msg, msg_size);
    if (rq->by_budget) return budget_run(am, rq->max_nmse, NULL, view, out, msg, msg_size);
    memset(out, 0, sizeof *out);
    out->trace = (select_trace)SELECT_TRACE_INIT;
    abrdf_selection_init(&out->sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &out->params);
    if (abrdf_select(am, rq->goal, NULL, NULL, &out->sel, &out->params,
                     keep_trace ? select_trace_keep : NULL, &out->trace) != ABRDF_OK) {
        snprintf(msg, msg_size, "%s", out->sel.message);
        return -1;
    }
    return 0;
}

/* sm's ambient reflectance after the choice c: a budget's is the reference's (the photoreal
 * choice), so that the budget changes only the reflectance the fit approximates. */
static void ambient_of(scene_material *sm, const select_request *rq, const budget_result *c)
{
    if (!rq->by_budget) {
        ka_from(sm, sm->lobes, sm->lobe_count, &sm->params);
        return;
    }
    for (int k = 0; k < c->trace.count; ++k) {
        const abrdf_select_step *st = &c->trace.steps[k];
        if (st->kind != ABRDF_STEP_REFERENCE) continue;
        abrdf_model rl[2];
        int rn = 0;
        if (st->diffuse != ABRDF_MODEL_NONE) rl[rn++] = st->diffuse;
        rl[rn++] = st->model;
        ka_from(sm, rl, rn, st->params);
    }
}

static void explain_choice(FILE *f, const scene_material *sm, const select_request *rq,
                           const mat_entry *e, const budget_result *c, const char *pred)
{
    char asked[64];
    if (rq->by_budget)
        snprintf(asked, sizeof asked, "budget NMSE < %g", rq->max_nmse);
    else
        snprintf(asked, sizeof asked, "goal %s", abrdf_goal_name(rq->goal));
    abrdf_model d = c->sel.diffuse;
    fprintf(f, "selection: material '%s' (line %d), %s%s%s: %s%s%s\n", sm->name, sm->line, asked,
            e ? ", table entry " : "", e ? e->name : "",
            d != ABRDF_MODEL_NONE ? abrdf_model_get(d)->name : "",
            d != ABRDF_MODEL_NONE ? " + " : "", abrdf_model_get(c->sel.specular)->name);
    if (rq->by_budget) fprintf(f, "  prediction: %s\n", pred);
    for (int k = 0; k < c->trace.count; ++k)
        fprintf(f, "  %2d. %s\n", k + 1, c->trace.steps[k].text);
}

/* The choice over sm's roughness map (pbr_select.h) as rq asks, into sm. 0, or -1 with the
 * reason in msg. */
static int select_pbr_range(scene_material *sm, const select_request *rq,
                            const scene_selection *how, const abrdf_view *view, const char *pred,
                            FILE *explain, char *msg, size_t msg_size)
{
    if (!how->map_range) {
        snprintf(msg, msg_size,
                 "its roughness map cannot be read here: the selection needs "
                 "the map's values");
        return -1;
    }
    pbr_range range;
    if (how->map_range(how->map_user, sm, &range, msg, msg_size)) return -1;
    select_trace trace = SELECT_TRACE_INIT;
    abrdf_model d, sp;
    abrdf_params params;
    char asked[64];
    if (rq->by_budget) {
        pbr_budget_choice c;
        if (pbr_budget_range(&sm->pbr_in, &range, rq->max_nmse, NULL, view, &c, &trace, msg,
                             msg_size))
            return -1;
        d = c.diffuse, sp = c.specular, params = c.params;
        /* a fitted stand-in: its fit per group, for each texel (scene_pbr_params); the
         * reference itself (NMSE 0) or the photoreal fallback is the mapping, per texel */
        sm->fit_count = c.within && c.nmse > 0 ? c.groups : 0;
        for (int k = 0; k < sm->fit_count; ++k)
            sm->fit_r[k] = c.group_r[k], sm->fit_params[k] = c.group_params[k];
        snprintf(asked, sizeof asked, "budget NMSE < %g", rq->max_nmse);
    } else {
        abrdf_selection sel;
        if (pbr_select_range(&sm->pbr_in, &range, rq->goal, NULL, NULL, &sel, &params, &trace, msg,
                             msg_size))
            return -1;
        d = sel.diffuse, sp = sel.specular;
        snprintf(asked, sizeof asked, "goal %s", abrdf_goal_name(rq->goal));
    }
    sm->kind = SCENE_MAT_MODELS;
    sm->lobe_count = 0;
    if (d != ABRDF_MODEL_NONE) sm->lobes[sm->lobe_count++] = d;
    sm->lobes[sm->lobe_count++] = sp;
    sm->params = params;
    ka_from(sm, sm->lobes, sm->lobe_count, &sm->params);
    if (explain) {
        fprintf(explain, "selection: material '%s' (line %d), %s over its roughness map: %s%s%s\n",
                sm->name, sm->line, asked, d != ABRDF_MODEL_NONE ? abrdf_model_get(d)->name : "",
                d != ABRDF_MODEL_NONE ? " + " : "", abrdf_model_get(sp)->name);
        if (rq->by_budget) fprintf(explain, "  prediction: %s\n", pred);
        for (int k = 0; k < trace.count; ++k)
            fprintf(explain, "  %2d. %s\n", k + 1, trace.steps[k].text);
    }
    select_trace_free(&trace);
    return 0;
}

/* A `pbr` material (glTF metallic-roughness) as rq asks: the selection reads the material
 * abrdf_pbr_material makes of its factors, or, with a roughness map, of each value of the
 * map (select_pbr_range). 0, or -1 with the message in err. */
static int select_pbr(scene_material *sm, const char *scene_name, const select_request *rq,
                      const scene_selection *how, const abrdf_view *view, const char *pred,
                      FILE *explain, char *err, size_t err_size)
{
    abrdf_material am;
    abrdf_material_init(&am);
    char msg[512];
    budget_result c;
    if (sm->maps[SCENE_MAP_ROUGHNESS].path) {
        if (select_pbr_range(sm, rq, how, view, pred, explain, msg, sizeof msg)) goto fail;
        return 0;
    }
    if (abrdf_pbr_material(&sm->pbr_in, &am) != ABRDF_OK) {
        abrdf_pbr_check(&sm->pbr_in, msg, sizeof msg);
        goto fail;
    }
    am.name = sm->name;
    if (choose(sm, &am, rq, view, explain != NULL, NULL, &c, msg, sizeof msg)) goto fail;
    sm->kind = SCENE_MAT_MODELS;
    sm->lobe_count = 0;
    if (c.sel.diffuse != ABRDF_MODEL_NONE) sm->lobes[sm->lobe_count++] = c.sel.diffuse;
    sm->lobes[sm->lobe_count++] = c.sel.specular;
    sm->params = c.params;
    ambient_of(sm, rq, &c);
    if (explain) explain_choice(explain, sm, rq, NULL, &c, pred);
    budget_result_free(&c);
    return 0;
fail:
    path_msg(err, err_size, scene_name, ":%d: material '%s': %s", sm->line, sm->name, msg);
    return -1;
}

/* Material sm as rq asks (scene_select): 0, or -1 with the message in err. */
static int select_material(scene_material *sm, int used, const char *scene_name,
                           const select_request *rq, const scene_selection *how,
                           const mat_table *table, const abrdf_view *view, const char *pred,
                           FILE *explain, char *err, size_t err_size)
{
    const mat_entry *e;
    if (sm->measured >= 0) {
        path_msg(err, err_size, scene_name,
                 ":%d: material '%s' is measured: the selection chooses from a material's "
                 "parameters; for a table, abrdf advise --measured FILE --budget B",
                 sm->line, sm->name);
        return -1;
    }
    if (sm->pbr) return select_pbr(sm, scene_name, rq, how, view, pred, explain, err, err_size);
    if (entry_of(sm, table, scene_name, &e, err, err_size)) return -1;
    if (!e && !described(sm, "r") && !described(sm, "n")) {
        path_msg(err, err_size, scene_name,
                 ":%d: adaptive material '%s' needs table=ENTRY, r= or n=", sm->line, sm->name);
        return -1;
    }
    abrdf_material am;
    abrdf_material_init(&am);
    if (e) am = e->m;
    describe(sm, &sm->params, &am);
    char msg[512];
    int explicit_models = sm->kind == SCENE_MAT_MODELS;
    if (!explicit_models &&
        selection_inputs(sm, e ? &e->m : NULL, rq->by_budget ? ABRDF_GOAL_PHOTOREAL : rq->goal, msg,
                         sizeof msg))
        goto fail;
    budget_result c;
    hair_store *tables = how->hair_tables && used && !sm->textured ? how->hair_tables : NULL;
    if (choose(sm, &am, rq, view, explain != NULL, tables, &c, msg, sizeof msg)) goto fail;
    sm->kind = SCENE_MAT_MODELS;
    sm->lobe_count = 0;
    if (c.sel.diffuse != ABRDF_MODEL_NONE) sm->lobes[sm->lobe_count++] = c.sel.diffuse;
    sm->lobes[sm->lobe_count++] = c.sel.specular;
    if (file_params(sm, &c.params, !explicit_models, msg, sizeof msg)) {
        budget_result_free(&c);
        goto fail;
    }
    sm->params = c.params;
    ambient_of(sm, rq, &c);
    if (explain) explain_choice(explain, sm, rq, e, &c, pred);
    budget_result_free(&c);
    return 0;
fail:
    path_msg(err, err_size, scene_name, ":%d: material '%s': %s", sm->line, sm->name, msg);
    return -1;
}

/* The request that chooses material sm (NULL: it keeps its models). */
static const select_request *request_of(const scene_material *sm, const scene_selection *how)
{
    static const select_request photoreal = {0, ABRDF_GOAL_PHOTOREAL, 0.0};
    return how->forced                      ? &how->all
           : sm->kind == SCENE_MAT_ADAPTIVE ? &sm->request
           : sm->kind == SCENE_MAT_TABLE    ? &photoreal /* a bare table= */
                                            : NULL;
}

/* A budget over a roughness map predicts per value of the map on the sphere (pbr_select.h). */
static int by_map(const scene_material *sm)
{
    return sm->pbr && sm->maps[SCENE_MAP_ROUGHNESS].path;
}

/* The view material i's budget is predicted on, and what it is in words (pred): its shading
 * points when how->points and it has some, else the sphere. */
static const abrdf_view *view_for(const scene *s, int i, const scene_points *pts,
                                  const abrdf_view *sphere, abrdf_view *own, char *pred,
                                  size_t pred_size)
{
    const char *sph = "on the sphere (scene_budget_view: the scene's camera and lights)";
    if (!pts) {
        snprintf(pred, pred_size, "%s", sph);
        return sphere;
    }
    if (by_map(&s->materials[i])) {
        snprintf(pred, pred_size, "%s, per value of its roughness map", sph);
        return sphere;
    }
    char left[128] = "", every[64] = "every pixel";
    int nmap = s->materials[i].maps[SCENE_MAP_NORMAL].path != NULL;
    if (pts->sampled_lights)
        snprintf(left, sizeof left, "; the scene's %d sampled light%s left out",
                 pts->sampled_lights, pts->sampled_lights > 1 ? "s" : "");
    if (!scene_points_view(pts, i, own)) {
        char why[160];
        if (pts->pixels[i] == 0)
            snprintf(why, sizeof why, "the camera sees it at no pixel centre");
        else if (pts->hits[i] == 0)
            snprintf(why, sizeof why,
                     "no camera sample of the %d of its %d pixels the pass kept sees its front",
                     pts->kept[i], pts->pixels[i]);
        else
            snprintf(why, sizeof why,
                     "no point or directional light reaches its points the camera sees in the %d "
                     "of its %d pixels the pass kept",
                     pts->kept[i], pts->pixels[i]);
        snprintf(pred, pred_size, "%s: %s%s%s", sph, why, left,
                 nmap ? "; its normal map left out (the sphere's own normals)" : "");
        return sphere;
    }
    if (pts->stride[i] > 1)
        snprintf(every, sizeof every, "one in every %d of its pixels, in scan order",
                 pts->stride[i] * pts->stride[i]);
    snprintf(pred, pred_size,
             "on the scene's shading points: %d of the %d pixels it covers at %d x %d (%s, %d "
             "samples each), %d light terms%s%s",
             pts->samples[i], pts->pixels[i], pts->width, pts->height, every, pts->spp,
             pts->term_count[i], nmap ? ", on the normals of its normal map" : "", left);
    return own;
}

int scene_select(scene *s, const char *scene_name, const scene_selection *how,
                 const mat_table *table, FILE *explain, char *err, size_t err_size)
{
    abrdf_light_dir lights[SCENE_MAX_LIGHTS];
    abrdf_view view, own;
    scene_budget_view(s, how->spp, &view, lights);
    scene_points pts;
    int traced = 0, rc = 0;
    for (int i = 0; i < s->material_count && how->points && !traced; ++i) {
        const select_request *rq = request_of(&s->materials[i], how);
        if (rq && rq->by_budget && !by_map(&s->materials[i])) {
            char msg[512];
            if (scene_points_trace(s, how->spp, &pts, msg, sizeof msg)) {
                path_msg(err, err_size, scene_name, ": the shading points of the budget: %s", msg);
                return -1;
            }
            traced = 1;
        }
    }
    for (int i = 0; i < s->material_count && !rc; ++i) {
        scene_material *sm = &s->materials[i];
        const select_request *rq = request_of(sm, how);
        char pred[512];
        const abrdf_view *v = view_for(s, i, traced ? &pts : NULL, &view, &own, pred, sizeof pred);
        int used = 0; /* an object shows it: only then is a huang table worth its build */
        for (int j = 0; j < s->object_count && !used; ++j) used = s->objects[j].material == i;
        if (rq &&
            select_material(sm, used, scene_name, rq, how, table, v, pred, explain, err, err_size))
            rc = -1;
    }
    if (traced) scene_points_free(&pts);
    return rc;
}

int scene_resolve(scene *s, const char *scene_name, const scene_selection *how, FILE *explain,
                  char *err, size_t err_size)
{
    mat_table table = {NULL, 0, 0};
    int rc = -1;
    if (how->forced || scene_needs_table(s)) {
        char tpath[4096];
        if (data_path_find("materials.csv", tpath, sizeof tpath) != 0) {
            path_msg(err, err_size, tpath, ": material table not found (set ABRDF_DATA_DIR)");
            goto done;
        }
        if (mat_table_load(&table, tpath, err, err_size)) goto done;
    }
    for (int i = 0; i < how->table_count; ++i)
        if (mat_table_load(&table, how->tables[i], err, err_size)) goto done;
    rc = scene_select(s, scene_name, how, &table, explain, err, err_size);
done:
    mat_table_free(&table);
    return rc;
}

int scene_replace_models(scene *s, abrdf_model model, char *err, size_t err_size)
{
    const abrdf_model_info *mi = abrdf_model_get(model);
    if (!mi) {
        snprintf(err, err_size, "unknown model id %d", (int)model);
        return -1;
    }
    if (mi->needs & ABRDF_NEEDS_TABLE) {
        snprintf(err, err_size,
                 "%s reads a table: name it in the scene (material NAME "
                 "measured=FILE)",
                 mi->name);
        return -1;
    }
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *m = &s->materials[i];
        abrdf_params p;
        abrdf_params_init(model, &p);
        for (int k = 0; k < mi->param_count; ++k) {
            int id = mi->params[k].id, shared = 0;
            for (int l = 0; l < m->lobe_count; ++l) shared |= cli_model_reads(m->lobes[l], id);
            double v[3];
            int cnt;
            if (shared && (cnt = abrdf_param_read(&m->params, id, v)) > 0)
                abrdf_param_set(&p, id, v, cnt); /* out of the new model's range: keep default */
        }
        char msg[256];
        if (abrdf_params_check(model, &p, msg, sizeof msg) != ABRDF_OK) {
            snprintf(err, err_size, "material '%s' as %s: %s", m->name, mi->name, msg);
            return -1;
        }
        m->kind = SCENE_MAT_MODELS;
        m->lobe_count = 1;
        m->lobes[0] = model;
        m->params = p;
        m->measured = -1; /* a measured material replaced: its table is no longer read */
    }
    return 0;
}

int scene_set_model(const char *cmd, scene *s, const char *model_name, const char *const *sets,
                    int nsets)
{
    abrdf_model m;
    char err[512];
    if (cli_model(cmd, model_name, &m)) return CLI_EXIT_USAGE;
    if (scene_replace_models(s, m, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", cmd, err);
        return 1;
    }
    for (int i = 0; i < nsets; ++i)
        for (int j = 0; j < s->material_count; ++j)
            if (cli_set_param(cmd, m, &s->materials[j].params, sets[i])) return CLI_EXIT_USAGE;
    return 0;
}
