/* hair_table_args.h - the options of huang tables (abrdf.h, "huang tabulated") that `abrdf
 * render`, `abrdf bench --budget`, `abrdf advise` and `abrdf export --cycles` share, parsed and
 * checked in one place:
 *
 *   --hair-table                       tabulate every huang material at the default sizes
 *   --hair-table-sizes NT,NV,NP,SETS   at these sizes (implies --hair-table)
 *   --hair-table-cache DIR             keep the tables in DIR (implies --hair-table)
 */
#ifndef ABRDF_HAIR_TABLE_ARGS_H
#define ABRDF_HAIR_TABLE_ARGS_H

typedef struct hair_table_args {
    int sizes[4];      /* sizes[0] 0: no table asked for */
    const char *cache; /* --hair-table-cache, or NULL */
} hair_table_args;

/* If argv[*i] is one of the options above, take it and its value (advancing *i): 1; 0 if it
 * is not one of them; < 0 after one line on stderr: -(the exit status). Sizes are checked
 * against the ranges abrdf.h gives and at most 2^28 values in all (the material checks the
 * rest: one view azimuth only for a round fibre). */
int hair_table_option(hair_table_args *h, const char *cmd, int argc, char **argv, int *i);

/* Once every option is read: the cache is a directory, and a cache alone asks for the default
 * sizes. 0, or the exit status after one line on stderr. */
int hair_table_check(hair_table_args *h, const char *cmd);

#endif
