#pragma once
// GL 3+ prototypes straight from libOSMesa (no loader; never link -lGL next to it).
#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
