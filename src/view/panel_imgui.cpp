/* view/panel_imgui.cpp — the viewer's Dear ImGui panel (view/panel.h): Debian's libimgui with its
 * GLFW and OpenGL 3 backends. Docked at the right of the window beside the image (viewer.c lays the
 * window out; dragging the panel's left edge sets its width), opaque, in collapsible sections that a
 * script can open, close or scroll to (v->panel_section). Names are shown in full: the label column is
 * as wide as the longest parameter or field name, or, in a panel too narrow for that, each name sits on
 * its own line above its widget; a parameter's tooltip gives its name, doc string, range and default.
 * Every widget calls a view/commands.c function (the ones `--script` lines call); failures become the
 * viewer's message. Material fields apply when an edit ends (each is a rebuild, in the background:
 * view/rebuild.c), lights and parameters while they are dragged. */
#include <float.h>
#include <math.h>
#include <new>
#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

extern "C" {
#include "sss/material.h"
#include "view/panel.h"
#include "view/script.h"
#include "view/viewer.h"
}

namespace {

const int HISTORY = 120;        /* frames in the frame-time graph */
const float ITEM_MIN = 120.0f;  /* the narrowest widget beside its name; narrower: names on their own line */
const float ITEM_WIDTH = 150.0f; /* a widget's width in the default panel */

/* The sections in view_panel_sections' order. */
enum { SEC_TECHNIQUE, SEC_VIEW, SEC_PARAMETERS, SEC_MATERIALS, SEC_LIGHTS, SEC_TIMING, SEC_KEYS };
const bool section_open_at_start[VIEW_PANEL_SECTION_COUNT] = {true, true, true, false, false, true, false};

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
    float label_width;      /* the widest parameter or field name (ImGui units) */
    bool stacked;           /* this frame: names on their own line above full-width widgets */
    float header_top[VIEW_PANEL_SECTION_COUNT], header_bottom[VIEW_PANEL_SECTION_COUNT]; /* in the panel */
    bool header_open[VIEW_PANEL_SECTION_COUNT];
    int request_frames;     /* frames the section request of v->panel_section has been drawn */
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

/* A section's header, opened, closed or scrolled to when a script asked (v->panel_section); records
 * where it is for the request's report. */
static bool section(viewer *v, view_panel *p, int k)
{
    bool asked = v->panel_section == k && p->request_frames <= (v->panel_op == VIEW_SECTION_SCROLL ? 2 : 1);
    if (asked) ImGui::SetNextItemOpen(v->panel_op != VIEW_SECTION_CLOSE, ImGuiCond_Always);
    bool open = ImGui::CollapsingHeader(view_panel_sections[k],
                                        section_open_at_start[k] ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    float top = ImGui::GetWindowPos().y;
    p->header_top[k] = ImGui::GetItemRectMin().y - top;
    p->header_bottom[k] = ImGui::GetItemRectMax().y - top;
    p->header_open[k] = open;
    if (asked && v->panel_op == VIEW_SECTION_SCROLL) ImGui::SetScrollHereY(0.0f); /* the header at the top */
    return open;
}

/* The label a widget gets: its name beside it, or (a narrow panel) the name as a line of its own
 * above a full-width widget, with the same tooltip. */
static const char *field_label(view_panel *p, const char *name, char *buf, size_t cap)
{
    if (!p->stacked) return name;
    ImGui::TextUnformatted(name);
    snprintf(buf, cap, "##%s", name);
    return buf;
}

static void technique_section(viewer *v, view_panel *p)
{
    if (!section(v, p, SEC_TECHNIQUE)) return;
    const sss_gl_technique_info *current = sss_gl_technique_at(v->tech);
    char buf[80];
    if (ImGui::BeginCombo(field_label(p, "technique", buf, sizeof buf), current->name)) {
        for (int i = 0; i < sss_gl_technique_count(); i++) {
            const sss_gl_technique_info *info = sss_gl_technique_at(i);
            if (ImGui::Selectable(info->name, i == v->tech) && i != v->tech) {
                sss_error err = {};
                report(v, view_cmd_technique(v, i, &err), err);
            }
            tooltip(info->summary);
        }
        ImGui::EndCombo();
    }
    tooltip(current->summary);
    if (v->kernel_cut[0]) /* sss_gl_kernel_cut: this technique cuts some material's kernel */
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "warning: %s", v->kernel_cut);
}

/* The parameter's name, doc string (the technique's table), range and default. */
static void param_tooltip(const sss_gl_param_info *p)
{
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 32.0f);
    ImGui::TextUnformatted(p->name);
    if (p->doc) ImGui::TextUnformatted(p->doc);
    ImGui::TextDisabled("range [%g, %g], default %g", p->min_value, p->max_value, p->default_value);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

/* One parameter as a checkbox, an integer or a float slider (logarithmic over wide positive ranges). */
static void param_widget(viewer *v, const char *tech, const sss_gl_param_info *p)
{
    double value = sss_gl_renderer_get_param(v->r, p->name);
    if (isnan(value)) return;
    char full[160], buf[80];
    snprintf(full, sizeof full, "%s.%s", tech, p->name);
    const char *label = field_label(v->panel, p->name, buf, sizeof buf);
    if (v->panel->stacked) param_tooltip(p);
    bool changed = false;
    double next = value;
    if (p->type == SSS_GL_PARAM_BOOL) {
        bool b = value != 0.0;
        changed = ImGui::Checkbox(label, &b);
        next = b ? 1.0 : 0.0;
    } else if (p->type == SSS_GL_PARAM_INT) {
        int k = (int)value, lo = (int)p->min_value, hi = (int)p->max_value;
        changed = ImGui::SliderInt(label, &k, lo, hi, "%d", ImGuiSliderFlags_AlwaysClamp);
        next = k;
    } else {
        ImGuiSliderFlags flags = ImGuiSliderFlags_AlwaysClamp;
        if (p->min_value >= 0.0 && p->max_value > 1000.0 * fmax(p->min_value, 1e-3)) /* e.g. [0, 1e30] */
            flags |= ImGuiSliderFlags_Logarithmic;
        changed = ImGui::SliderScalar(label, ImGuiDataType_Double, &next, &p->min_value, &p->max_value, "%.4g", flags);
    }
    param_tooltip(p);
    if (changed && next != value) {
        sss_error err = {};
        report(v, view_cmd_param(v, full, next, &err), err);
    }
}

static void params_section(viewer *v, view_panel *p)
{
    if (!section(v, p, SEC_PARAMETERS)) return;
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
    char buf[80];
    ImGui::DragScalarN(field_label(p, field, buf, sizeof buf), ImGuiDataType_Double, values, n, speed, &lo, &hi, "%.4g");
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
    char buf[80];
    if (ImGui::BeginCombo(field_label(v->panel, "medium", buf, sizeof buf), preview)) {
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

static void materials_section(viewer *v, view_panel *p)
{
    if (!section(v, p, SEC_MATERIALS)) return;
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

static void lights_section(viewer *v, view_panel *panel)
{
    if (!section(v, panel, SEC_LIGHTS)) return;
    char buf[80];
    for (size_t i = 0; i < v->scene->light_count; i++) {
        sss_light *l = &v->scene->lights[i];
        ImGui::PushID((int)i);
        ImGui::Text("light %zu", i);
        double *pos = l->type == SSS_LIGHT_AREA ? l->center : l->position;
        double p[3] = {pos[0], pos[1], pos[2]};
        if (l->type != SSS_LIGHT_DIRECTIONAL && l->type != SSS_LIGHT_ENVIRONMENT &&
            ImGui::DragScalarN(field_label(panel, "position", buf, sizeof buf), ImGuiDataType_Double, p, 3, 0.01f,
                               NULL, NULL, "%.3f"))
            light_edit(v, (int)i, "position", p, 3);
        const double *power = l->type == SSS_LIGHT_POINT || l->type == SSS_LIGHT_SPOT ? l->intensity
                              : l->type == SSS_LIGHT_ENVIRONMENT                      ? l->scale
                                                                                      : l->radiance;
        double peak = fmax(power[0], fmax(power[1], power[2])), zero = 0.0;
        if (ImGui::DragScalar(field_label(panel, "intensity", buf, sizeof buf), ImGuiDataType_Double, &peak, (float)(0.01 * (peak > 0 ? peak : 1)), &zero,
                              NULL, "%.4g"))
            light_edit(v, (int)i, "intensity", &peak, 1);
        float colour[3];
        for (int c = 0; c < 3; c++) colour[c] = peak > 0.0 ? (float)(power[c] / peak) : 1.0f;
        if (ImGui::ColorEdit3(field_label(panel, "colour", buf, sizeof buf), colour)) {
            double c3[3] = {colour[0], colour[1], colour[2]};
            light_edit(v, (int)i, "colour", c3, 3);
        }
        ImGui::PopID();
    }
}

static void timing_section(viewer *v, view_panel *p)
{
    if (!section(v, p, SEC_TIMING)) return;
    ImGui::Text("frame %.1f ms   passes %.1f ms (median)", v->frame_ms, v->timings.total_ms);
    for (int k = 0; k < p->pass_count; k++) {
        char overlay[64];
        const float *ms = p->passes[k].ms;
        snprintf(overlay, sizeof overlay, "%.2f ms", ms[(p->at + HISTORY - 1) % HISTORY]);
        ImGui::PlotLines(p->passes[k].name, ms, HISTORY, p->at, overlay, 0.0f, FLT_MAX, ImVec2(0, 28));
    }
}

static ImU32 scale_colour(double value)
{
    float c[3];
    view_error_colour(value, c);
    return ImGui::ColorConvertFloat4ToU32(ImVec4((float)sss_srgb_encode(c[0]), (float)sss_srgb_encode(c[1]),
                                                 (float)sss_srgb_encode(c[2]), 1.0f));
}

/* The error map's scale as in the image: 0 to the range, ticks at 5 (or 3) even steps with values. */
static void colour_bar(viewer *v)
{
    ImDrawList *dl = ImGui::GetWindowDrawList();
    ImVec2 at = ImGui::GetCursorScreenPos();
    float w = ImGui::GetContentRegionAvail().x, h = 12.0f, tick = 4.0f;
    const int steps = 32;
    for (int s = 0; s < steps; s++)
        dl->AddRectFilledMultiColor(ImVec2(at.x + w * s / steps, at.y), ImVec2(at.x + w * (s + 1) / steps, at.y + h),
                                    scale_colour((double)s / steps), scale_colour((double)(s + 1) / steps),
                                    scale_colour((double)(s + 1) / steps), scale_colour((double)s / steps));
    int count = w >= 5.0f * ImGui::CalcTextSize("0.000 ").x ? 5 : 3;
    float text_y = at.y + h + tick;
    for (int k = 0; k < count; k++) {
        float f = (float)k / (count - 1), x = at.x + f * (w - 1.0f);
        char label[32];
        snprintf(label, sizeof label, "%g", f * v->error_range);
        float lw = ImGui::CalcTextSize(label).x;
        float lx = k == 0 ? at.x : k == count - 1 ? at.x + w - lw : x - lw / 2.0f;
        dl->AddLine(ImVec2(x + 0.5f, at.y + h), ImVec2(x + 0.5f, at.y + h + tick), IM_COL32_WHITE);
        dl->AddText(ImVec2(lx, text_y), ImGui::GetColorU32(ImGuiCol_Text), label);
    }
    ImGui::Dummy(ImVec2(w, h + tick + ImGui::GetTextLineHeight()));
    ImGui::TextDisabled("per-pixel DSSIM; above %g: the top colour", v->error_range);
}

static void split_combo(viewer *v, view_panel *p)
{
    const char *split = v->split == VIEW_SPLIT_OFF         ? "off"
                        : v->split == VIEW_SPLIT_REFERENCE ? "reference"
                                                           : sss_gl_technique_at(v->split_tech)->name;
    double pos = v->split_pos;
    char buf[80];
    if (ImGui::BeginCombo(field_label(p, "split (right)", buf, sizeof buf), split)) {
        sss_error err = {};
        if (ImGui::Selectable("off", v->split == VIEW_SPLIT_OFF)) report(v, view_cmd_split(v, "off", pos, &err), err);
        if (ImGui::Selectable("reference", v->split == VIEW_SPLIT_REFERENCE))
            report(v, view_cmd_split(v, "reference", pos, &err), err);
        for (int i = 0; i < sss_gl_technique_count(); i++)
            if (ImGui::Selectable(sss_gl_technique_at(i)->name, v->split == VIEW_SPLIT_TECHNIQUE && v->split_tech == i))
                report(v, view_cmd_split(v, sss_gl_technique_at(i)->name, pos, &err), err);
        ImGui::EndCombo();
    }
    tooltip("a wipe: this technique left of the cut, the chosen one (or the reference) right of it");
    const double lo = 0.02, hi = 0.98;
    if (v->split && ImGui::SliderScalar(field_label(p, "wipe", buf, sizeof buf), ImGuiDataType_Double, &pos, &lo, &hi,
                                        "%.2f")) {
        sss_error err = {};
        report(v, view_cmd_split(v, split, pos, &err), err);
    }
}

static void error_map_widgets(viewer *v, view_panel *p)
{
    bool map = v->errormap != 0;
    if (ImGui::Checkbox("error map (DSSIM vs reference)", &map)) view_cmd_errormap(v, map, 0.0);
    if (!v->errormap) return;
    static const double ranges[] = {0.05, 0.1, 0.2, 0.5, 1.0};
    char buf[80], now[32];
    snprintf(now, sizeof now, "0 to %g", v->error_range);
    if (ImGui::BeginCombo(field_label(p, "range", buf, sizeof buf), now)) {
        for (double r : ranges) {
            char item[32];
            snprintf(item, sizeof item, "0 to %g", r);
            if (ImGui::Selectable(item, r == v->error_range)) view_cmd_errormap(v, 1, r);
        }
        ImGui::EndCombo();
    }
    tooltip("the colour bar's range: fixed, so that colours mean the same DSSIM in every view and technique");
    colour_bar(v);
}

static void view_section(viewer *v, view_panel *p)
{
    if (!section(v, p, SEC_VIEW)) return;
    char buf[80];
    if (ImGui::BeginCombo(field_label(p, "buffer", buf, sizeof buf), view_buffer_names[v->buffer])) {
        for (int b = 0; b < VIEW_BUFFER_COUNT; b++)
            if (ImGui::Selectable(view_buffer_names[b], b == v->buffer)) {
                sss_error err = {};
                report(v, view_cmd_buffer(v, b, &err), err);
            }
        ImGui::EndCombo();
    }
    split_combo(v, p);
    error_map_widgets(v, p);
    if (ImGui::Button("reference of this view (R)")) view_cmd_reference(v, 0);
    if (v->ref && v->dssim_gen) ImGui::Text("DSSIM %.4f (%s reference)", v->dssim, v->ref_draft ? "draft" : "final");
    else if (v->job) ImGui::Text("reference: rendering...");
}

/* The widest name a widget of the panel shows: every technique's parameters, the shared ones, the
 * panel's own fields. Needs the font atlas built. */
static float widest_label(void)
{
    static const char *const own[] = {"technique", "buffer", "split (right)", "wipe", "range", "medium", "scale", "eta",
                                      "g", "reflectance", "mfp", "sigma_a", "sigma_s", "position", "intensity", "colour"};
    ImFont *font = ImGui::GetIO().Fonts->Fonts[0];
    float widest = 0.0f;
    auto measure = [&](const char *name) { widest = fmaxf(widest, font->CalcTextSizeA(font->FontSize, FLT_MAX, 0.0f, name).x); };
    for (const char *name : own) measure(name);
    int n = 0;
    const sss_gl_param_info *shared = sss_gl_shared_params(&n);
    for (int i = 0; i < n; i++) measure(shared[i].name);
    for (int t = 0; t < sss_gl_technique_count(); t++)
        for (int i = 0; i < sss_gl_technique_at(t)->param_count; i++) measure(sss_gl_technique_at(t)->params[i].name);
    return widest;
}

/* The panel's width at start: a widget, the widest name beside it, the tree indent, padding and
 * scroll bar (framebuffer pixels). */
static double default_width(const view_panel *p, float fb_scale)
{
    const ImGuiStyle &st = ImGui::GetStyle();
    float w = ITEM_WIDTH + st.ItemInnerSpacing.x + p->label_width + st.IndentSpacing + 2.0f * st.WindowPadding.x +
              st.ScrollbarSize + 2.0f;
    return ceil(w * fb_scale);
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
    ImGui::GetStyle().WindowRounding = 0.0f; /* docked: a plain side panel */
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
    unsigned char *pixels = NULL;
    int tw = 0, th = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &tw, &th); /* builds the default font, to measure names */
    p->label_width = widest_label();
    int ww = 0, wh = 0, fw = 0, fh = 0;
    glfwGetWindowSize(v->window, &ww, &wh);
    glfwGetFramebufferSize(v->window, &fw, &fh);
    v->panel_want = default_width(p, ww > 0 && fw > 0 ? (float)fw / ww : 1.0f);
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

/* A script's section request (v->panel_section), drawn for a frame (open, close) or two (scroll: the
 * second scrolls with the opened section's height known), then reported and cleared. */
static void section_request_done(viewer *v, view_panel *p, float panel_height)
{
    if (v->panel_section < 0) {
        p->request_frames = 0;
        return;
    }
    if (++p->request_frames <= (v->panel_op == VIEW_SECTION_SCROLL ? 2 : 1)) return;
    int k = v->panel_section;
    bool in_view = p->header_top[k] >= 0.0f && p->header_bottom[k] <= panel_height;
    static const char *const ops[] = {"", "open", "close", "scroll"};
    view_message(v, "panel %s %s: %s, header at y %.0f of %.0f (%s)", ops[v->panel_op], view_panel_sections[k],
                 p->header_open[k] ? "open" : "closed", p->header_top[k], panel_height,
                 in_view ? "in view" : "out of view");
    v->panel_section = -1;
    p->request_frames = 0;
}

/* The panel docked at the right of the window, v->dock_width framebuffer pixels wide (viewer.c's
 * layout); dragging its left edge sets v->panel_want, which the next frame's layout follows. */
static void begin_docked(viewer *v)
{
    ImGuiIO &io = ImGui::GetIO();
    float scale = io.DisplayFramebufferScale.x > 0.0f ? io.DisplayFramebufferScale.x : 1.0f;
    float w = (float)v->dock_width / scale, width = io.DisplaySize.x, height = io.DisplaySize.y;
    float lo = VIEW_PANEL_MIN_WIDTH / scale, hi = fmaxf(lo, (float)(v->win_width - v->image_min) / scale);
    ImGui::SetNextWindowPos(ImVec2(width, 0.0f), ImGuiCond_Always, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(w, height), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(lo, height), ImVec2(hi, height));
    ImGui::SetNextWindowBgAlpha(1.0f);
    ImGui::Begin("sss view", NULL,
                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoScrollbar);
    float now = ImGui::GetWindowWidth();
    if (fabsf(now - w) >= 1.0f) v->panel_want = now * scale; /* dragged */
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
    begin_docked(v);
    if (v->message[0] && sss_time_seconds() < v->message_until) ImGui::TextWrapped("%s", v->message);
    /* the sections scroll below the message, so that a message coming or going does not move them */
    ImGui::BeginChild("sections");
    ImGui::PushTextWrapPos(0.0f); /* notes wrap at the panel's edge instead of running under it */
    const ImGuiStyle &st = ImGui::GetStyle();
    float room = ImGui::GetContentRegionAvail().x - p->label_width - st.ItemInnerSpacing.x - st.IndentSpacing;
    p->stacked = room < ITEM_MIN;
    ImGui::PushItemWidth(p->stacked ? -FLT_MIN : -(p->label_width + st.ItemInnerSpacing.x)); /* names in full */
    technique_section(v, p);
    view_section(v, p);
    params_section(v, p);
    materials_section(v, p);
    lights_section(v, p);
    timing_section(v, p);
    if (section(v, p, SEC_KEYS)) ImGui::TextUnformatted(sss_view_help_text());
    ImGui::PopItemWidth();
    ImGui::PopTextWrapPos();
    float height = ImGui::GetWindowHeight();
    ImGui::EndChild();
    ImGui::End();
    section_request_done(v, p, height);
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
