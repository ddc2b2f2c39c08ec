// CPU twin: sweep_point_default() in src/saliency/sweep_kernels.inc
#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: sweep8 in double for a list of vertices, a lane each: the recheck of the points
// whose mixed-precision maps are within rounding of a neighbour's (see gpu_near_ties.cpp).
#define FAST8
#define POINT_LIST
#include "sweep.glsl"
#include "sweep_layout_list.glsl"
