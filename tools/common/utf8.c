/* utf8.c - UTF-8 decoding (utf8.h; Unicode 15, Table 3-7 "Well-Formed UTF-8 Byte Sequences"). */
#include "utf8.h"

int utf8_decode(const char *s, unsigned long *cp)
{
    const unsigned char *u = (const unsigned char *)s;
    if (u[0] < 0x80) {
        *cp = u[0];
        return 1;
    }
    int len = u[0] >= 0xc2 && u[0] <= 0xdf   ? 2
              : u[0] >= 0xe0 && u[0] <= 0xef ? 3
              : u[0] >= 0xf0 && u[0] <= 0xf4 ? 4
                                             : 0;
    if (!len) return 0;
    unsigned long c = u[0] & (0x7f >> len);
    for (int i = 1; i < len; ++i) {
        if ((u[i] & 0xc0) != 0x80) return 0; /* also stops at the terminating NUL */
        c = (c << 6) | (u[i] & 0x3f);
    }
    /* Overlong forms, surrogates and code points past U+10FFFF are not UTF-8. */
    if ((len == 3 && c < 0x800) || (len == 4 && (c < 0x10000 || c > 0x10ffff)) ||
        (c >= 0xd800 && c <= 0xdfff))
        return 0;
    *cp = c;
    return len;
}
