#pragma once
// The specialization constants of the host's own shaders (shaders/gpu): ReduceStats's and those of the gpu
// tests. Each shader declares its own (no two share a name). gpu::Pipeline refuses a constant whose id, name
// or type the shader does not declare; tests/gpu/test_spec_contract.cpp checks every shader against kAll.
#include "gpu/spec_id.h"

namespace sixway::gpu::spec {

// reduce_stats.comp
inline constexpr SpecId kGroupSize{0, "local_size_x"};  // GLSL gives a local_size_x_id no name
inline constexpr SpecId kItemsPerThread{1, "ITEMS_PER_THREAD"};
inline constexpr SpecId kFromStats{2, "FROM_STATS"};
inline constexpr SpecId kStride{3, "STRIDE"};
inline constexpr SpecId kComponents{4, "COMPONENTS"};
// texel_buffer_scale.comp and fill_gradient.frag, of the tests.
inline constexpr SpecId kScale{0, "SCALE"};
inline constexpr SpecId kBlue{0, "BLUE"};

// Every constant above.
inline constexpr SpecId kAll[] = {kGroupSize,  kItemsPerThread, kFromStats, kStride,
                                  kComponents, kScale,          kBlue};

}  // namespace sixway::gpu::spec
