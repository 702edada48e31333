#include "sim/obstacle_set.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "io/error.h"
#include "io/obj.h"
#include "scene/obstacle_placement.h"
#include "sim/sim_spec.h"

namespace sixway::sim {
namespace {

constexpr uint32_t kFlagsGroupSize = 64;  // obstacles.comp's local_size_x

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Clang 14 (the fuzz build) does not deduce aggregate template arguments without a guide.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

struct VoxelizePush {
  glm::vec4 origin;
  glm::ivec4 grid;
  uint32_t triangleCount;
};

}  // namespace

ObstacleSet::ObstacleSet(const gpu::Context& context, const gpu::PipelineCache& cache,
                         const scene::Scene& scene, const LatticeUnits& units)
    : context_(&context), cache_(&cache), units_(units), origin_(scene.grid.origin), size_(scene.grid.size) {
  const uint64_t cells = uint64_t(scene.grid.size.x) * scene.grid.size.y * scene.grid.size.z;
  cells_ = cells;
  flags_ = gpu::Buffer::storage(context, cells * sizeof(uint32_t), "cell flags");
  flags_.upload(std::vector<uint32_t>(cells, 0u));
  gpu::ComputePipelineDesc desc;
  desc.shader = "sim/obstacles.comp";
  desc.bindings.assign(3, gpu::BindingType::StorageBuffer);
  desc.pushConstantBytes = sizeof(uint32_t);
  for (int a = 0; a < 3; ++a) desc.spec.set(spec::kSize[a], scene.grid.size[a]);
  flagsPipeline_ = std::make_unique<gpu::Pipeline>(context, cache, desc);
  flagsGroups_ = gpu::linearGroups(context, cells, kFlagsGroupSize, "cell flags");
  if (scene.obstacles.size() > kMaxObstacles)
    throw io::InputError(scene.name, "obstacles: at most " + std::to_string(kMaxObstacles) +
                                         " are supported, got " + std::to_string(scene.obstacles.size()));
  if (scene.inlets.size() > kMaxInlets)
    throw io::InputError(scene.name, "inlets: at most " + std::to_string(kMaxInlets) +
                                         " are supported, got " + std::to_string(scene.inlets.size()));
  for (const scene::Obstacle& o : scene.obstacles) obstacles_.push_back(placed(o));
  for (const scene::Inlet& in : scene.inlets) {
    GpuInlet g{};
    std::visit(Overloaded{
                   [&](const scene::InletDisk& d) {
                     g.centre = glm::vec4(units.toLattice(d.center, origin_), float(InletShape::Disk));
                     g.normal = glm::vec4(d.normal, d.radius * (1.0f / units.cellSize));
                   },
                   [&](const scene::InletBox& b) {
                     g.centre = glm::vec4(units.toLattice(b.min, origin_), float(InletShape::Box));
                     g.normal = glm::vec4(units.toLattice(b.max, origin_), 0.0f);
                   },
               },
               in.shape);
    g.velocity = glm::vec4(units.toLatticeVelocity(in.velocity), in.noise);
    g.smoke = glm::vec4(in.density, in.temperature, 0.0f, float(kInletSetsFlow));
    inlets_.push_back({g, in.start, in.stop, true});
  }
  if (Voxelization v = voxelize(scene.obstacles); v.sequence) v.sequence->submit();
}

ObstacleSet::Placed ObstacleSet::placed(const scene::Obstacle& o) const {
  const float toCells = 1.0f / units_.cellSize;
  GpuObstacle g{};
  glm::vec3 extent(0);
  std::visit(Overloaded{
                 [&](const scene::SphereObstacle& s) {
                   g.centre = glm::vec4(units_.toLattice(s.center, origin_), float(ShapeCode::Sphere));
                   g.size.x = s.radius * toCells;
                   extent = glm::vec3(g.size.x);
                 },
                 [&](const scene::CylinderObstacle& c) {
                   g.centre = glm::vec4(units_.toLattice(c.center, origin_), float(ShapeCode::Cylinder));
                   g.axis = glm::vec4(c.axis, 0.5f * c.height * toCells);
                   g.size.x = c.radius * toCells;
                   extent = g.axis.w * glm::abs(c.axis) + g.size.x * glm::sqrt(1.0f - c.axis * c.axis);
                 },
                 [&](const scene::CapsuleObstacle& c) {
                   g.centre = glm::vec4(units_.toLattice(c.center, origin_), float(ShapeCode::Capsule));
                   g.axis = glm::vec4(c.axis, (0.5f * c.height - c.radius) * toCells);
                   g.size.x = c.radius * toCells;
                   extent = g.axis.w * glm::abs(c.axis) + g.size.x;
                 },
                 [&](const scene::BoxObstacle& b) {
                   g.centre = glm::vec4(units_.toLattice(b.center, origin_), float(ShapeCode::Box));
                   g.size = glm::vec4(0.5f * b.size * toCells, 0.0f);
                   extent = glm::vec3(g.size);
                 },
                 [&](const scene::MeshObstacle& m) {
                   g.centre = glm::vec4(units_.toLattice(m.translate, origin_), float(ShapeCode::Mesh));
                   // lattice offset d → object: Rᵀ · d · cellSize / scale
                   const glm::mat3 toObject =
                       glm::transpose(scene::meshRotation(m)) * (units_.cellSize / m.scale);
                   for (int row = 0; row < 3; ++row)
                     g.rotation[row] = glm::vec4(toObject[0][row], toObject[1][row], toObject[2][row], 0.0f);
                 },
             },
             o.shape);
  return {g, o.motion, extent};
}

std::optional<gpu::Buffer> ObstacleSet::setObstacles(std::span<const scene::Obstacle> obstacles) {
  if (obstacles.size() > kMaxObstacles)
    throw std::invalid_argument(std::to_string(obstacles.size()) + " obstacles; at most " +
                                std::to_string(kMaxObstacles));
  std::vector<Placed> replaced;
  for (const scene::Obstacle& o : obstacles) replaced.push_back(placed(o));
  std::swap(obstacles_, replaced);
  if (std::none_of(obstacles.begin(), obstacles.end(), [](const scene::Obstacle& o) {
        return std::holds_alternative<scene::MeshObstacle>(o.shape);
      }))
    return std::nullopt;
  gpu::Buffer old = std::move(occupancy_);
  try {
    pending_ = voxelize(obstacles);
  } catch (...) {
    obstacles_ = std::move(replaced);
    occupancy_ = std::move(old);
    throw;
  }
  return old;
}

ObstacleSet::Voxelization ObstacleSet::voxelize(std::span<const scene::Obstacle> obstacles) {
  struct Job {
    io::Mesh mesh;
    GpuObstacle* target;
  };
  std::vector<Job> jobs;
  uint32_t words = 0;
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const auto* m = std::get_if<scene::MeshObstacle>(&obstacles[i].shape);
    if (!m) continue;
    GpuObstacle& g = obstacles_[i].shape;
    Job job{scene::meshTriangles(*m), &g};
    // Object-space voxels of half a lattice cell, over the mesh bounds plus a voxel of margin.
    const float voxel = 0.5f * units_.cellSize / m->scale;
    const glm::vec3 lo = job.mesh.boundsMin - voxel, hi = job.mesh.boundsMax + voxel;
    const glm::ivec3 cells = glm::ivec3(glm::ceil((hi - lo) / voxel));
    const uint64_t count = uint64_t(cells.x) * cells.y * cells.z;
    if (count > (64u << 20))
      throw io::InputError(
          m->data ? "obstacle " + std::to_string(i) + " (a mesh in memory)" : m->file.string(),
          "the mesh needs " + std::to_string(count) +
              " occupancy voxels at this cell size; reduce its scale");
    g.meshOrigin = glm::vec4(lo, voxel);
    // A sphere around the translation that holds every corner of the grid, whatever the rotation.
    float reach = 0;
    for (int corner = 0; corner < 8; ++corner)
      reach = std::max(reach, glm::length(glm::vec3(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y,
                                                    corner & 4 ? hi.z : lo.z)));
    obstacles_[i].halfExtent = glm::vec3(reach * m->scale / units_.cellSize);
    g.meshGrid = glm::ivec4(cells, int(words));
    words += uint32_t(count);
    jobs.push_back(std::move(job));
  }
  // Zeroed here only when no voxelization clears it first.
  occupancy_ = gpu::Buffer::storage(*context_, std::max<uint64_t>(words, 1) * sizeof(uint32_t),
                                    "mesh occupancy", jobs.empty());
  Voxelization v;
  if (jobs.empty()) return v;

  if (!voxelizePipeline_) {
    gpu::ComputePipelineDesc desc;
    desc.shader = "sim/voxelize_mesh.comp";
    desc.bindings = {gpu::BindingType::StorageBuffer, gpu::BindingType::StorageBuffer,
                     gpu::BindingType::StorageBuffer};
    desc.pushConstantBytes = sizeof(VoxelizePush);
    voxelizePipeline_ = std::make_unique<gpu::Pipeline>(*context_, *cache_, desc);
  }
  v.sequence = std::make_unique<gpu::Sequence>(*context_);
  v.sequence->fill(occupancy_, 0);
  // Host-visible inputs: written without a submission, read once.
  const auto input = [&](const auto& values, const char* name) {
    gpu::Buffer b(*context_, values.size() * sizeof(values[0]), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                  gpu::MemoryKind::HostUpload, name);
    b.upload(values);
    return b;
  };
  for (const Job& job : jobs) {
    std::vector<float> positions;
    for (const glm::vec3& p : job.mesh.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<uint32_t> triangles;
    for (const glm::uvec3& t : job.mesh.triangles) triangles.insert(triangles.end(), {t.x, t.y, t.z});
    v.inputs.push_back(input(positions, "mesh positions"));
    v.inputs.push_back(input(triangles, "mesh triangles"));
    const VoxelizePush push{job.target->meshOrigin, job.target->meshGrid,
                            uint32_t(job.mesh.triangles.size())};
    v.sequence->dispatch(*voxelizePipeline_,
                         {gpu::reads(v.inputs[v.inputs.size() - 2]), gpu::reads(v.inputs.back()),
                          gpu::readsWrites(occupancy_)},
                         push, (3 * push.triangleCount + 63) / 64);
  }
  v.sequence->finish();
  return v;
}

void ObstacleSet::recordFlags(gpu::Sequence& sequence, const gpu::Buffer& params,
                              const gpu::Buffer& dispatchArgs, uint32_t slot) const {
  sequence.dispatchIndirect(*flagsPipeline_,
                            {gpu::reads(params), gpu::reads(occupancy_), gpu::readsWrites(flags_)}, slot,
                            dispatchArgs, slot * kFlagsDispatchStride);
}

void ObstacleSet::setEmitters(std::span<const Emitter> emitters) {
  if (emitters.size() > kMaxInlets)
    throw std::invalid_argument(std::to_string(emitters.size()) + " emitters; at most " +
                                std::to_string(kMaxInlets));
  inlets_.clear();
  for (const Emitter& e : emitters) {
    GpuInlet g{};
    g.centre = glm::vec4(units_.toLattice(e.centre, origin_), float(InletShape::Ball));
    g.normal = glm::vec4(0.0f, 0.0f, 0.0f, e.radius / units_.cellSize);
    g.velocity = glm::vec4(units_.toLatticeVelocity(e.velocity), 0.0f);
    const uint32_t mode = kInletAdds | (e.velocity != glm::vec3(0.0f) ? kInletSetsFlow : 0u);
    const float perStep = float(units_.stepSeconds);
    g.smoke = glm::vec4(e.densityRate * perStep, e.temperatureRate * perStep, 0.0f, float(mode));
    inlets_.push_back({g, 0.0f, e.on ? std::numeric_limits<float>::infinity() : 0.0f, false});
  }
}

void ObstacleSet::setMotion(size_t obstacle, std::optional<scene::Motion> motion) {
  obstacles_.at(obstacle).motion = std::move(motion);
}

glm::vec3 ObstacleSet::positionAt(size_t obstacle, double seconds) const {
  const Placed& p = obstacles_.at(obstacle);
  if (p.motion) return scene::evaluateMotion(*p.motion, seconds).position;
  return origin_ + glm::vec3(p.shape.centre) * units_.cellSize;
}

glm::vec3 ObstacleSet::centreAt(size_t obstacle, uint64_t step) const {
  const Placed& p = obstacles_[obstacle];
  if (!p.motion) return glm::vec3(p.shape.centre);
  return units_.toLattice(scene::evaluateMotion(*p.motion, double(step) * units_.stepSeconds).position,
                          origin_);
}

std::pair<glm::ivec3, glm::ivec3> ObstacleSet::sweptBox() const {
  if (obstacles_.empty()) return {glm::ivec3(0), glm::ivec3(0)};
  // A motion interpolates its keyframes linearly, so it never leaves the box of their positions.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const Placed& p : obstacles_) {
    std::vector<glm::vec3> centres{glm::vec3(p.shape.centre)};
    if (p.motion)
      for (const scene::Keyframe& k : p.motion->keyframes)
        centres.push_back(units_.toLattice(k.position, origin_));
    for (const glm::vec3& c : centres) {
      lo = glm::min(lo, c - p.halfExtent);
      hi = glm::max(hi, c + p.halfExtent);
    }
  }
  glm::ivec3 first = glm::ivec3(glm::floor(lo)) - 2, last = glm::ivec3(glm::ceil(hi)) + 2;
  // A box that reaches a face spans its whole axis: through a periodic face the obstacle's links wrap around.
  for (int a = 0; a < 3; ++a)
    if (first[a] <= 0 || last[a] >= size_[a]) first[a] = 0, last[a] = size_[a];
  return {first, last};
}

std::pair<glm::ivec3, glm::ivec3> ObstacleSet::inletBox() const {
  if (inlets_.empty()) return {glm::ivec3(0), glm::ivec3(0)};
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (const TimedInlet& t : inlets_) {
    const GpuInlet& g = t.inlet;
    // A disk lies within its radius of the centre and half a cell of its plane, a ball within its radius,
    // a box between its corners.
    const bool box = g.centre.w == float(InletShape::Box);
    const glm::vec3 a = box ? glm::vec3(g.centre) : glm::vec3(g.centre) - (g.normal.w + 1);
    const glm::vec3 b = box ? glm::vec3(g.normal) : glm::vec3(g.centre) + (g.normal.w + 1);
    lo = glm::min(lo, a);
    hi = glm::max(hi, b);
  }
  // Kept within a cell of the lattice, so that a box reaching far past it converts to integers safely.
  lo = glm::clamp(lo, glm::vec3(-1.0f), glm::vec3(size_) + 1.0f);
  hi = glm::clamp(hi, glm::vec3(-1.0f), glm::vec3(size_) + 1.0f);
  // Cell i's centre is at i + 0.5: a centre in [lo, hi] has i in [floor(lo − 0.5), ceil(hi − 0.5)]; one more
  // each way.
  const glm::ivec3 first = glm::max(glm::ivec3(glm::floor(lo - 0.5f)) - 1, glm::ivec3(0));
  const glm::ivec3 last = glm::min(glm::ivec3(glm::ceil(hi - 0.5f)) + 2, size_);
  return {first, glm::max(last, first)};
}

void ObstacleSet::fill(StepParams& params, uint64_t step) const {
  const double seconds = double(step) * units_.stepSeconds;
  // The cells any obstacle covers now or covered a step ago, grown by two cells for the neighbours.
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  for (size_t i = 0; i < obstacles_.size(); ++i)
    for (uint64_t s : {step, step > 0 ? step - 1 : step}) {
      lo = glm::min(lo, centreAt(i, s) - obstacles_[i].halfExtent);
      hi = glm::max(hi, centreAt(i, s) + obstacles_[i].halfExtent);
    }
  if (obstacles_.empty()) {
    params.solidMin = params.solidMax = glm::ivec4(0);
  } else {
    params.solidMin = glm::ivec4(glm::clamp(glm::ivec3(glm::floor(lo)) - 2, glm::ivec3(0), size_), 0);
    params.solidMax = glm::ivec4(glm::clamp(glm::ivec3(glm::ceil(hi)) + 2, glm::ivec3(0), size_), 0);
  }
  for (size_t i = 0; i < obstacles_.size(); ++i) {
    GpuObstacle g = obstacles_[i].shape;
    if (obstacles_[i].motion) {
      const scene::MotionState state = scene::evaluateMotion(*obstacles_[i].motion, seconds);
      g.centre = glm::vec4(units_.toLattice(state.position, origin_), g.centre.w);
      g.velocity = glm::vec4(units_.toLatticeVelocity(state.velocity), 0.0f);
    }
    params.obstacles[i] = g;
  }
  for (size_t i = 0; i < inlets_.size(); ++i) {
    params.inlets[i] = inlets_[i].inlet;
    if (inlets_[i].scaled) params.inlets[i].velocity *= glm::vec4(glm::vec3(inletStrength_), 1.0f);
    params.inlets[i].smoke.z = (seconds >= inlets_[i].start && seconds < inlets_[i].stop) ? 1.0f : 0.0f;
  }
  params.counts = glm::uvec4(obstacles_.size(), inlets_.size(), uint32_t(step), 0);
}

}  // namespace sixway::sim
