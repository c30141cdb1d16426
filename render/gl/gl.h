#pragma once
// The one include for GL calls in the engine: glad's GL 4.5 core loader.
#include <glad/gl.h>
