/* cmd_models.c - `abrdf models [--json]`: the model registry as a table or JSON. */
#include <string.h>

#include "cli.h"

static const char *kind_name(abrdf_param_kind k)
{
    return k == ABRDF_PARAM_RGB ? "rgb" : k == ABRDF_PARAM_INT ? "int" : "scalar";
}

static void needs_list(unsigned needs, char *buf, size_t size)
{
    static const struct {
        unsigned bit;
        const char *name;
    } names[] = {{ABRDF_NEEDS_TANGENT, "tangent"},
                 {ABRDF_NEEDS_FRESNEL, "fresnel"},
                 {ABRDF_NEEDS_LAYERS, "layers"},
                 {ABRDF_NEEDS_INTEGRATION, "integration"},
                 {ABRDF_NEEDS_TABLE, "table"}};
    buf[0] = '\0';
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if ((needs & names[i].bit) && strlen(buf) + strlen(names[i].name) + 2 < size)
            strcat(strcat(buf, *buf ? "," : ""), names[i].name);
    if (!*buf) strcpy(buf, "-");
}

static void print_json(void)
{
    printf("{\"version\": ");
    cli_json_string(stdout, abrdf_version());
    printf(", \"models\": [");
    int first = 1;
    for (int i = 0; i < abrdf_model_count(); ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        char needs[64];
        needs_list(m->needs, needs, sizeof needs);
        printf("%s\n  {\"name\": ", first ? "" : ",");
        first = 0;
        cli_json_string(stdout, m->name);
        printf(", \"title\": ");
        cli_json_string(stdout, m->title);
        printf(", \"equation\": ");
        cli_json_string(stdout, m->equation);
        printf(", \"citation\": ");
        cli_json_string(stdout, m->citation);
        printf(", \"needs\": [");
        int fn = 1;
        for (char *tok = strtok(needs, ","); tok && strcmp(tok, "-"); tok = strtok(NULL, ",")) {
            printf("%s", fn ? "" : ", ");
            cli_json_string(stdout, tok);
            fn = 0;
        }
        printf("], \"reciprocal\": %s, \"energy_conserving\": %s, \"kind\": \"%s\"",
               (m->props & ABRDF_PROP_RECIPROCAL) ? "true" : "false",
               (m->props & ABRDF_PROP_ENERGY_CONSERVING) ? "true" : "false",
               (m->props & ABRDF_PROP_DIFFUSE)    ? "diffuse"
               : (m->props & ABRDF_PROP_SPECULAR) ? "specular"
                                                  : "special");
        if (m->paper_cycles >= 0)
            printf(", \"paper_cycles\": %d", m->paper_cycles);
        else
            printf(", \"paper_cycles\": null");
        const abrdf_sampler_info *s = abrdf_model_sampler((abrdf_model)i);
        if (s) {
            printf(", \"sampler\": {\"name\": ");
            cli_json_string(stdout, s->name);
            printf(", \"method\": ");
            cli_json_string(stdout, s->method);
            printf(", \"citation\": ");
            cli_json_string(stdout, s->citation);
            printf(", \"mixture\": %s, \"below_surface\": %s}",
                   (s->flags & ABRDF_SAMPLER_MIXTURE) ? "true" : "false",
                   (s->flags & ABRDF_SAMPLER_BELOW) ? "true" : "false");
        } else {
            printf(", \"sampler\": null");
        }
        printf(", \"params\": [");
        for (int k = 0; k < m->param_count; ++k) {
            const abrdf_param_info *pi = abrdf_param_get(m->params[k].id);
            double lo = m->params[k].min, hi = m->params[k].max;
            printf("%s{\"name\": ", k ? ", " : "");
            cli_json_string(stdout, pi->name);
            printf(", \"kind\": \"%s\", \"min\": %.17g, \"max\": %.17g, \"default\": %.17g, "
                   "\"help\": ",
                   kind_name(pi->kind), lo, hi, m->params[k].def);
            cli_json_string(stdout, pi->help);
            printf("}");
        }
        printf("]}");
    }
    printf("\n]}\n");
}

static void print_table(void)
{
    printf("%-22s %-16s %-20s %s\n", "model", "formula", "needs",
           "parameters (default [min, max])");
    for (int i = 0; i < abrdf_model_count(); ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        if (!m) continue;
        char needs[64];
        needs_list(m->needs, needs, sizeof needs);
        printf("%-22s %-16s %-20s", m->name, m->equation, needs);
        for (int k = 0; k < m->param_count; ++k) {
            const abrdf_param_info *pi = abrdf_param_get(m->params[k].id);
            double lo = m->params[k].min, hi = m->params[k].max;
            printf("%s%s=%g [%g, %g]", k ? ", " : " ", pi->name, m->params[k].def, lo, hi);
        }
        printf("\n");
    }
}

int cmd_models(int argc, char **argv)
{
    int json = 0;
    for (int i = 1; i < argc; ++i) {
        if (cli_is_help(argv[i])) {
            printf(
                "usage: abrdf models [--json]\n\n"
                "Lists every model of the library: stable name, the paper's formula number,\n"
                "what it needs (tangent, Fresnel, layers, integration) and its parameters with\n"
                "default and range. --json adds the citation, reciprocity, energy conservation,\n"
                "the paper's Table-4 cycle count and the importance sampler (abrdf sample;\n"
                "docs/RENDERER.md, \"Importance sampling\"): its name, method, citation, whether\n"
                "it mixes lobes and whether it can draw directions below the surface.\n");
            return 0;
        }
        if (!strcmp(argv[i], "--json"))
            json = 1;
        else
            return cli_fail("models", "unknown option '%s'; options: --json", argv[i]);
    }
    if (json)
        print_json();
    else
        print_table();
    return 0;
}
