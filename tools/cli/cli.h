/* cli.h - the `abrdf` command: one entry point per subcommand (cmd_*.c). */
#ifndef ABRDF_CLI_H
#define ABRDF_CLI_H

#include "cli_args.h"

/* A subcommand: name, one-line summary, entry point (argv[0] is the subcommand name). */
typedef struct cli_command {
    const char *name;
    const char *summary;
    int (*run)(int argc, char **argv);
} cli_command;

int cmd_models(int argc, char **argv);
int cmd_eval(int argc, char **argv);
int cmd_sample(int argc, char **argv);
int cmd_slice(int argc, char **argv);
int cmd_render(int argc, char **argv);
int cmd_export(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_tables(int argc, char **argv);
int cmd_calibrate(int argc, char **argv);
int cmd_advise(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_fit(int argc, char **argv);
int cmd_tabulate(int argc, char **argv);
int cmd_inspect(int argc, char **argv);
int cmd_explore(int argc, char **argv);

#endif
