/* The C API (C99) over include/sixway/'s C++ classes, for engines and languages that take C: opaque handles,
 * a result code from every call that can fail and the one-line message of the last failure on the calling
 * thread; nothing is thrown across it. The contracts are those of the C++ headers named at each call
 * (docs/embedding.md, "The C API"). Destroy renderers before their simulation and both before their device.
 */
#ifndef SIXWAY_SIXWAY_H
#define SIXWAY_SIXWAY_H

#include <stddef.h>
#include <stdint.h>
#include <vulkan/vulkan.h>

#include "sixway/version.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct SixwayDevice_T* SixwayDevice;
typedef struct SixwaySimulation_T* SixwaySimulation;
typedef struct SixwayRenderer_T* SixwayRenderer;

typedef enum SixwayResult {
  SIXWAY_SUCCESS = 0,
  SIXWAY_ERROR = 1,                  /* sixway::Error: bad input, a device limit, Vulkan, the watchdog */
  SIXWAY_ERROR_INVALID_ARGUMENT = 2, /* misuse: a null handle, a size of 0, a value out of range */
  SIXWAY_ERROR_OUT_OF_MEMORY = 3,    /* host memory */
  SIXWAY_ERROR_UNEXPECTED = 4        /* anything else (a bug: please report the message) */
} SixwayResult;

/* The message of the last call that failed on this thread ("" if none), valid until the next failure on it.
 */
const char* sixwayLastError(void);
/* The library's version (SIXWAY_VERSION_* are the headers'). */
void sixwayVersion(uint32_t* major, uint32_t* minor, uint32_t* patch);

/* sixway::Device: its own headless device (validate: the Khronos validation layer), or an engine's. */
SixwayResult sixwayCreateOwnDevice(int validate, SixwayDevice* device);
/* sixway::MemoryBlock: `memory` at `offset`, `mapped` when asked for, `token` the engine's own. */
typedef struct SixwayMemoryBlock {
  VkDeviceMemory memory;
  VkDeviceSize offset;
  void* mapped;
  uint64_t token;
} SixwayMemoryBlock;
typedef struct SixwayEngineDevice {
  VkInstance instance;
  VkPhysicalDevice physicalDevice;
  VkDevice device;
  VkQueue queue;
  uint32_t queueFamily;
  const char* const* enabledExtensions; /* as given to vkCreateDevice */
  uint32_t enabledExtensionCount;
  const void* enabledFeatures; /* the VkPhysicalDeviceFeatures2 chain given to vkCreateDevice */
  uint32_t framesInFlight;     /* 1..8 */
  /* Optional (NULL: sixway submits to `queue` and waits itself): where one-time work goes (EngineDevice::
   * submitAndWait). The engine calls record(recordContext, commands) on a recording primary command buffer
   * of its own, then submits it and waits for it. */
  void (*submitAndWait)(void* user, void (*record)(void* recordContext, VkCommandBuffer commands),
                        void* recordContext);
  void* submitUser;
  /* Optional (EngineDevice's): host memory callbacks for sixway's Vulkan objects; the engine's pipeline
   * cache (no cache file then); where notes go, one line each with `logUser` (NULL: stderr). */
  const VkAllocationCallbacks* allocator;
  VkPipelineCache pipelineCache;
  void (*log)(void* user, const char* line);
  void* logUser;
  /* Optional, both or neither (EngineDevice::memory): the engine's device-memory sub-allocator. */
  SixwayMemoryBlock (*allocateMemory)(void* user, const VkMemoryRequirements* requirements, uint32_t type,
                                      int map);
  void (*freeMemory)(void* user, const SixwayMemoryBlock* block);
  void* memoryUser;
  /* Optional (EngineDevice's): the engine's vkGetInstanceProcAddr, for every Vulkan function sixway calls. */
  PFN_vkGetInstanceProcAddr getInstanceProcAddr;
} SixwayEngineDevice;
SixwayResult sixwayCreateEngineDevice(const SixwayEngineDevice* engine, SixwayDevice* device);
/* Device::hostWaits: how often sixway waited on the GPU itself. */
SixwayResult sixwayDeviceHostWaits(SixwayDevice device, uint64_t* waits);
void sixwayDestroyDevice(SixwayDevice device);

/* sixway::SmokeSimulation of a scene file. */
SixwayResult sixwayCreateSimulation(SixwayDevice device, const char* scenePath, SixwaySimulation* simulation);
/* SmokeSimulation(device, SceneText): the scene's JSON text, `length` bytes; meshes relative to `directory`
 * (NULL: the working directory). */
SixwayResult sixwayCreateSimulationFromText(SixwayDevice device, const char* json, size_t length,
                                            const char* directory, SixwaySimulation* simulation);
/* SmokeSimulation(device, SmokeDomain): a domain without a scene file; sixwaySmokeDomainDefaults fills one.
 */
typedef struct SixwaySmokeDomain {
  int32_t cells[3];
  float cellSize, origin[3], frameSeconds, viscosity, buoyancy, extinction, albedo, phaseG, dissipation;
  int32_t lightmapSize;
} SixwaySmokeDomain;
void sixwaySmokeDomainDefaults(SixwaySmokeDomain* domain);
SixwayResult sixwayCreateSimulationFromDomain(SixwayDevice device, const SixwaySmokeDomain* domain,
                                              SixwaySimulation* simulation);
SixwayResult sixwaySimulationAdvance(SixwaySimulation simulation);
SixwayResult sixwaySimulationRecord(SixwaySimulation simulation, VkCommandBuffer commands, uint64_t frame);
/* SmokeSimulation::record for `seconds` of frame time; `steps` (may be NULL) receives the lattice steps
 * recorded. */
SixwayResult sixwaySimulationRecordSeconds(SixwaySimulation simulation, VkCommandBuffer commands,
                                           uint64_t frame, double seconds, uint32_t* steps);
/* SmokeSimulation::setPlacement; column-major, 16 floats. */
SixwayResult sixwaySimulationSetPlacement(SixwaySimulation simulation, const float worldFromScene[16]);
/* SmokeSimulation::obstacleCount and obstaclePosition (3 floats, world). */
SixwayResult sixwaySimulationObstacleCount(SixwaySimulation simulation, uint32_t* count);
SixwayResult sixwaySimulationObstaclePosition(SixwaySimulation simulation, uint32_t obstacle,
                                              float position[3]);
/* SmokeSimulation::steerObstacle(obstacle, target, seconds); `target`: 3 floats, world. */
SixwayResult sixwaySimulationSteerObstacle(SixwaySimulation simulation, uint32_t obstacle,
                                           const float target[3], double seconds);
/* SmokeSimulation::setEmitters: `count` emitters (0: none; `emitters` may then be NULL). */
typedef struct SixwayEmitter {
  float position[3]; /* world, m */
  float radius;      /* m */
  float velocity[3]; /* world, m/s */
  float densityRate, temperatureRate;
  int on;
} SixwayEmitter;
SixwayResult sixwaySimulationSetEmitters(SixwaySimulation simulation, const SixwayEmitter* emitters,
                                         uint32_t count);
/* SmokeSimulation::setObstacles: `count` obstacles (0: none; `obstacles` may then be NULL). */
typedef enum SixwayObstacleShape {
  SIXWAY_OBSTACLE_SPHERE = 0,
  SIXWAY_OBSTACLE_BOX = 1,
  SIXWAY_OBSTACLE_CAPSULE = 2,
  SIXWAY_OBSTACLE_MESH = 3
} SixwayObstacleShape;
typedef struct SixwayObstacle {
  SixwayObstacleShape shape;
  float position[3]; /* world, m: the centre */
  float radius;      /* sphere, capsule */
  float size[3];     /* box: full edge lengths along the smoke's axes */
  float height;      /* capsule: end to end */
  float axis[3];     /* capsule: world direction */
  int shadows;
  /* mesh: `vertexCount` xyz triples, `indexCount` indices (three per triangle), turned by `rotation`
   * (column-major 3x3, world; all zeros: none) and scaled by `scale`; read during the call. */
  const float* vertices;
  uint32_t vertexCount;
  const uint32_t* indices;
  uint32_t indexCount;
  float rotation[9];
  float scale;
} SixwayObstacle;
SixwayResult sixwaySimulationSetObstacles(SixwaySimulation simulation, const SixwayObstacle* obstacles,
                                          uint32_t count, double seconds);
void sixwayDestroySimulation(SixwaySimulation simulation);

/* sixway::SmokeRenderer with the network of `weightsPath`, into its own image (target NULL) or an engine's.
 */
typedef struct SixwayRenderTarget {
  VkImage colorImage;
  VkImageView colorView;
  VkFormat colorFormat;
  VkImage depthImage;
  VkImageView depthView;
  VkFormat depthFormat;
  uint32_t width, height;
} SixwayRenderTarget;
SixwayResult sixwayCreateRenderer(SixwayDevice device, SixwaySimulation simulation, const char* weightsPath,
                                  const SixwayRenderTarget* target, SixwayRenderer* renderer);
/* SmokeRenderer::setViewProjection; both matrices column-major, 16 floats (glm's and GLSL's layout). */
SixwayResult sixwayRendererSetViewProjection(SixwayRenderer renderer, const float view[16],
                                             const float projection[16]);
/* SmokeRenderer::setLights (sixway::Light; `kind` 0 directional, 1 point). */
typedef struct SixwayLight {
  int kind;
  float direction[3];
  float position[3];
  float color[3];
  float intensity;
  int shadows;
} SixwayLight;
SixwayResult sixwayRendererSetLights(SixwayRenderer renderer, const SixwayLight* lights, uint32_t count);
SixwayResult sixwayRendererRecord(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame);
/* A renderer whose targets come with each record (SmokeRenderer's VkFormat constructor and
 * record(commands, frame, FrameTargets)): the images, the layouts they are in and are to be left in, their
 * size and the camera's viewport (a zero extent: the whole image). */
typedef struct SixwayTargetImage {
  VkImage image;
  VkImageView view;
  VkFormat format;
  VkImageLayout layout, finalLayout;
} SixwayTargetImage;
typedef struct SixwayFrameTargets {
  SixwayTargetImage color, depth;
  uint32_t width, height;
  VkRect2D viewport;
} SixwayFrameTargets;
SixwayResult sixwayCreateRendererForFormat(SixwayDevice device, SixwaySimulation simulation,
                                           const char* weightsPath, VkFormat colorFormat,
                                           SixwayRenderer* renderer);
/* A renderer for the engine's images or rendering (RendererOptions' network fields and the constructors): the
 * network from `weightsPath`, or the weights file's `weightsSize` (> 0) bytes at `weightsData`, or
 * `shareNetwork`'s; into the engine's images of `colorFormat`
 * (sixwayRendererRecordTargets), or, with `renderingColorCount` > 0, inside the engine's rendering of these
 * formats (sixwayRendererRecordLightmaps, then sixwayRendererRecordComposite). */
typedef struct SixwayRendererInfo {
  const char* weightsPath;
  const void* weightsData;
  size_t weightsSize;
  SixwayRenderer shareNetwork;
  VkFormat colorFormat;
  const VkFormat* renderingColors;
  uint32_t renderingColorCount;
  VkFormat renderingDepth, renderingStencil;
  int lightmapPacking; /* LightmapPacking of sixwayRendererLightmaps: 0 Unity, 1 RLT/BBF, 2 O3DE */
} SixwayRendererInfo;
SixwayResult sixwayCreateRendererFromInfo(SixwayDevice device, SixwaySimulation simulation,
                                          const SixwayRendererInfo* info, SixwayRenderer* renderer);
/* SmokeRenderer::recordLightmaps and recordComposite (CompositeTargets). */
typedef struct SixwayCompositeTargets {
  VkImage depth;
  VkImageView depthView;
  VkFormat depthFormat;
  VkImageLayout depthLayout;
  uint32_t width, height;
  VkRect2D viewport;
} SixwayCompositeTargets;
SixwayResult sixwayRendererRecordLightmaps(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame,
                                           const SixwayCompositeTargets* targets);
SixwayResult sixwayRendererRecordComposite(SixwayRenderer renderer, VkCommandBuffer commands);
SixwayResult sixwayRendererRecordTargets(SixwayRenderer renderer, VkCommandBuffer commands, uint64_t frame,
                                         const SixwayFrameTargets* targets);
/* Own image: renders and waits; then copies its width × height RGBA floats (linear, premultiplied, row 0 at
 * the top) into `pixels`, which holds `count` floats. */
SixwayResult sixwayRendererRender(SixwayRenderer renderer);
SixwayResult sixwayRendererSize(SixwayRenderer renderer, uint32_t* width, uint32_t* height);
SixwayResult sixwayRendererImage(SixwayRenderer renderer, float* pixels, size_t count);
/* SmokeRenderer::lightmaps (LightmapTextures): corners bottom-left, bottom-right, top-right, top-left. */
typedef struct SixwayLightmapTextures {
  VkImage a, b;
  VkImageView viewA, viewB;
  VkFormat format;
  uint32_t width, height;
  float corners[4][3];
} SixwayLightmapTextures;
SixwayResult sixwayRendererLightmaps(SixwayRenderer renderer, SixwayLightmapTextures* lightmaps);
/* SmokeRenderer::forgetTargets. */
SixwayResult sixwayRendererForgetTargets(SixwayRenderer renderer);
void sixwayDestroyRenderer(SixwayRenderer renderer);

#ifdef __cplusplus
}
#endif

#endif
