/* paper_data.c - loader of data/paper_tables.csv (format in the file's header comment:
 * table,row,column,value per line, '#' comments, a header line, no quoting). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "data_path.h"
#include "in_file.h"
#include "paper_data.h"
#include "path_msg.h"

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
    size_t size = path ? strlen(path) + 1 : 4096;
    if (!(d->path = malloc(size))) {
        snprintf(err, err_size, "out of memory");
        return -1;
    }
    if (path)
        memcpy(d->path, path, size);
    else if (data_path_find(PAPER_DATA_FILE, d->path, size) != 0) {
        path_msg(err, err_size, d->path, ": not found (looked in $ABRDF_DATA_DIR first)");
        paper_data_free(d);
        return -1;
    }
    FILE *f = in_file_open(d->path, err, err_size);
    if (!f) {
        paper_data_free(d);
        return -1;
    }
    char *line = NULL;
    size_t cap = 0, ncells = 0;
    ssize_t len;
    int lineno = 0, header = 0, rc = 0;
    while ((len = in_file_line(f, &line, &cap)) >= 0) {
        ++lineno;
        if (strlen(line) != (size_t)len) {
            path_msg(err, err_size, d->path, ":%d: NUL byte (not a text file)", lineno);
            rc = -1;
            break;
        }
        if (line[0] == '#' || line[0] == '\0') continue;
        if (!header) { /* the column names */
            header = 1;
            if (strcmp(line, "table,row,column,value") != 0) break;
            continue;
        }
        if (d->count == ncells) {
            ncells = ncells ? 2 * ncells : 256;
            paper_cell *c = realloc(d->cells, ncells * sizeof *c);
            if (!c) {
                path_msg(err, err_size, d->path, ": out of memory");
                rc = -1;
                break;
            }
            d->cells = c;
        }
        paper_cell *c = &d->cells[d->count];
        char tab[16], *s = line;
        long t;
        if (field(&s, tab, sizeof tab, 0) || !cli_parse_int(tab, 1, 99, &t) ||
            field(&s, c->row, sizeof c->row, 0) || field(&s, c->col, sizeof c->col, 0) ||
            field(&s, c->value, sizeof c->value, 1)) {
            path_msg(err, err_size, d->path, ":%d: expected table,row,column,value", lineno);
            rc = -1;
            break;
        }
        c->table = (int)t;
        ++d->count;
    }
    if (!rc && ferror(f)) {
        path_msg(err, err_size, d->path, ": read error: %s", strerror(errno));
        rc = -1;
    }
    free(line);
    fclose(f);
    if (!rc && (!header || d->count == 0)) {
        path_msg(err, err_size, d->path, ": missing header 'table,row,column,value' or no cells");
        rc = -1;
    }
    if (rc) paper_data_free(d);
    return rc;
}

void paper_data_free(paper_data *d)
{
    free(d->cells);
    free(d->path);
    d->cells = NULL;
    d->path = NULL;
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
