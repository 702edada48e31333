#pragma once
// The specialization constants of the demo's shaders (shaders/demo). gpu::Pipeline refuses a constant whose
// id, name or type the shader does not declare; tests/gpu/test_spec_contract.cpp checks the shaders against
// kAll.
#include "gpu/spec_id.h"

namespace sixway::app::demo::spec {

using gpu::SpecId;

inline constexpr SpecId kEncodeSrgb{0, "kEncodeSrgb"};  // display.frag

// Every constant above.
inline constexpr SpecId kAll[] = {kEncodeSrgb};

}  // namespace sixway::app::demo::spec
