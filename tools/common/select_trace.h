/* select_trace.h - keeps abrdf_select's trace for the commands that print it after the
 * result (abrdf advise, abrdf render --explain): abrdf_select hands each decision to a
 * callback with a text valid only during the call, so the steps are copied here. */
#ifndef ABRDF_SELECT_TRACE_H
#define ABRDF_SELECT_TRACE_H

#include <stdio.h>
#include "abrdf_select.h"

typedef struct select_trace {
    abrdf_select_step *steps; /* copies; each text and parameter block is owned by the trace */
    int count, cap;
    int lost; /* steps not kept for want of memory */
} select_trace;

#define SELECT_TRACE_INIT                                                                          \
    {                                                                                              \
        NULL, 0, 0, 0                                                                              \
    }

/* An abrdf_select_trace_fn: append a copy of `step` to the select_trace at `trace`. */
void select_trace_keep(void *trace, const abrdf_select_step *step);
/* Free the copies; the trace is empty again. */
void select_trace_free(select_trace *t);

/* A flowchart choice with its kept trace as the JSON object of `abrdf advise MATERIAL --json`:
 * material and source (may be NULL), goal, surface type, models, tolerance, the parameter
 * block, the errors and costs, and every step. */
void select_json(FILE *f, const abrdf_selection *s, const abrdf_params *p,
                 const select_trace *trace, const char *material, const char *source,
                 const abrdf_tolerance *tol);

#endif
