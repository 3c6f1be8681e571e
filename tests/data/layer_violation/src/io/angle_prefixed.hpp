// A deliberate layer violation for the layer check's own test: io including the scene API by its prefixed path.
// Never compiled.
#pragma once

#include <impactlab/api/oscillator_registry.hpp>
