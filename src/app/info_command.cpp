#include "app/info_command.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "app/options.h"
#include "gpu/context.h"
#include "io/report.h"
#include "runtime/internal.h"

namespace sixway::app {
namespace {

std::string versionString(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

nlohmann::json describe(const gpu::Context& context) {
  const auto& props = context.properties();
  const auto& limits = context.limits();
  const auto& caps = context.capabilities();
  nlohmann::json devices = nlohmann::json::array();
  for (const std::string& line : gpu::listPhysicalDevices(context.instance())) devices.push_back(line);
  return {
      {"devices", devices},
      {"device", props.deviceName},
      {"type", gpu::deviceTypeName(props.deviceType)},
      {"api_version", versionString(props.apiVersion)},
      {"driver", std::string(context.driver().driverName) + " " + context.driver().driverInfo},
      {"device_memory_bytes", caps.deviceLocalHeapBytes},
      {"max_storage_buffer_range_bytes", limits.maxStorageBufferRange},
      {"max_compute_shared_memory_bytes", limits.maxComputeSharedMemorySize},
      {"max_compute_workgroup_invocations", limits.maxComputeWorkGroupInvocations},
      {"max_compute_workgroup_count",
       {limits.maxComputeWorkGroupCount[0], limits.maxComputeWorkGroupCount[1],
        limits.maxComputeWorkGroupCount[2]}},
      {"max_push_constants_bytes", limits.maxPushConstantsSize},
      {"max_image_dimension_2d", limits.maxImageDimension2D},
      {"max_image_dimension_3d", limits.maxImageDimension3D},
      {"subgroup_size", caps.subgroupSize},
      {"shader_float16", caps.shaderFloat16},
      {"storage_buffer_16bit", caps.storage16Bit},
      {"cooperative_matrix_mnk",
       {caps.cooperativeMatrix.m, caps.cooperativeMatrix.n, caps.cooperativeMatrix.k}},
      {"timestamps", caps.timestamps},
      {"timestamp_period_ns", caps.timestampPeriodNs},
      {"validation", context.validationEnabled()},
  };
}

void printInfo(const nlohmann::json& info) {
  auto yesNo = [](bool b) { return b ? "yes" : "no"; };
  std::printf("Vulkan devices:\n");
  for (const auto& line : info["devices"]) std::printf("  %s\n", line.get<std::string>().c_str());
  std::printf("using: %s (%s)\n", info["device"].get<std::string>().c_str(),
              info["type"].get<std::string>().c_str());
  std::printf("  Vulkan API                 %s\n", info["api_version"].get<std::string>().c_str());
  std::printf("  driver                     %s\n", info["driver"].get<std::string>().c_str());
  std::printf("  device memory              %s\n", gpu::formatBytes(info["device_memory_bytes"]).c_str());
  std::printf("  storage buffer range       %s\n",
              gpu::formatBytes(info["max_storage_buffer_range_bytes"]).c_str());
  std::printf("  compute shared memory      %s\n",
              gpu::formatBytes(info["max_compute_shared_memory_bytes"]).c_str());
  std::printf("  workgroup invocations      %u\n", info["max_compute_workgroup_invocations"].get<unsigned>());
  std::printf("  push constants             %u B\n", info["max_push_constants_bytes"].get<unsigned>());
  std::printf("  image 2D / 3D side         %u / %u\n", info["max_image_dimension_2d"].get<unsigned>(),
              info["max_image_dimension_3d"].get<unsigned>());
  std::printf("  subgroup size              %u\n", info["subgroup_size"].get<unsigned>());
  std::printf("  fp16 arithmetic            %s\n", yesNo(info["shader_float16"]));
  std::printf("  16-bit storage             %s\n", yesNo(info["storage_buffer_16bit"]));
  const auto& matrix = info["cooperative_matrix_mnk"];
  if (matrix[0].get<unsigned>() == 0)
    std::printf("  cooperative matrices       no\n");
  else
    std::printf("  cooperative matrices       %ux%ux%u (M x N x K: fp16 inputs, fp32 sums)\n",
                matrix[0].get<unsigned>(), matrix[1].get<unsigned>(), matrix[2].get<unsigned>());
  std::printf("  timestamps                 %s (%.3g ns per tick)\n", yesNo(info["timestamps"]),
              info["timestamp_period_ns"].get<double>());
  std::printf("  validation layers          %s\n", info["validation"].get<bool>() ? "on" : "off");
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  struct Options {
    CommonOptions common;
    std::filesystem::path report;
    bool force = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* command = app.add_subcommand("info", "The Vulkan device sixway uses and the limits that matter");
  options->common.addTo(*command);
  command->add_option("--report", options->report, "Also write the device description as JSON")
      ->check(filePath());
  command->add_flag("--force", options->force, "Overwrite an existing report");
  command->callback([options] {
    if (!options->report.empty()) io::requireWritableFile(options->report, options->force);
    const Device device(options->common.deviceOptions());
    nlohmann::json info = describe(runtime::Access::context(device));
    printInfo(info);
    if (!options->report.empty()) io::writeReport(options->report, info);
    requireNoValidationMessages(device);
  });
}

}  // namespace sixway::app
