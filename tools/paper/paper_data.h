/* paper_data.h - the paper's published tables (data/paper_tables.csv): reference values for
 * the "published" and "difference" columns of `abrdf tables`, never its results. */
#ifndef ABRDF_PAPER_DATA_H
#define ABRDF_PAPER_DATA_H
#include <stddef.h>

#define PAPER_DATA_FILE "paper_tables.csv"

typedef struct paper_cell {
    int table;       /* the paper's table number */
    char row[24];    /* model name or row label */
    char col[24];    /* column label, e.g. the exponent "100" or "cycles" */
    char value[128]; /* the cell as printed: a number or a short note */
} paper_cell;

typedef struct paper_data {
    paper_cell *cells;
    size_t count;
    char *path; /* the file read (malloc'd) */
} paper_data;

/* Load `path` (a regular file, lines of any length: in_file.h), or the data file found by
 * data_path_find when path is NULL. On failure returns -1 with a one-line reason in err. */
int paper_data_load(const char *path, paper_data *d, char *err, size_t err_size);
void paper_data_free(paper_data *d);
/* The cell's text, or NULL if the paper has no such cell. */
const char *paper_data_text(const paper_data *d, int table, const char *row, const char *col);
/* The cell as a number; returns 0 and sets *out, or -1 (missing or not a number). */
int paper_data_number(const paper_data *d, int table, const char *row, const char *col,
                      double *out);

#endif
