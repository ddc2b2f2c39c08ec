#version 450
#extension GL_GOOGLE_include_directive : require
// meshsal: sweepn for CPU devices (lavapipe): a thread per point, rows shared by the subgroup (see sweep.glsl).
#define UNIFORM_ROWS
#include "sweep.glsl"
