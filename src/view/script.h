/* view/script.h — the viewer's panel actions as text: one command per line of a `--script` file
 * (`technique ssss`, `param maisch2020.brightening 0`, `material 0 scale 2`, `split reference`,
 * `frames 3`, `screenshot out.png`, ...). Parsing only: names are checked against the technique
 * registry, the measured media and the buffer list, values against their kinds; nothing here needs a
 * window (view/commands.c applies a command to a running viewer, the panel calls the same code).
 * Does not: know the scene (object and light indices are checked when applied). */
#ifndef SSS_VIEW_SCRIPT_H
#define SSS_VIEW_SCRIPT_H

#include <stddef.h>

#include "sss/common.h"

typedef enum view_command_kind {
    VIEW_CMD_TECHNIQUE,  /* name: technique */
    VIEW_CMD_PARAM,      /* name: parameter ("tech.param" or "param"), values[0] */
    VIEW_CMD_MATERIAL,   /* index: objects[index], name: field, text: medium name or values */
    VIEW_CMD_LIGHT,      /* index: lights[index], name: position | intensity | colour, values */
    VIEW_CMD_BUFFER,     /* name: one of view_buffer_names */
    VIEW_CMD_SPLIT,      /* name: "off", "reference" or a technique; values[0]: wipe position (0, 1) */
    VIEW_CMD_ERRORMAP,   /* index: 1 on, 0 off; values[0]: the colour bar's range (0: unchanged) */
    VIEW_CMD_PANEL,      /* name: "on" | "off" (index 1 | 0), "open" | "close" | "scroll" (index: the
                            section in view_panel_sections), "width" (values[0]: pixels) */
    VIEW_CMD_REFERENCE,  /* index: 1 draft, 0 final */
    VIEW_CMD_KEY,        /* name: an input event of --input (keys, orbit:DX:DY, pan:DX:DY, zoom:STEPS) */
    VIEW_CMD_FRAMES,     /* index: frames to render */
    VIEW_CMD_WAIT,       /* frames until the material edits building in the background are applied */
    VIEW_CMD_SCREENSHOT  /* text: a .png path, the window as shown (panel included when shown) */
} view_command_kind;

#define VIEW_SCRIPT_TEXT 1024

typedef struct view_command {
    view_command_kind kind;
    int line;             /* 1-based line of the script */
    int index;
    char name[64];
    char text[VIEW_SCRIPT_TEXT];
    double values[3];
    int value_count;
} view_command;

typedef struct view_script {
    view_command *commands;
    int count;
} view_script;

/* The material fields a script or the panel may set (VIEW_CMD_MATERIAL name). */
#define VIEW_MATERIAL_FIELD_COUNT 8
extern const char *const view_material_fields[VIEW_MATERIAL_FIELD_COUNT];

/* The panel's sections, top to bottom (`panel open|close|scroll SECTION`: names match without regard
 * to case, '_' or '-' standing for a blank). */
#define VIEW_PANEL_SECTION_COUNT 7
extern const char *const view_panel_sections[VIEW_PANEL_SECTION_COUNT];
/* The section named s (as above), or -1. */
int view_panel_section_find(const char *s);
#define VIEW_PANEL_MAX_WIDTH 4096 /* `panel width` (pixels; the window's layout may give it less) */

/* One line (no newline). Returns 1 with *out filled, 0 for a blank or comment line (# ...), -1 when
 * the line is wrong: why receives the problem (without the file and line). */
int view_script_parse_line(const char *line, view_command *out, char *why, size_t why_cap);
/* Reads a script file through sss_read_file. Errors name the file and line: "s.txt:3: ...". */
sss_result view_script_load(const char *path, view_script *out, sss_error *err);
void view_script_free(view_script *s);

#endif
