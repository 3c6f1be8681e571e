// A deliberate layer violation for the layer check's own test: io (layer 2) including the scene API (layer 5), quoted, unprefixed.
// Never compiled.
#pragma once

#include "api/oscillator_registry.hpp"
