/* cmd_explore.c - `abrdf explore [--port N] [--bind ADDR] [--dir]`: serves the browser explorer
 * (docs/EXPLORER.md), the folder the CMake target `web` builds, on this machine. The folder is
 * static files only; python3's http.server serves it (any static server can). */
#define _POSIX_C_SOURCE 200809L /* getaddrinfo, execvp */
#include <errno.h>
#include <netdb.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

#include "cli.h"

#define CMD "explore"

#ifndef ABRDF_BUILD_WEB_DIR
#define ABRDF_BUILD_WEB_DIR "web"
#endif
#ifndef ABRDF_INSTALL_WEB_DIR
#define ABRDF_INSTALL_WEB_DIR "share/abrdf/web"
#endif

static int usage(void)
{
    printf("usage: abrdf explore [--port N] [--bind ADDR] [--dir]\n\n"
           "Serves the browser explorer (every model's lobe and lit sphere, two models compared,\n"
           "the selection and the budget) at http://ADDR:PORT/ until Ctrl-C, with python3's\n"
           "http.server ($ABRDF_PYTHON overrides the interpreter). The page runs libabrdf in\n"
           "WebAssembly in the browser; nothing is sent anywhere.\n"
           "  --port N     the port, 1-65535 (default 8000)\n"
           "  --bind ADDR  the address to listen on (default 127.0.0.1: this machine only)\n"
           "  --dir        print the explorer's folder and stop (to serve it another way)\n"
           "The folder is the first of $ABRDF_WEB_DIR, the build tree's web/ and the installed\n"
           "share/abrdf/web that holds index.html and abrdf_wasm.wasm.\n");
    return 0;
}

static int has_file(const char *dir, const char *name)
{
    char path[4096];
    int w = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (w < 0 || (size_t)w >= sizeof path) return 0;
    FILE *f = fopen(path, "rb");
    if (!f) return 0;
    fclose(f);
    return 1;
}

/* The explorer's folder, or NULL (after the message). */
static const char *web_dir(void)
{
    const char *env = getenv("ABRDF_WEB_DIR");
    if (env && *env) {
        if (has_file(env, "index.html") && has_file(env, "abrdf_wasm.wasm")) return env;
        cli_fail(CMD, "ABRDF_WEB_DIR=%s: no index.html and abrdf_wasm.wasm there", env);
        return NULL;
    }
    const char *dirs[2] = {ABRDF_BUILD_WEB_DIR, ABRDF_INSTALL_WEB_DIR};
    for (int i = 0; i < 2; ++i)
        if (has_file(dirs[i], "index.html") && has_file(dirs[i], "abrdf_wasm.wasm")) return dirs[i];
    cli_fail(CMD,
             "the explorer is not built (no index.html and abrdf_wasm.wasm in %s or %s): it needs "
             "emscripten (scripts/setup.sh installs it), then cmake --build",
             ABRDF_BUILD_WEB_DIR, ABRDF_INSTALL_WEB_DIR);
    return NULL;
}

/* 0 if ADDR:PORT can be listened on now; else the message and -1. */
static int port_free(const char *addr, const char *port)
{
    struct addrinfo hints, *res = NULL;
    memset(&hints, 0, sizeof hints);
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
    int rc = getaddrinfo(addr, port, &hints, &res);
    if (rc) return cli_fail(CMD, "--bind %s: %s", addr, gai_strerror(rc)) ? -1 : -1;
    int fd = socket(res->ai_family, res->ai_socktype, res->ai_protocol), ok = -1, e = 0;
    if (fd >= 0) {
        int one = 1;
        setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
        ok = bind(fd, res->ai_addr, res->ai_addrlen);
        e = errno;
        close(fd);
    } else {
        e = errno;
    }
    freeaddrinfo(res);
    if (ok) {
        cli_fail(CMD, "cannot listen on %s:%s: %s%s", addr, port, strerror(e),
                 e == EADDRINUSE ? " (choose another with --port)" : "");
        return -1;
    }
    return 0;
}

int cmd_explore(int argc, char **argv)
{
    const char *port = "8000", *addr = "127.0.0.1";
    int dir_only = 0;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--dir")) {
            dir_only = 1;
        } else if (!strcmp(a, "--port") || !strcmp(a, "--bind")) {
            if (i + 1 >= argc) return cli_fail(CMD, "%s needs a value", a);
            const char *v = argv[++i];
            if (a[2] == 'p') {
                char *end;
                long p = strtol(v, &end, 10);
                if (end == v || *end || p < 1 || p > 65535)
                    return cli_fail(CMD, "--port %s: not a port number in 1-65535", v);
                port = v;
            } else {
                addr = v;
            }
        } else {
            return cli_fail(CMD, "unknown argument '%s' (abrdf explore --help)", a);
        }
    }
    const char *dir = web_dir();
    if (!dir) return 1;
    if (dir_only) {
        printf("%s\n", dir);
        return 0;
    }
    if (port_free(addr, port)) return 1;
    const char *py = getenv("ABRDF_PYTHON");
    if (!py || !*py) py = "python3";
    printf("abrdf explore: serving %s at http://%s:%s/ (Ctrl-C stops)\n", dir, addr, port);
    fflush(stdout);
    char *args[] = {(char *)py,   "-m",          "http.server", (char *)port, "--bind",
                    (char *)addr, "--directory", (char *)dir,   NULL};
    execvp(py, args);
    return cli_fail(CMD, "cannot run %s (%s): serve %s with any static web server", py,
                    strerror(errno), dir);
}
