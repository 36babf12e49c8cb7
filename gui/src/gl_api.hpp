#pragma once
/// \file
/// OpenGL 3.3 core declarations for the renderer (private). Debian's libGL (glvnd) exports
/// every core entry point, so the prototypes of glext.h link directly without a loader.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
