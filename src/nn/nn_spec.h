#pragma once
// The network operators' specialization constants (shaders/nn), by the ids of shaders/common/nn_spec.glsl:
// one id per name across the family. gpu::Pipeline refuses a constant whose id, name or type the shader does
// not declare; tests/gpu/test_spec_contract.cpp checks every shader of the family against kAll.
#include "gpu/spec_id.h"

namespace sixway::nn::spec {

using gpu::SpecId;

// The workgroup size (local_size_x_id, local_size_y_id: GLSL gives them no name).
inline constexpr SpecId kLocalSizeX{0, "local_size_x"}, kLocalSizeY{1, "local_size_y"};
inline constexpr SpecId kWidth{2, "WIDTH"}, kHeight{3, "HEIGHT"};
inline constexpr SpecId kInWidth{4, "IN_WIDTH"}, kInHeight{5, "IN_HEIGHT"};
inline constexpr SpecId kOutWidth{6, "OUT_WIDTH"}, kOutHeight{7, "OUT_HEIGHT"};
inline constexpr SpecId kChannels{8, "CHANNELS"}, kGatedChannels{9, "GATED_CHANNELS"};
inline constexpr SpecId kFfnChannels{10, "FFN_CHANNELS"}, kProjectionChannels{11, "PROJECTION_CHANNELS"};
inline constexpr SpecId kGroups{12, "GROUPS"}, kGroupsIn{13, "GROUPS_IN"};
inline constexpr SpecId kGroupsA{14, "GROUPS_A"}, kGroupsB{15, "GROUPS_B"};
inline constexpr SpecId kPx{16, "PX"}, kPy{17, "PY"};
inline constexpr SpecId kKernel{18, "KERNEL"}, kStride{19, "STRIDE"};
inline constexpr SpecId kSlice{20, "SLICE"}, kWeightVec4s{21, "WEIGHT_VEC4S"};
inline constexpr SpecId kActivation{22, "ACTIVATION"}, kNegativeSlope{23, "NEGATIVE_SLOPE"};
inline constexpr SpecId kEps{24, "EPS"};
inline constexpr SpecId kFactor{25, "FACTOR"};
inline constexpr SpecId kPartialCount{26, "PARTIAL_COUNT"}, kPixels{27, "PIXELS"};
// input.comp
inline constexpr SpecId kGuideWidth{28, "GUIDE_WIDTH"}, kGuideHeight{29, "GUIDE_HEIGHT"};
inline constexpr SpecId kGuideChannels{30, "GUIDE_CHANNELS"};
// output.comp
inline constexpr SpecId kMapWidth{31, "MAP_WIDTH"}, kMapHeight{32, "MAP_HEIGHT"};
inline constexpr SpecId kSrgbMask{33, "SRGB_MASK"};
inline constexpr SpecId kSource[8] = {{34, "SOURCE_0"}, {35, "SOURCE_1"}, {36, "SOURCE_2"}, {37, "SOURCE_3"},
                                      {38, "SOURCE_4"}, {39, "SOURCE_5"}, {40, "SOURCE_6"}, {41, "SOURCE_7"}};
inline constexpr SpecId kLightmapA[4] = {{42, "A_0"}, {43, "A_1"}, {44, "A_2"}, {45, "A_3"}};
inline constexpr SpecId kLightmapB[4] = {{46, "B_0"}, {47, "B_1"}, {48, "B_2"}, {49, "B_3"}};
// input.comp
inline constexpr SpecId kAlbedoChannel{50, "ALBEDO_CHANNEL"};
// conv2d_matrix.comp
inline constexpr SpecId kMatrixM{51, "MATRIX_M"}, kMatrixN{52, "MATRIX_N"}, kMatrixK{53, "MATRIX_K"};
inline constexpr SpecId kNTiles{54, "N_TILES"}, kKChunks{55, "K_CHUNKS"}, kNPadded{56, "N_PADDED"};
inline constexpr SpecId kOutGroups{57, "OUT_GROUPS"};

// Every constant above.
inline constexpr SpecId kAll[] = {
    kLocalSizeX,    kLocalSizeY,   kWidth,         kHeight,        kInWidth,      kInHeight,
    kOutWidth,      kOutHeight,    kChannels,      kGatedChannels, kFfnChannels,  kProjectionChannels,
    kGroups,        kGroupsIn,     kGroupsA,       kGroupsB,       kPx,           kPy,
    kKernel,        kStride,       kSlice,         kWeightVec4s,   kActivation,   kNegativeSlope,
    kEps,           kFactor,       kPartialCount,  kPixels,        kGuideWidth,   kGuideHeight,
    kGuideChannels, kMapWidth,     kMapHeight,     kSrgbMask,      kSource[0],    kSource[1],
    kSource[2],     kSource[3],    kSource[4],     kSource[5],     kSource[6],    kSource[7],
    kLightmapA[0],  kLightmapA[1], kLightmapA[2],  kLightmapA[3],  kLightmapB[0], kLightmapB[1],
    kLightmapB[2],  kLightmapB[3], kAlbedoChannel, kMatrixM,       kMatrixN,      kMatrixK,
    kNTiles,        kKChunks,      kNPadded,       kOutGroups};

}  // namespace sixway::nn::spec
