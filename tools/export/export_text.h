/* export_text.h - text in generated code stays data: every string that reaches a POV-Ray or
 * Python file (scene paths, material names, directories, the selection's trace) goes through
 * the one escaping function of its language and place here. Any byte may come in; what comes
 * out is one comment line, or one string literal that holds exactly the text, or a refusal.
 *
 *   pov_comment        the text of a POV-Ray `//` comment line
 *   pov_comment_lines  lines of text as POV-Ray `//` comment lines
 *   pov_string         a POV-Ray string literal, or a refusal
 *   py_comment         the text of a Python `#` comment line
 *   py_comment_lines   lines of text as Python `#` comment lines
 *   py_string          a Python string literal that decodes to the same file-system name
 */
#ifndef ABRDF_EXPORT_TEXT_H
#define ABRDF_EXPORT_TEXT_H

#include <stdio.h>

/* Printable ASCII as it is; a backslash as \\ and any other byte (line breaks, control bytes,
 * non-ASCII) as \xHH, so the comment cannot end before the line does and shows every byte. */
void pov_comment(FILE *f, const char *s);
/* Each line of text (split at '\n') as "// LINE\n", escaped by pov_comment. */
void pov_comment_lines(FILE *f, const char *text);
/* "s" with \" and \\ escaped. POV-Ray 3.7 strings (charset ascii) replace non-ASCII by
 * spaces, so any byte outside printable ASCII is refused: returns -1, writes nothing. */
int pov_string(FILE *f, const char *s);
/* As pov_comment: Python source must be UTF-8 and a line break would end the comment. */
void py_comment(FILE *f, const char *s);
/* Each line of text (split at '\n') as "# LINE\n", escaped by py_comment. */
void py_comment_lines(FILE *f, const char *text);
/* "s" as a Python 3 str literal: printable ASCII as it is (\" and \\ escaped), control bytes
 * as \xHH, UTF-8 characters as \uXXXX / \UXXXXXXXX, and bytes that are not UTF-8 as \udcHH
 * (Python's surrogateescape), so os.fsencode() of the value gives back the original bytes:
 * a path stays the same path. The literal itself is ASCII. */
void py_string(FILE *f, const char *s);

#endif
