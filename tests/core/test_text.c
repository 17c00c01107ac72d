/* core/text.h: escaping control characters, shortening long messages in the middle, finding NUL
 * characters in JSON strings. Expected values are written out by hand from the rules in text.h. */
#include <string.h>

#include "check.h"
#include "core/text.h"
#include "sss/common.h"

static int escapes_to(const char *in, size_t n, const char *want)
{
    char out[256];
    sss_text_escape(in, n, out);
    if (strcmp(out, want) != 0) fprintf(stderr, "escape: got '%s', want '%s'\n", out, want);
    return strcmp(out, want) == 0;
}

static void test_escape(void)
{
    CHECK(escapes_to("plain/path.json", 15, "plain/path.json"));
    CHECK(escapes_to("\x1b[31mred", 8, "\\x1b[31mred"));
    CHECK(escapes_to("a\nb\rc\td", 7, "a\\nb\\rc\\td"));
    CHECK(escapes_to("\x7f\x01", 2, "\\x7f\\x01"));
    CHECK(escapes_to("caf\xc3\xa9 \xe2\x82\xac", 9, "caf\xc3\xa9 \xe2\x82\xac"));     /* valid UTF-8 kept */
    CHECK(escapes_to("\xc2\x9b" "2J", 4, "\\xc2\\x9b2J"));                          /* C1 CSI */
    CHECK(escapes_to("\x9b\xff\xc3", 3, "\\x9b\\xff\\xc3"));                        /* not UTF-8 */
    CHECK(escapes_to("\xed\xa0\x80", 3, "\\xed\\xa0\\x80"));                        /* a surrogate */
    CHECK(escapes_to("a\0b", 3, "a\\x00b"));
    CHECK(escapes_to("\\x1b", 4, "\\x1b")); /* already escaped: unchanged */
}

static void test_shorten(void)
{
    /* a 600-character path between a short start and the cause */
    char text[1024], path[601];
    memset(path, 'p', 600);
    path[0] = '/';
    path[599] = 'Z';
    path[600] = '\0';
    int n = snprintf(text, sizeof text, "sss: %s: cannot open: No such file", path);
    size_t len = sss_text_shorten_middle(text, (size_t)n, 100);
    CHECK(len == 100 && strlen(text) == 100);
    CHECK(strncmp(text, "sss: /ppp", 9) == 0);
    CHECK(strstr(text, "...") != NULL);
    CHECK(strstr(text, "pZ: cannot open: No such file") != NULL);
    /* short enough: unchanged */
    char small[] = "a b c";
    CHECK(sss_text_shorten_middle(small, 5, 100) == 5 && strcmp(small, "a b c") == 0);
    /* UTF-8 is not split: 300 two-byte characters */
    char u[700];
    for (int i = 0; i < 300; i++) memcpy(u + 2 * i, "\xc3\xa9", 2);
    u[600] = '\0';
    len = sss_text_shorten_middle(u, 600, 101);
    CHECK(len <= 101);
    char esc[4 * 700];
    sss_text_escape(u, len, esc);
    CHECK(strstr(esc, "\\x") == NULL); /* still valid UTF-8 */

    /* through sss_error_set: the cause at the end survives a 5000-character path */
    static char big[5001];
    memset(big, 'd', 5000);
    sss_error err;
    sss_error_set(&err, SSS_ERROR_IO, "%s/x.png: cannot create: File name too long", big);
    CHECK(strlen(err.message) == SSS_ERROR_MESSAGE_SIZE - 1);
    CHECK(strstr(err.message, "/x.png: cannot create: File name too long") != NULL);
    sss_error_set(&err, SSS_ERROR_PARSE, "%s: unknown medium", "\x1b]0;title\x07");
    CHECK(strcmp(err.message, "\\x1b]0;title\\x07: unknown medium") == 0);
    sss_error_prefix(&err, "scene\x1b.json");
    CHECK(strcmp(err.message, "scene\\x1b.json: \\x1b]0;title\\x07: unknown medium") == 0);
}

static int nul_at(const char *json, size_t n, const char *want)
{
    char path[256];
    int found = sss_json_find_nul(json, n, path, sizeof path);
    if (!want) return !found;
    if (!found || strcmp(path, want) != 0) fprintf(stderr, "json: got %d '%s', want '%s'\n", found, path, want);
    return found && strcmp(path, want) == 0;
}

#define NUL_AT(literal, want) nul_at(literal, sizeof literal - 1, want)

static void test_json_nul(void)
{
    CHECK(NUL_AT("{\"objects\": [{\"material\": {\"medium\": \"Marble\\u0000junk\"}}]}", "objects[0].material.medium"));
    CHECK(NUL_AT("{\"a\": 1, \"objects\": [{}, {\"mesh\": \"m.ply\\u0000/../..\"}]}", "objects[1].mesh"));
    CHECK(NUL_AT("{\"a\": [[1, 2], [3, \"x\\u0000\"]]}", "a[1][1]"));
    CHECK(NUL_AT("{\"b\": {\"k\\u0000ey\": 1}}", "b.k\\u0000ey"));           /* a member name */
    CHECK(NUL_AT("{\"name\": \"a\0b\"}", "name"));                            /* a raw 0 byte */
    CHECK(NUL_AT("{\"name\": \"Marble\\\\u0000\"}", NULL));                   /* \\ then u0000: no NUL */
    CHECK(NUL_AT("{\"name\": \"\\\\\\u0000\"}", "name"));                     /* \\ then \u0000 */
    CHECK(NUL_AT("{\"name\": \"\\u00000\", \"x\": \"\\u0001\"}", "name"));
    CHECK(NUL_AT("{\"ok\": \"\\u0001\\u1000\\\"u0000\"}", NULL));
    CHECK(NUL_AT("\"\\u0000\"", ""));                                         /* the root value */
    CHECK(NUL_AT("{\"cut\": \"\\u00", NULL));                                 /* truncated: no read past the end */
}

/* Distances counted by hand: the classic kitten -> sitting is 3 (two substitutions, one insertion);
 * a swap of neighbours is 1 (plain Levenshtein would give 2). */
static void test_edit_distance(void)
{
    CHECK(sss_text_edit_distance("kitten", "sitting") == 3);
    CHECK(sss_text_edit_distance("", "") == 0);
    CHECK(sss_text_edit_distance("", "abc") == 3);
    CHECK(sss_text_edit_distance("render", "render") == 0);
    CHECK(sss_text_edit_distance("rendr", "render") == 1);       /* a deletion */
    CHECK(sss_text_edit_distance("--widht", "--width") == 1);    /* a swap */
    CHECK(sss_text_edit_distance("maisch2020", "maisch2002") == 1);
    CHECK(sss_text_edit_distance("ca", "abc") == 3);              /* OSA: no edit of a swapped pair */
    CHECK(sss_text_edit_distance("Render", "render") == 1);       /* case-sensitive */
    char longer[SSS_TEXT_DISTANCE_MAX + 2];
    memset(longer, 'a', sizeof longer - 1);
    longer[sizeof longer - 1] = '\0';
    CHECK(sss_text_edit_distance(longer, longer) == SSS_TEXT_DISTANCE_MAX);
}

int main(void)
{
    test_edit_distance();
    test_escape();
    test_shorten();
    test_json_nul();
    return CHECK_DONE();
}
