#include "dataset/motion_field.h"

#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "render/gpu_layout.h"

namespace sixway::dataset {
namespace {

struct MotionParams {  // shaders/render/motion_field.comp
  render::layout::CameraRays camera;
  render::layout::VolumeGrid velocity;
  glm::vec4 shell;
  glm::ivec4 image;
};
static_assert(sizeof(MotionParams) == 16 * (5 + 2 + 2));

constexpr uint32_t kGroup = 8;  // the shader's local size in x and y

}  // namespace

MotionField::MotionField(const gpu::Context& context, const gpu::PipelineCache& cache, uint32_t size)
    : size_(size) {
  if (size == 0) throw std::invalid_argument("motion field: size 0");
  params_ = gpu::Buffer(context, sizeof(MotionParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                        gpu::MemoryKind::HostUpload, "motion parameters");
  motion_ = gpu::Buffer::storage(context, uint64_t(size) * size * 2 * sizeof(float), "motion field");
  using gpu::BindingType;
  pass_ = std::make_unique<gpu::Pipeline>(
      context, cache,
      gpu::ComputePipelineDesc{"render/motion_field.comp",
                               {BindingType::StorageBuffer, BindingType::StorageImage,
                                BindingType::StorageBuffer, BindingType::StorageBuffer}});
}

MotionField::~MotionField() = default;

void MotionField::record(gpu::Sequence& sequence, const gpu::Image& guide, const gpu::Buffer& velocity,
                         const render::VolumeGrid& velocityGrid) {
  const gpu::ImageDesc& d = guide.desc();
  if (d.width != size_ || d.height != size_ || d.depth != 1 || d.format != VK_FORMAT_R16G16B16A16_SFLOAT)
    throw std::invalid_argument("motion field: the guide must be RGBA16F, " + std::to_string(size_) +
                                " pixels square");
  if (velocity.size() < velocityGrid.cellCount() * 4 * sizeof(float))
    throw std::invalid_argument("motion field: the velocity buffer is smaller than its grid");
  velocityGrid_ = velocityGrid;
  const uint32_t groups = (size_ + kGroup - 1) / kGroup;
  sequence.beginStage("motion");
  sequence.dispatch(*pass_,
                    {gpu::reads(params_), gpu::reads(guide), gpu::reads(velocity), gpu::writes(motion_)},
                    std::span<const std::byte>(), groups, groups);
  sequence.endStage();
}

void MotionField::update(const render::Camera& camera, const render::ImagePlane& billboard,
                         const render::DepthRange& shellRange, float metresPerVelocityUnit) {
  const MotionParams p{render::layout::cameraRays(camera, billboard),
                       render::layout::volumeGrid(velocityGrid_),
                       glm::vec4(shellRange.near, shellRange.far, metresPerVelocityUnit, 0.0f),
                       glm::ivec4(int(size_), int(size_), 0, 0)};
  params_.upload(std::as_bytes(std::span(&p, 1)));
}

io::Image MotionField::download() const {
  io::Image out(static_cast<int>(size_), static_cast<int>(size_), {"motion_x", "motion_y"});
  out.pixels = motion_.download<float>();
  return out;
}

}  // namespace sixway::dataset
