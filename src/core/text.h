/* core/text.h — text helpers shared by the modules (internal, not public API).
 *
 * Messages: file names and scene strings come from data and may hold terminal escapes (ESC [ ...),
 * carriage returns or bytes that are not UTF-8. sss_text_escape writes them as visible escapes so
 * that nothing from data reaches a terminal raw; sss_error_set and the command-line tool's printer
 * pass every message through it.
 *
 * JSON: cJSON keeps strings as C strings, so a NUL inside one ("Marble\u0000junk") would silently
 * cut it; sss_json_find_nul finds such strings so that the readers can refuse them.
 */
#ifndef SSS_CORE_TEXT_H
#define SSS_CORE_TEXT_H

#include <stddef.h>

/* The most bytes sss_text_escape writes per input byte ("\xHH"). */
#define SSS_TEXT_ESCAPE_MAX 4

/* Copies the n bytes of src to dst with \n, \r, \t as such, other C0 controls, DEL and C1 controls
 * (U+0080..U+009F) as \xHH, and bytes that are not part of valid UTF-8 as \xHH; everything else
 * (printable ASCII, backslashes included, and valid UTF-8) is copied unchanged, so escaping twice
 * changes nothing. dst needs SSS_TEXT_ESCAPE_MAX * n + 1 bytes; it is NUL-terminated. Returns the
 * length written. */
size_t sss_text_escape(const char *src, size_t n, char *dst);

/* Shortens the NUL-terminated text (length len) in place to at most max bytes by replacing the middle
 * of its longest space-free run (usually a path) with "...", so that the start and the end of the
 * message (the file and the cause) survive; repeats for further long runs, and cuts the middle of the
 * whole text only when no run is long enough. Never splits a UTF-8 sequence. Returns the new length. */
size_t sss_text_shorten_middle(char *text, size_t len, size_t max);

/* Finds the first string of the JSON text (a value or a member name) holding a NUL character, as the
 * escape \u0000 or as a raw 0 byte ("\\u0000" is a backslash and "u0000", not a NUL). Returns 1 and
 * writes its JSON path in the scene loader's notation ("objects[0].material.medium"; for a member
 * name, the path it would have) to path (cap bytes, cut if longer); returns 0 when there is none.
 * Meant for text that has already parsed as JSON; other text never makes it read out of bounds. */
int sss_json_find_nul(const char *text, size_t size, char *path, size_t cap);

/* Edit distance of two NUL-terminated strings: the fewest insertions, deletions, substitutions and
 * swaps of two adjacent characters that turn a into b (the optimal string alignment distance, in
 * bytes, case-sensitive). Strings longer than SSS_TEXT_DISTANCE_MAX bytes count as that far from
 * everything (the "did you mean" of the command-line tool compares short names). */
#define SSS_TEXT_DISTANCE_MAX 64
int sss_text_edit_distance(const char *a, const char *b);

#endif
