#pragma once
// One place that includes OpenGL: Debian's libOSMesa exports the whole GL 3.3 core API as plain
// symbols, so prototypes are enough and no function loader is needed.

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
#include <GL/glext.h>
