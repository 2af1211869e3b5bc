/* test_files.c - files in and out (tools/common: out_file.h, in_file.h, path_msg.h, utf8.h):
 * an output replaces its target only when committed, whole, with the target's permissions,
 * through a link to where it points; a discarded or failed output leaves the target as it
 * was and no temporary file; outputs that are inputs are caught however they are named;
 * inputs must be regular files; lines have any length; messages keep their reason. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <dirent.h>
#include <unistd.h>

#include "in_file.h"
#include "out_file.h"
#include "path_msg.h"
#include "test_util.h"
#include "utf8.h"

static char dir[256];

static const char *at(const char *name)
{
    static char buf[4][512];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static void put(const char *name, const char *text)
{
    FILE *f = fopen(at(name), "w");
    ck_assert_ptr_nonnull(f);
    fputs(text, f);
    fclose(f);
}

static char *get(const char *name)
{
    static char buf[4096];
    FILE *f = fopen(at(name), "r");
    if (!f) return NULL;
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

/* Files of the directory (hidden temporary files included). */
static int count_files(void)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) ++n;
    closedir(d);
    return n;
}

START_TEST(commit_replaces_discard_keeps)
{
    char err[512];
    put("t.txt", "old");
    int files = count_files();
    out_file o = OUT_FILE_INIT;
    out_file *const one[1] = {&o};
    ck_assert_int_eq(out_file_open(&o, at("t.txt"), err, sizeof err), 0);
    ck_assert_int_eq(count_files(), files + 1); /* the temporary file, beside the target */
    fputs("new", o.f);
    ck_assert_int_eq(out_file_close(&o, err, sizeof err), 0);
    ck_assert_str_eq(get("t.txt"), "old"); /* complete, not yet visible */
    ck_assert_int_eq(out_file_commit(one, 1, err, sizeof err), 0);
    ck_assert_str_eq(get("t.txt"), "new");
    out_file_discard(&o);
    ck_assert_int_eq(count_files(), files);
    /* Discarded before or after closing: the target stays, the temporary file goes. */
    ck_assert_int_eq(out_file_open(&o, at("t.txt"), err, sizeof err), 0);
    fputs("lost", o.f);
    out_file_discard(&o);
    ck_assert_int_eq(out_file_open(&o, at("t.txt"), err, sizeof err), 0);
    fputs("lost", o.f);
    ck_assert_int_eq(out_file_close(&o, err, sizeof err), 0);
    out_file_discard(&o);
    ck_assert_str_eq(get("t.txt"), "new");
    ck_assert_int_eq(count_files(), files);
    out_file_discard(&o); /* twice is harmless */
}
END_TEST

START_TEST(several_outputs_all_or_none)
{
    char err[512];
    put("a.txt", "old a");
    put("b.txt", "old b");
    int files = count_files();
    out_file a = OUT_FILE_INIT, b = OUT_FILE_INIT;
    out_file *const both[2] = {&a, &b};
    ck_assert_int_eq(out_file_open(&a, at("a.txt"), err, sizeof err), 0);
    ck_assert_int_eq(out_file_open(&b, at("b.txt"), err, sizeof err), 0);
    fputs("new a", a.f);
    fputs("new b", b.f);
    ck_assert_int_eq(out_file_close(&a, err, sizeof err), 0);
    /* b is not complete: nothing is committed, every temporary file is removed */
    ck_assert_int_eq(out_file_commit(both, 2, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "b.txt"), "%s", err);
    out_file_discard(&a);
    out_file_discard(&b);
    ck_assert_str_eq(get("a.txt"), "old a");
    ck_assert_str_eq(get("b.txt"), "old b");
    ck_assert_int_eq(count_files(), files);
}
END_TEST

/* A file-size limit (a full disk without root): the write fails, the reason is EFBIG. */
START_TEST(a_failed_write_is_reported_with_its_reason)
{
    char err[512];
    put("big.txt", "old");
    struct rlimit old, lim = {100, 100};
    getrlimit(RLIMIT_FSIZE, &old);
    lim.rlim_max = old.rlim_max;
    ck_assert_int_eq(setrlimit(RLIMIT_FSIZE, &lim), 0);
    out_file o = OUT_FILE_INIT;
    ck_assert_int_eq(out_file_open(&o, at("big.txt"), err, sizeof err), 0); /* ignores SIGXFSZ */
    for (int i = 0; i < 1000; ++i) fputs("0123456789", o.f);
    int rc = out_file_close(&o, err, sizeof err);
    setrlimit(RLIMIT_FSIZE, &old);
    ck_assert_int_eq(rc, -1);
    ck_assert_msg(strstr(err, "big.txt: write failed: File too large"), "%s", err);
    out_file_discard(&o);
    ck_assert_str_eq(get("big.txt"), "old");
}
END_TEST

START_TEST(links_modes_devices_directories)
{
    char err[512];
    out_file o = OUT_FILE_INIT;
    out_file *const one[1] = {&o};
    put("real.txt", "old");
    chmod(at("real.txt"), 0640);
    ck_assert_int_eq(symlink("real.txt", at("link.txt")), 0);
    ck_assert_int_eq(out_file_open(&o, at("link.txt"), err, sizeof err), 0);
    fputs("through", o.f);
    ck_assert_int_eq(out_file_close(&o, err, sizeof err), 0);
    ck_assert_int_eq(out_file_commit(one, 1, err, sizeof err), 0);
    out_file_discard(&o);
    struct stat st;
    ck_assert_int_eq(lstat(at("link.txt"), &st), 0);
    ck_assert(S_ISLNK(st.st_mode)); /* the link stays a link */
    ck_assert_str_eq(get("real.txt"), "through");
    ck_assert_int_eq(stat(at("real.txt"), &st), 0);
    ck_assert_int_eq(st.st_mode & 0777, 0640);
    /* A character device is written in place, every write checked. */
    ck_assert_int_eq(out_file_open(&o, "/dev/null", err, sizeof err), 0);
    fputs("gone", o.f);
    ck_assert_int_eq(out_file_close(&o, err, sizeof err), 0);
    ck_assert_int_eq(out_file_commit(one, 1, err, sizeof err), 0);
    out_file_discard(&o);
    ck_assert_int_eq(out_file_open(&o, "/dev/full", err, sizeof err), 0);
    fputs("full", o.f);
    ck_assert_int_eq(out_file_close(&o, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "/dev/full: write failed: No space left on device"), "%s", err);
    out_file_discard(&o);
    ck_assert_int_eq(out_file_open(&o, dir, err, sizeof err), -1);
    ck_assert_msg(strstr(err, "is a directory"), "%s", err);
    ck_assert_int_eq(out_file_open(&o, at("no/such/x.txt"), err, sizeof err), -1);
    ck_assert_msg(strstr(err, "No such file or directory"), "%s", err);
    out_file_discard(&o);
}
END_TEST

START_TEST(outputs_that_are_inputs_are_caught)
{
    char err[512];
    put("in.scene", "scene");
    ck_assert_int_eq(symlink("in.scene", at("sym.scene")), 0);
    ck_assert_int_eq(link(at("in.scene"), at("hard.scene")), 0);
    char dot[600], rel[600];
    snprintf(dot, sizeof dot, "%s/./in.scene", dir);
    snprintf(rel, sizeof rel, "%s/../%s/in.scene", dir, strrchr(dir, '/') + 1);
    char in_path[600];
    snprintf(in_path, sizeof in_path, "%s", at("in.scene"));
    const char *in = in_path, *role = "scene", *orole[2] = {"output", "preview"};
    const char *names[] = {at("in.scene"), dot, rel, at("sym.scene"), at("hard.scene")};
    for (int i = 0; i < 5; ++i) {
        ck_assert_int_eq(out_files_distinct(&names[i], orole, 1, &in, &role, 1, err, sizeof err),
                         -1);
        ck_assert_msg(strstr(err, "is the same file as the scene"), "%s", err);
    }
    /* Two outputs that do not exist yet, named differently, are still the same file. */
    char new_dot[600];
    snprintf(new_dot, sizeof new_dot, "%s/./new.exr", dir);
    const char *outs[2] = {at("new.exr"), new_dot};
    ck_assert_int_eq(out_files_distinct(outs, orole, 2, &in, &role, 1, err, sizeof err), -1);
    const char *fine[2] = {at("new.exr"), at("new.png")};
    ck_assert_int_eq(out_files_distinct(fine, orole, 2, &in, &role, 1, err, sizeof err), 0);
    const char *none = NULL;
    ck_assert_int_eq(out_files_distinct(fine, orole, 2, &none, &role, 1, err, sizeof err), 0);
}
END_TEST

START_TEST(inputs_are_regular_files)
{
    char err[512];
    ck_assert_int_eq(mkfifo(at("fifo"), 0600), 0);
    ck_assert_ptr_null(in_file_open(at("fifo"), err, sizeof err)); /* does not block */
    ck_assert_msg(strstr(err, "fifo: is a FIFO, not a regular file"), "%s", err);
    ck_assert_ptr_null(in_file_open(dir, err, sizeof err));
    ck_assert_msg(strstr(err, "is a directory"), "%s", err);
    ck_assert_ptr_null(in_file_open("/dev/null", err, sizeof err));
    ck_assert_msg(strstr(err, "character device"), "%s", err);
    ck_assert_int_eq(in_file_check(at("missing"), err, sizeof err), -1);
    ck_assert_msg(strstr(err, "missing: cannot open: No such file or directory"), "%s", err);
}
END_TEST

START_TEST(lines_of_any_length)
{
    FILE *f = fopen(at("lines.txt"), "w");
    for (int i = 0; i < 100000; ++i) fputc('a' + i % 26, f);
    fputs("\r\nshort\n\nno newline", f);
    fclose(f);
    char err[512], *line = NULL;
    size_t cap = 0;
    f = in_file_open(at("lines.txt"), err, sizeof err);
    ck_assert_ptr_nonnull(f);
    ck_assert_int_eq(in_file_line(f, &line, &cap), 100000);
    ck_assert_uint_eq(strlen(line), 100000);
    ck_assert_int_eq(in_file_line(f, &line, &cap), 5);
    ck_assert_str_eq(line, "short");
    ck_assert_int_eq(in_file_line(f, &line, &cap), 0);
    ck_assert_int_eq(in_file_line(f, &line, &cap), 10);
    ck_assert_str_eq(line, "no newline");
    ck_assert_int_eq(in_file_line(f, &line, &cap), -1);
    free(line);
    fclose(f);
}
END_TEST

START_TEST(messages_keep_their_reason)
{
    char path[4200], msg[256];
    memset(path, 'p', 4100);
    memcpy(path + 4090, "/file.scene", 12);
    path_msg(msg, sizeof msg, path, ":%d: %s", 12, "unknown directive 'teapot'");
    ck_assert_msg(strstr(msg, "...") && strstr(msg, "file.scene:12: unknown directive 'teapot'"),
                  "%s", msg);
    ck_assert_uint_eq(strlen(msg), sizeof msg - 1);
    path_msg(msg, sizeof msg, "short.scene", ": %s", "fine");
    ck_assert_str_eq(msg, "short.scene: fine");
    /* A cut never splits a UTF-8 character. */
    char utf[400] = "";
    for (int i = 0; i < 100; ++i) strcat(utf, "\xc3\xa9");
    char s[64];
    path_short(s, sizeof s, utf, 20);
    ck_assert_uint_le(strlen(s), 20);
    for (const char *p = s; *p;) {
        unsigned long cp;
        int n = *p == '.' ? 1 : utf8_decode(p, &cp);
        ck_assert_int_gt(n, 0);
        p += n;
    }
}
END_TEST

START_TEST(utf8_as_the_standard_says)
{
    unsigned long cp;
    ck_assert_int_eq(utf8_decode("A", &cp), 1);
    ck_assert_int_eq(utf8_decode("\xc3\xa9", &cp), 2);
    ck_assert_uint_eq(cp, 0xe9);
    ck_assert_int_eq(utf8_decode("\xe2\x82\xac", &cp), 3);
    ck_assert_uint_eq(cp, 0x20ac);
    ck_assert_int_eq(utf8_decode("\xf4\x8f\xbf\xbf", &cp), 4);
    ck_assert_uint_eq(cp, 0x10ffff);
    const char *bad[] = {"\xe9",
                         "\xc0\xaf",
                         "\xe0\x80\xaf",
                         "\xed\xa0\x80",
                         "\xf4\x90\x80\x80",
                         "\xf8\x88\x80\x80\x80",
                         "\xc3",
                         "\x80",
                         "\xe2\x82"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        ck_assert_msg(utf8_decode(bad[i], &cp) == 0, "bad[%zu] accepted", i);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("files");
    TCase *t = tcase_create("files");
    tcase_add_test(t, commit_replaces_discard_keeps);
    tcase_add_test(t, several_outputs_all_or_none);
    tcase_add_test(t, a_failed_write_is_reported_with_its_reason);
    tcase_add_test(t, links_modes_devices_directories);
    tcase_add_test(t, outputs_that_are_inputs_are_caught);
    tcase_add_test(t, inputs_are_regular_files);
    tcase_add_test(t, lines_of_any_length);
    tcase_add_test(t, messages_keep_their_reason);
    tcase_add_test(t, utf8_as_the_standard_says);
    suite_add_tcase(s, t);
    return s;
}

int main(void)
{
    snprintf(dir, sizeof dir, "%s/abrdf_files_XXXXXX",
             getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(dir)) return 1;
    int rc = tu_run(suite());
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0) rc = 1;
    return rc;
}
