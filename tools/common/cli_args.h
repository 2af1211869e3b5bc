/* cli_args.h - what every `abrdf` subcommand and tool shares: argument parsing with one-line
 * errors (exit status 2), model and parameter lookup with suggestions, JSON string output. */
#ifndef ABRDF_CLI_ARGS_H
#define ABRDF_CLI_ARGS_H

#include <stdio.h>
#include "abrdf.h"

#define CLI_EXIT_USAGE 2

/* Print "abrdf CMD: message" to stderr (one line: control bytes shown as \xHH) and return
 * CLI_EXIT_USAGE. */
int cli_fail(const char *cmd, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* Strict number parsing: the whole string, finite. */
int cli_parse_double(const char *s, double *out);
int cli_parse_int(const char *s, long lo, long hi, long *out);
/* "X,Y,Z" -> v; finite components. */
int cli_parse_vec3(const char *s, double v[3]);
/* cli_parse_vec3 for a direction: the vector is scaled by 1 / its largest |component| (the
 * direction is the same; 1e308,0,1e308 no longer overflows its length). 0,0,0 stays 0,0,0. */
int cli_parse_dir3(const char *s, double v[3]);
/* An option given twice would silently take its last value: the first option word of argv
 * (from 1; "--NAME", "-o", "-n") that repeats an earlier one and is not in `repeatable`
 * (NULL-terminated: "--set", "--materials"), or the value of a --set NAME=VALUE whose NAME
 * an earlier --set gave; else NULL. */
const char *cli_repeated_option(int argc, char **argv, const char *const *repeatable);
/* Model by name; on failure prints the valid names (or the nearest ones) and returns 2. */
int cli_model(const char *cmd, const char *name, abrdf_model *out);
/* Does the model read parameter id (is it among the registry's parameters of the model)? */
int cli_model_reads(abrdf_model model, int id);
/* Apply "NAME=VALUE" or "NAME=R,G,B" to params for model; errors name the valid params. */
int cli_set_param(const char *cmd, abrdf_model model, abrdf_params *p, const char *assign);
/* Levenshtein distance, for "did you mean" suggestions. */
int cli_edit_distance(const char *a, const char *b);
/* True if `typed` is close enough to `name` to suggest it (prefix or small edit distance). */
int cli_is_near(const char *typed, const char *name);
/* Write s as a JSON string literal; bytes that are not UTF-8 become U+FFFD (JSON is UTF-8). */
void cli_json_string(FILE *f, const char *s);
/* Write v as a JSON number ("%.10g"), or null when it is not finite (JSON has no inf/nan). */
void cli_json_number(FILE *f, double v);
/* True if argv[i] is "-h" or "--help". */
int cli_is_help(const char *arg);

/* A command's options as tables: a flag sets *slot = value; a string option takes the next
 * word; a number option takes a whole number in [1, max]. */
typedef struct cli_flag {
    const char *name;
    int *slot, value;
} cli_flag;
typedef struct cli_string {
    const char *name, **slot;
} cli_string;
typedef struct cli_number {
    const char *name;
    long max;
    int *slot;
} cli_number;
typedef struct cli_options {
    const cli_flag *flags;
    size_t nflags;
    const cli_string *strings;
    size_t nstrings;
    const cli_number *numbers;
    size_t nnumbers;
} cli_options;

/* If argv[*i] is one of o's options, take it and its value (advancing *i): 1; 0 if it is not
 * one of them; CLI_EXIT_USAGE after the message ("abrdf CMD: --spp needs a whole number in
 * [1, 4096]") for a missing or bad value. */
int cli_option_take(const char *cmd, const cli_options *o, int argc, char **argv, int *i);

#endif
