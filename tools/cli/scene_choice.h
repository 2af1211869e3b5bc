/* scene_choice.h - the options `abrdf render` and `abrdf export` share: how the scene's
 * materials are chosen and the material tables they are chosen from, parsed and checked in
 * one place and applied to a parsed scene in one call.
 *
 *   --model NAME [--set NAME=VALUE ...]          every material becomes one model
 *   --adaptive --goal photoreal|performance       every material chosen by abrdf_select
 *   --adaptive --budget none|slight|noticeable|NMSE   ... by the budget mode
 *   --materials FILE ...                          tables merged over data/materials.csv
 *
 *   scene_choice_option   take one of these options from argv (with its value)
 *   scene_choice_check    the rules between them, once every option is read
 *   scene_choice_apply    resolve a parsed scene's materials as they ask
 *   select_request_budget a --budget value into a select_request (abrdf advise's too)
 */
#ifndef ABRDF_SCENE_CHOICE_H
#define ABRDF_SCENE_CHOICE_H

#include <stdio.h>

#include "scene_select.h"

#define SCENE_CHOICE_MAX_SETS 64
#define SCENE_CHOICE_MAX_FILES 16

typedef struct scene_choice {
    scene_selection how;    /* --adaptive: how.forced, with --goal|--budget in how.all (after
                               scene_choice_check); --materials: how.tables */
    const char *model_name; /* --model, or NULL */
    const char *goal;       /* --goal as given, or NULL */
    const char *budget;     /* --budget as given, or NULL */
    const char *sets[SCENE_CHOICE_MAX_SETS]; /* --set NAME=VALUE, in order */
    int nsets;
    const char *mats[SCENE_CHOICE_MAX_FILES]; /* --materials FILE, in order (how.tables) */
} scene_choice;

/* No option taken yet. */
void scene_choice_init(scene_choice *c);

/* If argv[*i] is one of the options above, take it and its value (advancing *i): 1; 0 if it is
 * not one of them; -1 after the message on a missing value or too many (exit CLI_EXIT_USAGE). */
int scene_choice_option(scene_choice *c, const char *cmd, int argc, char **argv, int *i);
/* The rules between the options (--adaptive with --goal or --budget, --set with --model, ...);
 * the goal or budget parsed into c->how.all: 0, or CLI_EXIT_USAGE after the message. */
int scene_choice_check(scene_choice *c, const char *cmd);
/* rq asks for the budget `text` (--budget's value: a Table-8 class or an NMSE, budget_parse);
 * abrdf advise's --budget too: 0, or CLI_EXIT_USAGE after "abrdf CMD: --budget: ...". */
int select_request_budget(select_request *rq, const char *cmd, const char *text);
/* Resolve s's table and adaptive materials (all of them with --adaptive; scene_resolve), the
 * budget's prediction sampled at spp per pixel, then --model/--set: 0, or the command's exit
 * status after the message ("abrdf CMD: ..."). explain: the selection's traces, or NULL. */
int scene_choice_apply(scene_choice *c, const char *cmd, scene *s, const char *scene_path, int spp,
                       FILE *explain);

#endif
