// The motion field (shaders/render/motion_field.comp) against its CPU oracle (cpu_motion.h) on a synthetic
// velocity buffer and guide, and against the closed form of a flow parallel to the image plane.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "cpu_motion.h"
#include "dataset/motion_field.h"
#include "gpu/sequence.h"
#include "render/billboard.h"
#include "support/gpu_fixture.h"

namespace sixway::test {
namespace {

constexpr int kSize = 24;
const render::VolumeGrid kGrid{{10, 12, 8}, {-0.5f, 0.0f, -0.4f}, 0.1f};

// Shell depths over the pixels (fp16, as the guide stores them), every fifth pixel without a shell.
std::vector<uint16_t> guideTexels() {
  std::vector<uint16_t> texels(size_t(kSize) * kSize * 4, 0);
  for (int i = 0; i < kSize * kSize; ++i) {
    const int x = i % kSize, y = i / kSize;
    const float encoded = i % 5 == 0 ? 1.0f : 0.15f + 0.7f * float(x + 2 * y) / float(3 * kSize);
    texels[size_t(i) * 4 + 2] = glm::packHalf1x16(encoded);
  }
  return texels;
}

std::vector<float> shellDepths(const std::vector<uint16_t>& texels) {
  std::vector<float> depths(size_t(kSize) * kSize);
  for (size_t i = 0; i < depths.size(); ++i) depths[i] = glm::unpackHalf1x16(texels[i * 4 + 2]);
  return depths;
}

class MotionFieldTest : public GpuTest {
 protected:
  // The GPU field for a velocity of `unitsPerCell` (any unit) and `metresPerUnit`.
  std::vector<glm::vec2> gpuField(const std::vector<glm::dvec3>& velocity, float metresPerUnit) {
    std::vector<glm::vec4> cells;
    for (const glm::dvec3& v : velocity) cells.emplace_back(glm::vec3(v), 1.0f);
    gpu::Buffer buffer = gpu::Buffer::storage(context(), cells.size() * sizeof(glm::vec4), "test velocity");
    buffer.upload(cells);
    dataset::MotionField motion(context(), pipelineCache(), kSize);
    gpu::Image guide(context(), {kSize, kSize, 1, VK_FORMAT_R16G16B16A16_SFLOAT,
                                 VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT, "test guide"});
    const std::vector<uint16_t> texels = guideTexels();
    guide.upload(std::as_bytes(std::span(texels)));
    gpu::Sequence sequence(context());
    motion.record(sequence, guide, buffer, kGrid);
    sequence.finish();
    motion.update(camera_, billboard_, range_, metresPerUnit);
    sequence.submit();
    const io::Image image = motion.download();
    std::vector<glm::vec2> field;
    for (size_t i = 0; i < image.pixels.size(); i += 2)
      field.emplace_back(image.pixels[i], image.pixels[i + 1]);
    return field;
  }

  const render::Camera camera_ =
      render::Camera::lookAt({1.4f, 1.3f, 2.1f}, kGrid.bounds().centre(), {0, 1, 0}, 40);
  const render::ImagePlane billboard_ = render::billboardBounds(camera_, kGrid.bounds(), 1.0f);
  const render::DepthRange range_ = render::boxDepthRange(camera_, kGrid.bounds());
};

TEST_F(MotionFieldTest, MatchesTheCpuOracleOnARotatingRisingFlow) {
  // Rotation about the vertical axis through the box centre (2 rad/s) plus a rise of 0.3 m/s, at cell
  // centres.
  CpuVelocityGrid flow{kGrid, {}};
  const glm::dvec3 centre(kGrid.bounds().centre());
  for (int k = 0; k < kGrid.size.z; ++k)
    for (int j = 0; j < kGrid.size.y; ++j)
      for (int i = 0; i < kGrid.size.x; ++i) {
        const glm::dvec3 r =
            glm::dvec3(kGrid.origin) + (glm::dvec3(i, j, k) + 0.5) * double(kGrid.cellSize) - centre;
        flow.velocity.push_back(glm::cross(glm::dvec3(0, 2, 0), r) + glm::dvec3(0, 0.3, 0));
      }
  // The buffer holds cells per step; with 0.01 m per unit over the interval, 1 unit = 0.01 m per interval.
  const double interval = 0.1;
  std::vector<glm::dvec3> units;
  for (const glm::dvec3& v : flow.velocity) units.push_back(v * interval / 0.01);
  const std::vector<glm::vec2> gpu = gpuField(units, 0.01f);
  const std::vector<glm::dvec2> cpu =
      cpuMotionField(camera_, billboard_, range_, shellDepths(guideTexels()), kSize, flow, interval);
  double largest = 0, worst = 0;
  int moving = 0;
  for (size_t i = 0; i < cpu.size(); ++i) {
    const double error = glm::length(glm::dvec2(gpu[i]) - cpu[i]);
    largest = std::max(largest, glm::length(cpu[i]));
    worst = std::max(worst, error);
    moving += glm::length(cpu[i]) > 0.05;
    if (i % 5 == 0) {
      EXPECT_EQ(gpu[i], glm::vec2(0.0f)) << "no shell, no motion: pixel " << i;
    }
    EXPECT_LE(error, 1e-4 + 1e-4 * glm::length(cpu[i])) << "pixel " << i;
  }
  std::printf("rotating flow: largest motion %.3f px, worst GPU error %.2e px, %d moving pixels\n", largest,
              worst, moving);
  EXPECT_GT(largest, 0.5) << "the test flow must move the smoke visibly";
  EXPECT_GT(moving, kSize * kSize / 3) << "shell points outside the grid do not move";
}

TEST_F(MotionFieldTest, FlowAlongTheImagePlaneMovesByDisplacementOverDepth) {
  // A uniform flow along the camera's right axis keeps every point's view depth z, so the image-plane shift
  // is d / z exactly: motion = (d / z · W / billboard width, 0) with d the distance moved.
  const glm::dvec3 right(camera_.right);
  const double metres = 0.04;
  std::vector<glm::dvec3> units(kGrid.cellCount(), right * metres);  // 1 m per unit
  const std::vector<glm::vec2> gpu = gpuField(units, 1.0f);
  const std::vector<float> depths = shellDepths(guideTexels());
  const render::Box box = kGrid.bounds();
  int moved = 0;
  for (int i = 0; i < kSize * kSize; ++i) {
    const double z = range_.near + double(depths[i]) * (range_.far - range_.near);
    const glm::dvec2 q(glm::mix(billboard_.min.x, billboard_.max.x, (i % kSize + 0.5f) / kSize),
                       glm::mix(billboard_.max.y, billboard_.min.y, (i / kSize + 0.5f) / kSize));
    const glm::dvec3 p =
        glm::dvec3(camera_.position) +
        z * (glm::dvec3(camera_.forward) + q.x * glm::dvec3(camera_.right) + q.y * glm::dvec3(camera_.up));
    const bool inside = glm::all(glm::greaterThan(p, glm::dvec3(box.min) + 1e-4)) &&
                        glm::all(glm::lessThan(p, glm::dvec3(box.max) - 1e-4));
    const bool outside = glm::any(glm::lessThan(p, glm::dvec3(box.min) - 1e-4)) ||
                         glm::any(glm::greaterThan(p, glm::dvec3(box.max) + 1e-4));
    // No shell, or a shell point outside the grid (no velocity there): no motion.
    if (depths[i] >= 1.0f || outside) {
      EXPECT_EQ(gpu[i], glm::vec2(0.0f)) << "pixel " << i;
    }
    if (depths[i] >= 1.0f || !inside) continue;
    const double expected = metres / z * kSize / double(billboard_.max.x - billboard_.min.x);
    EXPECT_NEAR(gpu[i].x, expected, 1e-4 * expected + 1e-5) << "pixel " << i;
    EXPECT_NEAR(gpu[i].y, 0.0, 1e-4) << "pixel " << i;
    ++moved;
  }
  EXPECT_GT(moved, kSize * kSize / 4) << "most shell points lie in the grid";
}

}  // namespace
}  // namespace sixway::test
