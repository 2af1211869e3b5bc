/* tables_cost.c - Table 4 of the paper: the cost of the Table-1 approximations. Prints the
 * paper's operation counts and Zen 4 cycles (the library's default cost model,
 * abrdf_costs_paper) beside ns/eval measured on this machine on the float batch path, each
 * also as a ratio to f2 so the two rankings can be compared, in cycles (ns x the core's clock,
 * measured: clock_rate.h; a cost file's own "# clock:" line), and the ratio to the bare powf
 * Blinn-Phong loop (the unit of abrdf calibrate). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cost_file.h"
#include "measure.h"
#include "tables.h"

enum {
    C_ADDS,
    C_MULS,
    C_DIVS,
    C_CYCLES_PAPER,
    C_CYCLES_OPS,
    C_CYCLES_F2,
    C_NS,
    C_CYCLES_HERE,
    C_NS_F2,
    C_UNIT,
    C_COUNT
};

/* The paper's cycle weights on Zen 4: ADD 1, MUL 3, DIV 10. */
#define CYCLES(adds, muls, divs) ((adds) + 3.0 * (muls) + 10.0 * (divs))

static void progress(const char *name)
{
    (void)name;
    fputc('.', stderr);
}

int tables_cost(const table_gen *self, const tables_opts *o, const paper_data *paper)
{
    (void)self;
    abrdf_costs lib, meas;
    abrdf_costs_paper(&lib);
    double unit_ns = -1.0, ghz = -1.0;
    char source[1400], clock_how[400];
    if (o->costs_path) {
        char err[1200];
        if (costs_load(o->costs_path, &meas, &unit_ns, err, sizeof err) != 0) {
            fprintf(stderr, "abrdf tables: %s\n", err);
            return 1;
        }
        const char *base = strrchr(o->costs_path, '/');
        snprintf(source, sizeof source, "read from the cost file %s",
                 base ? base + 1 : o->costs_path);
        ghz = costs_load_clock(o->costs_path);
        if (ghz > 0.0)
            snprintf(clock_how, sizeof clock_how,
                     "cycles (here) = ns x the clock the cost file gives, %.2f GHz", ghz);
        else
            snprintf(clock_how, sizeof clock_how,
                     "cycles (here): none, the cost file gives no clock (no '# clock:' line)");
    } else {
        measure_opts mo;
        measure_defaults(&mo, 1);
        mo.reps = o->reps;
        /* only what the table shows: its models and the library's Blinn-Phong */
        abrdf_model which[ABRDF_MODEL_COUNT];
        int count = 0;
        for (int i = 0; i < ABRDF_MODEL_COUNT; ++i)
            if (abrdf_costs_get(&lib, (abrdf_model)i) >= 0.0 || i == ABRDF_BLINN_PHONG)
                which[count++] = (abrdf_model)i;
        fprintf(stderr, "abrdf tables 4: measuring ");
        if (measure_models(&mo, which, count, &meas, &unit_ns, progress) != 0) {
            fprintf(stderr, "\nabrdf tables: out of memory\n");
            return 1;
        }
        fprintf(stderr, "\n");
        clock_rate clock;
        clock_rate_measure(&clock);
        ghz = clock.ghz;
        char text[256];
        clock_rate_text(&clock, text, sizeof text);
        snprintf(clock_how, sizeof clock_how, "cycles (here) = ns x the clock measured now, %s",
                 text);
        char machine[384];
        costs_machine(machine, sizeof machine);
        snprintf(
            source, sizeof source,
            "measured now on %s: float batch path, %zu random front-facing pairs, median of %d "
            "repetitions of %.0f ms",
            machine, mo.pairs, mo.reps, 1e3 * mo.rep_seconds);
    }

    static const char *cols[C_COUNT] = {
        "adds",         "muls",        "divs",        "paper_cycles", "ops_cycles",
        "cycles_vs_f2", "ns_per_eval", "cycles_here", "ns_vs_f2",     "vs_powf_blinn_phong"};
    static const char *md_cols[C_COUNT] = {
        "ADDs",        "MULs",           "DIVs",          "cycles (paper)", "ADD+3MUL+10DIV",
        "cycles / f2", "ns/eval (here)", "cycles (here)", "ns / f2",        "x powf Blinn-Phong"};
    tab_grid g;
    tab_init(&g, NULL, "model", C_COUNT, "%.2f");
    for (int c = 0; c < C_COUNT; ++c) strcpy(g.col[c], o->csv ? cols[c] : md_cols[c]);
    g.fmt[C_ADDS] = g.fmt[C_MULS] = g.fmt[C_DIVS] = g.fmt[C_CYCLES_PAPER] = "%.0f";
    g.fmt[C_CYCLES_OPS] = "%.0f";
    g.fmt[C_NS] = "%.3f";
    g.fmt[C_CYCLES_HERE] = "%.1f";

    double f2_cycles = abrdf_costs_get(&lib, ABRDF_F2), f2_ns = abrdf_costs_get(&meas, ABRDF_F2);
    int mismatch = 0;
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        if (!(abrdf_costs_get(&lib, (abrdf_model)i) >= 0.0) && i != ABRDF_BLINN_PHONG) continue;
        const char *name = abrdf_model_get((abrdf_model)i)->name;
        int r = tab_row(&g, name);
        double v;
        if (paper_data_number(paper, 4, name, "adds", &v) == 0) g.v[r][C_ADDS] = v;
        if (paper_data_number(paper, 4, name, "muls", &v) == 0) g.v[r][C_MULS] = v;
        if (paper_data_number(paper, 4, name, "divs", &v) == 0) g.v[r][C_DIVS] = v;
        if (paper_data_number(paper, 4, name, "cycles", &v) == 0) g.v[r][C_CYCLES_PAPER] = v;
        if (!isnan(g.v[r][C_ADDS]) && !isnan(g.v[r][C_MULS]) && !isnan(g.v[r][C_DIVS]))
            g.v[r][C_CYCLES_OPS] = CYCLES(g.v[r][C_ADDS], g.v[r][C_MULS], g.v[r][C_DIVS]);
        if (abrdf_costs_get(&lib, (abrdf_model)i) >= 0.0) { /* the library's default cost model */
            if (f2_cycles > 0.0)
                g.v[r][C_CYCLES_F2] = abrdf_costs_get(&lib, (abrdf_model)i) / f2_cycles;
            mismatch |= abrdf_costs_get(&lib, (abrdf_model)i) != g.v[r][C_CYCLES_PAPER] ||
                        abrdf_costs_get(&lib, (abrdf_model)i) != g.v[r][C_CYCLES_OPS];
        }
        if (abrdf_costs_get(&meas, (abrdf_model)i) > 0.0) {
            g.v[r][C_NS] = abrdf_costs_get(&meas, (abrdf_model)i);
            if (ghz > 0.0) g.v[r][C_CYCLES_HERE] = ghz * g.v[r][C_NS];
            if (f2_ns > 0.0) g.v[r][C_NS_F2] = abrdf_costs_get(&meas, (abrdf_model)i) / f2_ns;
            if (unit_ns > 0.0) g.v[r][C_UNIT] = abrdf_costs_get(&meas, (abrdf_model)i) / unit_ns;
        }
    }
    if (unit_ns > 0.0) {
        int r = tab_row(&g, COSTS_UNIT_NAME);
        g.v[r][C_NS] = unit_ns;
        if (ghz > 0.0) g.v[r][C_CYCLES_HERE] = ghz * unit_ns;
        if (f2_ns > 0.0) g.v[r][C_NS_F2] = unit_ns / f2_ns;
        g.v[r][C_UNIT] = 1.0;
    }

    if (o->csv) {
        tab_csv(&g, NULL, NULL, 1);
        return 0;
    }
    printf("## Table 4: cost of the Table-1 approximations\n\n"
           "Paper: AMD Zen 4 cycles, ADD 1, MUL 3, DIV 10; cycles / f2 uses abrdf_costs_paper().\n"
           "Here: ns per evaluation, %s.\n"
           "%s.\n"
           "blinn_phong is the library's guarded Blinn-Phong on the same path; %s is a bare\n"
           "loop H = normalise(wi + wo), powf(H.z, 100), the unit of the last column.\n\n",
           source, clock_how, COSTS_UNIT_NAME);
    tab_markdown(&g);
    for (int i = 0; i < ABRDF_MODEL_COUNT; ++i) {
        const abrdf_model_info *m = abrdf_model_get((abrdf_model)i);
        const char *note = m ? paper_data_text(paper, 4, m->name, "note") : NULL;
        if (note) printf("- %s (paper): %s\n", m->name, note);
    }
    printf("\nabrdf_costs_paper() (the selection's default costs) %s the published cycles and\n"
           "ADD + 3 MUL + 10 DIV for every model of the table.\n",
           mismatch ? "DIFFERS from" : "equals");
    return 0;
}
