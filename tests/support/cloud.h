// The particle cloud of the tests and raycast-bench: n normal-shaded spheres of one radius
// filling the view of a fixed camera, their total projected area (the
// coverage) the same for every n, and the same cloud as scene-file JSON.
#pragma once
#include <cstdint>
#include <string>

#include "scene/scene.h"

namespace raycast_test {
using namespace raycast;

// The camera at the origin looking down -z (the lesson's frame), vfov 50
// degrees, 1920x1080. Centres uniform in the volume of the view's frustum
// between depths 2 and 12; std::mt19937 with a fixed seed (its output is
// specified by the standard) and explicit arithmetic on its words, so the
// cloud is the same everywhere. Every coordinate is rounded to 1e-6 and the
// radius to 5 significant digits as the JSON writes them, so parsing
// cloud_json(n) gives exactly these spheres. Below n = 20 or so the radius
// exceeds the nearest depth (the camera may sit inside a sphere): the rows
// are about large n.
// coverage: the spheres' summed screen area in image areas (1.5: the sparse
// family, 3: the dense one, about three spheres behind each pixel).
api::scene particle_cloud(int64_t n, double coverage = 1.5);

// The radius that keeps the cloud's coverage at that many image areas (cloud.cpp).
double cloud_radius(int64_t n, double coverage = 1.5);

// The packed box of particle data (a granular pack, a simulation snapshot):
// n equal spheres at packing fraction 0.3 in a cube of side 1 at the origin,
// each in its own cell of a lattice of m^3 >= n cells (the cells chosen by a
// fixed shuffle), jittered within it without overlapping; radius r with
// n (4/3) pi r^3 = 0.3. Seen from outside a corner, (1, 1, 1) from the
// centre, through a 30 degree lens, 1920x1080 (a ray through the cube passes
// some 50 spheres at 10^6); the same rounding as particle_cloud.
// Orthographic: the same box seen along an axis (-z), from an image plane
// 1.2 high (the box fills most of the picture's height; a ray passes m
// spheres' cells, 100 at 10^6).
api::scene particle_box(int64_t n, bool orthographic = false);

// The same cube, camera and radius with the centres uniform in it (spheres
// may overlap: a gas's snapshot rather than a packing). The lattice box lists
// each sphere in one cell of a grid of n cells (where m^3 = n, as at 10^6,
// the lattice is such a grid); here a sphere reaches into several, as in
// most particle data.
api::scene particle_box_random(int64_t n);

// p as scene-file text (formats/json.h), about 85 bytes a sphere: each
// sphere's shading, and the colour of a flat or lit one.
std::string cloud_json(const api::scene& p);

}  // namespace raycast_test
