/* fuzz_cli.c - fuzz target of the `abrdf` argument parsing: an input is an argument vector,
 * one argument per line, run through the subcommands whose work is quick (eval, slice,
 * advise, models; the first line names one, else one is picked from the input's length).
 * Each must exit 0, 1 or 2; an exit status 2 (bad arguments) must come with exactly one
 * line on stderr, "abrdf CMD: ...", and nothing else there. Standard output goes to
 * /dev/null. libFuzzer entry point; fuzz_driver.c runs it under CTest. */
#define _POSIX_C_SOURCE 200809L
#include <fcntl.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "fuzz_target.h"

static unsigned long runs, refused;

const char *const fuzz_tokens[] = {
    "\n",
    "\0",
    "-",
    "--",
    "=",
    ",",
    "eval",
    "slice",
    "advise",
    "models",
    "--wi",
    "--wo",
    "--normal",
    "--tangent",
    "--set",
    "--json",
    "--csv",
    "--steps",
    "--theta-i",
    "--goal",
    "--n",
    "--r",
    "--kd",
    "--ks",
    "--f0",
    "--eta",
    "--type",
    "--max-rel-error",
    "--max-abs-error",
    "--anisotropy",
    "--melanin",
    "--redness",
    "--list",
    "--rules",
    "--help",
    "0,0,1",
    "0,0,0",
    "1e-310,0,1",
    "nan,0,1",
    "inf",
    "1e308",
    "-1",
    "0",
    "0.03",
    "1e6",
    "1,2",
    "1,2,3,4",
    "r=",
    "n=",
    "kd=0.5",
    "f0=0.9,0.6,0.3",
    "layer_count=4",
    "layer0_eta=",
    "disney_specular",
    "huang",
    "belcour",
    "kajiya_kay",
    "gold",
    "hair",
    "none",
    "performance",
    "photoreal",
    "\xff\xfe",
    "\xc3\xa9",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu runs, %lu refused with one line", runs, refused); }

#define MAX_ARGS 48

static const cli_command commands[] = {{"eval", "", cmd_eval},
                                       {"slice", "", cmd_slice},
                                       {"advise", "", cmd_advise},
                                       {"models", "", cmd_models}};

/* During a run, stdout goes to /dev/null and stderr to a file read back afterwards. */
static int err_fd = -1, null_fd = -1;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (err_fd < 0) {
        char name[] = "/tmp/abrdf_fuzz_cli_XXXXXX";
        null_fd = open("/dev/null", O_WRONLY);
        if ((err_fd = mkstemp(name)) < 0 || null_fd < 0) abort();
        unlink(name);
    }
    char *text = malloc(size + 1);
    if (!text) abort();
    memcpy(text, data, size);
    text[size] = '\0';
    char *argv[MAX_ARGS + 1];
    int argc = 0;
    for (char *p = text; argc < MAX_ARGS;) {
        argv[argc++] = p;
        char *nl = memchr(p, '\n', (size_t)(text + size - p));
        if (!nl) break;
        *nl = '\0';
        p = nl + 1;
    }
    argv[argc] = NULL;
    const cli_command *c = &commands[size % 4];
    for (int i = 0; i < 4; ++i)
        if (!strcmp(argv[0], commands[i].name)) c = &commands[i];

    fflush(stdout);
    fflush(stderr);
    int saved_out = dup(STDOUT_FILENO), saved_err = dup(STDERR_FILENO);
    if (saved_out < 0 || saved_err < 0 || ftruncate(err_fd, 0) != 0 ||
        lseek(err_fd, 0, SEEK_SET) != 0)
        abort();
    dup2(null_fd, STDOUT_FILENO);
    dup2(err_fd, STDERR_FILENO);
    int rc = c->run(argc, argv);
    fflush(stdout);
    fflush(stderr);
    dup2(saved_out, STDOUT_FILENO);
    dup2(saved_err, STDERR_FILENO);
    close(saved_out);
    close(saved_err);
    char said[4096];
    ssize_t n = pread(err_fd, said, sizeof said - 1, 0);
    said[n > 0 ? n : 0] = '\0';
    ++runs;
    int bad = rc < 0 || rc > 2;
    if (rc == 2) {
        char prefix[32];
        snprintf(prefix, sizeof prefix, "abrdf %s: ", c->name);
        const char *nl = strchr(said, '\n');
        bad |= strncmp(said, prefix, strlen(prefix)) != 0 || !nl || nl[1] != '\0';
        ++refused;
    }
    if (bad) {
        fprintf(stderr, "fuzz_cli: abrdf %s exited %d with stderr:\n%s\narguments:\n", c->name, rc,
                said);
        for (int i = 0; i < argc; ++i) fprintf(stderr, "  [%d] '%s'\n", i, argv[i]);
        abort();
    }
    free(text);
    return 0;
}
