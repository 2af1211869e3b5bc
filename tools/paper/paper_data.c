/* paper_data.c - loader of data/paper_tables.csv (format in the file's header comment:
 * table,row,column,value per line, '#' comments, a header line, no quoting). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "data_path.h"
#include "paper_data.h"

/* Copy the next comma-separated field of *s into out (at most size - 1 chars). The last
 * field takes the rest of the line. Returns 0 on success. */
static int field(char **s, char *out, size_t size, int last)
{
    char *end = last ? *s + strlen(*s) : strchr(*s, ',');
    if (!end) return -1;
    size_t n = (size_t)(end - *s);
    if (n == 0 || n >= size) return -1;
    memcpy(out, *s, n);
    out[n] = '\0';
    *s = last ? end : end + 1;
    return 0;
}

int paper_data_load(const char *path, paper_data *d, char *err, size_t err_size)
{
    memset(d, 0, sizeof *d);
    if (path)
        snprintf(d->path, sizeof d->path, "%s", path);
    else if (data_path_find(PAPER_DATA_FILE, d->path, sizeof d->path) != 0) {
        snprintf(err, err_size, "cannot find %s (looked in $ABRDF_DATA_DIR, %s)", PAPER_DATA_FILE,
                 d->path);
        return -1;
    }
    FILE *f = fopen(d->path, "r");
    if (!f) {
        snprintf(err, err_size, "cannot read %s: %s", d->path, strerror(errno));
        return -1;
    }
    char line[512];
    size_t cap = 0;
    int lineno = 0, header = 0;
    while (fgets(line, sizeof line, f)) {
        ++lineno;
        line[strcspn(line, "\r\n")] = '\0';
        if (line[0] == '#' || line[0] == '\0') continue;
        if (!header) { /* the column names */
            header = 1;
            if (strcmp(line, "table,row,column,value") != 0) break;
            continue;
        }
        if (d->count == cap) {
            cap = cap ? 2 * cap : 256;
            paper_cell *c = realloc(d->cells, cap * sizeof *c);
            if (!c) {
                snprintf(err, err_size, "%s: out of memory", d->path);
                fclose(f);
                paper_data_free(d);
                return -1;
            }
            d->cells = c;
        }
        paper_cell *c = &d->cells[d->count];
        char tab[16], *s = line;
        long t;
        if (field(&s, tab, sizeof tab, 0) || !cli_parse_int(tab, 1, 99, &t) ||
            field(&s, c->row, sizeof c->row, 0) || field(&s, c->col, sizeof c->col, 0) ||
            field(&s, c->value, sizeof c->value, 1)) {
            snprintf(err, err_size, "%s:%d: expected table,row,column,value", d->path, lineno);
            fclose(f);
            paper_data_free(d);
            return -1;
        }
        c->table = (int)t;
        ++d->count;
    }
    fclose(f);
    if (!header || d->count == 0) {
        snprintf(err, err_size, "%s: missing header 'table,row,column,value' or no cells", d->path);
        paper_data_free(d);
        return -1;
    }
    return 0;
}

void paper_data_free(paper_data *d)
{
    free(d->cells);
    d->cells = NULL;
    d->count = 0;
}

const char *paper_data_text(const paper_data *d, int table, const char *row, const char *col)
{
    for (size_t i = 0; i < d->count; ++i)
        if (d->cells[i].table == table && !strcmp(d->cells[i].row, row) &&
            !strcmp(d->cells[i].col, col))
            return d->cells[i].value;
    return NULL;
}

int paper_data_number(const paper_data *d, int table, const char *row, const char *col, double *out)
{
    const char *v = paper_data_text(d, table, row, col);
    return v && cli_parse_double(v, out) ? 0 : -1;
}
