#pragma once
// The simulation shaders' specialization constants (shaders/sim), by the ids of shaders/common/sim_spec.glsl:
// one id per name across the family. gpu::Pipeline refuses a constant whose id, name or type the shader does
// not declare; tests/gpu/test_spec_contract.cpp checks every shader of the family against kAll.
#include "gpu/spec_id.h"

namespace sixway::sim::spec {

using gpu::SpecId;

inline constexpr SpecId kSize[3] = {{0, "NX"}, {1, "NY"}, {2, "NZ"}};  // the lattice
inline constexpr SpecId kSmokeUpres{3, "SMOKE_UPRES"};
// Boundary type per face, in scene::Scene's face order (-x, +x, -y, +y, -z, +z).
inline constexpr SpecId kFaces[6] = {{4, "FACE_XM"}, {5, "FACE_XP"}, {6, "FACE_YM"},
                                     {7, "FACE_YP"}, {8, "FACE_ZM"}, {9, "FACE_ZP"}};
inline constexpr SpecId kPeriodic[3] = {{10, "PERIODIC_X"}, {11, "PERIODIC_Y"}, {12, "PERIODIC_Z"}};
inline constexpr SpecId kInterpolatedBounceBack{13, "INTERPOLATED_BOUNCE_BACK"};
// lbm_step.comp's fluid.
inline constexpr SpecId kTau0{14, "TAU0"};
inline constexpr SpecId kSmagorinsky{15, "SMAGORINSKY"};
inline constexpr SpecId kBuoyancyTemperature{16, "BUOYANCY_T"};
inline constexpr SpecId kBuoyancyDensity{17, "BUOYANCY_D"};
inline constexpr SpecId kUp[3] = {{18, "UP_X"}, {19, "UP_Y"}, {20, "UP_Z"}};
inline constexpr SpecId kBody[3] = {{21, "BODY_X"}, {22, "BODY_Y"}, {23, "BODY_Z"}};
inline constexpr SpecId kWind[3] = {{24, "WIND_X"}, {25, "WIND_Y"}, {26, "WIND_Z"}};
inline constexpr SpecId kParabolicInflow{27, "PARABOLIC_INFLOW"};
inline constexpr SpecId kBoundaryCells{28, "BOUNDARY_CELLS"};
inline constexpr SpecId kDecay{29, "DECAY"};    // smoke_sources.comp
inline constexpr SpecId kPull{31, "PULL"};      // stream_bound.comp
inline constexpr SpecId kSparse{32, "SPARSE"};  // the FCT passes: skip inactive bricks (sim_bricks.glsl)
inline constexpr SpecId kSparseThreshold{33, "SPARSE_THRESHOLD"};  // smoke_activity.comp
// lbm_step.comp's boundary pipelines: which cells and which boundary code (the face slabs, the obstacles'
// box).
inline constexpr SpecId kBoundaryFaces{34, "BOUNDARY_FACES"};
inline constexpr SpecId kBoundaryObstacles{35, "BOUNDARY_OBSTACLES"};
// The in-place lattice's step parity (lbm_in_place.glsl).
inline constexpr SpecId kParity{36, "PARITY"};
// lbm_step.comp's last pipeline: the cells a moving obstacle uncovered.
inline constexpr SpecId kUncoveredCells{37, "UNCOVERED_CELLS"};

// Every constant above.
// clang-format off
inline constexpr SpecId kAll[] = {
    kSize[0], kSize[1], kSize[2], kSmokeUpres,
    kFaces[0], kFaces[1], kFaces[2], kFaces[3], kFaces[4], kFaces[5],
    kPeriodic[0], kPeriodic[1], kPeriodic[2], kInterpolatedBounceBack,
    kTau0, kSmagorinsky, kBuoyancyTemperature, kBuoyancyDensity,
    kUp[0], kUp[1], kUp[2], kBody[0], kBody[1], kBody[2], kWind[0], kWind[1], kWind[2],
    kParabolicInflow, kBoundaryCells,
    kDecay, kPull, kSparse, kSparseThreshold, kBoundaryFaces, kBoundaryObstacles, kParity,
    kUncoveredCells};
// clang-format on

}  // namespace sixway::sim::spec
