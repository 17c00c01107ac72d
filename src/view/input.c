/* view/input.c — mouse and keys (the GLFW callbacks, and the --input / `key` events of scripts), the
 * top of the viewer's command path: events go to the panel first, then to commands.c. The camera
 * moves at once (the renderer reads the scene's camera every frame); everything that rebuilds GL
 * resources is queued in v->act_* for the loop (view_cmd_keys). The key bindings' help text is
 * status.c's. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include "view/panel.h"
#include "view/viewer.h"

#define ORBIT_DEG_PER_PIXEL 0.3
#define ZOOM_PER_WHEEL_STEP 0.9

static viewer *get(GLFWwindow *w) { return glfwGetWindowUserPointer(w); }

static void handle_key(viewer *v, int key, int action, int mods)
{
    int shift = (mods & GLFW_MOD_SHIFT) != 0;
    switch (key) {
    case GLFW_KEY_ESCAPE:
    case GLFW_KEY_Q: glfwSetWindowShouldClose(v->window, GLFW_TRUE); break;
    case GLFW_KEY_TAB: v->act_tech += shift ? -1 : 1; break;
    case GLFW_KEY_1:
    case GLFW_KEY_KP_1: v->act_part = 1 + PART_ALL; break;
    case GLFW_KEY_2:
    case GLFW_KEY_KP_2: v->act_part = 1 + PART_TRANSLUCENCY; break;
    case GLFW_KEY_3:
    case GLFW_KEY_KP_3: v->act_part = 1 + PART_SCREEN; break;
    case GLFW_KEY_B: v->act_buffer = shift ? -1 : 1; break;
    case GLFW_KEY_R: v->act_reference = shift ? 2 : 1; break;
    case GLFW_KEY_M: v->act_medium += shift ? -1 : 1; break;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
    case GLFW_KEY_RIGHT_BRACKET: v->act_scale = (v->act_scale != 0.0 ? v->act_scale : 1.0) * 2.0; break;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
    case GLFW_KEY_LEFT_BRACKET: v->act_scale = (v->act_scale != 0.0 ? v->act_scale : 1.0) * 0.5; break;
    case GLFW_KEY_L: v->act_light += shift ? -1 : 1; break;
    case GLFW_KEY_SPACE:
        if (action == GLFW_PRESS) {
            v->playing = !v->playing;
            v->wall_last = glfwGetTime();
        }
        break;
    case GLFW_KEY_S:
    case GLFW_KEY_F12: v->act_screenshot = 1; break;
    case GLFW_KEY_C: view_cmd_camera_home(v); break;
    case GLFW_KEY_O:
        if (action == GLFW_PRESS) v->overlay = !v->overlay;
        break;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
        if (action == GLFW_PRESS) v->help = !v->help;
        break;
    default: break;
    }
}

static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    viewer *v = get(w);
    if (v && v->panel) view_panel_key(v, key, scancode, action, mods);
    if (v && action != GLFW_RELEASE && !view_panel_wants(v, 0)) handle_key(v, key, action, mods);
}

static void on_char(GLFWwindow *w, unsigned codepoint)
{
    viewer *v = get(w);
    if (v && v->panel) view_panel_char(v, codepoint);
}

/* A drag by (dx, dy) framebuffer pixels with a mouse button. */
static void drag(viewer *v, int button, double dx, double dy)
{
    if (dx == 0.0 && dy == 0.0) return;
    if (button == GLFW_MOUSE_BUTTON_LEFT) view_cmd_orbit(v, -dx * ORBIT_DEG_PER_PIXEL, dy * ORBIT_DEG_PER_PIXEL);
    else view_cmd_pan(v, dx, dy);
}

static void wheel(viewer *v, double steps)
{
    if (steps == 0.0) return;
    view_cmd_zoom(v, pow(ZOOM_PER_WHEEL_STEP, steps));
}

static void on_button(GLFWwindow *w, int button, int action, int mods)
{
    viewer *v = get(w);
    if (!v) return;
    if (v->panel) view_panel_button(v, button, action, mods);
    if (action == GLFW_PRESS && v->drag_button < 0 && !view_panel_wants(v, 1)) {
        v->drag_button = button;
        glfwGetCursorPos(w, &v->mouse_x, &v->mouse_y);
    } else if (action == GLFW_RELEASE && button == v->drag_button) {
        v->drag_button = -1;
    }
}

static void on_cursor(GLFWwindow *w, double x, double y)
{
    viewer *v = get(w);
    if (!v || v->drag_button < 0) return;
    /* cursor positions are in window coordinates; pan needs framebuffer pixels */
    int ww = 1, wh = 1;
    glfwGetWindowSize(w, &ww, &wh);
    double sx = ww > 0 ? (double)v->width / ww : 1.0, sy = wh > 0 ? (double)v->height / wh : 1.0;
    double dx = (x - v->mouse_x) * sx, dy = (y - v->mouse_y) * sy;
    v->mouse_x = x;
    v->mouse_y = y;
    drag(v, v->drag_button, dx, dy);
}

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    viewer *v = get(w);
    if (v && v->panel) view_panel_scroll(v, dx, dy);
    if (v && !view_panel_wants(v, 1)) wheel(v, dy);
}

/* ---- Scripted input (the fixed-frame mode of tests) ------------------------------------------- */

static const struct {
    const char *name;
    int key;
} key_names[] = {{"tab", GLFW_KEY_TAB},   {"space", GLFW_KEY_SPACE}, {"esc", GLFW_KEY_ESCAPE},
                 {"f1", GLFW_KEY_F1},     {"f12", GLFW_KEY_F12},     {"+", GLFW_KEY_EQUAL},
                 {"-", GLFW_KEY_MINUS},   {"[", GLFW_KEY_LEFT_BRACKET}, {"]", GLFW_KEY_RIGHT_BRACKET}};

static int parse_key(const char *s, int *key, int *mods)
{
    *mods = 0;
    if (strncmp(s, "shift+", 6) == 0) {
        *mods = GLFW_MOD_SHIFT;
        s += 6;
    }
    for (size_t i = 0; i < sizeof key_names / sizeof key_names[0]; i++)
        if (strcmp(s, key_names[i].name) == 0) {
            *key = key_names[i].key;
            return 1;
        }
    if (s[0] && !s[1] && s[0] >= 'a' && s[0] <= 'z') *key = GLFW_KEY_A + (s[0] - 'a');
    else if (s[0] && !s[1] && s[0] >= '0' && s[0] <= '9') *key = GLFW_KEY_0 + (s[0] - '0');
    else return 0;
    return 1;
}

int view_input_event(viewer *v, const char *event, int apply)
{
    double a = 0.0, b = 0.0;
    char tail;
    int key = 0, mods = 0;
    if (sscanf(event, "orbit:%lf:%lf%c", &a, &b, &tail) == 2 || sscanf(event, "pan:%lf:%lf%c", &a, &b, &tail) == 2) {
        if (apply) drag(v, event[0] == 'o' ? GLFW_MOUSE_BUTTON_LEFT : GLFW_MOUSE_BUTTON_RIGHT, a, b);
        return 1;
    }
    if (sscanf(event, "zoom:%lf%c", &a, &tail) == 1) {
        if (apply) wheel(v, a);
        return 1;
    }
    if (!parse_key(event, &key, &mods)) return 0;
    if (apply) handle_key(v, key, GLFW_PRESS, mods);
    return 1;
}

void view_install_callbacks(viewer *v)
{
    glfwSetWindowUserPointer(v->window, v);
    glfwSetKeyCallback(v->window, on_key);
    glfwSetMouseButtonCallback(v->window, on_button);
    glfwSetCursorPosCallback(v->window, on_cursor);
    glfwSetScrollCallback(v->window, on_scroll);
    glfwSetCharCallback(v->window, on_char);
}
