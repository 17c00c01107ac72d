/* view/layout.c — the window split into the image and the docked panel: the panel sits at the right,
 * beside the image, so the renderer renders at the image's size and nothing of the image is hidden. */
#include "view/view_internal.h"

int view_dock_width(int win_width, double want, int shown, int image_min)
{
    if (!shown || win_width <= image_min) return 0;
    int most = win_width - image_min;
    int w = want > VIEW_PANEL_MIN_WIDTH ? (want < most ? (int)(want + 0.5) : most) : VIEW_PANEL_MIN_WIDTH;
    return w < most ? w : most;
}
