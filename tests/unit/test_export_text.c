/* test_export_text.c - the escaping of every string that reaches generated POV-Ray or Python
 * text (tools/export/export_text.h), with hostile strings: quotes, backslashes, line breaks,
 * '#' directives, non-ASCII and invalid UTF-8, a 4 KiB name. What must hold: a comment stays
 * on its line and shows every byte; a string literal holds the text exactly (checked by
 * decoding it back here as POV-Ray and Python would), or is refused. The generated files are
 * parsed by the real hosts in tests/cli/test_cli_export.py (Python) and
 * tests/ports/test_pov_hostile.py (POV-Ray). */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "export_text.h"
#include "test_util.h"

static const char *const hostile[] = {
    "plain",
    "a\")box{-9,9}//",                   /* ends a string, adds geometry, comments the rest */
    "x\\q",                              /* an escape POV-Ray refuses */
    "line\n#fopen F \"/tmp/x\" write\n", /* a line break, then a directive */
    "cr\r#declare X = 1;",
    "trail\\",
    "quote\"\"\"triple",
    "caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80", /* UTF-8: 2, 3 and 4 bytes */
    "latin1 caf\xe9 \xff\xfe",                   /* not UTF-8 */
    "\xed\xa0\x80 surrogate, \xc0\xaf overlong", /* not UTF-8 either */
    "tab\there \x01\x1f\x7f",
    "",
};
#define HOSTILE_COUNT (sizeof hostile / sizeof hostile[0])

typedef void (*writer)(FILE *, const char *);

/* What a writer makes of s, as a malloc'd string. */
static char *render(writer w, const char *s)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    ck_assert_ptr_nonnull(f);
    w(f, s);
    fclose(f);
    return buf;
}

static int pov_string_ok;
static void pov_string_writer(FILE *f, const char *s) { pov_string_ok = pov_string(f, s); }

/* A comment's text: one line of printable ASCII that shows every byte (decoding the \\ and
 * \xHH escapes gives the input back). */
static void check_comment(writer w, const char *s)
{
    char *out = render(w, s);
    char *back = malloc(strlen(out) + 1), *b = back;
    for (const char *p = out; *p; ++p) {
        ck_assert_msg(*p >= 0x20 && *p <= 0x7e, "byte 0x%02x in a comment", (unsigned char)*p);
        if (*p != '\\') {
            *b++ = *p;
        } else if (p[1] == '\\') {
            *b++ = '\\', ++p;
        } else {
            ck_assert_int_eq(p[1], 'x');
            unsigned v;
            ck_assert_int_eq(sscanf(p + 2, "%2x", &v), 1);
            *b++ = (char)v, p += 3;
        }
    }
    *b = '\0';
    ck_assert_str_eq(back, s);
    free(back);
    free(out);
}

START_TEST(comments_stay_on_their_line)
{
    for (size_t i = 0; i < HOSTILE_COUNT; ++i) {
        check_comment(pov_comment, hostile[i]);
        check_comment(py_comment, hostile[i]);
    }
}
END_TEST

START_TEST(comment_lines_are_one_per_line)
{
    char *buf = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&buf, &len);
    pov_comment_lines(f, "first\nsecond #include \"x\"\n\nlast");
    py_comment_lines(f, "one\r\ntwo");
    fclose(f);
    ck_assert_str_eq(buf, "// first\n// second #include \"x\"\n// \n// last\n"
                          "# one\\x0d\n# two\n");
    free(buf);
}
END_TEST

/* POV-Ray 3.7 string escapes: \" and \\ (and \n, \t, ... which the writer never needs). */
START_TEST(pov_strings_hold_the_text_or_are_refused)
{
    for (size_t i = 0; i < HOSTILE_COUNT; ++i) {
        const char *s = hostile[i];
        int printable = 1;
        for (const char *p = s; *p; ++p) printable &= *p >= 0x20 && *p <= 0x7e;
        char *out = render(pov_string_writer, s);
        if (!printable) { /* POV-Ray would replace non-ASCII by spaces: refused */
            ck_assert_int_eq(pov_string_ok, -1);
            ck_assert_str_eq(out, "");
            free(out);
            continue;
        }
        ck_assert_int_eq(pov_string_ok, 0);
        size_t n = strlen(out);
        ck_assert(n >= 2 && out[0] == '"' && out[n - 1] == '"');
        char *back = malloc(n), *b = back;
        for (size_t k = 1; k + 1 < n; ++k) {
            ck_assert_msg(out[k] != '"' || out[k - 1] == '\\', "a bare quote in %s", out);
            if (out[k] == '\\') {
                ++k;
                ck_assert(out[k] == '"' || out[k] == '\\');
            }
            *b++ = out[k];
        }
        *b = '\0';
        ck_assert_str_eq(back, s);
        free(back);
        free(out);
    }
    char *out = render(pov_string_writer, "a\")box{-9,9}//");
    ck_assert_str_eq(out, "\"a\\\")box{-9,9}//\"");
    free(out);
}
END_TEST

/* Python: the literal is ASCII; decoding its escapes as Python does, then encoding with
 * surrogateescape (os.fsencode), gives the original bytes back. */
static void put_utf8(char **b, unsigned long cp)
{
    unsigned char *u = (unsigned char *)*b;
    if (cp >= 0xdc80 && cp <= 0xdcff) { /* surrogateescape: the original byte */
        *u++ = (unsigned char)(cp - 0xdc00);
    } else if (cp < 0x80) {
        *u++ = (unsigned char)cp;
    } else if (cp < 0x800) {
        *u++ = (unsigned char)(0xc0 | cp >> 6), *u++ = (unsigned char)(0x80 | (cp & 0x3f));
    } else if (cp < 0x10000) {
        *u++ = (unsigned char)(0xe0 | cp >> 12);
        *u++ = (unsigned char)(0x80 | ((cp >> 6) & 0x3f));
        *u++ = (unsigned char)(0x80 | (cp & 0x3f));
    } else {
        *u++ = (unsigned char)(0xf0 | cp >> 18);
        *u++ = (unsigned char)(0x80 | ((cp >> 12) & 0x3f));
        *u++ = (unsigned char)(0x80 | ((cp >> 6) & 0x3f));
        *u++ = (unsigned char)(0x80 | (cp & 0x3f));
    }
    *b = (char *)u;
}

static void check_python(const char *s)
{
    char *out = render(py_string, s);
    size_t n = strlen(out);
    ck_assert(n >= 2 && out[0] == '"' && out[n - 1] == '"');
    char *back = malloc(4 * n), *b = back;
    for (size_t k = 1; k + 1 < n; ++k) {
        ck_assert_msg(out[k] >= 0x20 && out[k] <= 0x7e, "byte 0x%02x", (unsigned char)out[k]);
        ck_assert_msg(out[k] != '"', "a bare quote in %s", out);
        if (out[k] != '\\') {
            *b++ = out[k];
            continue;
        }
        char kind = out[++k];
        int digits = kind == 'x' ? 2 : kind == 'u' ? 4 : kind == 'U' ? 8 : 0;
        if (!digits) {
            ck_assert(kind == '"' || kind == '\\');
            *b++ = kind;
            continue;
        }
        char hex[9] = {0};
        memcpy(hex, out + k + 1, (size_t)digits);
        put_utf8(&b, strtoul(hex, NULL, 16));
        k += (size_t)digits;
    }
    *b = '\0';
    ck_assert_str_eq(back, s);
    free(back);
    free(out);
}

START_TEST(python_strings_give_back_the_bytes)
{
    for (size_t i = 0; i < HOSTILE_COUNT; ++i) check_python(hostile[i]);
    char *out = render(py_string, "caf\xe9");
    ck_assert_str_eq(out, "\"caf\\udce9\"");
    free(out);
    out = render(py_string, "\xc3\xa9\xf0\x9f\x98\x80");
    ck_assert_str_eq(out, "\"\\u00e9\\U0001f600\"");
    free(out);
}
END_TEST

/* A 4 KiB name full of everything above: nothing is cut, nothing escapes. */
START_TEST(four_kib_names)
{
    char big[4097];
    size_t n = 0;
    for (size_t i = 0; n + 40 < sizeof big; i = (i + 1) % (HOSTILE_COUNT - 1)) {
        size_t l = strlen(hostile[i]);
        if (n + l >= sizeof big) break;
        memcpy(big + n, hostile[i], l);
        n += l;
    }
    while (n < sizeof big - 1) big[n++] = 'z';
    big[n] = '\0';
    ck_assert_uint_eq(strlen(big), 4096);
    check_comment(pov_comment, big);
    check_comment(py_comment, big);
    check_python(big);
    char *out = render(pov_string_writer, big);
    ck_assert_int_eq(pov_string_ok, -1); /* it holds non-ASCII */
    free(out);
    memset(big, 'q', 4096);
    big[100] = '"', big[200] = '\\';
    out = render(pov_string_writer, big);
    ck_assert_int_eq(pov_string_ok, 0);
    ck_assert_uint_eq(strlen(out), 4096 + 2 + 2);
    free(out);
}
END_TEST

static Suite *suite(void)
{
    Suite *s = suite_create("export_text");
    TCase *t = tcase_create("escaping");
    tcase_add_test(t, comments_stay_on_their_line);
    tcase_add_test(t, comment_lines_are_one_per_line);
    tcase_add_test(t, pov_strings_hold_the_text_or_are_refused);
    tcase_add_test(t, python_strings_give_back_the_bytes);
    tcase_add_test(t, four_kib_names);
    suite_add_tcase(s, t);
    return s;
}

int main(void) { return tu_run(suite()); }
