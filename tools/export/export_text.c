/* export_text.c - escaping for generated POV-Ray and Python text (export_text.h). */
#include <string.h>

#include "export_text.h"
#include "utf8.h"

static int printable(unsigned char c) { return c >= 0x20 && c <= 0x7e; }

/* Shared by the comment writers of both languages: neither may see a raw line break, and
 * showing every other byte as \xHH keeps the line ASCII. */
static void comment_text(FILE *f, const char *s, size_t n)
{
    for (size_t i = 0; s && i < n; ++i) {
        unsigned char c = (unsigned char)s[i];
        if (c == '\\')
            fputs("\\\\", f);
        else if (printable(c))
            fputc(c, f);
        else
            fprintf(f, "\\x%02x", c);
    }
}

/* comment_text of each line of text after `lead`, one output line per input line. */
static void comment_lines(FILE *f, const char *lead, const char *text)
{
    while (text && *text) {
        const char *nl = strchr(text, '\n');
        size_t n = nl ? (size_t)(nl - text) : strlen(text);
        fputs(lead, f);
        comment_text(f, text, n);
        fputc('\n', f);
        text += n + (nl != NULL);
    }
}

void pov_comment(FILE *f, const char *s) { comment_text(f, s, s ? strlen(s) : 0); }

void pov_comment_lines(FILE *f, const char *text) { comment_lines(f, "// ", text); }

void py_comment(FILE *f, const char *s) { comment_text(f, s, s ? strlen(s) : 0); }

void py_comment_lines(FILE *f, const char *text) { comment_lines(f, "# ", text); }

int pov_string(FILE *f, const char *s)
{
    for (const char *p = s; p && *p; ++p)
        if (!printable((unsigned char)*p)) return -1;
    fputc('"', f);
    for (; s && *s; ++s) {
        if (*s == '"' || *s == '\\') fputc('\\', f);
        fputc(*s, f);
    }
    fputc('"', f);
    return 0;
}

void py_string(FILE *f, const char *s)
{
    fputc('"', f);
    while (s && *s) {
        unsigned char c = (unsigned char)*s;
        unsigned long cp;
        int len = utf8_decode(s, &cp);
        if (!len)
            fprintf(f, "\\udc%02x", c); /* surrogateescape of a stray byte */
        else if (c == '"' || c == '\\')
            fprintf(f, "\\%c", c);
        else if (printable(c))
            fputc(c, f);
        else if (cp < 0x80)
            fprintf(f, "\\x%02x", c);
        else if (cp < 0x10000)
            fprintf(f, "\\u%04lx", cp);
        else
            fprintf(f, "\\U%08lx", cp);
        s += len ? len : 1;
    }
    fputc('"', f);
}
