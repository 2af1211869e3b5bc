/* fuzz_materials.c - fuzz target of the material-table reader (tools/common/materials.c,
 * data/materials.csv and `--materials FILE`): any bytes are either rejected with
 * "fuzz:LINE: problem" (the table unchanged), or merged into the table, whose every entry
 * then has a source, a valid name, and passes abrdf_select (the photoreal goal: the
 * performance goal's error analysis would cost ~0.1 s per entry) or is refused with a
 * message. libFuzzer entry point; fuzz_driver.c runs it under CTest. */
#define _POSIX_C_SOURCE 200809L /* fmemopen */
#include <stdlib.h>
#include <string.h>

#include "abrdf_select.h"
#include "fuzz_target.h"
#include "materials.h"

static unsigned long accepted, entries;

#define LONG_TEXT_64 "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"
#define LONG_TEXT LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64
const char *const fuzz_tokens[] = {
    "\n",
    ",",
    ",,",
    " ",
    "#",
    "\r",
    "\0",
    "0",
    "1",
    "-1",
    "0.5",
    "1e-310",
    "1e308",
    "nan",
    "inf",
    "general",
    "hair",
    "cloth_rough",
    "cloth_shiny",
    "layered_plastic",
    "layered_plate",
    "layered_metal",
    "gold",
    "Gold",
    "name,type,n,r",
    "1.5",
    "40",
    "1e4",
    "# " LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT LONG_TEXT,
    LONG_TEXT,
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read, %lu entries checked", accepted, entries); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    FILE *in = fmemopen(size ? (void *)data : (void *)"", size ? size : 1, "r");
    if (!in) abort();
    if (!size) getc(in);
    mat_table t = {NULL, 0, 0};
    char err[512];
    err[0] = '\0';
    int rc = mat_table_read(&t, in, "fuzz", err, sizeof err);
    fclose(in);
    if (rc != 0) {
        if (strncmp(err, "fuzz:", 5) != 0 || memchr(err, '\0', sizeof err) == NULL) abort();
        if (t.count != 0) abort(); /* a bad file leaves the table as it was */
        mat_table_free(&t);
        return 0;
    }
    ++accepted;
    for (int i = 0; i < t.count; ++i) {
        const mat_entry *e = &t.items[i];
        if (!e->name[0] || !e->source[0] || mat_table_find(&t, e->name) != e) abort();
        abrdf_selection sel;
        abrdf_selection_init(&sel);
        int st = abrdf_select(&e->m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &sel, NULL, NULL, NULL);
        if (st != ABRDF_OK && !sel.message[0]) abort();
        ++entries;
    }
    mat_table_free(&t);
    return 0;
}
