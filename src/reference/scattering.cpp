#include "reference/scattering.h"

#include "io/error.h"

namespace sixway::reference {

const char* scatteringName(Scattering scattering) {
  return scattering == Scattering::Single ? "single" : "multiple";
}

Scattering parseScattering(const std::string& name, const std::string& source) {
  if (name == "single") return Scattering::Single;
  if (name == "multiple") return Scattering::Multiple;
  throw io::InputError(source, "unknown scattering \"" + name + "\" (single or multiple)");
}

}  // namespace sixway::reference
