#pragma once
// The specialization constants of the renderers' shaders (shaders/render). Each shader declares its own (no
// two share a name). gpu::Pipeline refuses a constant whose id, name or type the shader does not declare;
// tests/gpu/test_spec_contract.cpp checks every shader of the family against kAll.
#include "gpu/spec_id.h"

namespace sixway::render::spec {

using gpu::SpecId;

inline constexpr SpecId kGuideLights{0, "kGuideLights"};  // guide_lightmaps.comp
// guide_march.comp
inline constexpr SpecId kShadowedLights{0, "kShadowedLights"};
inline constexpr SpecId kFrontLight{1, "kFrontLight"};
inline constexpr SpecId kLightGrids{2, "kLightGrids"};
inline constexpr SpecId kFineAlpha{3, "kFineAlpha"};
inline constexpr SpecId kEmission{4, "kEmission"};
inline constexpr SpecId kSixWay{0, "SIXWAY"};  // path_trace.comp

// Every constant above.
inline constexpr SpecId kAll[] = {kGuideLights, kShadowedLights, kFrontLight, kLightGrids,
                                  kFineAlpha,   kEmission,       kSixWay};

}  // namespace sixway::render::spec
