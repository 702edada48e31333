// Rays against the obstacles (src/render/obstacle_bvh.h and shaders/common/obstacle_trace.glsl) against the
// CPU oracles of cpu_obstacles.h: analytic spheres and boxes, the Stanford bunny's OBJ triangles tested one
// by one, moving obstacles at their keyframed positions, shadow casters only; then the GPU traversal
// (shaders/render/obstacle_ray_probe.comp) against the CPU one, ray for ray.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <random>

#include "cpu_obstacles.h"
#include "gpu/buffer.h"
#include "gpu/pipeline.h"
#include "gpu/sequence.h"
#include "render/obstacle_bvh.h"
#include "render/obstacle_meshes.h"
#include "support/gpu_fixture.h"
#include "support/scene_parts.h"

namespace sixway::test {
namespace {

scene::Obstacle boxAt(glm::vec3 centre, glm::vec3 size, bool shadows = true) {
  scene::Obstacle o;
  o.shape = scene::BoxObstacle{centre, size};
  o.shadows = shadows;
  return o;
}

scene::Obstacle bunny() {
  scene::Obstacle o;
  o.shape = scene::MeshObstacle{std::filesystem::path(SIXWAY_ASSETS_DIR) / "meshes/stanford-bunny.obj", 6.0f,
                                glm::vec3(0.05f, -0.35f, 0.1f), glm::vec3(10.0f, 30.0f, -5.0f)};
  return o;
}

glm::vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<float> n;
  return glm::normalize(glm::vec3(n(rng), n(rng), n(rng)));
}

class ObstacleBvhTest : public GpuTest {};

// Rays from all around towards a sphere and a box: the nearest hit is the analytic one (within the sphere's
// tessellation depth), the normal the shape's, and rays that miss the analytic shape by more than that miss.
TEST_F(ObstacleBvhTest, SpheresAndBoxesMatchTheirAnalyticHits) {
  const glm::vec3 centre(0.2f, -0.1f, 0.3f), boxMin(-0.9f, 0.2f, -0.4f), boxMax(-0.5f, 0.8f, 0.0f);
  const float radius = 0.35f;
  const render::ObstacleBvh bvh(context(),
                                {sphereAt(centre, radius), boxAt(0.5f * (boxMin + boxMax), boxMax - boxMin)});
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> spread(-1.2f, 1.2f);
  int hits = 0, misses = 0;
  for (int i = 0; i < 4000; ++i) {
    const glm::vec3 origin = 3.0f * randomUnit(rng);
    const glm::vec3 target(spread(rng), spread(rng), spread(rng));
    const Ray ray{dvec3(origin), glm::normalize(dvec3(target - origin))};
    const auto sphere = hitSphere(ray, dvec3(centre), radius);
    const auto box = hitBox(ray, dvec3(boxMin), dvec3(boxMax));
    const auto found = bvh.nearestHit(origin, glm::vec3(ray.direction), 0.0f, 100.0f);
    // A ray grazing the sphere within the facets' depth may hit or miss the tessellation.
    const auto grazing = hitSphere(ray, dvec3(centre), radius - render::sphereFacetDepth(radius));
    if (sphere.has_value() != grazing.has_value()) continue;
    std::optional<double> expected = sphere;
    int obstacle = 0;
    if (box && (!sphere || *box < *sphere)) expected = box, obstacle = 1;
    ASSERT_EQ(found.has_value(), expected.has_value()) << "ray " << i;
    if (!expected) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_EQ(found->obstacle, uint32_t(obstacle));
    if (obstacle == 0) {  // between the sphere and the sphere its facets' deepest points lie on
      EXPECT_GE(found->t, *expected - 1e-4) << "ray " << i;
      EXPECT_LE(found->t, *grazing + 1e-4) << "ray " << i;
    } else {
      EXPECT_NEAR(found->t, *expected, 1e-4) << "ray " << i;
    }
    const glm::dvec3 p = ray.origin + *expected * ray.direction;
    if (obstacle == 0) {
      EXPECT_GT(glm::dot(glm::dvec3(found->normal), glm::normalize(p - dvec3(centre))), 0.999);
    }
  }
  EXPECT_GT(hits, 400);
  EXPECT_GT(misses, 800);
}

// Camera rays through a 64 × 64 image of the bunny: the hierarchy's nearest hit is the nearest of all the OBJ
// triangles placed as the scene format says (CpuMesh), pixel for pixel.
TEST_F(ObstacleBvhTest, MeshMatchesEveryTriangleTested) {
  const scene::Obstacle mesh = bunny();
  const render::ObstacleBvh bvh(context(), {mesh});
  EXPECT_GT(bvh.triangleCount(), 60000u);
  const render::Camera camera =
      render::Camera::lookAt({0.3f, 0.5f, 3.0f}, {0.0f, 0.1f, 0.0f}, glm::vec3(0, 1, 0), 35.0f);
  const render::ImagePlane plane = render::fullFrame(camera, 64, 64);
  CpuMesh cpu(std::get<scene::MeshObstacle>(mesh.shape));
  cpu.bin(camera, plane, 64, 64, 1);
  int covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Ray ray = pixelRay(camera, plane, x + 0.5, y + 0.5, 64, 64);
      const auto expected = cpu.hitPixel(x + 0.5, y + 0.5);
      const auto found = bvh.nearestHit(glm::vec3(ray.origin), glm::vec3(ray.direction), 0.0f, 100.0f);
      ASSERT_EQ(found.has_value(), expected.has_value()) << x << "," << y;
      if (!expected) continue;
      ++covered;
      EXPECT_NEAR(found->t, *expected, 1e-4) << x << "," << y;
      EXPECT_LT(glm::dot(found->normal, glm::vec3(ray.direction)), 0.5f)
          << "normal faces away at " << x << "," << y;
    }
  EXPECT_GT(covered, 500);
}

// A moving sphere is where its keyframes put it at the frame's time, and obstacles that cast no shadows are
// skipped by shadow rays only.
TEST_F(ObstacleBvhTest, MotionAndCasters) {
  scene::Obstacle moving = sphereAt({0.0f, 0.0f, 0.0f}, 0.2f);
  moving.motion = scene::Motion{{{0.0f, {0.0f, 0.0f, 0.0f}}, {1.0f, {1.0f, 0.0f, 0.0f}}}, false};
  render::ObstacleBvh bvh(context(), {moving, sphereAt({0.0f, 1.0f, 0.0f}, 0.2f, false)});
  bvh.update(0.5);
  const auto atHalf = bvh.nearestHit({0.5f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f);
  ASSERT_TRUE(atHalf);
  EXPECT_NEAR(atHalf->t, 4.8, 1.5 * render::sphereFacetDepth(0.2));
  EXPECT_FALSE(bvh.nearestHit({0.0f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f));
  EXPECT_TRUE(bvh.nearestHit({0.0f, 1.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f));
  EXPECT_FALSE(bvh.nearestHit({0.0f, 1.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f, true));
  EXPECT_FALSE(bvh.nearestHit({0.5f, 0.0f, 5.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 4.7f)) << "tMax";
}

// obstacle_trace.glsl against nearestHit, ray for ray, on the bunny, spheres, a box and a moved obstacle:
// nearest hits (distance, normal, obstacle), and shadow-caster any-hit queries.
TEST_F(ObstacleBvhTest, GpuTraversalMatchesTheCpu) {
  scene::Obstacle moving = sphereAt({0.8f, 0.0f, 0.0f}, 0.25f);
  moving.motion = scene::Motion{{{0.0f, {0.8f, 0.0f, 0.0f}}, {1.0f, {0.8f, 0.6f, 0.0f}}}, false};
  render::ObstacleBvh bvh(context(), {bunny(), moving, boxAt({-0.8f, 0.3f, 0.2f}, {0.3f, 0.5f, 0.2f}, false),
                                      sphereAt({0.0f, -0.8f, 0.4f}, 0.3f)});
  bvh.update(0.7);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> spread(-1.0f, 1.0f);
  constexpr uint32_t kRays = 4096;
  std::vector<glm::vec4> rays;
  for (uint32_t i = 0; i < kRays; ++i) {
    const glm::vec3 origin = 2.5f * randomUnit(rng);
    const glm::vec3 w = glm::normalize(glm::vec3(spread(rng), spread(rng), spread(rng)) - origin);
    rays.push_back(glm::vec4(origin, i % 5 == 0 ? 0.5f : 0.0f));
    rays.push_back(glm::vec4(w, i % 7 == 0 ? 2.0f : 100.0f));
  }
  gpu::Buffer rayBuffer(context(), rays.size() * sizeof(glm::vec4),
                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                        gpu::MemoryKind::Device, "rays");
  rayBuffer.upload(rays);
  gpu::Buffer hitBuffer = gpu::Buffer::storage(context(), rays.size() * sizeof(glm::vec4), "hits");
  gpu::ComputePipelineDesc desc;
  desc.shader = "render/obstacle_ray_probe.comp";
  desc.bindings = std::vector<gpu::BindingType>(5, gpu::BindingType::StorageBuffer);
  desc.pushConstantBytes = 16;
  const gpu::Pipeline pipeline(context(), pipelineCache(), desc);
  for (const bool shadowRays : {false, true}) {
    SCOPED_TRACE(shadowRays ? "casters, any hit" : "nearest hit");
    const struct {
      uint32_t rays, obstacles, castersOnly, anyHit;
    } push{kRays, bvh.obstacleCount(), shadowRays, shadowRays};
    gpu::Sequence sequence(context());
    sequence.dispatch(pipeline,
                      {gpu::reads(bvh.nodes()), gpu::reads(bvh.triangles()), gpu::reads(bvh.placements()),
                       gpu::reads(rayBuffer), gpu::writes(hitBuffer)},
                      push, (kRays + 63) / 64);
    sequence.submit();
    const std::vector<glm::vec4> hits = hitBuffer.download<glm::vec4>();
    int found = 0;
    for (uint32_t i = 0; i < kRays; ++i) {
      const glm::vec4 o = rays[2 * i], w = rays[2 * i + 1];
      const auto expected = bvh.nearestHit(glm::vec3(o), glm::vec3(w), o.w, w.w, shadowRays);
      ASSERT_EQ(hits[2 * i].x >= 0.0f, expected.has_value()) << "ray " << i;
      if (!expected) continue;
      ++found;
      if (shadowRays) continue;  // any hit: which one is the traversal's choice
      EXPECT_NEAR(hits[2 * i].x, expected->t, 1e-4f * expected->t) << "ray " << i;
      EXPECT_EQ(uint32_t(hits[2 * i + 1].w), expected->obstacle) << "ray " << i;
      EXPECT_GT(glm::dot(glm::vec3(hits[2 * i + 1]), expected->normal), 0.9999f) << "ray " << i;
    }
    EXPECT_GT(found, 400);
  }
}

}  // namespace
}  // namespace sixway::test
