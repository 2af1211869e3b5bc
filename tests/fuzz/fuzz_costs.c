/* fuzz_costs.c - fuzz target of the cost file reader (tools/common/cost_file.c, `abrdf advise
 * --costs`, `abrdf tables 4 --costs`): any bytes are either rejected with "fuzz:LINE: problem"
 * or "fuzz: problem", or read into a table of finite positive costs that abrdf_select takes
 * (the photoreal goal for every table; the performance goal, which ranks by the costs but
 * costs ~0.1 s of error analysis, for every 64th). libFuzzer entry point; fuzz_driver.c
 * runs it under CTest. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "abrdf_select.h"
#include "cost_file.h"
#include "fuzz_target.h"

static unsigned long accepted, selected;

#define LONG_TEXT_64 "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"
#define LONG_TEXT LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64
/* Long comments are comments however long (the reader once cut lines at 512 bytes). */
const char *const fuzz_tokens[] = {
    "\n",
    " ",
    "\t",
    "#",
    "\r",
    "\0",
    "0",
    "-1",
    "1e-310",
    "1e308",
    "1e309",
    "nan",
    "inf",
    "0x1p3",
    "12.5",
    "powf_blinn_phong",
    "lambert",
    "f8",
    "f16",
    "disney_specular",
    "huang",
    "belcour",
    "unknown_model",
    "# " LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT,
    LONG_TEXT,
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read, %lu selections made", accepted, selected); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *in = fmemopen(size ? (void *)data : (void *)"", size ? size : 1, "r");
    if (!in) abort();
    if (!size) getc(in); /* an empty input: fmemopen needs one byte, skip it */
    abrdf_costs c;
    double unit;
    char err[512];
    err[0] = '\0';
    int rc = costs_read(in, "fuzz", &c, &unit, err, sizeof err);
    fclose(in);
    if (rc != 0) {
        if (strncmp(err, "fuzz:", 5) != 0 || memchr(err, '\0', sizeof err) == NULL) abort();
        return 0;
    }
    ++accepted;
    if (!(unit == -1.0 || (unit > 0 && isfinite(unit)))) abort();
    for (int i = 0; i < ABRDF_COSTS_CAPACITY; ++i) {
        double v = abrdf_costs_get(&c, (abrdf_model)i);
        if (!(v == -1.0 || (v > 0 && isfinite(v)))) abort();
    }
    for (int goal = accepted % 64 == 1 ? 0 : 1; goal < 2; ++goal) {
        abrdf_material m;
        abrdf_material_init(&m);
        m.n = 300;
        abrdf_selection sel;
        abrdf_selection_init(&sel);
        if (abrdf_select(&m, (abrdf_goal)goal, NULL, &c, &sel, NULL, NULL, NULL) != ABRDF_OK)
            abort();
        if (isnan(sel.cost_total) || isnan(sel.cost_specular)) abort();
        ++selected;
    }
    return 0;
}
