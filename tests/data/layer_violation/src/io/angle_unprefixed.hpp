// A deliberate layer violation for the layer check's own test: io including the scene API in angle brackets, unprefixed.
// Never compiled.
#pragma once

#include <api/oscillator_registry.hpp>
