#include "cpu_shading.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <glm/geometric.hpp>

namespace sixway::test {
namespace {

using glm::dvec3;
constexpr double kPi = std::numbers::pi;

// Keys' cubic convolution kernel with a = −1/2 (Catmull-Rom), at distance x in texels.
double cubicKernel(double x) {
  constexpr double a = -0.5;
  x = std::abs(x);
  if (x <= 1.0) return (a + 2.0) * x * x * x - (a + 3.0) * x * x + 1.0;
  if (x < 2.0) return a * x * x * x - 5.0 * a * x * x + 8.0 * a * x - 4.0 * a;
  return 0.0;
}

// Texture lookup through the Catmull-Rom cubic with clamp-to-edge addressing at normalised coordinates (u,
// v): the sum over the 4 × 4 texels around the point of the image times the kernel at each one's distance.
std::array<double, 4> catmullRom(const io::Image& image, double u, double v) {
  const double x = u * image.width - 0.5, y = v * image.height - 0.5;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  std::array<double, 4> out{};
  for (int yj = y0 - 1; yj <= y0 + 2; ++yj)
    for (int xi = x0 - 1; xi <= x0 + 2; ++xi) {
      const double w = cubicKernel(x - xi) * cubicKernel(y - yj);
      const int cx = std::clamp(xi, 0, image.width - 1), cy = std::clamp(yj, 0, image.height - 1);
      for (int c = 0; c < 4; ++c) out[c] += w * image.at(cx, cy, c);
    }
  return out;
}

double unitClamp(double x) {
  return std::clamp(x, 0.0, 1.0);
}

// Unity's "Lightmap Remap" on a straight value.
double remap(double value, const render::RemapRange& r) {
  const double unit = unitClamp((value - r.inMin) / (r.inMax - r.inMin));
  return std::max(0.0, r.outMin + unit * (r.outMax - r.outMin));
}

// What transmission t (our units: 1 = white Lambertian under irradiance π) becomes under the controls.
dvec3 response(double t, double alpha, const render::ShadingControls& c) {
  if (!c.absorption) return t * dvec3(c.color);
  // docs/conventions.md, "Shading", in Unity's units (ours / π), range scaled by alpha for premultiplied
  // lightmaps.
  const double range = (1.0 - 1.0 / kPi) * c.absorptionStrength + 1.0 / kPi;
  const double r = range * (alpha > 0.0 ? alpha : 1.0);
  const double tUnity = t / kPi;
  dvec3 out;
  for (int k = 0; k < 3; ++k) {
    const double s = 1.0 + std::log2(std::max(1e-5, double(c.color[k]))) / std::log2(0.2);
    out[k] = kPi * std::pow(unitClamp(tUnity / r), s) * r;
  }
  return out;
}

dvec3 gradient(const std::vector<render::GradientKey>& given, double x) {
  std::vector<render::GradientKey> keys = given;
  if (keys.empty()) keys.push_back({1.0f, glm::vec3(1.0f)});
  x = std::max(x, 0.0);
  // Keys with an implicit black key at 0; past the last key the colour is proportional to x.
  double p0 = 0.0;
  dvec3 c0(0.0);
  for (const render::GradientKey& key : keys) {
    if (x <= key.position) return c0 + (dvec3(key.color) - c0) * ((x - p0) / (key.position - p0));
    p0 = key.position;
    c0 = dvec3(key.color);
  }
  return c0 * (x / p0);
}

// One cell of a shadow tile along an axis, the edge cells reaching to infinity (clamp to edge).
double cellOverlap(int i, int size, double lo, double hi) {
  const double a = i == 0 ? -std::numeric_limits<double>::infinity() : double(i);
  const double b = i == size - 1 ? std::numeric_limits<double>::infinity() : double(i + 1);
  return std::max(0.0, std::min(b, hi) - std::max(a, lo));
}

}  // namespace

double cpuShadowVisibility(const io::Image& atlas, int tileSize, int tile, const glm::mat4& shadowMatrix,
                           const dvec3& world, double radius, double bias) {
  const glm::dvec4 clip = glm::dmat4(shadowMatrix) * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0) return 1.0;
  const dvec3 ndc = dvec3(clip) / clip.w;
  if (std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0 || ndc.z < 0.0 || ndc.z > 1.0) return 1.0;
  const double px = (0.5 + 0.5 * ndc.x) * tileSize, py = (0.5 - 0.5 * ndc.y) * tileSize;
  const double depth = ndc.z - bias;
  auto lit = [&](int ix, int iy) { return depth <= atlas.at(ix, tile * tileSize + iy, 0) ? 1.0 : 0.0; };
  if (radius <= 0.0)
    return lit(std::clamp(int(std::floor(px)), 0, tileSize - 1),
               std::clamp(int(std::floor(py)), 0, tileSize - 1));
  double sum = 0.0;
  for (int iy = 0; iy < tileSize; ++iy) {
    const double oy = cellOverlap(iy, tileSize, py - radius, py + radius);
    if (oy == 0.0) continue;
    for (int ix = 0; ix < tileSize; ++ix) {
      const double ox = cellOverlap(ix, tileSize, px - radius, px + radius);
      if (ox > 0.0) sum += ox * oy * lit(ix, iy);
    }
  }
  return sum / (4.0 * radius * radius);
}

double cpuWideShadowVisibility(const io::Image& atlas, int tileSize, int tile, const glm::mat4& shadowMatrix,
                               const dvec3& world, double halfWidth, double radius, double bias) {
  const glm::dmat4 m(shadowMatrix);
  const glm::dvec4 clip = m * glm::dvec4(world, 1.0);
  if (clip.w <= 0.0) return 1.0;
  const dvec3 ndc = dvec3(clip) / clip.w;
  if (std::abs(ndc.x) > 1.0 || std::abs(ndc.y) > 1.0 || ndc.z < 0.0 || ndc.z > 1.0) return 1.0;
  // Texels per metre across the beam: d(ndc.x)/d(world) = the x row over w, half a tile per unit of ndc.
  const double spread = halfWidth * 0.5 * tileSize * glm::length(dvec3(m[0][0], m[1][0], m[2][0])) / clip.w;
  if (spread <= radius) return cpuShadowVisibility(atlas, tileSize, tile, shadowMatrix, world, radius, bias);
  const double px = (0.5 + 0.5 * ndc.x) * tileSize, py = (0.5 - 0.5 * ndc.y) * tileSize;
  const double depth = ndc.z - bias;
  double lit = 0.0;
  for (double oy : {-0.75, -0.25, 0.25, 0.75})
    for (double ox : {-0.75, -0.25, 0.25, 0.75}) {
      const int ix = std::clamp(int(std::floor(px + ox * spread)), 0, tileSize - 1);
      const int iy = std::clamp(int(std::floor(py + oy * spread)), 0, tileSize - 1);
      lit += depth <= atlas.at(ix, tile * tileSize + iy, 0) ? 1.0 : 0.0;
    }
  return lit / 16.0;
}

namespace {

struct PixelPoint {
  glm::dvec2 q;   // image plane at distance 1
  glm::dvec2 uv;  // on the billboard
  bool covered;
};

PixelPoint pixelPoint(const CpuShadingInputs& in, int width, int height, int x, int y) {
  const render::ImagePlane& f = in.frame;
  const render::ImagePlane& b = in.billboard;
  PixelPoint p;
  p.q = {f.min.x + (x + 0.5) / width * (f.max.x - f.min.x),
         f.max.y - (y + 0.5) / height * (f.max.y - f.min.y)};
  p.uv = {(p.q.x - b.min.x) / (b.max.x - b.min.x), (b.max.y - p.q.y) / (b.max.y - b.min.y)};
  p.covered = p.uv.x > 0.0 && p.uv.x < 1.0 && p.uv.y > 0.0 && p.uv.y < 1.0;
  return p;
}

// View depth of the shaded point: the shell where the guide has one, else the billboard's depth, interpolated
// over the guide's texels as the shader does.
double shadedDepth(const CpuShadingInputs& in, glm::dvec2 uv) {
  const double billboardDepth = 0.5 * (double(in.shellRange.near) + in.shellRange.far);
  if (!in.guide) return billboardDepth;
  return cpuShadedViewDepth(*in.guide, uv, in.shellRange.near, in.shellRange.far, billboardDepth);
}

dvec3 worldPoint(const render::Camera& c, glm::dvec2 q, double depth) {
  return dvec3(c.position) + depth * (dvec3(c.forward) + q.x * dvec3(c.right) + q.y * dvec3(c.up));
}

}  // namespace

double cpuShadedViewDepth(const io::Image& guide, glm::dvec2 uv, double near, double far, double planeDepth) {
  const glm::dvec2 g = uv * glm::dvec2(guide.width, guide.height) - 0.5;
  const int x0 = int(std::floor(g.x)), y0 = int(std::floor(g.y));
  const glm::dvec2 t = g - glm::dvec2(x0, y0);
  double depth = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int cx = k & 1, cy = k >> 1;
    const double encoded =
        guide.at(std::clamp(x0 + cx, 0, guide.width - 1), std::clamp(y0 + cy, 0, guide.height - 1), 2);
    const double w = (cx ? t.x : 1.0 - t.x) * (cy ? t.y : 1.0 - t.y);
    depth += w * (encoded < 1.0 ? near + encoded * (far - near) : planeDepth);
  }
  return depth;
}

std::array<double, 3> cpuShadowDepths(const io::Image& levels, glm::dvec2 uv, double near, double far,
                                      double planeDepth) {
  const glm::dvec2 g = uv * glm::dvec2(levels.width, levels.height) - 0.5;
  const int x0 = int(std::floor(g.x)), y0 = int(std::floor(g.y));
  const glm::dvec2 t = g - glm::dvec2(x0, y0);
  std::array<double, 3> depths{};
  for (int k = 0; k < 4; ++k) {
    const int cx = k & 1, cy = k >> 1;
    const int tx = std::clamp(x0 + cx, 0, levels.width - 1), ty = std::clamp(y0 + cy, 0, levels.height - 1);
    const double w = (cx ? t.x : 1.0 - t.x) * (cy ? t.y : 1.0 - t.y);
    double last = planeDepth;
    for (int i = 0; i < 3; ++i) {
      const double encoded = levels.at(tx, ty, i);
      if (encoded < 1.0) last = near + encoded * (far - near);
      depths[i] += w * last;
    }
  }
  return depths;
}

namespace {

// The knots (depth, opacity) of the opacity curve; empty without smoke.
std::vector<std::pair<double, double>> opacityKnots(const std::array<double, 4>& levels, double total,
                                                    double thinDepth) {
  constexpr double kLevels[4] = {0.1, 0.35, 0.6, 0.85};
  if (total <= 0.0) return {};
  int reached = 0;
  while (reached < 4 && levels[reached] >= 0.0) ++reached;
  if (reached == 0) return {{thinDepth, 0.0}, {thinDepth, total}};
  std::vector<std::pair<double, double>> knots;
  knots.push_back({reached >= 2 ? levels[0] - 0.4 * (levels[1] - levels[0]) : levels[0], 0.0});
  for (int k = 0; k < reached; ++k) knots.push_back({levels[k], kLevels[k]});
  const int last = reached - 1;
  const double slope =
      reached >= 2 ? (levels[last] - levels[last - 1]) / (kLevels[last] - kLevels[last - 1]) : 0.0;
  const double rest = std::max(total - kLevels[last], 0.0);
  knots.push_back({levels[last] + rest * slope, kLevels[last] + rest});
  return knots;
}

// The curve at d: 0 before the first knot, linear between knots, the last knot's opacity after it.
double curveAt(const std::vector<std::pair<double, double>>& knots, double d) {
  if (knots.empty() || d <= knots.front().first) return 0.0;
  for (size_t i = 1; i < knots.size(); ++i)
    if (d <= knots[i].first) {
      const auto [d0, o0] = knots[i - 1];
      const auto [d1, o1] = knots[i];
      return d1 > d0 ? o0 + (o1 - o0) * (d - d0) / (d1 - d0) : o1;
    }
  return knots.back().second;
}

}  // namespace

double cpuOpacityInFront(const std::array<double, 4>& levels, double total, double d, double thinDepth,
                         double w) {
  const auto knots = opacityKnots(levels, total, thinDepth);
  if (knots.empty() || d + w <= knots.front().first) return 0.0;
  if (d - w >= knots.back().first) return knots.back().second;  // also for d = ∞ (no obstacle)
  // The mean over [d − w, d + w]: the curve is linear between consecutive breakpoints (the interval's ends
  // and the knots inside), so each piece's mean is its value at the piece's midpoint.
  std::vector<double> breaks = {d - w, d + w};
  for (const auto& knot : knots)
    if (knot.first > d - w && knot.first < d + w) breaks.push_back(knot.first);
  std::sort(breaks.begin(), breaks.end());
  double area = 0.0;
  for (size_t i = 1; i < breaks.size(); ++i)
    area += (breaks[i] - breaks[i - 1]) * curveAt(knots, 0.5 * (breaks[i - 1] + breaks[i]));
  return area / (2.0 * w);
}

namespace {

// The share of the smoke's opacity in front of view depth `obstacle` at `uv`: bilinear over the four nearest
// texels of each one's own share (opacity in front / its total; 1 where it has no smoke).
double visibleShare(const CpuShadingInputs& in, glm::dvec2 uv, double obstacle, double halfWidth) {
  const io::Image& levels = *in.opacityDepths;
  const double near = in.shellRange.near, far = in.shellRange.far, plane = 0.5 * (near + far);
  const glm::dvec2 g = uv * glm::dvec2(levels.width, levels.height) - 0.5;
  const int x0 = int(std::floor(g.x)), y0 = int(std::floor(g.y));
  const glm::dvec2 t = g - glm::dvec2(x0, y0);
  double share = 0.0;
  for (int k = 0; k < 4; ++k) {
    const int cx = k & 1, cy = k >> 1;
    const int tx = std::clamp(x0 + cx, 0, levels.width - 1), ty = std::clamp(y0 + cy, 0, levels.height - 1);
    std::array<double, 4> depths;
    for (int i = 0; i < 4; ++i) {
      const double encoded = levels.at(tx, ty, i);
      depths[i] = encoded < 1.0 ? near + encoded * (far - near) : -1.0;
    }
    const double fine = in.guide->at(tx, ty, 3);
    const double total = fine > 0.0 ? fine : in.guide->at(tx, ty, 1);
    const double own =
        total > 0.0 ? std::min(cpuOpacityInFront(depths, total, obstacle, plane, halfWidth) / total, 1.0)
                    : 1.0;
    share += (cx ? t.x : 1.0 - t.x) * (cy ? t.y : 1.0 - t.y) * own;
  }
  return share;
}

}  // namespace

glm::dvec3 cpuShadedPoint(const CpuShadingInputs& in, int width, int height, int x, int y) {
  const PixelPoint p = pixelPoint(in, width, height, x, y);
  return worldPoint(in.camera, p.q, shadedDepth(in, p.uv));
}

io::Image cpuSixWayShading(const CpuShadingInputs& in, const io::Image& background) {
  const int width = background.width, height = background.height;
  const render::ShadingControls& controls = in.controls;
  const render::Camera& cam = in.camera;
  const dvec3 axes[3] = {dvec3(cam.right), dvec3(cam.up), dvec3(cam.forward)};

  // Ambient radiance L(w) = L0 + L1·w; L1 along the six-way axes.
  dvec3 l0(0.0), l1[3] = {dvec3(0.0), dvec3(0.0), dvec3(0.0)};
  if (in.ambient) {
    if (const auto* constant = std::get_if<scene::AmbientColor>(&*in.ambient)) {
      l0 = dvec3(constant->color);
    } else {
      const auto& sh = std::get<scene::AmbientSh>(*in.ambient).coefficients;
      l0 = dvec3(sh[0]);
      for (int i = 0; i < 3; ++i)
        for (int w = 0; w < 3; ++w) l1[i] += dvec3(sh[1 + w]) * axes[i][w];
    }
  }

  io::Image out = background;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const PixelPoint p = pixelPoint(in, width, height, x, y);
      if (!p.covered) continue;
      double depth = shadedDepth(in, p.uv);
      double obstacle = std::numeric_limits<double>::infinity();
      if (in.obstacleDepth) {
        const double d = in.obstacleDepth->at(x, y, 0), n = in.sceneRange.near, f = in.sceneRange.far;
        obstacle = n * f / (f - d * (f - n));
      }
      // The share of the smoke drawn, and the depths where its lights' shadows are looked up.
      double visible = obstacle >= depth ? 1.0 : 0.0;
      std::array<double, 3> shadowDepths = {depth, depth, depth};
      // A lightmap texel's width per unit of view depth: the filter width of the composite and the shadows.
      const double texelPerDepth = (in.billboard.max.x - in.billboard.min.x) / in.lightmapA->width;
      if (in.opacityDepths) {
        visible = visibleShare(in, p.uv, obstacle, texelPerDepth * std::min(obstacle, 1e6));
        shadowDepths = cpuShadowDepths(*in.opacityDepths, p.uv, in.shellRange.near, in.shellRange.far,
                                       0.5 * (double(in.shellRange.near) + in.shellRange.far));
      }
      if (visible <= 0.0) continue;  // hidden: nothing drawn over the background
      depth = std::min(depth, obstacle);
      const dvec3 world = worldPoint(cam, p.q, depth);

      // The cubic's overshoot clamped as the shader does: light and emission ≥ 0, alpha in [0, 1].
      auto a = catmullRom(*in.lightmapA, p.uv.x, p.uv.y), b = catmullRom(*in.lightmapB, p.uv.x, p.uv.y);
      for (int c = 0; c < 4; ++c) {
        a[c] = c == 3 ? unitClamp(a[c]) : std::max(a[c], 0.0);
        b[c] = std::max(b[c], 0.0);
      }
      double positive[3] = {a[0], a[1], a[2]}, negative[3] = {b[0], b[1], b[2]};
      double alpha = a[3], emissive = b[3];
      if (controls.lightmapRemap && alpha > 0.0)
        for (int i = 0; i < 3; ++i) {
          positive[i] = alpha * remap(positive[i] / alpha, *controls.lightmapRemap);
          negative[i] = alpha * remap(negative[i] / alpha, *controls.lightmapRemap);
        }
      if (controls.alphaRemap) {
        const double remapped = unitClamp(remap(alpha, *controls.alphaRemap));
        const double scale = alpha > 0.0 ? remapped / alpha : 0.0;
        for (int i = 0; i < 3; ++i) {
          positive[i] *= scale;
          negative[i] *= scale;
        }
        emissive *= scale;
        alpha = remapped;
      }

      dvec3 radiance(0.0);
      for (const render::ShadingLight& light : in.lights) {
        dvec3 toLight = dvec3(light.vector);
        dvec3 irradiance = dvec3(light.radiance);
        if (light.type == render::ShadingLight::Type::Point) {
          toLight -= world;
          const double r2 = glm::dot(toLight, toLight);
          irradiance /= r2;
          toLight /= std::sqrt(r2);
        }
        double visibility = 1.0;
        if (light.shadowTile >= 0 && in.shadowAtlas) {
          visibility = 0.0;
          for (double shadowDepth : shadowDepths) {
            const double z = std::min(shadowDepth, obstacle);
            visibility += cpuWideShadowVisibility(*in.shadowAtlas, in.tileSize, light.shadowTile,
                                                  light.shadowMatrix, worldPoint(cam, p.q, z),
                                                  texelPerDepth * z, in.pcfRadius, in.depthBias) /
                          3.0;
          }
        }
        double t = 0.0;
        for (int i = 0; i < 3; ++i) {
          const double d = glm::dot(toLight, axes[i]);
          t += d * d * (d >= 0.0 ? positive[i] : negative[i]);
        }
        radiance += visibility * irradiance / kPi * response(t, alpha, controls);
      }
      dvec3 ambient(0.0);
      for (int i = 0; i < 3; ++i)
        ambient += response(positive[i], alpha, controls) * (l0 + l1[i]) +
                   response(negative[i], alpha, controls) * (l0 - l1[i]);
      radiance += (2.0 / 3.0) * ambient;
      if (controls.emissiveStraightScale) {
        const double s = *controls.emissiveStraightScale;
        if (alpha > 0.0)
          radiance += double(controls.emissiveMultiplier) * alpha * s *
                      gradient(controls.emissiveGradient, emissive / (alpha * s));
      } else {
        radiance += double(controls.emissiveMultiplier) * gradient(controls.emissiveGradient, emissive);
      }

      for (int c = 0; c < 4; ++c) {
        const double source = visible * (c < 3 ? radiance[c] : alpha);
        out.at(x, y, c) = float(source + (1.0 - visible * alpha) * background.at(x, y, c));
      }
    }
  return out;
}

}  // namespace sixway::test
