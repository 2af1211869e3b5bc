/* advise_asset.c - `abrdf advise FILE`: the selection for every pbr material of a glTF,
 * MaterialX or scene file (advise_asset.h, docs/GLTF.md "Advising a file"). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "advise_asset.h"
#include "advise_budget.h"
#include "cli.h"
#include "budget_run.h"
#include "in_file.h"
#include "map_range.h"
#include "path_msg.h"
#include "pbr_select.h"
#include "scene_load.h"
#include "scene_select.h"

#define CMD "advise"
#define BRIDGE_MAX_OUTPUT (16u << 20) /* bytes of material lines from the MaterialX reader */

static int ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    if (n < m) return 0;
    for (size_t i = 0; i < m; ++i) {
        char c = s[n - m + i];
        if (c >= 'A' && c <= 'Z') c = (char)(c - 'A' + 'a');
        if (c != tail[i]) return 0;
    }
    return 1;
}

int advise_is_asset(const char *name)
{
    return ends_with(name, ".gltf") || ends_with(name, ".glb") || ends_with(name, ".mtlx") ||
           ends_with(name, ".scene");
}

/* ---- MaterialX through the Python package --------------------------------------------- */

/* Read both pipes to their end (stdout up to BRIDGE_MAX_OUTPUT, stderr's first 1 KiB). */
static int drain(int out_fd, int err_fd, char **out, size_t *out_len, char *errbuf,
                 size_t errbuf_size)
{
    size_t cap = 0, len = 0, elen = 0;
    char *buf = NULL;
    int open_fds = 2, too_long = 0;
    struct pollfd pf[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
    while (open_fds) {
        if (poll(pf, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int k = 0; k < 2; ++k) {
            if (pf[k].fd < 0 || !(pf[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char chunk[8192];
            ssize_t got = read(pf[k].fd, chunk, sizeof chunk);
            if (got <= 0) {
                if (got < 0 && errno == EINTR) continue;
                pf[k].fd = -1, --open_fds;
                continue;
            }
            if (k == 1) { /* the last errbuf_size - 1 bytes: the one-line message is last */
                size_t take = (size_t)got, room = errbuf_size - 1;
                const char *from = chunk;
                if (take > room) from += take - room, take = room;
                if (elen + take > room) {
                    size_t drop = elen + take - room;
                    memmove(errbuf, errbuf + drop, elen - drop);
                    elen -= drop;
                }
                memcpy(errbuf + elen, from, take);
                elen += take;
                errbuf[elen] = '\0';
                continue;
            }
            if (len + (size_t)got > BRIDGE_MAX_OUTPUT) {
                too_long = 1;
                continue;
            }
            if (len + (size_t)got + 1 > cap) {
                size_t grown = cap ? 2 * cap : 65536;
                while (grown < len + (size_t)got + 1) grown *= 2;
                char *b = realloc(buf, grown);
                if (!b) {
                    free(buf);
                    return -1;
                }
                buf = b, cap = grown;
            }
            memcpy(buf + len, chunk, (size_t)got);
            len += (size_t)got;
        }
    }
    if (too_long) {
        free(buf);
        return -2;
    }
    if (!buf) buf = calloc(1, 1);
    if (!buf) return -1;
    buf[len] = '\0';
    *out = buf, *out_len = len;
    return 0;
}

/* The last non-empty line of text (the reader's one-line message after any traceback). */
static const char *last_line(char *text)
{
    char *end = text + strlen(text);
    while (end > text && (end[-1] == '\n' || end[-1] == '\r' || end[-1] == ' ')) *--end = '\0';
    char *nl = strrchr(text, '\n');
    return nl ? nl + 1 : text;
}

/* `python -m abrdf.scene_materials PATH`: its stdout, the document's material lines. */
static int mtlx_lines(const char *path, char **text, size_t *len, char *err, size_t err_size)
{
    const char *py = getenv("ABRDF_PYTHON");
    if (!py || !*py) py = "python3";
    int out_pipe[2], err_pipe[2];
    if (pipe(out_pipe)) {
        path_msg(err, err_size, path, ": cannot start the MaterialX reader: %s", strerror(errno));
        return -1;
    }
    if (pipe(err_pipe)) {
        close(out_pipe[0]), close(out_pipe[1]);
        path_msg(err, err_size, path, ": cannot start the MaterialX reader: %s", strerror(errno));
        return -1;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        dup2(out_pipe[1], 1), dup2(err_pipe[1], 2);
        close(out_pipe[0]), close(out_pipe[1]), close(err_pipe[0]), close(err_pipe[1]);
        int devnull = open("/dev/null", O_RDONLY);
        if (devnull >= 0) dup2(devnull, 0), close(devnull);
        /* PYTHONSAFEPATH (Python 3.11 on): the working directory is not put on the module
         * path, so a directory holding an asset cannot plant its own `abrdf` package */
        setenv("PYTHONSAFEPATH", "1", 1);
        char dashed[4096];
        const char *arg = path;
        if (path[0] == '-' && snprintf(dashed, sizeof dashed, "./%s", path) < (int)sizeof dashed)
            arg = dashed;
        execlp(py, py, "-m", "abrdf.scene_materials", arg, (char *)NULL);
        fprintf(stderr, "cannot run %s: %s\n", py, strerror(errno));
        _exit(127);
    }
    close(out_pipe[1]), close(err_pipe[1]);
    if (pid < 0) {
        close(out_pipe[0]), close(err_pipe[0]);
        path_msg(err, err_size, path, ": cannot start the MaterialX reader: %s", strerror(errno));
        return -1;
    }
    char errbuf[1024] = "";
    int rc = drain(out_pipe[0], err_pipe[0], text, len, errbuf, sizeof errbuf);
    close(out_pipe[0]), close(err_pipe[0]);
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    int ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (rc == 0 && ok) return 0;
    if (rc == 0) free(*text);
    const char *why = last_line(errbuf);
    if (rc == -2)
        snprintf(err, err_size, "%s: more than %u bytes of materials", path, BRIDGE_MAX_OUTPUT);
    else if (rc == -1)
        snprintf(err, err_size, "out of memory");
    else if (strstr(why, "No module named") || (WIFEXITED(status) && WEXITSTATUS(status) == 127))
        /* the reader is not there: say what to install and how to point at it */
        snprintf(err, err_size,
                 "%s: reading MaterialX needs the abrdf Python package and MaterialX (%s: %s); "
                 "ABRDF_PYTHON names the interpreter that has them",
                 path, py, *why ? why : "failed");
    else
        /* the reader's own message already names the file */
        snprintf(err, err_size, "%s", *why ? why : "the MaterialX reader failed");
    return -1;
}

int advise_asset_load(const char *path, scene *out, char *err, size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (ends_with(path, ".scene") || scene_is_gltf(path))
        return scene_load(path, out, err, err_size);
    if (in_file_check(path, err, err_size)) return -1;
    if (ends_with(path, ".mtlx")) {
        char *text;
        size_t len;
        if (mtlx_lines(path, &text, &len, err, err_size)) return -1;
        char name[1200];
        snprintf(name, sizeof name, "%s (its materials as scene lines)", path);
        int rc = scene_parse_materials(name, text, len, out, err, err_size);
        free(text);
        /* the lines are the reader's, not the document's: a material is named by the file */
        for (int i = 0; !rc && i < out->material_count; ++i) out->materials[i].line = 0;
        return rc;
    }
    snprintf(err, err_size, "%s: not a file abrdf advise reads (.gltf, .glb, .mtlx, .scene)", path);
    return -1;
}

/* ---- the choices ------------------------------------------------------------------------ */

/* The table-entry form the printers take: the material's name and where it comes from. */
static void entry_of(const scene_material *sm, const char *path, const abrdf_material *m,
                     mat_entry *e)
{
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", sm->name);
    snprintf(e->file, sizeof e->file, "%s", path);
    e->line = sm->line;
    snprintf(e->source, sizeof e->source, "%s%s", sm->textured ? "textured " : "",
             "glTF metallic-roughness material (abrdf_pbr_material, docs/GLTF.md)");
    e->m = *m;
    e->m.name = e->name;
}

/* The budget mode over a roughness map (pbr_budget_range), printed. */
static void print_budget_map(const char *path, const scene_material *sm, double max_nmse,
                             const pbr_range *range, const pbr_budget_choice *c,
                             const select_trace *trace, int json)
{
    char pair[128];
    budget_pair_name(c->diffuse, c->specular, &c->params, pair, sizeof pair);
    if (json) {
        printf("{\"material\": ");
        cli_json_string(stdout, sm->name);
        printf(", \"file\": ");
        cli_json_string(stdout, path);
        printf(", \"budget\": {\"max_nmse\": %.10g}, \"roughness_map\": ", max_nmse);
        cli_json_string(stdout, range->what ? range->what : "");
        printf(", \"groups\": %d, \"within\": %s,\n \"diffuse\": ", c->groups,
               c->within ? "true" : "false");
        if (c->diffuse == ABRDF_MODEL_NONE)
            printf("null");
        else
            cli_json_string(stdout, abrdf_model_get(c->diffuse)->name);
        printf(", \"specular\": ");
        cli_json_string(stdout, abrdf_model_get(c->specular)->name);
        printf(", \"params\": ");
        budget_params_json(stdout, c->diffuse, c->specular, &c->params);
        printf(",\n \"error\": {\"nmse_pred\": %.10g}, \"cost\": {\"total\": ", c->nmse);
        if (c->cost >= 0)
            printf("%.10g", c->cost);
        else
            printf("null");
        printf(", \"unit\": ");
        cli_json_string(stdout, c->unit ? c->unit : "");
        printf("},\n \"trace\": [");
        for (int k = 0; k < trace->count; ++k) {
            printf("%s\n  {\"text\": ", k ? "," : "");
            cli_json_string(stdout, trace->steps[k].text);
            printf("}");
        }
        printf("\n]}\n");
        return;
    }
    printf("material   %s (textured; %s)\n", sm->name, path);
    printf("budget     NMSE < %g over the roughness map %s (%d groups of texels)\n", max_nmse,
           range->what ? range->what : "", c->groups);
    printf("choice     %s  ", pair);
    budget_params_text(stdout, c->diffuse, c->specular, &c->params);
    printf("\n");
    if (c->within)
        printf("error      NMSE %.3g predicted over the map (the texels' share-weighted mean)\n",
               c->nmse);
    else
        printf("error      none within the budget at every value: the photoreal choice\n");
    if (c->cost >= 0) printf("cost       %.3g %s\n", c->cost, c->unit ? c->unit : "");
    printf("why:\n");
    for (int k = 0; k < trace->count; ++k) printf("  %2d. %s\n", k + 1, trace->steps[k].text);
}

/* A material with a roughness map: the choice over the map's values (pbr_select.h). */
static int advise_map(const char *path, const scene *s, const scene_material *sm,
                      const mat_entry *e, const select_request *rq, const abrdf_tolerance *tol,
                      const abrdf_costs *costs, int json, advise_printer print)
{
    char msg[1024];
    pbr_range range;
    if (map_range_read(NULL, sm, &range, msg, sizeof msg))
        return cli_fail(CMD, "%s: material '%s': %s", path, sm->name, msg);
    select_trace trace = SELECT_TRACE_INIT;
    int rc = 0;
    if (rq->by_budget) {
        /* predicted as `abrdf render --adaptive --budget` predicts it: on the file's own
         * camera and lights (scene_budget_view), so that both choose the same pair */
        abrdf_light_dir lights[SCENE_MAX_LIGHTS];
        abrdf_view view;
        scene_budget_view(s, 4, &view, lights);
        pbr_budget_choice c;
        if (pbr_budget_range(&sm->pbr_in, &range, rq->max_nmse, costs, &view, &c, &trace, msg,
                             sizeof msg))
            rc = cli_fail(CMD, "%s: material '%s': %s", path, sm->name, msg);
        else
            print_budget_map(path, sm, rq->max_nmse, &range, &c, &trace, json);
    } else {
        abrdf_selection sel;
        abrdf_params params;
        if (pbr_select_range(&sm->pbr_in, &range, rq->goal, tol, costs, &sel, &params, &trace, msg,
                             sizeof msg))
            rc = cli_fail(CMD, "%s: material '%s': %s", path, sm->name, msg);
        else
            print(&sel, &params, &trace, e, tol, json);
    }
    select_trace_free(&trace);
    return rc;
}

static int advise_one(const char *path, const scene *s, const scene_material *sm,
                      const select_request *rq, const abrdf_tolerance *tol,
                      const abrdf_costs *costs, int json, advise_printer print)
{
    abrdf_material m;
    abrdf_material_init(&m);
    char msg[512];
    if (abrdf_pbr_material(&sm->pbr_in, &m) != ABRDF_OK) {
        abrdf_pbr_check(&sm->pbr_in, msg, sizeof msg);
        return cli_fail(CMD, "%s: material '%s': %s", path, sm->name, msg);
    }
    mat_entry e;
    entry_of(sm, path, &m, &e);
    if (sm->maps[SCENE_MAP_ROUGHNESS].path)
        return advise_map(path, s, sm, &e, rq, tol, costs, json, print);
    if (rq->by_budget) return advise_budget(&e.m, &e, rq->max_nmse, costs, json, 0, NULL, NULL);
    abrdf_selection sel;
    abrdf_params params;
    select_trace trace = SELECT_TRACE_INIT;
    abrdf_selection_init(&sel);
    abrdf_params_init(ABRDF_MODEL_NONE, &params);
    int rc = 0;
    if (abrdf_select(&e.m, rq->goal, tol, costs, &sel, &params, select_trace_keep, &trace) !=
        ABRDF_OK)
        rc = cli_fail(CMD, "%s: material '%s': %s", path, sm->name, sel.message);
    else if (trace.lost)
        rc = cli_fail(CMD, "out of memory");
    else
        print(&sel, &params, &trace, &e, tol, json);
    select_trace_free(&trace);
    return rc;
}

int advise_asset(const char *path, const select_request *rq, const abrdf_tolerance *tol,
                 const abrdf_costs *costs, int json, advise_printer print)
{
    scene s;
    char err[1024];
    if (advise_asset_load(path, &s, err, sizeof err)) return cli_fail(CMD, "%s", err);
    int count = 0, rc = 0;
    for (int i = 0; i < s.material_count; ++i) count += s.materials[i].pbr;
    if (!count) {
        scene_free(&s);
        return cli_fail(CMD, "%s: no glTF-style (pbr) material to advise", path);
    }
    for (int i = 0; i < s.material_count; ++i) { /* every material sound before any output */
        const scene_material *sm = &s.materials[i];
        char msg[512];
        if (sm->pbr && abrdf_pbr_check(&sm->pbr_in, msg, sizeof msg) != ABRDF_OK) {
            scene_free(&s);
            return cli_fail(CMD, "%s: material '%s': %s", path, sm->name, msg);
        }
    }
    if (json) {
        printf("{\"file\": ");
        cli_json_string(stdout, path);
        printf(", \"materials\": [\n");
    }
    int done = 0;
    for (int i = 0; i < s.material_count && !rc; ++i) {
        if (!s.materials[i].pbr) continue;
        if (json && done) printf(",\n");
        if (!json && done) printf("\n");
        rc = advise_one(path, &s, &s.materials[i], rq, tol, costs, json, print);
        ++done;
    }
    if (json && !rc) printf("]}\n");
    scene_free(&s);
    return rc;
}
