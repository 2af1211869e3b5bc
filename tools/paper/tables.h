/* tables.h - `abrdf tables N`: each of the paper's tables is recomputed by a generator and
 * printed beside the published values (data/paper_tables.csv). Adding a table = one
 * generator function and one line in the generator list of cmd_tables.c. */
#ifndef ABRDF_TABLES_H
#define ABRDF_TABLES_H
#include "abrdf.h"
#include "paper_data.h"
#include "paper_images.h"

typedef struct tables_opts {
    int csv;                     /* 1: CSV, 0: Markdown (default) */
    const char *costs_path;      /* Table 4: a cost file instead of measuring now */
    int reps;                    /* Table 4: repetitions when measuring now */
    paper_images_options images; /* Tables 6-7: the rendering set-up */
} tables_opts;

typedef struct table_gen table_gen;
struct table_gen {
    const char *id;      /* the paper's table number as typed on the command line */
    const char *summary; /* one line for the usage text */
    int (*run)(const table_gen *self, const tables_opts *o, const paper_data *paper);
};

/* ---- a small grid printer shared by the generators ------------------------------------ */
#define TAB_MAX_ROWS 32
#define TAB_MAX_COLS 16

typedef struct tab_grid {
    const char *title;  /* Markdown heading (### title); unused in CSV */
    const char *corner; /* header of the label column */
    int rows, cols;
    char row[TAB_MAX_ROWS][32];
    char col[TAB_MAX_COLS][40];
    const char *fmt[TAB_MAX_COLS];        /* printf format per column, e.g. "%.2f" */
    double v[TAB_MAX_ROWS][TAB_MAX_COLS]; /* NAN = no value (an empty cell) */
} tab_grid;

/* Empty grid with `cols` columns, every cell NAN and every format `fmt`. */
void tab_init(tab_grid *g, const char *title, const char *corner, int cols, const char *fmt);
/* Append a row; returns its index. */
int tab_row(tab_grid *g, const char *label);
/* Markdown table; columns that are empty in every row are left out. */
void tab_markdown(const tab_grid *g);
/* CSV rows "label[,tag],v,v,..." (empty for NAN); header first if `header`. tag_name and
 * tag may be NULL (no tag column). */
void tab_csv(const tab_grid *g, const char *tag_name, const char *tag, int header);

/* The generators (tables_error.c: 2 and 3; tables_cost.c: 4; paper_images.c: 6 and 7). */
int tables_error(const table_gen *self, const tables_opts *o, const paper_data *paper);
int tables_cost(const table_gen *self, const tables_opts *o, const paper_data *paper);
int tables_images(const table_gen *self, const tables_opts *o, const paper_data *paper);
/* Not the paper's: the glTF mapping's measured error (tools/pbr/tables_gltf.c). */
int tables_gltf(const table_gen *self, const tables_opts *o, const paper_data *paper);

#endif
