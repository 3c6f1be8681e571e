// A deliberate layer violation for the layer check's own test: analysis including io (downward) without the project prefix.
// Never compiled.
#pragma once

#include "io/scene.hpp"
