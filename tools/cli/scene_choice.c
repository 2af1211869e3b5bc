/* scene_choice.c - the options render and export share (scene_choice.h). */
#include <string.h>

#include "budget_run.h"
#include "cli_args.h"
#include "map_range.h"
#include "scene_choice.h"
#include "scene_select.h"

void scene_choice_init(scene_choice *c)
{
    memset(c, 0, sizeof *c);
    c->how = (scene_selection)SCENE_SELECTION_INIT;
    c->how.tables = c->mats;
    c->how.map_range = map_range_read; /* a roughness map's values (map_range.h) */
    c->how.points = 1;                 /* a budget predicts on the scene's shading points */
}

int scene_choice_option(scene_choice *c, const char *cmd, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (!strcmp(a, "--adaptive")) {
        c->how.forced = 1;
        return 1;
    }
    const char **slot = !strcmp(a, "--model")    ? &c->model_name
                        : !strcmp(a, "--goal")   ? &c->goal
                        : !strcmp(a, "--budget") ? &c->budget
                                                 : NULL;
    int set = !strcmp(a, "--set"), mats = !strcmp(a, "--materials");
    if (!slot && !set && !mats) return 0;
    if (*i + 1 >= argc) {
        cli_fail(cmd, "%s needs a value", a);
        return -1;
    }
    const char *val = argv[++*i];
    if (slot) {
        *slot = val;
    } else if (set) {
        if (c->nsets == SCENE_CHOICE_MAX_SETS) {
            cli_fail(cmd, "too many --set options (%d at most)", SCENE_CHOICE_MAX_SETS);
            return -1;
        }
        c->sets[c->nsets++] = val;
    } else {
        if (c->how.table_count == SCENE_CHOICE_MAX_FILES) {
            cli_fail(cmd, "too many --materials files (%d at most)", SCENE_CHOICE_MAX_FILES);
            return -1;
        }
        c->mats[c->how.table_count++] = val;
    }
    return 1;
}

int select_request_budget(select_request *rq, const char *cmd, const char *text)
{
    char err[256];
    if (budget_parse(text, &rq->max_nmse, err, sizeof err))
        return cli_fail(cmd, "--budget: %s", err);
    rq->by_budget = 1;
    return 0;
}

int scene_choice_check(scene_choice *c, const char *cmd)
{
    int adaptive = c->how.forced;
    select_request *rq = &c->how.all;
    if (adaptive && c->model_name)
        return cli_fail(cmd, "--adaptive and --model exclude each other");
    if (c->goal && !adaptive) return cli_fail(cmd, "--goal needs --adaptive");
    if (c->budget && !adaptive) return cli_fail(cmd, "--budget needs --adaptive");
    if (c->budget && c->goal)
        return cli_fail(cmd, "--goal and --budget exclude each other (a budget's reference is "
                             "the photoreal choice)");
    if (c->budget && select_request_budget(rq, cmd, c->budget)) return CLI_EXIT_USAGE;
    if (c->nsets && !c->model_name)
        return cli_fail(cmd, "--set needs --model (the scene file sets materials' parameters)");
    abrdf_model m;
    if (c->model_name && abrdf_model_find(c->model_name, &m) == ABRDF_OK &&
        (abrdf_model_get(m)->needs & ABRDF_NEEDS_TABLE))
        return cli_fail(cmd,
                        "--model %s: %s reads a table: name it in the scene (material NAME "
                        "measured=FILE)",
                        c->model_name, c->model_name);
    if (adaptive && !c->budget && (!c->goal || abrdf_goal_find(c->goal, &rq->goal) != ABRDF_OK))
        return cli_fail(cmd, "--adaptive needs --goal photoreal, --goal performance or --budget B");
    return 0;
}

int scene_choice_apply(scene_choice *c, const char *cmd, scene *s, const char *scene_path, int spp,
                       FILE *explain)
{
    char err[1024];
    c->how.spp = spp;
    if (scene_resolve(s, scene_path, &c->how, explain, err, sizeof err)) {
        fprintf(stderr, "abrdf %s: %s\n", cmd, err);
        return 1;
    }
    return c->model_name ? scene_set_model(cmd, s, c->model_name, c->sets, c->nsets) : 0;
}
