/* view/commands.c — what the user asks the viewer for, one function per action, so that every front end
 * goes through the same code: the panel's widgets and the script's lines (technique, parameter,
 * material field: the scene file's JSON is edited and loaded again, LUTs and kernels follow; light:
 * moved or recoloured in place, no rebuild; buffer; split view; error map; reference), the mouse and
 * the C key (the camera), and the keys that input.c queues in v->act_* (view_cmd_keys).
 * Layering: input.c, panel_imgui.cpp and the loop's script runner call down into here; this calls
 * rebuild.c (material edits over frames) and actions.c, never back up. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view/script.h"
#include "view/viewer.h"

sss_result view_cmd_technique(viewer *v, int tech, sss_error *err)
{
    if (!sss_gl_technique_at(tech)) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no technique %d", tech);
    v->part_saved_tech = -1;
    sss_result res = view_make_renderer(v, tech, err);
    if (res == SSS_OK) view_message(v, "technique %s", sss_gl_technique_at(tech)->name);
    return res;
}

/* The parameter name without its "tech." prefix when that is the current technique's; NULL when the
 * parameter belongs to another technique (it is kept for when that one is chosen). */
static const char *param_for_current(const viewer *v, const char *name)
{
    const char *dot = strchr(name, '.');
    if (!dot) return name;
    const char *cur = sss_gl_technique_at(v->tech)->name;
    return strlen(cur) == (size_t)(dot - name) && strncmp(cur, name, (size_t)(dot - name)) == 0 ? dot + 1 : NULL;
}

sss_result view_cmd_param(viewer *v, const char *name, double value, sss_error *err)
{
    const char *here = param_for_current(v, name);
    if (here) {
        double old = sss_gl_renderer_get_param(v->r, here);
        if (isnan(old) && strchr(name, '.') == NULL)
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "technique %s has no parameter '%s'",
                                 sss_gl_technique_at(v->tech)->name, name);
        sss_result res = sss_gl_renderer_set_param(v->r, here, value, err);
        if (res != SSS_OK) return res;
    }
    int slot = 0;
    while (slot < v->set_count && strcmp(v->set_names[slot], name) != 0) slot++;
    if (slot == VIEW_MAX_SET_PARAMS) return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "too many parameters set");
    if (strlen(name) >= sizeof v->set_names[0])
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "parameter name too long");
    snprintf(v->set_names[slot], sizeof v->set_names[slot], "%s", name);
    v->set_params[slot].name = v->set_names[slot];
    v->set_params[slot].value = value;
    if (slot == v->set_count) v->set_count++;
    view_invalidate(v);
    return SSS_OK;
}

sss_result view_cmd_material(viewer *v, int object, const char *field, const char *medium, const double *values,
                             int value_count, sss_error *err)
{
    if (object < 0 || (size_t)object >= v->scene->object_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: objects[%d]: the scene has %zu objects",
                             v->scene->name, object, v->scene->object_count);
    char *text = NULL;
    sss_result res = view_material_json(v->text, v->text_size, v->scene->name, object, field, medium, values,
                                        value_count, &v->scene->objects[object].material, &text, err);
    if (res != SSS_OK) return res;
    free(v->text);
    v->text = text;
    v->text_size = strlen(text);
    char what[96];
    snprintf(what, sizeof what, "objects[%d].material.%s set", object, field);
    view_request_rebuild(v, what, v->script_line);
    return SSS_OK;
}

/* The light's power: intensity, radiance or environment scale by type. */
static double *light_power(sss_light *l)
{
    switch (l->type) {
    case SSS_LIGHT_POINT:
    case SSS_LIGHT_SPOT: return l->intensity;
    case SSS_LIGHT_DIRECTIONAL:
    case SSS_LIGHT_AREA: return l->radiance;
    case SSS_LIGHT_ENVIRONMENT: return l->scale;
    }
    return l->intensity;
}

static double max3(const double v[3]) { return fmax(v[0], fmax(v[1], v[2])); }

/* The new value of the edited field into out[3]; 0 with err set when the values are not allowed. */
static int light_values(sss_light *l, const char *field, const double *values, int n, double out[3], sss_error *err)
{
    for (int c = 0; c < n; c++)
        if (!isfinite(values[c]) || (strcmp(field, "position") != 0 && values[c] < 0.0))
            return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "light %s: %g: must be %s", field, values[c],
                                 strcmp(field, "position") ? "finite and >= 0" : "finite"), 0;
    double *power = light_power(l), peak = max3(power);
    if (strcmp(field, "position") == 0) {
        memcpy(out, values, 3 * sizeof *out);
    } else if (strcmp(field, "intensity") == 0) {
        for (int c = 0; c < 3; c++) out[c] = peak > 0.0 ? power[c] / peak * values[0] : values[0];
    } else {
        double m = max3(values);
        for (int c = 0; c < 3; c++) out[c] = m > 0.0 ? values[c] / m * peak : 0.0;
    }
    return 1;
}

sss_result view_cmd_light(viewer *v, int light, const char *field, const double *values, int value_count,
                          sss_error *err)
{
    if (light < 0 || (size_t)light >= v->scene->light_count)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "%s: lights[%d]: the scene has %zu lights",
                             v->scene->name, light, v->scene->light_count);
    sss_light *l = &v->scene->lights[light];
    double out[3];
    if (value_count != (strcmp(field, "intensity") == 0 ? 1 : 3))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "light %s: wrong number of values", field);
    if (!light_values(l, field, values, value_count, out, err)) return err ? err->code : SSS_ERROR_INVALID_ARGUMENT;
    int position = strcmp(field, "position") == 0;
    char *text = NULL;
    sss_result res = view_light_json(v->text, v->text_size, v->scene->name, light, position ? "position" : "power",
                                     out, &text, err);
    if (res != SSS_OK) return res;
    free(v->text);
    v->text = text;
    v->text_size = strlen(text);
    double *dst = position ? (l->type == SSS_LIGHT_AREA ? l->center : l->position) : light_power(l);
    memcpy(dst, out, sizeof out);
    view_light_changed(v);
    return SSS_OK;
}

sss_result view_cmd_buffer(viewer *v, int buffer, sss_error *err)
{
    if (buffer < 0 || buffer >= VIEW_BUFFER_COUNT)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "no buffer %d", buffer);
    sss_image tmp = {0};
    if (buffer > 0 && !v->need_render) { /* a renderer without a frame yet is checked when shown */
        sss_result res = sss_gl_renderer_read_buffer(v->r, view_buffer_names[buffer], &tmp, err);
        sss_image_free(&tmp);
        if (res != SSS_OK) return res;
    }
    v->buffer = buffer;
    v->shown_gen = 0;
    return SSS_OK;
}

sss_result view_cmd_split(viewer *v, const char *what, double position, sss_error *err)
{
    if (!(position > 0.0 && position < 1.0))
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "split: position %g is not in (0, 1)", position);
    int mode = strcmp(what, "off") == 0 ? VIEW_SPLIT_OFF : strcmp(what, "reference") == 0 ? VIEW_SPLIT_REFERENCE
                                                                                        : VIEW_SPLIT_TECHNIQUE;
    const sss_gl_technique_info *info = mode == VIEW_SPLIT_TECHNIQUE ? sss_gl_technique_find(what) : NULL;
    if (mode == VIEW_SPLIT_TECHNIQUE && !info)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "split: unknown technique '%s'", what);
    int tech = v->split_tech;
    for (int i = 0; info && i < sss_gl_technique_count(); i++)
        if (sss_gl_technique_at(i) == info) tech = i;
    int same = mode == v->split && (mode != VIEW_SPLIT_TECHNIQUE || tech == v->split_tech);
    v->split_pos = position;
    v->composed_gen = 0;
    if (same) return SSS_OK; /* the wipe moved: nothing to rebuild */
    v->split = mode;
    v->split_tech = tech;
    view_split_refresh(v);
    if (mode == VIEW_SPLIT_TECHNIQUE && !v->split_r)
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "split: %s", v->message);
    if (mode == VIEW_SPLIT_REFERENCE && !v->ref && !v->job) view_request_reference(v, v->desc->reference_draft);
    v->need_render = 1;
    return SSS_OK;
}

void view_cmd_errormap(viewer *v, int on)
{
    v->errormap = on;
    v->composed_gen = 0;
    if (on && !v->ref && !v->job) view_request_reference(v, v->desc->reference_draft);
}

void view_cmd_reference(viewer *v, int draft) { view_request_reference(v, draft || v->desc->reference_draft); }

sss_result view_cmd_run(viewer *v, const view_command *c, sss_error *err)
{
    switch (c->kind) {
    case VIEW_CMD_TECHNIQUE: {
        for (int i = 0; i < sss_gl_technique_count(); i++)
            if (strcmp(sss_gl_technique_at(i)->name, c->name) == 0) return view_cmd_technique(v, i, err);
        return sss_error_set(err, SSS_ERROR_INVALID_ARGUMENT, "unknown technique '%s'", c->name);
    }
    case VIEW_CMD_PARAM: return view_cmd_param(v, c->name, c->values[0], err);
    case VIEW_CMD_MATERIAL:
        return view_cmd_material(v, c->index, c->name, c->text, c->values, c->value_count, err);
    case VIEW_CMD_LIGHT: return view_cmd_light(v, c->index, c->name, c->values, c->value_count, err);
    case VIEW_CMD_BUFFER: return view_cmd_buffer(v, c->index, err);
    case VIEW_CMD_SPLIT: return view_cmd_split(v, c->name, c->values[0], err);
    case VIEW_CMD_ERRORMAP: view_cmd_errormap(v, c->index); return SSS_OK;
    case VIEW_CMD_PANEL: v->overlay = c->index; return SSS_OK;
    case VIEW_CMD_REFERENCE: view_cmd_reference(v, c->index); return SSS_OK;
    case VIEW_CMD_KEY: /* input events: the loop hands them to input.c, which comes back here */
    case VIEW_CMD_FRAMES:
    case VIEW_CMD_WAIT:
    case VIEW_CMD_SCREENSHOT: break;
    }
    return SSS_OK;
}

/* ---- The camera (mouse, C key) ------------------------------------------------------------------ */

void view_cmd_orbit(viewer *v, double azimuth_deg, double elevation_deg)
{
    view_orbit(&v->scene->camera, azimuth_deg, elevation_deg);
    view_camera_changed(v);
}

void view_cmd_pan(viewer *v, double dx, double dy)
{
    view_pan(&v->scene->camera, dx, dy, v->width, v->height);
    view_camera_changed(v);
}

void view_cmd_zoom(viewer *v, double factor)
{
    view_zoom(&v->scene->camera, factor);
    view_camera_changed(v);
}

void view_cmd_camera_home(viewer *v)
{
    v->home.width = v->scene->camera.width;
    v->home.height = v->scene->camera.height;
    v->scene->camera = v->home;
    view_camera_changed(v);
}

/* ---- The key actions (input.c queues them in v->act_*, the loop runs them) ---------------------- */

static void next_buffer(viewer *v, int step)
{
    /* skip the buffers the technique does not have */
    for (int k = 1; k < VIEW_BUFFER_COUNT; k++) {
        int b = ((v->buffer + step * k) % VIEW_BUFFER_COUNT + VIEW_BUFFER_COUNT) % VIEW_BUFFER_COUNT;
        sss_image tmp = {0};
        if (b == 0 || sss_gl_renderer_read_buffer(v->r, view_buffer_names[b], &tmp, NULL) == SSS_OK) {
            sss_image_free(&tmp);
            v->buffer = b;
            v->shown_gen = 0;
            view_message(v, "buffer %s", view_buffer_names[b]);
            return;
        }
    }
}

/* M / Shift+M (the next measured medium for every subsurface material), + / - (the scale). */
static void medium_and_scale(viewer *v, int medium_step, double scale)
{
    if (medium_step) {
        int m = (int)sss_measured_medium_count() + 1; /* -1 (the file's) and the table */
        v->medium = ((v->medium + 1 + medium_step) % m + m) % m - 1;
    }
    if (scale != 0.0) v->scale_factor *= scale;
    char what[128];
    if (v->medium >= 0)
        snprintf(what, sizeof what, "medium %s, scale x%g", sss_measured_medium_at((size_t)v->medium)->name,
                 v->scale_factor);
    else
        snprintf(what, sizeof what, "the scene's materials, scale x%g", v->scale_factor);
    view_request_rebuild(v, what, 0);
}

/* L / Shift+L: lights[0] turned by steps x 15 degrees about the vertical through look_at. */
static void turn_light(viewer *v, int steps)
{
    if (!v->has_light) {
        view_message(v, "the scene has no light to move");
        return;
    }
    view_rotate_light_y(&v->scene->lights[0], v->scene->camera.look_at, 15.0 * steps);
    v->light_angle = fmod(v->light_angle + 15.0 * steps + 540.0, 360.0) - 180.0;
    view_light_changed(v);
    view_message(v, "light 0 at %+.0f degrees about the vertical through look_at", v->light_angle);
}

void view_cmd_keys(viewer *v)
{
    int n = sss_gl_technique_count();
    if (v->act_tech && n > 0) {
        int t = ((v->tech + v->act_tech) % n + n) % n;
        v->act_tech = 0;
        v->part_saved_tech = -1;
        view_switch_technique(v, t, 0);
    }
    if (v->act_part) {
        int p = v->act_part - 1;
        v->act_part = 0;
        view_apply_part(v, p);
    }
    if (v->act_buffer) {
        next_buffer(v, v->act_buffer);
        v->act_buffer = 0;
    }
    if (v->act_medium || v->act_scale != 0.0) {
        int step = v->act_medium;
        double scale = v->act_scale;
        v->act_medium = 0;
        v->act_scale = 0.0;
        medium_and_scale(v, step, scale);
    }
    if (v->act_light) {
        int steps = v->act_light;
        v->act_light = 0;
        turn_light(v, steps);
    }
    if (v->act_reference) {
        int draft = v->act_reference == 2;
        v->act_reference = 0;
        view_cmd_reference(v, draft);
    }
}
