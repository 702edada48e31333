#include "cpu_obstacles.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <numbers>
#include <variant>

#include "io/obj.h"

namespace sixway::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Rotations about the world axes by `deg` degrees (right-handed), as columns.
glm::dmat3 rotationX(double deg) {
  const double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  return glm::dmat3(1, 0, 0, 0, c, s, 0, -s, c);
}
glm::dmat3 rotationY(double deg) {
  const double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  return glm::dmat3(c, 0, -s, 0, 1, 0, s, 0, c);
}
glm::dmat3 rotationZ(double deg) {
  const double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
  return glm::dmat3(c, s, 0, -s, c, 0, 0, 0, 1);
}

// Pixel coordinates of a world point in front of the camera.
glm::dvec2 toPixel(const render::Camera& camera, const render::ImagePlane& plane, int width, int height,
                   dvec3 p) {
  const dvec3 d = p - dvec3(camera.position);
  const double z = glm::dot(d, dvec3(camera.forward));
  const double qx = glm::dot(d, dvec3(camera.right)) / z, qy = glm::dot(d, dvec3(camera.up)) / z;
  return {(qx - plane.min.x) / (plane.max.x - plane.min.x) * width,
          (plane.max.y - qy) / (plane.max.y - plane.min.y) * height};
}

}  // namespace

Ray pixelRay(const render::Camera& camera, const render::ImagePlane& plane, double px, double py, int width,
             int height) {
  const double qx = plane.min.x + (plane.max.x - plane.min.x) * px / width;
  const double qy = plane.max.y - (plane.max.y - plane.min.y) * py / height;
  const dvec3 d = dvec3(camera.forward) + qx * dvec3(camera.right) + qy * dvec3(camera.up);
  return {dvec3(camera.position), glm::normalize(d)};
}

std::optional<double> hitSphere(const Ray& ray, dvec3 centre, double radius) {
  const dvec3 oc = ray.origin - centre;
  const double b = glm::dot(oc, ray.direction), c = glm::dot(oc, oc) - radius * radius;
  const double disc = b * b - c;
  if (disc < 0) return std::nullopt;
  const double root = std::sqrt(disc);
  for (double t : {-b - root, -b + root})
    if (t > 0) return t;
  return std::nullopt;
}

std::optional<double> hitBox(const Ray& ray, dvec3 min, dvec3 max) {
  double lo = 0, hi = 1e300;
  for (int a = 0; a < 3; ++a) {
    const double inv = 1.0 / ray.direction[a];
    double t0 = (min[a] - ray.origin[a]) * inv, t1 = (max[a] - ray.origin[a]) * inv;
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
  }
  if (lo > hi) return std::nullopt;
  return lo;
}

std::optional<double> hitTriangle(const Ray& ray, dvec3 a, dvec3 b, dvec3 c) {
  const dvec3 e1 = b - a, e2 = c - a;
  const dvec3 p = glm::cross(ray.direction, e2);
  const double det = glm::dot(e1, p);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const dvec3 s = ray.origin - a;
  const double u = glm::dot(s, p) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(ray.direction, q) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = glm::dot(e2, q) / det;
  if (t <= 0) return std::nullopt;
  return t;
}

CpuMesh::CpuMesh(const scene::MeshObstacle& mesh) {
  const io::Mesh obj = io::readObj(mesh.file);
  const glm::dmat3 turn =
      rotationZ(mesh.rotateDeg.z) * rotationY(mesh.rotateDeg.y) * rotationX(mesh.rotateDeg.x);
  for (const glm::uvec3& t : obj.triangles)
    for (int k = 0; k < 3; ++k)
      corners_.push_back(dvec3(mesh.translate) + turn * (double(mesh.scale) * dvec3(obj.positions[t[k]])));
}

void CpuMesh::bin(const render::Camera& camera, const render::ImagePlane& plane, int width, int height,
                  int margin) {
  camera_ = camera, plane_ = plane, width_ = width, height_ = height, margin_ = margin;
  const int w = width + 2 * margin, h = height + 2 * margin;
  bins_.assign(size_t(w) * h, {});
  for (size_t t = 0; t < corners_.size() / 3; ++t) {
    glm::dvec2 lo(1e300), hi(-1e300);
    for (int k = 0; k < 3; ++k) {
      const glm::dvec2 p = toPixel(camera, plane, width, height, corners_[3 * t + k]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    // A ray through pixel coordinate (px, py) is binned at floor(px), floor(py): grow by one for rounding.
    const int x0 = std::max(0, int(std::floor(lo.x)) - 1 + margin),
              x1 = std::min(w - 1, int(hi.x) + 1 + margin);
    const int y0 = std::max(0, int(std::floor(lo.y)) - 1 + margin),
              y1 = std::min(h - 1, int(hi.y) + 1 + margin);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) bins_[size_t(y) * w + x].push_back(unsigned(t));
  }
}

std::optional<double> CpuMesh::hitPixel(double px, double py) const {
  const int x = int(std::floor(px)) + margin_, y = int(std::floor(py)) + margin_;
  const int w = width_ + 2 * margin_;
  if (x < 0 || y < 0 || x >= w || y >= height_ + 2 * margin_) return std::nullopt;
  const Ray ray = pixelRay(camera_, plane_, px, py, width_, height_);
  std::optional<double> nearest;
  for (unsigned t : bins_[size_t(y) * w + x])
    if (auto hit = hitTriangle(ray, corners_[3 * t], corners_[3 * t + 1], corners_[3 * t + 2]))
      if (!nearest || *hit < *nearest) nearest = hit;
  return nearest;
}

bool nearSilhouette(const std::function<bool(double, double)>& covered, int x, int y) {
  const double cx = x + 0.5, cy = y + 0.5;
  const bool centre = covered(cx, cy);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if ((dx || dy) && covered(cx + dx, cy + dy) != centre) return true;
  return false;
}

double viewDepthFromDepthBuffer(double d, double near, double far) {
  return near * far / (far - d * (far - near));
}

dvec3 lambert(dvec3 albedo, dvec3 p, dvec3 n, const std::vector<scene::Light>& lights,
              const std::optional<scene::Ambient>& ambient) {
  dvec3 irradiance(0);
  for (const scene::Light& light : lights) {
    dvec3 l;
    double falloff = 1;
    if (const auto* d = std::get_if<scene::DirectionalLight>(&light.source)) {
      l = glm::normalize(dvec3(d->direction));
    } else {
      const dvec3 toLight = dvec3(std::get<scene::PointLight>(light.source).position) - p;
      falloff = 1 / glm::dot(toLight, toLight);
      l = glm::normalize(toLight);
    }
    irradiance += double(light.intensity) * dvec3(light.color) * falloff * std::max(0.0, glm::dot(n, l));
  }
  dvec3 ambientRadiance(0);
  if (ambient) {
    if (const auto* c = std::get_if<scene::AmbientColor>(&*ambient)) {
      ambientRadiance = dvec3(c->color);
    } else {
      const auto& sh = std::get<scene::AmbientSh>(*ambient).coefficients;
      const dvec3 l1 = n.x * dvec3(sh[1]) + n.y * dvec3(sh[2]) + n.z * dvec3(sh[3]);
      ambientRadiance = glm::max(dvec3(0), dvec3(sh[0]) + (2.0 / 3.0) * l1);
    }
  }
  return albedo * (irradiance / kPi + ambientRadiance);
}

dvec3 keyframePosition(const scene::Motion& motion, double seconds) {
  const auto& k = motion.keyframes;
  if (seconds <= k.front().time) return dvec3(k.front().position);
  for (size_t i = 0; i + 1 < k.size(); ++i)
    if (seconds < k[i + 1].time) {
      const double s = (seconds - k[i].time) / (k[i + 1].time - k[i].time);
      return dvec3(k[i].position) + s * (dvec3(k[i + 1].position) - dvec3(k[i].position));
    }
  return dvec3(k.back().position);
}

dvec3 project(const glm::mat4& m, dvec3 p) {
  const glm::dvec4 clip = glm::dmat4(m) * glm::dvec4(p, 1);
  return dvec3(clip) / clip.w;
}

std::pair<dvec3, dvec3> unproject(const glm::mat4& m, double ndcX, double ndcY) {
  const glm::dmat4 inverse = glm::inverse(glm::dmat4(m));
  const glm::dvec4 a = inverse * glm::dvec4(ndcX, ndcY, 0, 1), b = inverse * glm::dvec4(ndcX, ndcY, 1, 1);
  return {dvec3(a) / a.w, dvec3(b) / b.w};
}

}  // namespace sixway::test
