/* sss/sss.h — the whole sss library. Include the module headers instead when you need only one
 * concern: version (SSS_VERSION_*, sss_version), common (errors), material + profile (physics),
 * kernel, image, mesh, scene, reference (CPU ground truth), export (PBRT), gl (real-time renderer),
 * sam (spatial adjacency maps), eval, view. */
#ifndef SSS_SSS_H
#define SSS_SSS_H
#include "sss/version.h"
#include "sss/common.h"
#include "sss/material.h"
#include "sss/profile.h"
#include "sss/kernel.h"
#include "sss/image.h"
#include "sss/mesh.h"
#include "sss/scene.h"
#include "sss/gltf.h"
#include "sss/reference.h"
#include "sss/export.h"
#include "sss/gl.h"
#include "sss/gl_pass.h"
#include "sss/sam.h"
#include "sss/eval.h"
#include "sss/view.h"
#endif
