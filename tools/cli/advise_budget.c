/* advise_budget.c - `abrdf advise MATERIAL --budget CLASS|NMSE` and `--pareto [--plot FILE]`:
 * the selection's budget mode (abrdf_select_budget, docs/SELECTION.md, "The budget mode") for
 * one material: the cheapest fitted candidate whose predicted image NMSE is within the budget,
 * every candidate with its fitted parameters, predicted NMSE and cost, and the cost/error
 * front. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "advise_budget.h"
#include "budget_run.h"
#include "out_file.h"
#include "plot_grid.h"
#include "cli.h"
#include "metrics.h"

#define CMD "advise"
#define MAX_CAND 256

static void print_human(const budget_result *r, const mat_entry *e, double max_nmse,
                        const abrdf_select_step *const *cand, int n, const int *front, int nf,
                        int pareto)
{
    const abrdf_select_step *ref = budget_reference_step(r);
    char nm[128], unit[32] = "units";
    if (r->sel.cost_unit) sscanf(r->sel.cost_unit, "%31s", unit);
    if (e && e->line > 0)
        printf("material   %s (%s; %s:%d)\n", e->name, abrdf_surface_name(r->sel.type), e->file,
               e->line);
    else if (e) /* a glTF or MaterialX material: the file holds no line for it */
        printf("material   %s (%s; %s)\n", e->name, abrdf_surface_name(r->sel.type), e->file);
    else
        printf("material   explicit values (%s)\n", abrdf_surface_name(r->sel.type));
    budget_pair_name(ref ? ref->diffuse : ABRDF_MODEL_NONE, ref ? ref->model : ABRDF_MODEL_NONE,
                     ref ? ref->params : NULL, nm, sizeof nm);
    printf("reference  %s (the flowchart's photoreal choice%s), %.3g %s\n", nm,
           r->prepared ? ", from its huang table" : "", ref ? ref->cost : -1.0, unit);
    if (!pareto) {
        const char *bc = budget_class_name(max_nmse);
        printf("budget     predicted image NMSE < %g%s%s%s\n", max_nmse, bc ? " (" : "",
               bc ? bc : "", bc ? ")" : "");
        budget_pair_name(r->sel.diffuse, r->sel.specular, &r->params, nm, sizeof nm);
        printf("choice     %s\nparams     ", nm);
        budget_params_text(stdout, r->sel.diffuse, r->sel.specular, &r->params);
        printf("\nerror      predicted NMSE %.3g (%s); highlight %.3g%%, max abs %.3g against the "
               "reference\n",
               r->sel.err_nmse, abrdf_nmse_class(r->sel.err_nmse), r->sel.err_rel_pct,
               r->sel.err_abs);
        printf("cost       %.3g %s  [%s]\n", r->sel.cost_total, unit,
               r->sel.cost_unit ? r->sel.cost_unit : "");
    }
    printf("%s (%d, %.2f s):\n", pareto ? "cost/error front" : "candidates", pareto ? nf : n,
           r->seconds);
    printf("  %-36s %10s %11s  %-12s %s\n", "model", "cost", "NMSE", "class", "fitted");
    for (int k = 0; k < (pareto ? nf : n); ++k) {
        const abrdf_select_step *c = cand[pareto ? front[k] : k];
        budget_pair_name(c->diffuse, c->model, c->params, nm, sizeof nm);
        printf("  %-36s %10.3g %11.3g  %-12s ", nm, c->cost, c->value, abrdf_nmse_class(c->value));
        budget_params_text(stdout, c->diffuse, c->model, c->params);
        printf("\n");
    }
    if (!pareto) {
        printf("why:\n");
        for (int i = 0; i < r->trace.count; ++i)
            printf("  %2d. %s\n", i + 1, r->trace.steps[i].text);
    }
    if (e) printf("source: %s\n", e->source);
}

/* The cost/error plane: every candidate, the front as a staircase, Table 8's classes. */
static void write_plot(FILE *f, const char *title, const abrdf_select_step *const *cand, int n,
                       const int *front, int nf)
{
    const double W = 760, H = 520, L = 70, Rm = 200, T = 40, B = 60;
    double x0 = INFINITY, x1 = 0, y0 = 1e-6, y1 = 1.0;
    for (int i = 0; i < n; ++i)
        if (cand[i]->cost > 0.0) x0 = fmin(x0, cand[i]->cost), x1 = fmax(x1, cand[i]->cost);
    if (!(x1 > 0.0)) x0 = 1, x1 = 10;
    double lx0 = floor(log10(x0)), lx1 = ceil(log10(x1)), ly0 = log10(y0), ly1 = log10(y1);
    if (lx1 <= lx0) lx1 = lx0 + 1;
#define PX(v) (L + (log10(v) - lx0) / (lx1 - lx0) * (W - L - Rm))
#define PY(v) (H - B - (log10(fmin(fmax(v, y0), y1)) - ly0) / (ly1 - ly0) * (H - T - B))
    fprintf(f,
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%g\" height=\"%g\" "
            "font-family=\"sans-serif\" font-size=\"11\">\n"
            "<rect width=\"100%%\" height=\"100%%\" fill=\"white\"/>\n"
            "<text x=\"%g\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">",
            W, H, (L + W - Rm) / 2);
    for (const char *c = title; *c; ++c) {
        if (*c == '<')
            fputs("&lt;", f);
        else if (*c == '&')
            fputs("&amp;", f);
        else
            fputc(*c, f);
    }
    fprintf(f, "</text>\n");
    plot_grid g = {W, H, L, Rm, T, B, lx0, lx1, ly0, ly1, y0, y1};
    plot_grid_write(f, &g);
    fprintf(f,
            "<rect x=\"%g\" y=\"%g\" width=\"%g\" height=\"%g\" fill=\"none\" stroke=\"black\"/>\n"
            "<text x=\"%g\" y=\"%g\" text-anchor=\"middle\">cost per evaluation (ns, the "
            "selection's cost table)</text>\n"
            "<text transform=\"translate(18,%g) rotate(-90)\" text-anchor=\"middle\">predicted "
            "image NMSE vs the reference (below 1e-6 drawn at 1e-6)</text>\n",
            L, T, W - L - Rm, H - T - B, (L + W - Rm) / 2, H - 20, (T + H - B) / 2);
    const double *cls = abrdf_select_rules_get()->nmse_class_max;
    static const char *const cname[3] = {"none", "slight", "noticeable"};
    for (int k = 0; k < 3; ++k)
        fprintf(
            f,
            "<line x1=\"%g\" y1=\"%.1f\" x2=\"%g\" y2=\"%.1f\" stroke=\"#c80\" "
            "stroke-dasharray=\"2,3\"/><text x=\"%g\" y=\"%.1f\" fill=\"#c80\">%s &lt; %g</text>\n",
            L, PY(cls[k]), W - Rm, PY(cls[k]), W - Rm + 4, PY(cls[k]) + 4, cname[k], cls[k]);
    fprintf(f, "<polyline fill=\"none\" stroke=\"#d62728\" points=\"");
    for (int k = 0; k < nf; ++k) {
        const abrdf_select_step *c = cand[front[k]];
        if (k) fprintf(f, "%.1f,%.1f ", PX(c->cost), PY(cand[front[k - 1]]->value));
        fprintf(f, "%.1f,%.1f ", PX(c->cost), PY(c->value));
    }
    fprintf(f, "\"/>\n");
    for (int i = 0; i < n; ++i) {
        if (!(cand[i]->cost > 0.0)) continue;
        int on = 0;
        for (int k = 0; k < nf; ++k) on |= front[k] == i;
        char nm[128];
        budget_pair_name(cand[i]->diffuse, cand[i]->model, cand[i]->params, nm, sizeof nm);
        double x = PX(cand[i]->cost), y = PY(cand[i]->value);
        fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"%d\" fill=\"%s\"/>", x, y, on ? 4 : 2,
                i == 0 ? "#1f77b4"
                : on   ? "#d62728"
                       : "#999");
        if (on || i == 0)
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\">%s%s</text>", x + 6, y - 4, nm,
                    i == 0 ? " (reference)" : "");
        fprintf(f, "\n");
    }
#undef PX
#undef PY
    fprintf(f, "</svg>\n");
}

int advise_budget(const abrdf_material *m, const mat_entry *e, double max_nmse,
                  const abrdf_costs *costs, int json, int pareto, const char *plot,
                  hair_store *tables)
{
    budget_result r;
    char err[1024];
    /* The plot exists (as a temporary file) before the fits: a directory that is missing or
     * read-only fails now; it replaces the target only when complete (out_file.h). */
    out_file plot_out = OUT_FILE_INIT;
    out_file *const plot_files[1] = {&plot_out};
    if (plot && out_file_open(&plot_out, plot, err, sizeof err)) {
        fprintf(stderr, "abrdf advise: %s\n", err);
        return 1;
    }
    /* the front lists every candidate at its best fit (abrdf_select_budget refits every one
     * with every metric); a budget of 1 lets every candidate pass */
    char what[160];
    snprintf(what, sizeof what, "material '%s'", e ? e->name : "given by values");
    int done = tables ? hair_store_budget(tables, m, pareto ? 1.0 : max_nmse, costs, NULL, what, &r,
                                          err, sizeof err)
                      : 0;
    if (tables && !done) /* the option asked for a table: say why there is none */
        fprintf(stderr,
                "abrdf advise: note: --hair-table: %s's photoreal choice is not huang, or its "
                "table cannot be timed (no huang cost in the costs): the budget's reference is "
                "the per-call choice\n",
                e ? e->name : "the material");
    if (done < 0 ||
        (!done && budget_run(m, pareto ? 1.0 : max_nmse, costs, NULL, &r, err, sizeof err))) {
        out_file_discard(&plot_out);
        return cli_fail(CMD, "%s", err);
    }
    const abrdf_select_step *cand[MAX_CAND];
    int n = budget_candidates(&r, cand, MAX_CAND), front[MAX_CAND];
    int nf = budget_pareto(cand, n, front);
    int rc = 0;
    if (plot) {
        char title[160];
        snprintf(title, sizeof title, "%s: budget candidates, cost vs predicted image NMSE",
                 e ? e->name : "explicit material");
        write_plot(plot_out.f, title, cand, n, front, nf);
        if (out_file_close(&plot_out, err, sizeof err) ||
            out_file_commit(plot_files, 1, err, sizeof err)) {
            fprintf(stderr, "abrdf advise: %s\n", err);
            rc = 1;
        }
    }
    out_file_discard(&plot_out);
    if (!rc) {
        if (json)
            budget_json(stdout, &r, e ? e->name : NULL, pareto ? 1.0 : max_nmse, cand, n, front, nf,
                        pareto);
        else
            print_human(&r, e, max_nmse, cand, n, front, nf, pareto);
    }
    budget_result_free(&r);
    return rc;
}
