/*
 * Stratum C ABI.
 *
 * The only interface between the native path tracer and its hosts (the Blender add-on via
 * ctypes, the native CLI, the tests). Rules:
 *   - opaque handles, plain structs, status codes; no C++ type or exception crosses it;
 *   - every input is validated here: a bad value returns STRATUM_ERROR_INVALID_ARGUMENT and
 *     stratum_last_error() names the value; nothing aborts the host process;
 *   - matrices are 4x4, row-major, object-to-world, as Blender's Matrix (m[row*4 + col]);
 *   - coordinates are bounded so that no ray can leave the range Embree accepts (its
 *     assertions abort the process): a vertex, a translation, a placed mesh's extent, a lamp or
 *     camera position at most 1e12 from the origin; a linear transform element at most 1e12;
 *     lens 1e-3..1e6 mm, sensor 1e-3..1e4 mm; ortho_scale, aperture radius, focus distance, lamp
 *     radius and size at most 1e12. Beyond them a call fails naming the value;
 *   - render settings are named values; an unknown name is an error, so a host setting and its
 *     native meaning cannot drift apart silently.
 *
 * The declarations are in four parts, by what they work on: stratum/base.h (status, errors,
 * listings), stratum/helpers.h (no scene), stratum/scene.h and stratum/render.h. Hosts include
 * this header.
 */
#ifndef STRATUM_STRATUM_H
#define STRATUM_STRATUM_H

#include "stratum/base.h"
#include "stratum/helpers.h"
#include "stratum/render.h"
#include "stratum/scene.h"
#include "stratum/shader_nodes.h"

#endif
