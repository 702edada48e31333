#pragma once
// Which light six-way lightmaps hold: single scattering (what the exact baker computes) or multiple
// scattering (all orders: what DCC tools bake, and the physically correct truth).
#include <string>

namespace sixway::reference {

enum class Scattering { Single, Multiple };
const char* scatteringName(Scattering scattering);  // "single", "multiple"
// Throws io::InputError naming `source` for another name.
Scattering parseScattering(const std::string& name, const std::string& source);

}  // namespace sixway::reference
