// A deliberate layer violation for the layer check's own test: the engine's core including the event loop above it.
// Never compiled.
#pragma once

#include <impactlab/simulate/simulator.hpp>
