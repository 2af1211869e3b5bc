/* module_open.c - the tool's modules, found by one rule (module_open.h). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "module_open.h"

static void *open_in(const char *dir, const char *rel, const char *name)
{
    char path[4096];
    if (snprintf(path, sizeof path, "%s/%s%s", dir, rel, name) >= (int)sizeof path) return NULL;
    if (access(path, R_OK) != 0) return NULL;
    return dlopen(path, RTLD_NOW | RTLD_LOCAL);
}

void *module_open(const char *env_var, const char *name, const char *relative)
{
    const char *env = getenv(env_var);
    if (env && *env) return dlopen(env, RTLD_NOW | RTLD_LOCAL);
    void *h = NULL;
    char exe[4096];
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (n > 0) {
        exe[n] = 0;
        char *slash = strrchr(exe, '/');
        if (slash) *slash = 0;
        h = open_in(exe, "", name);
        if (!h) {
            char rel[1024];
            snprintf(rel, sizeof rel, "%s/", relative);
            h = open_in(exe, rel, name);
        }
    }
    if (!h) h = dlopen(name, RTLD_NOW | RTLD_LOCAL); /* the loader's search path */
    return h;
}
