/* scene_select.c - material-table and adaptive scene materials -> explicit models through
 * abrdf_select (the paper's Fig. 2). The selection's trace is what --explain prints. */
#include <string.h>

#include "scene_select.h"
#include "cli_args.h"
#include "data_path.h"
#include "path_msg.h"
#include "render.h"
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
    for (int l = 0; l < m->lobe_count; ++l) {
        const abrdf_model_info *mi = abrdf_model_get(m->lobes[l]);
        for (int k = 0; k < mi->param_count; ++k)
            if (mi->params[k].id == id) return 1;
    }
    return 0;
}

static void take_rgb(const scene_material *m, const char *name, const double *src, double dst[3])
{
    if (described(m, name)) memcpy(dst, src, 3 * sizeof *dst);
}

int scene_select_materials(scene *s, const char *scene_name, const mat_table *table, int force_goal,
                           FILE *explain, char *err, size_t err_size)
{
    for (int i = 0; i < s->material_count; ++i) {
        scene_material *sm = &s->materials[i];
        if (sm->kind == SCENE_MAT_MODELS && force_goal < 0) continue;
        abrdf_goal goal = ABRDF_GOAL_PHOTOREAL; /* a bare table= entry renders photoreal */
        if (force_goal >= 0)
            goal = (abrdf_goal)force_goal;
        else if (sm->kind == SCENE_MAT_ADAPTIVE && abrdf_goal_find(sm->goal, &goal) != ABRDF_OK) {
            path_msg(err, err_size, scene_name, ":%d: unknown goal '%s'", sm->line, sm->goal);
            return -1;
        }
        abrdf_material am;
        abrdf_material_init(&am);
        const mat_entry *e = NULL;
        if (sm->table[0]) {
            e = table ? mat_table_find(table, sm->table) : NULL;
            if (!e) {
                const char *near[4];
                int k = table ? mat_table_nearest(table, sm->table, near, 4) : 0;
                char hint[256] = "";
                for (int j = 0; j < k; ++j) strcat(strcat(hint, j ? ", " : ""), near[j]);
                path_msg(err, err_size, scene_name,
                         ":%d: material '%s': no entry '%s' in the material table%s%s%s", sm->line,
                         sm->name, sm->table, k ? "; did you mean: " : "", hint,
                         k ? "?" : " (abrdf advise --list)");
                return -1;
            }
            am = e->m;
        }
        /* The file's values (or, for an explicit material, its lobes' values) describe it. */
        const abrdf_params *p = &sm->params;
        if (described(sm, "r")) am.r = p->r;
        if (described(sm, "n")) am.n = p->n;
        if (!e && !described(sm, "r") && !described(sm, "n")) {
            path_msg(err, err_size, scene_name,
                     ":%d: adaptive material '%s' needs table=ENTRY, r= or n=", sm->line, sm->name);
            return -1;
        }
        take_rgb(sm, "kd", p->kd, am.kd);
        take_rgb(sm, "ks", p->ks, am.ks);
        if (described(sm, "f0")) memcpy(am.f0, p->f0, sizeof am.f0), am.eta = -1.0;
        if (described(sm, "anisotropic")) am.anisotropy = p->anisotropic;
        abrdf_selection sel;
        abrdf_params chosen;
        select_trace trace = SELECT_TRACE_INIT;
        abrdf_selection_init(&sel);
        abrdf_params_init(ABRDF_MODEL_NONE, &chosen);
        if (abrdf_select(&am, goal, NULL, NULL, &sel, &chosen, explain ? select_trace_keep : NULL,
                         &trace) != ABRDF_OK) {
            path_msg(err, err_size, scene_name, ":%d: material '%s': %s", sm->line, sm->name,
                     sel.message);
            select_trace_free(&trace);
            return -1;
        }
        sm->kind = SCENE_MAT_MODELS;
        sm->lobe_count = 0;
        if (sel.diffuse != ABRDF_MODEL_NONE) sm->lobes[sm->lobe_count++] = sel.diffuse;
        sm->lobes[sm->lobe_count++] = sel.specular;
        sm->params = chosen;
        if (!sm->ka_given) {
            int kd_id, uses = 0;
            abrdf_param_find("kd", &kd_id);
            for (int l = 0; l < sm->lobe_count; ++l) {
                const abrdf_model_info *mi = abrdf_model_get(sm->lobes[l]);
                for (int k = 0; k < mi->param_count; ++k) uses |= mi->params[k].id == kd_id;
            }
            for (int c = 0; c < 3; ++c) sm->ka[c] = uses ? sm->params.kd[c] : 0.0;
        }
        if (explain) {
            fprintf(explain, "selection: material '%s' (line %d), goal %s%s%s: %s%s%s\n", sm->name,
                    sm->line, abrdf_goal_name(goal), e ? ", table entry " : "", e ? e->name : "",
                    sel.diffuse != ABRDF_MODEL_NONE ? abrdf_model_get(sel.diffuse)->name : "",
                    sel.diffuse != ABRDF_MODEL_NONE ? " + " : "",
                    abrdf_model_get(sel.specular)->name);
            for (int k = 0; k < trace.count; ++k)
                fprintf(explain, "  %2d. %s\n", k + 1, trace.steps[k].text);
        }
        select_trace_free(&trace);
    }
    return 0;
}

int scene_resolve(scene *s, const char *scene_name, const char *const *files, int nfiles,
                  int force_goal, FILE *explain, char *err, size_t err_size)
{
    mat_table table = {NULL, 0, 0};
    int rc = -1;
    if (force_goal >= 0 || scene_needs_table(s)) {
        char tpath[4096];
        if (data_path_find("materials.csv", tpath, sizeof tpath) != 0) {
            path_msg(err, err_size, tpath, ": material table not found (set ABRDF_DATA_DIR)");
            goto done;
        }
        if (mat_table_load(&table, tpath, err, err_size)) goto done;
    }
    for (int i = 0; i < nfiles; ++i)
        if (mat_table_load(&table, files[i], err, err_size)) goto done;
    rc = scene_select_materials(s, scene_name, &table, force_goal, explain, err, err_size);
done:
    mat_table_free(&table);
    return rc;
}

int scene_set_model(const char *cmd, scene *s, const char *model_name, const char **sets, int nsets)
{
    abrdf_model m;
    char err[512];
    if (cli_model(cmd, model_name, &m)) return CLI_EXIT_USAGE;
    if (render_set_model(s, m, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", cmd, err);
        return 1;
    }
    for (int i = 0; i < nsets; ++i)
        for (int j = 0; j < s->material_count; ++j)
            if (cli_set_param(cmd, m, &s->materials[j].params, sets[i])) return CLI_EXIT_USAGE;
    return 0;
}
