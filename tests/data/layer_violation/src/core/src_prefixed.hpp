// A deliberate layer violation for the layer check's own test: the engine's core including its integrate folder, src/-prefixed.
// Never compiled.
#pragma once

#include "src/integrate/taylor_stepper.hpp"
