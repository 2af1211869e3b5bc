/* cost_file.h - cost files: the measured cost of every model on a machine (abrdf calibrate),
 * loaded into an abrdf_costs for the selection (abrdf advise --costs FILE) and Table 4.
 *
 * FORMAT (text, one entry per line):
 *   # comment lines: machine, date and command that produced the file; "# clock: G GHz, how"
 *     gives the core's clock measured with the costs (clock_rate.h), the unit of "cycles"
 *   NAME NS_PER_EVAL   [# optional trailing comment]
 * NAME is a registered model name (abrdf models) or COSTS_UNIT_NAME, the bare powf
 * Blinn-Phong loop that serves as the unit of the ratios. NS_PER_EVAL is a positive number:
 * nanoseconds per evaluation on the float batch path. Models missing from the file have
 * cost < 0 (unknown). A name may appear once. */
#ifndef ABRDF_COST_FILE_H
#define ABRDF_COST_FILE_H
#include <stddef.h>
#include <stdio.h>
#include "abrdf_select.h"
#include "clock_rate.h"

#define COSTS_UNIT_NAME "powf_blinn_phong"
#define COSTS_UNIT "ns/eval (measured, abrdf calibrate)"

/* Load `path` (a regular file: in_file.h) into out (unit COSTS_UNIT); *unit_ns receives the
 * powf Blinn-Phong time, or -1 if absent (unit_ns may be NULL). Lines may have any length.
 * Returns 0, or -1 with "path:line: reason" in err. */
int costs_load(const char *path, abrdf_costs *out, double *unit_ns, char *err, size_t err_size);
/* The same from an open stream; `name` is used in messages (tests/fuzz/fuzz_costs.c). */
int costs_read(FILE *f, const char *name, abrdf_costs *out, double *unit_ns, char *err,
               size_t err_size);

/* The clock of a cost file's "# clock: G GHz" line: G, or -1 when the file has none (or
 * cannot be read: costs_load reports that). */
double costs_load_clock(const char *path);

/* Write a cost file: header comments (machine, date, command, `how` and, when clock is not
 * NULL, the clock), the unit line, then one line per model with cost >= 0 and, as a comment,
 * its ratio to the unit and (with a clock) its cycles per evaluation. */
void costs_write(FILE *f, const abrdf_costs *c, double unit_ns, const char *command,
                 const char *how, const clock_rate *clock);

/* "cpu model (arch, cores)" of this machine, for headers. */
void costs_machine(char *buf, size_t size);

#endif
