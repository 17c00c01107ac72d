/* sss/sss.h — the whole sss library (physics, kernels, images, meshes). Include the module headers
 * instead when you need only one concern. */
#ifndef SSS_SSS_H
#define SSS_SSS_H
#include "sss/common.h"
#include "sss/material.h"
#include "sss/profile.h"
#include "sss/kernel.h"
#include "sss/image.h"
#include "sss/mesh.h"
#include "sss/scene.h"
#endif
