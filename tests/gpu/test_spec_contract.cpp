// The specialization-constant contract of each shader family: every constant that a shader of the family
// declares has the id its C++ header gives the name (src/<area>/*_spec.h), one type across the family, and
// every id of the header is declared by a shader of the family. Families are the folders below shaders/.
#include <gtest/gtest.h>

#include <sixway/shader_registry.h>
#include <algorithm>
#include <map>
#include <ostream>
#include <set>
#include <span>
#include <string>
#include <string_view>

#include "app/demo/demo_spec.h"
#include "gpu/gpu_spec.h"
#include "gpu/spirv_reflect.h"
#include "nn/nn_spec.h"
#include "render/render_spec.h"
#include "sim/sim_spec.h"

namespace sixway::test {
namespace {

using gpu::SpecId;

struct Family {
  std::string_view name;
  std::string_view folder;  // below shaders/
  std::span<const SpecId> ids;
};

void PrintTo(const Family& family, std::ostream* os) {
  *os << family.name;
}

const Family kFamilies[] = {{"Sim", "sim/", sim::spec::kAll},
                            {"Network", "nn/", nn::spec::kAll},
                            {"Render", "render/", render::spec::kAll},
                            {"Host", "gpu/", gpu::spec::kAll},
                            {"Demo", "demo/", app::demo::spec::kAll}};

// The header's entry for a constant of a shader: by name, or for a workgroup size (which GLSL leaves unnamed)
// by id among the entries named local_size_*.
const SpecId* hostEntry(std::span<const SpecId> ids, uint32_t id, const std::string& name) {
  const auto entry = std::find_if(ids.begin(), ids.end(), [&](const SpecId& host) {
    return name.empty() ? host.id == id && host.name.starts_with("local_size_") : host.name == name;
  });
  return entry == ids.end() ? nullptr : &*entry;
}

void expectContract(const Family& family) {
  std::map<std::string_view, gpu::SpecType> typeOf;  // by the header's name, across the family
  std::set<std::string_view> declared;
  int shaderCount = 0;
  for (std::string_view shader : shaders::names()) {
    if (!shader.starts_with(family.folder)) continue;
    ++shaderCount;
    for (const auto& [id, constant] : gpu::reflectSpecConstants(shaders::spirv(shader))) {
      const SpecId* host = hostEntry(family.ids, id, constant.name);
      if (!host) {
        ADD_FAILURE() << shader << " declares specialization constant " << id << " " << constant.name
                      << ", which the family's C++ header does not";
        continue;
      }
      EXPECT_EQ(host->id, id) << shader << ": " << constant.name << " has id " << id << ", the header says "
                              << host->id;
      const auto [type, first] = typeOf.emplace(host->name, constant.type);
      EXPECT_EQ(gpu::specTypeName(type->second), gpu::specTypeName(constant.type))
          << shader << ": " << host->name << " has another type than in the family's other shaders";
      declared.insert(host->name);
    }
  }
  EXPECT_GT(shaderCount, 0) << "no shader in " << family.folder;
  for (const SpecId& host : family.ids)
    EXPECT_TRUE(declared.contains(host.name))
        << host.name << " (" << host.id << ") is declared by no shader in " << family.folder;
}

class SpecContract : public ::testing::TestWithParam<Family> {};

TEST_P(SpecContract, HeaderAndShadersAgree) {
  expectContract(GetParam());
}

INSTANTIATE_TEST_SUITE_P(Families, SpecContract, ::testing::ValuesIn(kFamilies),
                         [](const ::testing::TestParamInfo<Family>& info) {
                           return std::string(info.param.name);
                         });

TEST(SpecFamilies, EveryShaderWithConstantsBelongsToOne) {
  for (std::string_view shader : shaders::names()) {
    const bool inFamily = std::any_of(std::begin(kFamilies), std::end(kFamilies), [&](const Family& family) {
      return shader.starts_with(family.folder);
    });
    if (!inFamily) {
      EXPECT_TRUE(gpu::reflectSpecConstants(shaders::spirv(shader)).empty()) << shader;
    }
  }
}

}  // namespace
}  // namespace sixway::test
