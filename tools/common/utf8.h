/* utf8.h - reading UTF-8 as the Unicode standard defines it (shortest form, no surrogates, at
 * most U+10FFFF), for the writers that must not pass invalid text on (JSON, Python). */
#ifndef ABRDF_UTF8_H
#define ABRDF_UTF8_H

/* The UTF-8 sequence at s: its length (1-4) with its code point in *cp, or 0 if s does not
 * start a valid sequence (the caller then treats *s as one stray byte). s[0] must not be 0. */
int utf8_decode(const char *s, unsigned long *cp);

#endif
