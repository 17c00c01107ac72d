/* view/panel_imgui.cpp — the viewer's Dear ImGui panel (view/panel.h): Debian's libimgui with its
 * GLFW and OpenGL 3 backends. Every widget calls a view/commands.c function (the ones `--script` lines
 * call); failures become the viewer's message. Material fields apply when an edit ends (each is a
 * rebuild, in the background: view/rebuild.c), lights and parameters while they are dragged. */
#include <float.h>
#include <math.h>
#include <new>
#include <stdio.h>
#include <string.h>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

extern "C" {
#include "sss/material.h"
#include "view/panel.h"
#include "view/viewer.h"
}

namespace {

const int HISTORY = 120; /* frames in the frame-time graph */

struct pass_history {
    char name[32];
    float ms[HISTORY];
};

}

struct view_panel {
    ImGuiContext *ctx;
    pass_history passes[SSS_GL_MAX_PASSES + 1]; /* the last one is the whole frame */
    int pass_count;
    int at;                 /* next slot of the ring */
    unsigned recorded_gen;  /* image_gen of the last recorded frame */
    ImGuiID edit_id;        /* the material field being edited (its values live here until applied) */
    double edit_values[3];
};

static void report(viewer *v, sss_result res, const sss_error &err)
{
    if (res != SSS_OK) view_message(v, "%s", err.message);
}

static void record_timings(viewer *v, view_panel *p)
{
    if (p->recorded_gen == v->image_gen) return;
    p->recorded_gen = v->image_gen;
    sss_gl_timings t;
    sss_gl_renderer_timings(v->r, &t);
    for (int i = 0; i <= SSS_GL_MAX_PASSES; i++) p->passes[i].ms[p->at] = 0.0f;
    for (int i = 0; i < t.pass_count; i++) {
        int k = 0;
        while (k < p->pass_count && strcmp(p->passes[k].name, t.passes[i].name) != 0) k++;
        if (k == p->pass_count && k < SSS_GL_MAX_PASSES) {
            memset(&p->passes[k], 0, sizeof p->passes[k]);
            snprintf(p->passes[k].name, sizeof p->passes[k].name, "%s", t.passes[i].name);
            p->pass_count++;
        }
        if (k < SSS_GL_MAX_PASSES) p->passes[k].ms[p->at] += (float)t.passes[i].ms;
    }
    p->passes[SSS_GL_MAX_PASSES].ms[p->at] = (float)v->frame_ms;
    p->at = (p->at + 1) % HISTORY;
}

static void tooltip(const char *doc)
{
    if (doc && ImGui::IsItemHovered()) ImGui::SetTooltip("%s", doc);
}

static void technique_section(viewer *v)
{
    if (!ImGui::CollapsingHeader("Technique", ImGuiTreeNodeFlags_DefaultOpen)) return;
    for (int i = 0; i < sss_gl_technique_count(); i++) {
        const sss_gl_technique_info *info = sss_gl_technique_at(i);
        if (ImGui::Selectable(info->name, i == v->tech) && i != v->tech) {
            sss_error err = {};
            report(v, view_cmd_technique(v, i, &err), err);
        }
        tooltip(info->summary);
    }
}

/* One parameter as a checkbox, an integer or a float slider (logarithmic over wide positive ranges). */
static void param_widget(viewer *v, const char *tech, const sss_gl_param_info *p)
{
    double value = sss_gl_renderer_get_param(v->r, p->name);
    if (isnan(value)) return;
    char full[160];
    snprintf(full, sizeof full, "%s.%s", tech, p->name);
    bool changed = false;
    double next = value;
    if (p->type == SSS_GL_PARAM_BOOL) {
        bool b = value != 0.0;
        changed = ImGui::Checkbox(p->name, &b);
        next = b ? 1.0 : 0.0;
    } else if (p->type == SSS_GL_PARAM_INT) {
        int k = (int)value, lo = (int)p->min_value, hi = (int)p->max_value;
        changed = ImGui::SliderInt(p->name, &k, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
        next = k;
    } else {
        ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
        if (p->min_value >= 0.0 && p->max_value > 1000.0 * fmax(p->min_value, 1e-3)) /* e.g. [0, 1e30] */
            flags |= ImGuiSliderFlags_Logarithmic;
        changed = ImGui::SliderScalar(p->name, ImGuiDataType_Double, &next, &p->min_value, &p->max_value, "%.4g", flags);
    }
    tooltip(p->doc);
    if (changed && next != value) {
        sss_error err = {};
        report(v, view_cmd_param(v, full, next, &err), err);
    }
}

static void params_section(viewer *v)
{
    if (!ImGui::CollapsingHeader("Parameters", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const sss_gl_technique_info *info = sss_gl_technique_at(v->tech);
    for (int i = 0; i < info->param_count; i++) param_widget(v, info->name, &info->params[i]);
    if (ImGui::TreeNode("shared (every technique)")) {
        int n = 0;
        const sss_gl_param_info *shared = sss_gl_shared_params(&n);
        for (int i = 0; i < n; i++) param_widget(v, info->name, &shared[i]);
        ImGui::TreePop();
    }
}

static void material_apply(viewer *v, int object, const char *field, const char *medium, const double *values, int n)
{
    sss_error err = {};
    report(v, view_cmd_material(v, object, field, medium, values, n, &err), err);
}

/* A field edited as doubles, applied when the edit ends; while it lasts the values are the panel's. */
static void material_values(viewer *v, int object, const char *field, double *values, int n, double lo, double hi)
{
    view_panel *p = v->panel;
    ImGuiID id = ImGui::GetID(field);
    if (p->edit_id == id) memcpy(values, p->edit_values, sizeof(double) * (size_t)n);
    float speed = (float)(0.005 * (fabs(values[0]) > 1e-3 ? fabs(values[0]) : 1.0));
    ImGui::DragScalarN(field, ImGuiDataType_Double, values, n, speed, &lo, &hi, "%.4g");
    if (ImGui::IsItemActive()) {
        p->edit_id = id;
        memcpy(p->edit_values, values, sizeof(double) * (size_t)n);
    }
    if (ImGui::IsItemDeactivatedAfterEdit()) {
        p->edit_id = 0;
        material_apply(v, object, field, NULL, values, n);
    } else if (!ImGui::IsItemActive() && p->edit_id == id) {
        p->edit_id = 0;
    }
}

static void material_object(viewer *v, int i)
{
    const sss_scene_material *m = &v->scene->objects[i].material;
    if (m->type != SSS_SCENE_MATERIAL_SUBSURFACE) return;
    char label[48];
    snprintf(label, sizeof label, "object %d", i);
    if (!ImGui::TreeNode(label)) return;
    const char *preview = m->source == SSS_SUBSURFACE_MEDIUM && m->medium ? m->medium->name
                          : m->source == SSS_SUBSURFACE_COEFFICIENTS  ? "(coefficients)"
                                                                      : "(reflectance + mfp)";
    if (ImGui::BeginCombo("medium", preview)) {
        for (size_t k = 0; k < sss_measured_medium_count(); k++) {
            const char *name = sss_measured_medium_at(k)->name;
            if (ImGui::Selectable(name, m->medium && strcmp(m->medium->name, name) == 0))
                material_apply(v, i, "medium", name, NULL, 0);
        }
        ImGui::EndCombo();
    }
    double eta = m->optical.eta, g = m->optical.g, scale = m->scale;
    if (m->source != SSS_SUBSURFACE_REFLECTANCE) material_values(v, i, "scale", &scale, 1, 1e-6, 1e6);
    material_values(v, i, "eta", &eta, 1, SSS_ETA_MIN, SSS_ETA_MAX);
    if (m->source == SSS_SUBSURFACE_COEFFICIENTS) material_values(v, i, "g", &g, 1, -0.99, 0.99);
    double a[3], b[3];
    memcpy(a, m->source == SSS_SUBSURFACE_REFLECTANCE ? m->reflectance : m->input_sigma_a, sizeof a);
    memcpy(b, m->source == SSS_SUBSURFACE_REFLECTANCE ? m->mfp : m->input_sigma_s, sizeof b);
    if (m->source == SSS_SUBSURFACE_REFLECTANCE) {
        material_values(v, i, "reflectance", a, 3, 1e-3, 0.999);
        material_values(v, i, "mfp", b, 3, 1e-9, 1e9);
    } else if (m->source == SSS_SUBSURFACE_COEFFICIENTS) {
        material_values(v, i, "sigma_a", a, 3, 0.0, 1e9);
        material_values(v, i, "sigma_s", b, 3, 0.0, 1e9);
    }
    if (m->source != SSS_SUBSURFACE_COEFFICIENTS && ImGui::Button("as sigma_a, sigma_s"))
        material_apply(v, i, "sigma_a", NULL, m->optical.sigma_a, 3);
    if (m->source != SSS_SUBSURFACE_REFLECTANCE && ImGui::Button("as reflectance, mfp"))
        material_apply(v, i, "reflectance", NULL, m->albedo, 3);
    ImGui::TreePop();
}

static void materials_section(viewer *v)
{
    if (!ImGui::CollapsingHeader("Materials")) return;
    if (view_rebuild_busy(v))
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "rebuilding in the background (%d frames so far)",
                           v->build_frames);
    ImGui::Text("last rebuild: %.1f ms, of which %.1f ms on the window thread", v->rebuild_ms, v->rebuild_window_ms);
    for (size_t i = 0; i < v->scene->object_count; i++) material_object(v, (int)i);
}

static void light_edit(viewer *v, int i, const char *field, const double *values, int n)
{
    sss_error err = {};
    report(v, view_cmd_light(v, i, field, values, n, &err), err);
}

static void lights_section(viewer *v)
{
    if (!ImGui::CollapsingHeader("Lights")) return;
    for (size_t i = 0; i < v->scene->light_count; i++) {
        sss_light *l = &v->scene->lights[i];
        ImGui::PushID((int)i);
        ImGui::Text("light %zu", i);
        double *pos = l->type == SSS_LIGHT_AREA ? l->center : l->position;
        double p[3] = {pos[0], pos[1], pos[2]};
        if (l->type != SSS_LIGHT_DIRECTIONAL && l->type != SSS_LIGHT_ENVIRONMENT &&
            ImGui::DragScalarN("position", ImGuiDataType_Double, p, 3, 0.01f, NULL, NULL, "%.3f"))
            light_edit(v, (int)i, "position", p, 3);
        const double *power = l->type == SSS_LIGHT_POINT || l->type == SSS_LIGHT_SPOT ? l->intensity
                              : l->type == SSS_LIGHT_ENVIRONMENT                      ? l->scale
                                                                                      : l->radiance;
        double peak = fmax(power[0], fmax(power[1], power[2])), zero = 0.0;
        if (ImGui::DragScalar("intensity", ImGuiDataType_Double, &peak, (float)(0.01 * (peak > 0 ? peak : 1)), &zero,
                              NULL, "%.4g"))
            light_edit(v, (int)i, "intensity", &peak, 1);
        float colour[3];
        for (int c = 0; c < 3; c++) colour[c] = peak > 0.0 ? (float)(power[c] / peak) : 1.0f;
        if (ImGui::ColorEdit3("colour", colour)) {
            double c3[3] = {colour[0], colour[1], colour[2]};
            light_edit(v, (int)i, "colour", c3, 3);
        }
        ImGui::PopID();
    }
}

static void timing_section(viewer *v, view_panel *p)
{
    if (!ImGui::CollapsingHeader("Frame time", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::Text("frame %.1f ms   passes %.1f ms (median)", v->frame_ms, v->timings.total_ms);
    for (int k = 0; k < p->pass_count; k++) {
        char overlay[64];
        const float *ms = p->passes[k].ms;
        snprintf(overlay, sizeof overlay, "%.2f ms", ms[(p->at + HISTORY - 1) % HISTORY]);
        ImGui::PlotLines(p->passes[k].name, ms, HISTORY, p->at, overlay, 0.0f, FLT_MAX, ImVec2(0, 28));
    }
}

static void colour_bar(viewer *v)
{
    ImDrawList *dl = ImGui::GetWindowDrawList();
    ImVec2 at = ImGui::GetCursorScreenPos();
    float w = ImGui::GetContentRegionAvail().x, h = 12.0f;
    const int steps = 32;
    for (int s = 0; s < steps; s++) {
        float a[3], b[3];
        view_error_colour((double)s / steps, a);
        view_error_colour((double)(s + 1) / steps, b);
        ImU32 ca = ImGui::ColorConvertFloat4ToU32(ImVec4((float)sss_srgb_encode(a[0]), (float)sss_srgb_encode(a[1]),
                                                         (float)sss_srgb_encode(a[2]), 1.0f));
        ImU32 cb = ImGui::ColorConvertFloat4ToU32(ImVec4((float)sss_srgb_encode(b[0]), (float)sss_srgb_encode(b[1]),
                                                         (float)sss_srgb_encode(b[2]), 1.0f));
        dl->AddRectFilledMultiColor(ImVec2(at.x + w * s / steps, at.y), ImVec2(at.x + w * (s + 1) / steps, at.y + h),
                                    ca, cb, cb, ca);
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::Text("0");
    ImGui::SameLine(w - 60.0f);
    ImGui::Text("%.3g DSSIM", v->error_range);
}

static void view_section(viewer *v)
{
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (ImGui::BeginCombo("buffer", view_buffer_names[v->buffer])) {
        for (int b = 0; b < VIEW_BUFFER_COUNT; b++)
            if (ImGui::Selectable(view_buffer_names[b], b == v->buffer)) {
                sss_error err = {};
                report(v, view_cmd_buffer(v, b, &err), err);
            }
        ImGui::EndCombo();
    }
    const char *split = v->split == VIEW_SPLIT_OFF         ? "off"
                        : v->split == VIEW_SPLIT_REFERENCE ? "reference"
                                                           : sss_gl_technique_at(v->split_tech)->name;
    double pos = v->split_pos;
    if (ImGui::BeginCombo("split (right)", split)) {
        sss_error err = {};
        if (ImGui::Selectable("off", v->split == VIEW_SPLIT_OFF)) report(v, view_cmd_split(v, "off", pos, &err), err);
        if (ImGui::Selectable("reference", v->split == VIEW_SPLIT_REFERENCE))
            report(v, view_cmd_split(v, "reference", pos, &err), err);
        for (int i = 0; i < sss_gl_technique_count(); i++)
            if (ImGui::Selectable(sss_gl_technique_at(i)->name, v->split == VIEW_SPLIT_TECHNIQUE && v->split_tech == i))
                report(v, view_cmd_split(v, sss_gl_technique_at(i)->name, pos, &err), err);
        ImGui::EndCombo();
    }
    const double lo = 0.02, hi = 0.98;
    if (v->split && ImGui::SliderScalar("wipe", ImGuiDataType_Double, &pos, &lo, &hi, "%.2f")) {
        sss_error err = {};
        report(v, view_cmd_split(v, split, pos, &err), err);
    }
    bool map = v->errormap != 0;
    if (ImGui::Checkbox("error map (DSSIM vs reference)", &map)) view_cmd_errormap(v, map);
    if (v->errormap) colour_bar(v);
    if (ImGui::Button("reference of this view (R)")) view_cmd_reference(v, 0);
    if (v->ref && v->dssim_gen) ImGui::Text("DSSIM %.4f (%s reference)", v->dssim, v->ref_draft ? "draft" : "final");
    else if (v->job) ImGui::Text("reference: rendering...");
}

extern "C" {

sss_result view_panel_create(viewer *v, sss_error *err)
{
    view_panel *p = new (std::nothrow) view_panel();
    if (!p) return sss_error_set(err, SSS_ERROR_OUT_OF_MEMORY, "out of memory (panel)");
    IMGUI_CHECKVERSION();
    p->ctx = ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = NULL; /* no imgui.ini in the user's folder */
    io.LogFilename = NULL;
    ImGui::StyleColorsDark();
    if (!ImGui_ImplGlfw_InitForOpenGL(v->window, false)) {
        ImGui::DestroyContext(p->ctx);
        delete p;
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "the ImGui GLFW backend did not start");
    }
    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) {
        ImGui_ImplGlfw_Shutdown();
        ImGui::DestroyContext(p->ctx);
        delete p;
        return sss_error_set(err, SSS_ERROR_UNSUPPORTED, "the ImGui OpenGL 3 backend did not start");
    }
    v->panel = p;
    return SSS_OK;
}

void view_panel_destroy(viewer *v)
{
    if (!v->panel) return;
    ImGui::SetCurrentContext(v->panel->ctx);
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext(v->panel->ctx);
    delete v->panel;
    v->panel = NULL;
}

sss_result view_panel_draw(viewer *v, sss_error *err)
{
    (void)err;
    view_panel *p = v->panel;
    ImGui::SetCurrentContext(p->ctx);
    record_timings(v, p);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    float w = v->width * 0.4f < 340.0f ? v->width * 0.4f : 340.0f;
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(w, (float)v->height), ImGuiCond_Once);
    ImGui::SetNextWindowBgAlpha(0.85f);
    if (ImGui::Begin("sss view")) {
        ImGui::PushItemWidth(ImGui::GetWindowWidth() * 0.55f); /* room for the labels */
        if (v->message[0] && sss_time_seconds() < v->message_until) ImGui::TextWrapped("%s", v->message);
        technique_section(v);
        params_section(v);
        view_section(v);
        timing_section(v, p);
        materials_section(v);
        lights_section(v);
        if (ImGui::CollapsingHeader("Keys")) ImGui::TextUnformatted(sss_view_help_text());
        ImGui::PopItemWidth();
    }
    ImGui::End();
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return SSS_OK;
}

int view_panel_wants(const viewer *v, int mouse)
{
    if (!v->panel || !v->overlay) return 0;
    ImGui::SetCurrentContext(v->panel->ctx);
    return mouse ? ImGui::GetIO().WantCaptureMouse : ImGui::GetIO().WantCaptureKeyboard;
}

void view_panel_key(viewer *v, int key, int scancode, int action, int mods)
{
    ImGui::SetCurrentContext(v->panel->ctx);
    ImGui_ImplGlfw_KeyCallback(v->window, key, scancode, action, mods);
}

void view_panel_char(viewer *v, unsigned codepoint)
{
    ImGui::SetCurrentContext(v->panel->ctx);
    ImGui_ImplGlfw_CharCallback(v->window, codepoint);
}

void view_panel_button(viewer *v, int button, int action, int mods)
{
    ImGui::SetCurrentContext(v->panel->ctx);
    ImGui_ImplGlfw_MouseButtonCallback(v->window, button, action, mods);
}

void view_panel_scroll(viewer *v, double dx, double dy)
{
    ImGui::SetCurrentContext(v->panel->ctx);
    ImGui_ImplGlfw_ScrollCallback(v->window, dx, dy);
}
}
