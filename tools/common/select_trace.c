/* select_trace.c - copies of abrdf_select's trace steps (select_trace.h). */
#include <stdlib.h>
#include <string.h>

#include "select_trace.h"

void select_trace_keep(void *trace, const abrdf_select_step *step)
{
    select_trace *t = trace;
    if (t->count == t->cap) {
        int cap = t->cap ? 2 * t->cap : 16;
        abrdf_select_step *grown = realloc(t->steps, (size_t)cap * sizeof *grown);
        if (!grown) {
            ++t->lost;
            return;
        }
        t->steps = grown;
        t->cap = cap;
    }
    const char *text = step->text ? step->text : "";
    size_t len = strlen(text) + 1;
    char *copy = malloc(len);
    abrdf_params *params = NULL;
    if (step->params && (params = malloc(sizeof *params)) != NULL) {
        /* the library's block in this program's layout */
        abrdf_params_init(ABRDF_MODEL_NONE, params);
        size_t n =
            step->params->struct_size < sizeof *params ? step->params->struct_size : sizeof *params;
        memcpy(params, step->params, n);
        params->struct_size = sizeof *params;
    }
    if (!copy || (step->params && !params)) {
        free(copy);
        free(params);
        ++t->lost;
        return;
    }
    memcpy(copy, text, len);
    t->steps[t->count] = *step;
    t->steps[t->count].params = params;
    t->steps[t->count++].text = copy;
}

void select_trace_free(select_trace *t)
{
    for (int i = 0; i < t->count; ++i) {
        free((char *)t->steps[i].text);
        free((abrdf_params *)t->steps[i].params);
    }
    free(t->steps);
    t->steps = NULL;
    t->count = t->cap = t->lost = 0;
}
