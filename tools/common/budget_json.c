/* budget_json.c - the budget mode's result as JSON (budget_run.h): what `abrdf advise
 * MATERIAL --budget CLASS --json` and `--pareto --json` print, and the browser explorer returns
 * (tools/web). */
#include <math.h>
#include <stdio.h>

#include "budget_run.h"
#include "cli_args.h"
#include "metrics.h"

static const char *name_or_null(abrdf_model m)
{
    const abrdf_model_info *i = abrdf_model_get(m);
    return i ? i->name : NULL;
}

static void json_model(FILE *f, abrdf_model m)
{
    const char *n = name_or_null(m);
    if (n)
        cli_json_string(f, n);
    else
        fprintf(f, "null");
}

static void json_num(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.10g", v);
    else
        fprintf(f, "null");
}

const char *budget_class_name(double max)
{
    static const char *const names[3] = {"none", "slight", "noticeable"};
    const double *c = abrdf_select_rules_get()->nmse_class_max;
    for (int i = 0; i < 3; ++i)
        if (max == c[i]) return names[i];
    return NULL;
}

const abrdf_select_step *budget_reference_step(const budget_result *r)
{
    for (int i = 0; i < r->trace.count; ++i)
        if (r->trace.steps[i].kind == ABRDF_STEP_REFERENCE) return &r->trace.steps[i];
    return NULL;
}

void budget_json(FILE *f, const budget_result *r, const char *material, double max_nmse,
                 const abrdf_select_step *const *cand, int n, const int *front, int nf, int pareto)
{
    const abrdf_select_step *ref = budget_reference_step(r);
    const char *bc = budget_class_name(max_nmse);
    fprintf(f, "{\"material\": ");
    if (material)
        cli_json_string(f, material);
    else
        fprintf(f, "null");
    fprintf(f, ", \"type\": \"%s\", \"budget\": {\"max_nmse\": %.10g, \"class\": ",
            abrdf_surface_name(r->sel.type), max_nmse);
    if (bc && !pareto)
        fprintf(f, "\"%s\"", bc);
    else
        fprintf(f, "null");
    fprintf(f, "},\n \"reference\": {\"diffuse\": ");
    json_model(f, ref ? ref->diffuse : ABRDF_MODEL_NONE);
    fprintf(f, ", \"specular\": ");
    json_model(f, ref ? ref->model : ABRDF_MODEL_NONE);
    fprintf(f, ", \"cost\": ");
    json_num(f, ref ? ref->cost : NAN);
    fprintf(f, ", \"prepared\": %s", r->prepared ? "true" : "false");
    fprintf(f, "},\n \"diffuse\": ");
    json_model(f, r->sel.diffuse);
    fprintf(f, ", \"specular\": ");
    json_model(f, r->sel.specular);
    fprintf(f, ", \"params\": ");
    budget_params_json(f, r->sel.diffuse, r->sel.specular, &r->params);
    fprintf(f, ",\n \"error\": {\"nmse_pred\": ");
    json_num(f, r->sel.err_nmse);
    fprintf(f, ", \"class\": \"%s\", \"rel_pct\": ", abrdf_nmse_class(r->sel.err_nmse));
    json_num(f, r->sel.err_rel_pct);
    fprintf(f, ", \"abs\": ");
    json_num(f, r->sel.err_abs);
    fprintf(f, "},\n \"cost\": {\"total\": ");
    json_num(f, r->sel.cost_total);
    fprintf(f, ", \"unit\": ");
    cli_json_string(f, r->sel.cost_unit ? r->sel.cost_unit : "");
    fprintf(f, "}, \"seconds\": %.3f,\n \"candidates\": [", r->seconds);
    for (int i = 0; i < n; ++i) {
        int on_front = 0;
        for (int k = 0; k < nf; ++k) on_front |= front[k] == i;
        fprintf(f, "%s\n  {\"diffuse\": ", i ? "," : "");
        json_model(f, cand[i]->diffuse);
        fprintf(f, ", \"specular\": ");
        json_model(f, cand[i]->model);
        fprintf(f, ", \"params\": ");
        budget_params_json(f, cand[i]->diffuse, cand[i]->model, cand[i]->params);
        fprintf(f, ", \"nmse_pred\": ");
        json_num(f, cand[i]->value);
        fprintf(f, ", \"class\": \"%s\", \"rel_l2\": ", abrdf_nmse_class(cand[i]->value));
        json_num(f, cand[i]->value2);
        fprintf(f, ", \"cost\": ");
        json_num(f, cand[i]->cost >= 0.0 ? cand[i]->cost : NAN);
        fprintf(f, ", \"within\": %s, \"pareto\": %s}", cand[i]->passed ? "true" : "false",
                on_front ? "true" : "false");
    }
    fprintf(f, "\n], \"trace\": [");
    for (int i = 0; i < r->trace.count; ++i) {
        const abrdf_select_step *t = &r->trace.steps[i];
        fprintf(f, "%s\n  {\"step\": \"%s\", \"model\": ", i ? "," : "", abrdf_step_name(t->kind));
        json_model(f, t->model);
        fprintf(f, ", \"diffuse\": ");
        json_model(f, t->diffuse);
        fprintf(f, ", \"value\": ");
        json_num(f, t->value);
        fprintf(f, ", \"threshold\": ");
        json_num(f, t->threshold);
        fprintf(f, ", \"cost\": ");
        json_num(f, t->cost >= 0.0 ? t->cost : NAN);
        fprintf(f, ", \"passed\": %s, \"text\": ", t->passed ? "true" : "false");
        cli_json_string(f, t->text);
        fprintf(f, "}");
    }
    fprintf(f, "\n]}\n");
}
