#include "modes/render_mode.h"

#include "io/error.h"

namespace sixway::modes {

RenderMode parseRenderMode(const std::string& name) {
  for (RenderMode m : {RenderMode::Neural, RenderMode::Reference, RenderMode::ReferenceMs,
                       RenderMode::ReferenceFit, RenderMode::Traditional, RenderMode::TraditionalMs,
                       RenderMode::Guide, RenderMode::GuideLit, RenderMode::PathTrace})
    if (name == renderModeName(m)) return m;
  throw io::InputError("--mode",
                       "unknown mode \"" + name +
                           "\" (known: neural, reference, reference-ms, reference-fit, traditional, "
                           "traditional-ms, guide, guide-lit, pathtrace)");
}

const char* renderModeName(RenderMode mode) {
  switch (mode) {
    case RenderMode::Neural:
      return "neural";
    case RenderMode::Reference:
      return "reference";
    case RenderMode::ReferenceMs:
      return "reference-ms";
    case RenderMode::ReferenceFit:
      return "reference-fit";
    case RenderMode::Traditional:
      return "traditional";
    case RenderMode::TraditionalMs:
      return "traditional-ms";
    case RenderMode::Guide:
      return "guide";
    case RenderMode::GuideLit:
      return "guide-lit";
    case RenderMode::PathTrace:
      return "pathtrace";
  }
  return "?";
}

}  // namespace sixway::modes
