/* select_json.c - the flowchart's choice as JSON (select_trace.h): what `abrdf advise MATERIAL
 * --json` prints, and the browser explorer returns (tools/web). */
#include <math.h>
#include <stdio.h>

#include "cli_args.h"
#include "select_trace.h"

static void json_num(FILE *f, double v) { cli_json_number(f, v); }

/* -1 marks "not applicable" in abrdf_selection; JSON says null. */
static void json_opt(FILE *f, double v)
{
    if (v < 0.0)
        fprintf(f, "null");
    else
        json_num(f, v);
}

/* A threshold: null where the step has none (infinite) or it is unknown (negative). */
static void json_limit(FILE *f, double v) { json_opt(f, isinf(v) ? -1.0 : v); }

static void json_rgb(FILE *f, const double v[3])
{
    fprintf(f, "[%.10g, %.10g, %.10g]", v[0], v[1], v[2]);
}

static void json_name(FILE *f, const char *s)
{
    if (s)
        cli_json_string(f, s);
    else
        fprintf(f, "null");
}

/* The model's stable name; NULL for ABRDF_MODEL_NONE. */
static const char *model_name(abrdf_model m)
{
    const abrdf_model_info *info = abrdf_model_get(m);
    return info ? info->name : NULL;
}

void select_json(FILE *f, const abrdf_selection *s, const abrdf_params *p,
                 const select_trace *trace, const char *material, const char *source,
                 const abrdf_tolerance *tol)
{
    fprintf(f, "{\"material\": ");
    json_name(f, material);
    fprintf(f, ", \"source\": ");
    json_name(f, source);
    fprintf(f, ", \"goal\": \"%s\", \"type\": \"%s\", \"diffuse\": ", abrdf_goal_name(s->goal),
            abrdf_surface_name(s->type));
    json_name(f, model_name(s->diffuse));
    fprintf(f, ", \"specular\": ");
    json_name(f, model_name(s->specular));
    fprintf(f, ",\n \"tolerance\": {\"max_rel_pct\": ");
    json_num(f, tol->max_rel_pct);
    fprintf(f, ", \"max_abs\": ");
    json_num(f, tol->max_abs);
    fprintf(f, "},\n \"params\": {\"kd\": ");
    json_rgb(f, p->kd);
    fprintf(f, ", \"ks\": ");
    json_rgb(f, p->ks);
    fprintf(f, ", \"f0\": ");
    json_rgb(f, p->f0);
    fprintf(
        f,
        ", \"n\": %.10g, \"r\": %.10g, \"anisotropic\": %.10g, \"eta\": %.10g, \"melanin\": %.10g, "
        "\"redness\": %.10g, \"layers\": [",
        p->n, p->r, p->anisotropic, p->eta, p->melanin, p->redness);
    for (int i = 0; i < p->layer_count; ++i) {
        fprintf(
            f, "%s{\"eta\": %.10g, \"kappa\": %.10g, \"r\": %.10g, \"depth\": %.10g, \"sigma_a\": ",
            i ? ", " : "", p->layers[i].eta, p->layers[i].kappa, p->layers[i].r,
            p->layers[i].depth);
        json_rgb(f, p->layers[i].sigma_a);
        fprintf(f, "}");
    }
    fprintf(f, "]},\n \"error\": {\"rel_pct\": ");
    json_opt(f, s->err_rel_pct);
    fprintf(f, ", \"abs\": ");
    json_opt(f, s->err_abs);
    fprintf(f, ", \"nmse\": ");
    json_opt(f, s->err_nmse);
    fprintf(f, "},\n \"cost\": {\"diffuse\": ");
    json_opt(f, s->cost_diffuse);
    fprintf(f, ", \"specular\": ");
    json_opt(f, s->cost_specular);
    fprintf(f, ", \"total\": ");
    json_opt(f, s->cost_total);
    fprintf(f, ", \"unit\": ");
    json_name(f, s->cost_unit);
    fprintf(f, "},\n \"trace\": [");
    for (int i = 0; i < trace->count; ++i) {
        const abrdf_select_step *t = &trace->steps[i];
        fprintf(f, "%s\n  {\"step\": \"%s\", \"model\": ", i ? "," : "", abrdf_step_name(t->kind));
        json_name(f, model_name(t->model));
        fprintf(f, ", \"value\": ");
        json_opt(f, t->value);
        fprintf(f, ", \"threshold\": ");
        json_limit(f, t->threshold);
        fprintf(f, ", \"value2\": ");
        json_opt(f, t->value2);
        fprintf(f, ", \"threshold2\": ");
        json_limit(f, t->threshold2);
        fprintf(f, ", \"cost\": ");
        json_opt(f, t->cost);
        fprintf(f, ", \"passed\": %s, \"text\": ", t->passed ? "true" : "false");
        cli_json_string(f, t->text);
        fprintf(f, "}");
    }
    fprintf(f, "\n]}\n");
}
