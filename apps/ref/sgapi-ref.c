/* sgapi-ref - renders scene files with Vulkan on Mesa's lavapipe (llvmpipe), headless, as the
 * reference that sgapi's images are checked against.
 *
 *   sgapi-ref [--frames N] [--scene NAME]... [--threads T] [--shaders LIB.so]... SCENE.json...
 *             -o DIR
 *
 * Same scene loader, same conventions as sgapi-render (see docs/reference.md): OpenGL clip space
 * mapped to Vulkan's in the vertex shader, texture rows uploaded bottom first so t = 0 is the
 * bottom row, RGBA8 unorm colour, D32 float depth, no mipmaps; alpha blending is pipeline state,
 * the draw colour a uniform the vertex shader multiplies by, back-to-front sorting done on the CPU;
 * lit draws evaluate sgapi's lighting equation in GLSL per vertex (Gouraud), per pixel (Phong) or
 * per triangle in a geometry shader (flat), with the lights in the same per-draw uniform block;
 * a scene's shadow is a depth-only pass into a D32 map before the scene's pass, the bias written by
 * the fragment shader, and the receivers' test done in GLSL with texelFetch; a mesh's lines are a
 * line list drawn after its triangles, and wireframes polygon mode LINE, both rasterised as
 * Bresenham lines (VK_EXT_line_rasterization).
 * A shader draw runs its shader's GLSL twin (sgapi/sgapi_shaders.h), compiled once per run with
 * glslang's library: the twin's main is renamed and wrapped by one that maps its OpenGL clip
 * position to Vulkan's as the fixed stages do; the matrices are pushed transposed (GLSL's
 * column-major mat4), the uniforms are a storage buffer and the textures an array of 8 samplers.
 * Writes DIR/<scene>.png and prints the time per frame (submit to fence, median of N). --threads
 * sets LP_NUM_THREADS.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <glslang/Include/glslang_c_interface.h>
#include <glslang/Public/resource_limits_c.h>
#include <vulkan/vulkan.h>

#include "cli.h"
#include "depth_sort.h"
#include "image_io.h"
#include "scene.h"
#include "sgapi/sgapi_util.h"
#include "scene_keys.h"
#include "shader_lib.h"
#include "shadow.h"
#include "spv_color_frag.h"
#include "spv_color_shadow_frag.h"
#include "spv_color_shadow_vert.h"
#include "spv_color_vert.h"
#include "spv_depth_frag.h"
#include "spv_depth_vert.h"
#include "spv_resolve_comp.h"
#include "spv_flat_geom.h"
#include "spv_lit_flat_frag.h"
#include "spv_lit_flat_texture_frag.h"
#include "spv_lit_flat_vert.h"
#include "spv_lit_gouraud_frag.h"
#include "spv_lit_gouraud_texture_frag.h"
#include "spv_lit_gouraud_vert.h"
#include "spv_lit_phong_frag.h"
#include "spv_flat_shadow_geom.h"
#include "spv_lit_flat_shadow_frag.h"
#include "spv_lit_flat_shadow_texture_frag.h"
#include "spv_lit_gouraud_shadow_frag.h"
#include "spv_lit_gouraud_shadow_texture_frag.h"
#include "spv_lit_gouraud_shadow_vert.h"
#include "spv_lit_phong_shadow_frag.h"
#include "spv_lit_phong_shadow_texture_frag.h"
#include "spv_lit_phong_texture_frag.h"
#include "spv_lit_phong_vert.h"
#include "spv_texture_frag.h"
#include "spv_texture_shadow_frag.h"
#include "spv_texture_shadow_vert.h"
#include "spv_texture_vert.h"

#define MAX_PIPELINES 512

/* The shader modules. Lit stages are indexed by mode: SC_LIGHTING_FLAT - 1, GOURAUD - 1,
 * PHONG - 1; lit fragment stages by mode * 2 + textured. The _SHADOW ones are those of draws that
 * receive the scene's shadow; SH_DEPTH_* draw the casters into its map. */
enum {
    SH_COLOR_VERT,
    SH_COLOR_FRAG,
    SH_TEXTURE_VERT,
    SH_TEXTURE_FRAG,
    SH_LIT_VERT,                   /* 3 modes */
    SH_LIT_FRAG = SH_LIT_VERT + 3, /* 3 modes x (untextured, textured) */
    SH_FLAT_GEOM = SH_LIT_FRAG + 6,
    SH_COLOR_SHADOW_VERT,
    SH_COLOR_SHADOW_FRAG,
    SH_TEXTURE_SHADOW_VERT,
    SH_TEXTURE_SHADOW_FRAG,
    SH_PHONG_SHADOW_FRAG, /* untextured, textured */
    /* Flat and Gouraud receivers: the Gouraud vertex stage, the flat geometry stage, and the
     * fragment stages by (mode - 1) * 2 + textured. */
    SH_GOURAUD_SHADOW_VERT = SH_PHONG_SHADOW_FRAG + 2,
    SH_FLAT_SHADOW_GEOM,
    SH_SPLIT_SHADOW_FRAG,
    SH_DEPTH_VERT = SH_SPLIT_SHADOW_FRAG + 4,
    SH_DEPTH_FRAG,
    SH_RESOLVE_COMP, /* a 4-sample colour image averaged into the readback buffer */
    SH_COUNT
};

/* What a pipeline draws: a draw of the scene's pass, one of them that receives the scene's
 * shadow, or a caster into the shadow map. */
typedef enum draw_kind { DRAW_PLAIN, DRAW_RECEIVER, DRAW_CASTER } draw_kind;

/* The per-draw uniform block of the shaders, std140 (apps/ref/shaders/draw.glsl): the draw
 * colour, which every shader reads, then what lit shaders read, then the scene's shadow. */
typedef struct draw_block {
    float color[4];
    float ambient[4];  /* rgb */
    float specular[4]; /* rgb, shininess */
    float nm[3][4];    /* rows of the normal matrix */
    int32_t light_count, pad[3];
    struct {
        float vec[4]; /* directional: L, w = 0; point: position, w = 1 */
        float color[4];
        float attenuation[4];
    } lights[SC_MAX_LIGHTS];
    float shadow_matrix[16]; /* row-major: view space -> the light's clip space */
    float shadow[4];         /* the map's size, bias, slope bias */
    int32_t shadow_flags[4]; /* the shadowed light, PCF */
} draw_block;
_Static_assert(sizeof(draw_block) == 592, "draw_block must match the std140 block of the shaders");

typedef struct buffer {
    VkBuffer buffer;
    VkDeviceMemory memory;
    void *mapped;
} buffer;

typedef struct texture {
    VkImage image;
    VkDeviceMemory memory;
    VkImageView view;
} texture;

typedef struct pipeline_entry {
    uint32_t key;
    int twin;    /* index into ref.twins, or -1: the fixed stages */
    int samples; /* of the pass it draws in */
    VkPipeline pipeline;
} pipeline_entry;

/* A shader's GLSL twin, compiled: once per run, whatever the number of draws using it. */
typedef struct twin {
    const sgShaderInfo *info;
    VkShaderModule vert, frag;
} twin;

/* The bindings of a twin (docs/api.md, "Shaders"): the draw's uniforms, its textures. */
#define TWIN_TEXTURES 8
_Static_assert(TWIN_TEXTURES == SG_MAX_DRAW_TEXTURES, "twins bind sgapi's number of textures");

typedef struct ref {
    VkInstance instance;
    VkPhysicalDevice phys;
    VkDevice device;
    VkQueue queue;
    uint32_t queue_family;
    VkPhysicalDeviceMemoryProperties mem;
    VkCommandPool cmd_pool;
    VkCommandBuffer cmd;
    VkFence fence;
    VkShaderModule modules[SH_COUNT];
    bool has_geometry;  /* geometryShader: needed by flat lighting */
    bool has_lines;     /* VK_EXT_line_rasterization's bresenhamLines: needed by lines */
    bool has_wireframe; /* fillModeNonSolid: needed by polygon mode line */
    VkDescriptorSetLayout color_layout;   /* set 0: the draws' uniform blocks, dynamic offset */
    VkDescriptorSetLayout texture_layout; /* set 1: the texture and its sampler */
    VkDescriptorSetLayout shadow_layout;  /* set 2: the shadow map, a sampled image */
    VkPipelineLayout layout_color, layout_texture;
    VkPipelineLayout layout_shadow; /* sets 0, 1 and 2: a receiver, textured or not */
    VkDeviceSize draw_stride;       /* bytes between draws in a scene's uniform buffer */
    VkSampler samplers[12]; /* [mipmap none, nearest, linear][filter bilinear?][wrap clamp?] */
    VkRenderPass render_pass;
    /* The same with 4 samples a pixel: multisampled colour and depth, the colour resolved into
     * a one-sample image at the pass's end. */
    VkRenderPass render_pass_ms;
    int samples;                              /* the scene being rendered: 1 or 4 */
    VkDescriptorSetLayout resolve_set_layout; /* the 4-sample colour, the readback buffer */
    VkPipelineLayout layout_resolve;
    VkPipeline resolve;
    VkRenderPass depth_pass; /* the shadow map's: depth only, left ready for sampling */
    pipeline_entry pipelines[MAX_PIPELINES];
    int pipeline_count;
    /* Shader draws. */
    const sc_shaders *shaders; /* the registry the draws' names are looked up in */
    bool glslang_ready;        /* glslang_initialize_process done */
    twin *twins;               /* compiled twins, twin_count of them */
    int twin_count;
    VkDescriptorSetLayout twin_set_layout; /* set 0: uniforms (storage), textures[8] */
    VkPipelineLayout layout_twin;
    VkDeviceSize storage_align; /* minStorageBufferOffsetAlignment */
    texture blank;              /* 1 x 1 (0, 0, 0, 1): what an unbound texture slot samples */
    sc_msg err;                 /* the last failure */
} ref;

/* Records a failure; the arguments may name the last one (r->err.text). Returns false. */
static bool fail(ref *r, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);
static bool fail(ref *r, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vset(&r->err, fmt, ap);
    va_end(ap);
    return false;
}

#define VK_CHECK(r, call)                                                                          \
    do {                                                                                           \
        VkResult vr_ = (call);                                                                     \
        if (vr_ != VK_SUCCESS) return fail(r, "%s failed (VkResult %d)", #call, (int)vr_);         \
    } while (0)

static bool find_memory(ref *r, uint32_t bits, VkMemoryPropertyFlags want, uint32_t *out) {
    for (uint32_t i = 0; i < r->mem.memoryTypeCount; i++)
        if ((bits & (1u << i)) && (r->mem.memoryTypes[i].propertyFlags & want) == want) {
            *out = i;
            return true;
        }
    return fail(r, "no Vulkan memory type with flags 0x%x", (unsigned)want);
}

static bool create_instance(ref *r) {
    VkApplicationInfo app = {.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO,
                             .pApplicationName = "sgapi-ref",
                             .apiVersion = VK_API_VERSION_1_1};
    VkInstanceCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO,
                                .pApplicationInfo = &app};
    VkResult vr = vkCreateInstance(&ici, NULL, &r->instance);
    if (vr != VK_SUCCESS)
        return fail(r,
                    "cannot create a Vulkan instance (VkResult %d): is the Vulkan loader "
                    "(libvulkan1) and Mesa's lavapipe (mesa-vulkan-drivers) installed?",
                    (int)vr);
    uint32_t n = 0;
    vkEnumeratePhysicalDevices(r->instance, &n, NULL);
    VkPhysicalDevice devs[16];
    if (n > 16) n = 16;
    vkEnumeratePhysicalDevices(r->instance, &n, devs);
    for (uint32_t i = 0; i < n; i++) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(devs[i], &p);
        /* The reference is lavapipe only: a GPU or another software driver would be another
         * reference with other rounding. */
        if (p.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU && strstr(p.deviceName, "llvmpipe")) {
            r->phys = devs[i];
            return true;
        }
    }
    return fail(r,
                "no llvmpipe (lavapipe) Vulkan device among %u device(s): install Debian's "
                "mesa-vulkan-drivers",
                n);
}

static bool create_device(ref *r) {
    vkGetPhysicalDeviceMemoryProperties(r->phys, &r->mem);
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(r->phys, &props);
    /* One block per draw, each at an offset the device accepts for a dynamic uniform buffer. */
    VkDeviceSize align = props.limits.minUniformBufferOffsetAlignment, size = sizeof(draw_block);
    r->draw_stride = align > 1 ? (size + align - 1) / align * align : size;
    r->storage_align = props.limits.minStorageBufferOffsetAlignment;
    if (r->storage_align < 4) r->storage_align = 4;
    /* sgapi's lines follow the diamond-exit rule: Bresenham lines, an extension's feature. */
    bool line_ext = false;
    uint32_t next = 0;
    vkEnumerateDeviceExtensionProperties(r->phys, NULL, &next, NULL);
    VkExtensionProperties *exts = calloc(next ? next : 1, sizeof *exts);
    if (!exts) return fail(r, "out of memory");
    vkEnumerateDeviceExtensionProperties(r->phys, NULL, &next, exts);
    for (uint32_t i = 0; i < next; i++)
        line_ext |= strcmp(exts[i].extensionName, VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME) == 0;
    free(exts);
    VkPhysicalDeviceLineRasterizationFeaturesEXT lines_have = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT};
    VkPhysicalDeviceFeatures2 have = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                      .pNext = line_ext ? &lines_have : NULL};
    vkGetPhysicalDeviceFeatures2(r->phys, &have);
    /* Flat lighting runs in a geometry shader, wireframes need fillModeNonSolid, lines the
     * extension; without one, only the draws that need it fail. */
    r->has_geometry = have.features.geometryShader == VK_TRUE;
    r->has_wireframe = have.features.fillModeNonSolid == VK_TRUE;
    r->has_lines = line_ext && lines_have.bresenhamLines == VK_TRUE;
    VkPhysicalDeviceLineRasterizationFeaturesEXT lines_want = {
        .sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_LINE_RASTERIZATION_FEATURES_EXT,
        .bresenhamLines = r->has_lines ? VK_TRUE : VK_FALSE};
    VkPhysicalDeviceFeatures2 want = {.sType = VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2,
                                      .pNext = r->has_lines ? &lines_want : NULL};
    want.features.geometryShader = have.features.geometryShader;
    want.features.fillModeNonSolid = have.features.fillModeNonSolid;
    const char *line_ext_name = VK_EXT_LINE_RASTERIZATION_EXTENSION_NAME;
    uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(r->phys, &n, NULL);
    VkQueueFamilyProperties qf[16];
    if (n > 16) n = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(r->phys, &n, qf);
    r->queue_family = UINT32_MAX;
    for (uint32_t i = 0; i < n; i++)
        if (qf[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
            r->queue_family = i;
            break;
        }
    if (r->queue_family == UINT32_MAX) return fail(r, "lavapipe has no graphics queue");
    float prio = 1.0f;
    VkDeviceQueueCreateInfo qci = {.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO,
                                   .queueFamilyIndex = r->queue_family,
                                   .queueCount = 1,
                                   .pQueuePriorities = &prio};
    VkDeviceCreateInfo dci = {.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO,
                              .pNext = &want,
                              .queueCreateInfoCount = 1,
                              .pQueueCreateInfos = &qci,
                              .enabledExtensionCount = r->has_lines ? 1 : 0,
                              .ppEnabledExtensionNames = &line_ext_name};
    VK_CHECK(r, vkCreateDevice(r->phys, &dci, NULL, &r->device));
    vkGetDeviceQueue(r->device, r->queue_family, 0, &r->queue);
    VkCommandPoolCreateInfo cpi = {.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO,
                                   .flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT,
                                   .queueFamilyIndex = r->queue_family};
    VK_CHECK(r, vkCreateCommandPool(r->device, &cpi, NULL, &r->cmd_pool));
    VkCommandBufferAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO,
                                       .commandPool = r->cmd_pool,
                                       .level = VK_COMMAND_BUFFER_LEVEL_PRIMARY,
                                       .commandBufferCount = 1};
    VK_CHECK(r, vkAllocateCommandBuffers(r->device, &cai, &r->cmd));
    VkFenceCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(r, vkCreateFence(r->device, &fci, NULL, &r->fence));
    return true;
}

static bool create_shaders_and_layouts(ref *r) {
    static const struct {
        const uint32_t *code;
        size_t size;
    } spv[SH_COUNT] = {
        [SH_COLOR_VERT] = {spv_color_vert, sizeof spv_color_vert},
        [SH_RESOLVE_COMP] = {spv_resolve_comp, sizeof spv_resolve_comp},
        [SH_COLOR_FRAG] = {spv_color_frag, sizeof spv_color_frag},
        [SH_TEXTURE_VERT] = {spv_texture_vert, sizeof spv_texture_vert},
        [SH_TEXTURE_FRAG] = {spv_texture_frag, sizeof spv_texture_frag},
        [SH_LIT_VERT + 0] = {spv_lit_flat_vert, sizeof spv_lit_flat_vert},
        [SH_LIT_VERT + 1] = {spv_lit_gouraud_vert, sizeof spv_lit_gouraud_vert},
        [SH_LIT_VERT + 2] = {spv_lit_phong_vert, sizeof spv_lit_phong_vert},
        [SH_LIT_FRAG + 0] = {spv_lit_flat_frag, sizeof spv_lit_flat_frag},
        [SH_LIT_FRAG + 1] = {spv_lit_flat_texture_frag, sizeof spv_lit_flat_texture_frag},
        [SH_LIT_FRAG + 2] = {spv_lit_gouraud_frag, sizeof spv_lit_gouraud_frag},
        [SH_LIT_FRAG + 3] = {spv_lit_gouraud_texture_frag, sizeof spv_lit_gouraud_texture_frag},
        [SH_LIT_FRAG + 4] = {spv_lit_phong_frag, sizeof spv_lit_phong_frag},
        [SH_LIT_FRAG + 5] = {spv_lit_phong_texture_frag, sizeof spv_lit_phong_texture_frag},
        [SH_FLAT_GEOM] = {spv_flat_geom, sizeof spv_flat_geom},
        [SH_COLOR_SHADOW_VERT] = {spv_color_shadow_vert, sizeof spv_color_shadow_vert},
        [SH_COLOR_SHADOW_FRAG] = {spv_color_shadow_frag, sizeof spv_color_shadow_frag},
        [SH_TEXTURE_SHADOW_VERT] = {spv_texture_shadow_vert, sizeof spv_texture_shadow_vert},
        [SH_TEXTURE_SHADOW_FRAG] = {spv_texture_shadow_frag, sizeof spv_texture_shadow_frag},
        [SH_PHONG_SHADOW_FRAG + 0] = {spv_lit_phong_shadow_frag, sizeof spv_lit_phong_shadow_frag},
        [SH_PHONG_SHADOW_FRAG + 1] = {spv_lit_phong_shadow_texture_frag,
                                      sizeof spv_lit_phong_shadow_texture_frag},
        [SH_GOURAUD_SHADOW_VERT] = {spv_lit_gouraud_shadow_vert,
                                    sizeof spv_lit_gouraud_shadow_vert},
        [SH_FLAT_SHADOW_GEOM] = {spv_flat_shadow_geom, sizeof spv_flat_shadow_geom},
        [SH_SPLIT_SHADOW_FRAG + 0] = {spv_lit_flat_shadow_frag, sizeof spv_lit_flat_shadow_frag},
        [SH_SPLIT_SHADOW_FRAG + 1] = {spv_lit_flat_shadow_texture_frag,
                                      sizeof spv_lit_flat_shadow_texture_frag},
        [SH_SPLIT_SHADOW_FRAG + 2] = {spv_lit_gouraud_shadow_frag,
                                      sizeof spv_lit_gouraud_shadow_frag},
        [SH_SPLIT_SHADOW_FRAG + 3] = {spv_lit_gouraud_shadow_texture_frag,
                                      sizeof spv_lit_gouraud_shadow_texture_frag},
        [SH_DEPTH_VERT] = {spv_depth_vert, sizeof spv_depth_vert},
        [SH_DEPTH_FRAG] = {spv_depth_frag, sizeof spv_depth_frag},
    };
    for (int i = 0; i < SH_COUNT; i++) {
        /* A module with the Geometry capability needs the feature enabled. */
        if ((i == SH_FLAT_GEOM || i == SH_FLAT_SHADOW_GEOM) && !r->has_geometry) continue;
        VkShaderModuleCreateInfo smi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                        .codeSize = spv[i].size,
                                        .pCode = spv[i].code};
        VK_CHECK(r, vkCreateShaderModule(r->device, &smi, NULL, &r->modules[i]));
    }
    /* The draw block is read by every stage of a lit pipeline. */
    VkShaderStageFlags draw_stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT |
                                     (r->has_geometry ? VK_SHADER_STAGE_GEOMETRY_BIT : 0);
    VkDescriptorSetLayoutBinding cb = {.binding = 0,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
                                       .descriptorCount = 1,
                                       .stageFlags = draw_stages};
    VkDescriptorSetLayoutCreateInfo dli = {.sType =
                                               VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 1,
                                           .pBindings = &cb};
    VK_CHECK(r, vkCreateDescriptorSetLayout(r->device, &dli, NULL, &r->color_layout));
    VkDescriptorSetLayoutBinding tb = {.binding = 0,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                       .descriptorCount = 1,
                                       .stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT};
    dli.pBindings = &tb;
    VK_CHECK(r, vkCreateDescriptorSetLayout(r->device, &dli, NULL, &r->texture_layout));
    /* The shadow map is read with texelFetch: an image without a sampler. */
    VkDescriptorSetLayoutBinding sb = {.binding = 0,
                                       .descriptorType = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
                                       .descriptorCount = 1,
                                       .stageFlags = VK_SHADER_STAGE_FRAGMENT_BIT};
    dli.pBindings = &sb;
    VK_CHECK(r, vkCreateDescriptorSetLayout(r->device, &dli, NULL, &r->shadow_layout));
    /* 128 bytes, the two matrices: the least every Vulkan device offers, and lavapipe's limit. */
    VkPushConstantRange pcr = {.stageFlags = VK_SHADER_STAGE_VERTEX_BIT, .size = 128};
    VkDescriptorSetLayout sets[3] = {r->color_layout, r->texture_layout, r->shadow_layout};
    VkPipelineLayoutCreateInfo pli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                      .setLayoutCount = 1,
                                      .pSetLayouts = sets,
                                      .pushConstantRangeCount = 1,
                                      .pPushConstantRanges = &pcr};
    VK_CHECK(r, vkCreatePipelineLayout(r->device, &pli, NULL, &r->layout_color));
    pli.setLayoutCount = 2;
    VK_CHECK(r, vkCreatePipelineLayout(r->device, &pli, NULL, &r->layout_texture));
    /* An untextured receiver leaves set 1 unbound: its shaders do not use it. */
    pli.setLayoutCount = 3;
    VK_CHECK(r, vkCreatePipelineLayout(r->device, &pli, NULL, &r->layout_shadow));
    /* Twins: one set, the draw's uniforms and its textures, and the matrices pushed; either stage
     * may read any of them. */
    VkShaderStageFlags twin_stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
    VkDescriptorSetLayoutBinding twb[2] = {
        {.binding = 0,
         .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
         .descriptorCount = 1,
         .stageFlags = twin_stages},
        {.binding = 1,
         .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
         .descriptorCount = TWIN_TEXTURES,
         .stageFlags = twin_stages}};
    dli.bindingCount = 2;
    dli.pBindings = twb;
    VK_CHECK(r, vkCreateDescriptorSetLayout(r->device, &dli, NULL, &r->twin_set_layout));
    VkPushConstantRange twin_pcr = {.stageFlags = twin_stages, .size = 128};
    pli.setLayoutCount = 1;
    pli.pSetLayouts = &r->twin_set_layout;
    pli.pPushConstantRanges = &twin_pcr;
    VK_CHECK(r, vkCreatePipelineLayout(r->device, &pli, NULL, &r->layout_twin));
    for (int m = 0; m < 3; m++)
        for (int f = 0; f < 2; f++)
            for (int w = 0; w < 2; w++) {
                VkSamplerAddressMode am =
                    w ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE : VK_SAMPLER_ADDRESS_MODE_REPEAT;
                VkFilter filter = f ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
                /* Without mipmaps maxLod 0: level 0 whatever the minification. With them no
                 * clamp but the view's levels (sgapi's rule; it also keeps lavapipe on the LOD
                 * code docs/accuracy.md describes, which a maxLod below its limit leaves). */
                VkSamplerCreateInfo sci = {
                    .sType = VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO,
                    .magFilter = filter,
                    .minFilter = filter,
                    .mipmapMode = m == SC_MIPMAP_LINEAR ? VK_SAMPLER_MIPMAP_MODE_LINEAR
                                                        : VK_SAMPLER_MIPMAP_MODE_NEAREST,
                    .addressModeU = am,
                    .addressModeV = am,
                    .addressModeW = am,
                    .maxLod = m == SC_MIPMAP_NONE ? 0.0f : VK_LOD_CLAMP_NONE};
                VK_CHECK(r,
                         vkCreateSampler(r->device, &sci, NULL, &r->samplers[m * 4 + f * 2 + w]));
            }
    VkAttachmentDescription att[2] = {
        {.format = VK_FORMAT_R8G8B8A8_UNORM,
         .samples = VK_SAMPLE_COUNT_1_BIT,
         .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
         .storeOp = VK_ATTACHMENT_STORE_OP_STORE,
         .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
         .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
         .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
         .finalLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL},
        {.format = VK_FORMAT_D32_SFLOAT,
         .samples = VK_SAMPLE_COUNT_1_BIT,
         .loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR,
         .storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
         .stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE,
         .stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE,
         .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED,
         .finalLayout = VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL}};
    VkAttachmentReference cref = {0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkAttachmentReference dref = {1, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                                .colorAttachmentCount = 1,
                                .pColorAttachments = &cref,
                                .pDepthStencilAttachment = &dref};
    VkRenderPassCreateInfo rpi = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                  .attachmentCount = 2,
                                  .pAttachments = att,
                                  .subpassCount = 1,
                                  .pSubpasses = &sub};
    VK_CHECK(r, vkCreateRenderPass(r->device, &rpi, NULL, &r->render_pass));

    /* 4 samples a pixel: the colour is stored and left for the resolve's compute pass to read
     * (create_resolve). */
    VkAttachmentDescription att_ms[2] = {att[0], att[1]};
    att_ms[0].samples = att_ms[1].samples = VK_SAMPLE_COUNT_4_BIT;
    att_ms[0].finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkSubpassDependency to_resolve = {.srcSubpass = 0,
                                      .dstSubpass = VK_SUBPASS_EXTERNAL,
                                      .srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
                                      .dstStageMask = VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                      .srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
                                      .dstAccessMask = VK_ACCESS_SHADER_READ_BIT};
    VkRenderPassCreateInfo rpi_ms = rpi;
    rpi_ms.pAttachments = att_ms;
    rpi_ms.dependencyCount = 1;
    rpi_ms.pDependencies = &to_resolve;
    VK_CHECK(r, vkCreateRenderPass(r->device, &rpi_ms, NULL, &r->render_pass_ms));

    /* The resolve: the 4-sample colour (with any sampler: texelFetch) into the readback buffer. */
    VkDescriptorSetLayoutBinding rb[2] = {
        {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL},
        {1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, VK_SHADER_STAGE_COMPUTE_BIT, NULL}};
    VkDescriptorSetLayoutCreateInfo rli = {.sType =
                                               VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO,
                                           .bindingCount = 2,
                                           .pBindings = rb};
    VK_CHECK(r, vkCreateDescriptorSetLayout(r->device, &rli, NULL, &r->resolve_set_layout));
    VkPushConstantRange rpc = {VK_SHADER_STAGE_COMPUTE_BIT, 0, 8};
    VkPipelineLayoutCreateInfo rpli = {.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO,
                                       .setLayoutCount = 1,
                                       .pSetLayouts = &r->resolve_set_layout,
                                       .pushConstantRangeCount = 1,
                                       .pPushConstantRanges = &rpc};
    VK_CHECK(r, vkCreatePipelineLayout(r->device, &rpli, NULL, &r->layout_resolve));
    VkComputePipelineCreateInfo cpi = {
        .sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO,
        .stage = {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
                  .stage = VK_SHADER_STAGE_COMPUTE_BIT,
                  .module = r->modules[SH_RESOLVE_COMP],
                  .pName = "main"},
        .layout = r->layout_resolve};
    VK_CHECK(r, vkCreateComputePipelines(r->device, VK_NULL_HANDLE, 1, &cpi, NULL, &r->resolve));

    /* The shadow map's pass: cleared to 1.0, stored, and left in the layout the scene's pass
     * samples it in, its depth writes made visible to those reads. */
    VkAttachmentDescription map = att[1];
    map.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    map.finalLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    VkAttachmentReference mref = {0, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription dsub = {.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                                 .pDepthStencilAttachment = &mref};
    VkSubpassDependency deps[2] = {
        /* The previous frame's reads of the map come before this frame's clear. */
        {.srcSubpass = VK_SUBPASS_EXTERNAL,
         .dstSubpass = 0,
         .srcStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
         .dstStageMask =
             VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
         .srcAccessMask = 0,
         .dstAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                          VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT},
        {.srcSubpass = 0,
         .dstSubpass = VK_SUBPASS_EXTERNAL,
         .srcStageMask =
             VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT,
         .dstStageMask = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
         .srcAccessMask = VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
         .dstAccessMask = VK_ACCESS_SHADER_READ_BIT}};
    VkRenderPassCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO,
                                  .attachmentCount = 1,
                                  .pAttachments = &map,
                                  .subpassCount = 1,
                                  .pSubpasses = &dsub,
                                  .dependencyCount = 2,
                                  .pDependencies = deps};
    VK_CHECK(r, vkCreateRenderPass(r->device, &dpi, NULL, &r->depth_pass));
    return true;
}

/* A vertex twin's source is patched: after its #version line, a macro renames its main (#line
 * keeps glslang's line numbers those of the twin); at its end, a main that runs it, then takes
 * gl_Position from OpenGL's clip convention to Vulkan's with the fixed stages' very expression
 * (y flipped, z from [-w, w] to [0, w]), so that shader and fixed draws rasterise alike. */
static const char twin_vertex_main[] =
    "\n#undef main\n"
    "void main() {\n"
    "    sg_twin_main();\n"
    "    gl_Position = vec4(gl_Position.x, -gl_Position.y, 0.5 * (gl_Position.z + gl_Position.w),\n"
    "                       gl_Position.w);\n"
    "}\n";

/* The length of glslang's log without its trailing blank lines. */
static int log_length(const char *log) {
    size_t n = log ? strlen(log) : 0;
    while (n > 0 && (log[n - 1] == '\n' || log[n - 1] == ' ')) n--;
    return (int)n;
}

/* Compiles one stage of a twin to SPIR-V and a module; on failure the message names the shader
 * and the stage and gives glslang's log. */
static bool compile_twin_stage(ref *r, const sgShaderInfo *info, bool vertex, VkShaderModule *out) {
    const char *stage_name = vertex ? "vertex" : "fragment";
    const char *text = vertex ? info->glsl_vertex : info->glsl_fragment;
    if (!text)
        return fail(r, "shader '%s' has no GLSL %s twin (sgShaderInfo.glsl_%s)", info->name,
                    stage_name, stage_name);
    char *code;
    if (vertex) {
        /* After the #version line (the first line of a twin, or a later one after comments). */
        const char *version = strstr(text, "#version");
        if (!version)
            return fail(r, "shader '%s': the GLSL vertex twin has no #version line", info->name);
        const char *eol = strchr(version, '\n');
        int head = eol ? (int)(eol + 1 - text) : (int)strlen(text);
        int next_line = 1; /* the number of the line after #version's */
        for (int i = 0; i < head; i++) next_line += text[i] == '\n';
        code = sc_format("%.*s%s#define main sg_twin_main\n#line %d\n%s%s", head, text,
                         eol ? "" : "\n", next_line, text + head, twin_vertex_main);
    } else {
        code = sc_format("%s", text);
    }
    if (!code) return fail(r, "out of memory");
    glslang_stage_t stage = vertex ? GLSLANG_STAGE_VERTEX : GLSLANG_STAGE_FRAGMENT;
    glslang_input_t in = {.language = GLSLANG_SOURCE_GLSL,
                          .stage = stage,
                          .client = GLSLANG_CLIENT_VULKAN,
                          .client_version = GLSLANG_TARGET_VULKAN_1_1,
                          .target_language = GLSLANG_TARGET_SPV,
                          .target_language_version = GLSLANG_TARGET_SPV_1_3,
                          .code = code,
                          .default_version = 450,
                          .default_profile = GLSLANG_NO_PROFILE,
                          .messages = GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT,
                          .resource = glslang_default_resource()};
    glslang_shader_t *sh = glslang_shader_create(&in);
    glslang_program_t *prog = NULL;
    bool ok = sh != NULL || fail(r, "shader '%s': glslang cannot start", info->name);
    if (ok && (!glslang_shader_preprocess(sh, &in) || !glslang_shader_parse(sh, &in)))
        ok =
            fail(r, "shader '%s': the GLSL %s twin does not compile:\n%.*s", info->name, stage_name,
                 log_length(glslang_shader_get_info_log(sh)), glslang_shader_get_info_log(sh));
    if (ok) {
        prog = glslang_program_create();
        ok = prog != NULL || fail(r, "out of memory");
    }
    if (ok) {
        glslang_program_add_shader(prog, sh);
        if (!glslang_program_link(prog, GLSLANG_MSG_SPV_RULES_BIT | GLSLANG_MSG_VULKAN_RULES_BIT))
            ok = fail(r, "shader '%s': the GLSL %s twin does not link:\n%.*s", info->name,
                      stage_name, log_length(glslang_program_get_info_log(prog)),
                      glslang_program_get_info_log(prog));
    }
    if (ok) {
        glslang_program_SPIRV_generate(prog, stage);
        const char *msgs = glslang_program_SPIRV_get_messages(prog);
        size_t words = glslang_program_SPIRV_get_size(prog);
        if (words == 0)
            ok = fail(r, "shader '%s': no SPIR-V for the GLSL %s twin:\n%.*s", info->name,
                      stage_name, log_length(msgs), msgs ? msgs : "");
    }
    if (ok) {
        VkShaderModuleCreateInfo smi = {.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO,
                                        .codeSize = glslang_program_SPIRV_get_size(prog) * 4,
                                        .pCode = glslang_program_SPIRV_get_ptr(prog)};
        VkResult vr = vkCreateShaderModule(r->device, &smi, NULL, out);
        if (vr != VK_SUCCESS)
            ok = fail(r, "shader '%s': vkCreateShaderModule of the %s twin failed (VkResult %d)",
                      info->name, stage_name, (int)vr);
    }
    if (prog) glslang_program_delete(prog);
    if (sh) glslang_shader_delete(sh);
    free(code);
    return ok;
}

/* The compiled twin of the shader a draw names, compiled on first use; *index into r->twins. */
static bool get_twin(ref *r, const char *name, int *index) {
    for (int i = 0; i < r->twin_count; i++)
        if (strcmp(r->twins[i].info->name, name) == 0) {
            *index = i;
            return true;
        }
    const sgShaderInfo *info = r->shaders ? sc_shaders_find(r->shaders, name) : NULL;
    if (!info) return fail(r, "unknown shader '%s'", name);
    if (!r->glslang_ready) {
        if (!glslang_initialize_process()) return fail(r, "glslang cannot start");
        r->glslang_ready = true;
    }
    twin t = {.info = info};
    if (!compile_twin_stage(r, info, true, &t.vert)) return false;
    if (!compile_twin_stage(r, info, false, &t.frag)) {
        vkDestroyShaderModule(r->device, t.vert, NULL);
        return false;
    }
    twin *grown = realloc(r->twins, (size_t)(r->twin_count + 1) * sizeof *grown);
    if (!grown) {
        vkDestroyShaderModule(r->device, t.vert, NULL);
        vkDestroyShaderModule(r->device, t.frag, NULL);
        return fail(r, "out of memory");
    }
    r->twins = grown;
    r->twins[r->twin_count] = t;
    *index = r->twin_count++;
    return true;
}

/* The pipeline state a draw needs, packed into a key: for its triangles, or (lines) for its mesh's
 * line list, where the polygon mode plays no part. A caster's depth-only pipeline depends on its
 * cull, winding and polygon mode alone (the bias is in the uniform block). */
static uint32_t pipeline_key(const sc_draw *d, bool textured, draw_kind kind, bool lines) {
    uint32_t prim = lines ? 1u << 14 : (uint32_t)d->polygon_mode << 15;
    if (kind == DRAW_CASTER)
        return (uint32_t)d->cull << 1 | (uint32_t)d->front_face << 3 | 1u << 13 | prim;
    return (uint32_t)textured | (uint32_t)d->cull << 1 | (uint32_t)d->front_face << 3 |
           (uint32_t)d->depth_compare << 4 | (uint32_t)d->depth_write << 8 |
           (uint32_t)d->blend << 9 | (uint32_t)d->lighting << 10 |
           (uint32_t)(kind == DRAW_RECEIVER) << 12 | prim;
}

static const VkCompareOp compare_ops[] = {
    [SC_COMPARE_LESS] = VK_COMPARE_OP_LESS,
    [SC_COMPARE_NEVER] = VK_COMPARE_OP_NEVER,
    [SC_COMPARE_EQUAL] = VK_COMPARE_OP_EQUAL,
    [SC_COMPARE_LESS_EQUAL] = VK_COMPARE_OP_LESS_OR_EQUAL,
    [SC_COMPARE_GREATER] = VK_COMPARE_OP_GREATER,
    [SC_COMPARE_NOT_EQUAL] = VK_COMPARE_OP_NOT_EQUAL,
    [SC_COMPARE_GREATER_EQUAL] = VK_COMPARE_OP_GREATER_OR_EQUAL,
    [SC_COMPARE_ALWAYS] = VK_COMPARE_OP_ALWAYS,
};

/* The layout of a pipeline's descriptor sets and push constants. */
static VkPipelineLayout layout_of(const ref *r, bool textured, draw_kind kind) {
    if (kind == DRAW_RECEIVER) return r->layout_shadow;
    return textured && kind == DRAW_PLAIN ? r->layout_texture : r->layout_color;
}

/* The pipeline of a draw's triangles or lines: with the fixed stages (twin -1), or with the
 * compiled twin r->twins[twin] (a shader draw of the scene's pass: untextured in the fixed sense,
 * unlit, receiving no shadow). */
static bool get_pipeline(ref *r, const sc_draw *d, bool textured, draw_kind kind, bool lines,
                         int twin, VkPipeline *out) {
    if (kind == DRAW_CASTER) textured = false;
    if (kind == DRAW_CASTER) twin = -1;
    uint32_t key = pipeline_key(d, textured, kind, lines);
    const int samples = kind == DRAW_CASTER ? 1 : r->samples; /* the shadow map has one */
    for (int i = 0; i < r->pipeline_count; i++)
        if (r->pipelines[i].key == key && r->pipelines[i].twin == twin &&
            r->pipelines[i].samples == samples) {
            *out = r->pipelines[i].pipeline;
            return true;
        }
    if (r->pipeline_count == MAX_PIPELINES) return fail(r, "too many pipeline states");
    const bool lit = d->lighting != SC_LIGHTING_NONE && kind != DRAW_CASTER && twin < 0;
    if (lit && d->lighting == SC_LIGHTING_FLAT && !r->has_geometry)
        return fail(r, "flat lighting needs geometry shaders, which this lavapipe does not offer "
                       "(VkPhysicalDeviceFeatures.geometryShader)");
    /* The loader lets no flat-lit draw have lines: the geometry shader takes triangles. */
    const bool wireframe = !lines && d->polygon_mode == SC_POLYGON_MODE_LINE;
    if (wireframe && !r->has_wireframe)
        return fail(r, "polygon mode line needs VkPhysicalDeviceFeatures.fillModeNonSolid, which "
                       "this lavapipe does not offer");
    if ((lines || wireframe) && !r->has_lines)
        return fail(r, "lines need Bresenham line rasterisation (VK_EXT_line_rasterization, "
                       "bresenhamLines), which this lavapipe does not offer");
    VkPipelineShaderStageCreateInfo stages[3] = {
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_VERTEX_BIT,
         .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_FRAGMENT_BIT,
         .pName = "main"},
        {.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO,
         .stage = VK_SHADER_STAGE_GEOMETRY_BIT,
         .module = r->modules[SH_FLAT_GEOM],
         .pName = "main"}};
    if (twin >= 0) {
        stages[0].module = r->twins[twin].vert;
        stages[1].module = r->twins[twin].frag;
    } else if (kind == DRAW_CASTER) {
        stages[0].module = r->modules[SH_DEPTH_VERT];
        stages[1].module = r->modules[SH_DEPTH_FRAG];
    } else if (lit) {
        int mode = (int)d->lighting - 1;
        stages[0].module = r->modules[SH_LIT_VERT + mode];
        stages[1].module = r->modules[SH_LIT_FRAG + mode * 2 + textured];
        if (kind == DRAW_RECEIVER && d->lighting == SC_LIGHTING_PHONG) {
            stages[1].module = r->modules[SH_PHONG_SHADOW_FRAG + textured];
        } else if (kind == DRAW_RECEIVER) { /* flat or Gouraud: the split equation */
            if (d->lighting == SC_LIGHTING_GOURAUD)
                stages[0].module = r->modules[SH_GOURAUD_SHADOW_VERT];
            else
                stages[2].module = r->modules[SH_FLAT_SHADOW_GEOM];
            stages[1].module = r->modules[SH_SPLIT_SHADOW_FRAG + mode * 2 + textured];
        }
    } else if (kind == DRAW_RECEIVER) {
        stages[0].module = r->modules[textured ? SH_TEXTURE_SHADOW_VERT : SH_COLOR_SHADOW_VERT];
        stages[1].module = r->modules[textured ? SH_TEXTURE_SHADOW_FRAG : SH_COLOR_SHADOW_FRAG];
    } else {
        stages[0].module = r->modules[textured ? SH_TEXTURE_VERT : SH_COLOR_VERT];
        stages[1].module = r->modules[textured ? SH_TEXTURE_FRAG : SH_COLOR_FRAG];
    }
    /* Positions, colours, texcoords, normals: the sections of the mesh's vertex buffer. Unlit
     * shaders read the first two, or three when textured; lit ones all four. */
    VkVertexInputBindingDescription bind[4] = {{0, 16, VK_VERTEX_INPUT_RATE_VERTEX},
                                               {1, 16, VK_VERTEX_INPUT_RATE_VERTEX},
                                               {2, 8, VK_VERTEX_INPUT_RATE_VERTEX},
                                               {3, 12, VK_VERTEX_INPUT_RATE_VERTEX}};
    VkVertexInputAttributeDescription attr[4] = {{0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                 {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
                                                 {2, 2, VK_FORMAT_R32G32_SFLOAT, 0},
                                                 {3, 3, VK_FORMAT_R32G32B32_SFLOAT, 0}};
    uint32_t inputs = kind == DRAW_CASTER ? 1 : lit ? 4 : textured ? 3 : 2;
    /* A twin's inputs (docs/api.md, "Shaders"), binding b at location b: position, colour,
     * normal, texcoord, then the four attributes. */
    VkVertexInputBindingDescription twin_bind[8] = {
        {0, 16, VK_VERTEX_INPUT_RATE_VERTEX}, {1, 16, VK_VERTEX_INPUT_RATE_VERTEX},
        {2, 12, VK_VERTEX_INPUT_RATE_VERTEX}, {3, 8, VK_VERTEX_INPUT_RATE_VERTEX},
        {4, 16, VK_VERTEX_INPUT_RATE_VERTEX}, {5, 16, VK_VERTEX_INPUT_RATE_VERTEX},
        {6, 16, VK_VERTEX_INPUT_RATE_VERTEX}, {7, 16, VK_VERTEX_INPUT_RATE_VERTEX}};
    VkVertexInputAttributeDescription twin_attr[8] = {
        {0, 0, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
        {2, 2, VK_FORMAT_R32G32B32_SFLOAT, 0},    {3, 3, VK_FORMAT_R32G32_SFLOAT, 0},
        {4, 4, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {5, 5, VK_FORMAT_R32G32B32A32_SFLOAT, 0},
        {6, 6, VK_FORMAT_R32G32B32A32_SFLOAT, 0}, {7, 7, VK_FORMAT_R32G32B32A32_SFLOAT, 0}};
    if (twin >= 0) inputs = 8;
    VkPipelineVertexInputStateCreateInfo vi = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO,
        .vertexBindingDescriptionCount = inputs,
        .pVertexBindingDescriptions = twin >= 0 ? twin_bind : bind,
        .vertexAttributeDescriptionCount = inputs,
        .pVertexAttributeDescriptions = twin >= 0 ? twin_attr : attr};
    VkPipelineInputAssemblyStateCreateInfo ia = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO,
        .topology = lines ? VK_PRIMITIVE_TOPOLOGY_LINE_LIST : VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST};
    VkPipelineViewportStateCreateInfo vp = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO,
        .viewportCount = 1,
        .scissorCount = 1};
    /* sgapi's lines: one pixel wide, diamond exit, whether a line list or a triangle's edges.
     * Filled triangles go without it, as they always have. */
    VkPipelineRasterizationLineStateCreateInfoEXT ls = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_LINE_STATE_CREATE_INFO_EXT,
        .lineRasterizationMode = VK_LINE_RASTERIZATION_MODE_BRESENHAM_EXT};
    /* The y flip in the vertex shader keeps on-screen winding, so CCW means CCW as displayed.
     * Culling applies to triangles only, before a wireframe's edges are drawn. */
    VkPipelineRasterizationStateCreateInfo rs = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO,
        .pNext = lines || wireframe ? &ls : NULL,
        .polygonMode = wireframe ? VK_POLYGON_MODE_LINE : VK_POLYGON_MODE_FILL,
        .cullMode = d->cull == SC_CULL_BACK    ? VK_CULL_MODE_BACK_BIT
                    : d->cull == SC_CULL_FRONT ? VK_CULL_MODE_FRONT_BIT
                                               : VK_CULL_MODE_NONE,
        .frontFace = d->front_face == SC_FRONT_FACE_CW ? VK_FRONT_FACE_CLOCKWISE
                                                       : VK_FRONT_FACE_COUNTER_CLOCKWISE,
        .lineWidth = 1.0f};
    VkPipelineMultisampleStateCreateInfo ms = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO,
        .rasterizationSamples = samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT};
    /* Casters: the nearest depth wins, whatever the draw's own depth state. */
    VkPipelineDepthStencilStateCreateInfo ds = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO,
        .depthTestEnable = VK_TRUE,
        .depthWriteEnable = d->depth_write || kind == DRAW_CASTER ? VK_TRUE : VK_FALSE,
        .depthCompareOp = kind == DRAW_CASTER ? VK_COMPARE_OP_LESS : compare_ops[d->depth_compare]};
    VkPipelineColorBlendAttachmentState cba = {.colorWriteMask = 0xf};
    if (d->blend == SC_BLEND_ALPHA && kind != DRAW_CASTER) {
        /* src * src_alpha + dst * (1 - src_alpha) on all four channels, as sgapi's
         * SG_BLEND_ALPHA and OpenGL's glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA). */
        cba.blendEnable = VK_TRUE;
        cba.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        cba.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        cba.colorBlendOp = VK_BLEND_OP_ADD;
        cba.srcAlphaBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
        cba.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        cba.alphaBlendOp = VK_BLEND_OP_ADD;
    }
    VkPipelineColorBlendStateCreateInfo cb = {
        .sType = VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO,
        .attachmentCount = kind == DRAW_CASTER ? 0 : 1, /* the map's pass has no colour */
        .pAttachments = &cba};
    VkDynamicState dyn[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy = {.sType =
                                               VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO,
                                           .dynamicStateCount = 2,
                                           .pDynamicStates = dyn};
    VkGraphicsPipelineCreateInfo gpi = {
        .sType = VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO,
        .stageCount = lit && d->lighting == SC_LIGHTING_FLAT ? 3 : 2,
        .pStages = stages,
        .pVertexInputState = &vi,
        .pInputAssemblyState = &ia,
        .pViewportState = &vp,
        .pRasterizationState = &rs,
        .pMultisampleState = &ms,
        .pDepthStencilState = &ds,
        .pColorBlendState = &cb,
        .pDynamicState = &dy,
        .layout = twin >= 0 ? r->layout_twin : layout_of(r, textured, kind),
        .renderPass = kind == DRAW_CASTER ? r->depth_pass
                      : samples == 4      ? r->render_pass_ms
                                          : r->render_pass};
    VK_CHECK(r, vkCreateGraphicsPipelines(r->device, VK_NULL_HANDLE, 1, &gpi, NULL, out));
    r->pipelines[r->pipeline_count].samples = samples;
    r->pipelines[r->pipeline_count].key = key;
    r->pipelines[r->pipeline_count].twin = twin;
    r->pipelines[r->pipeline_count].pipeline = *out;
    r->pipeline_count++;
    return true;
}

static bool create_buffer(ref *r, VkDeviceSize size, VkBufferUsageFlags usage, buffer *b) {
    VkBufferCreateInfo bci = {
        .sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, .size = size ? size : 4, .usage = usage};
    VK_CHECK(r, vkCreateBuffer(r->device, &bci, NULL, &b->buffer));
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(r->device, b->buffer, &req);
    uint32_t type = 0;
    if (!find_memory(r, req.memoryTypeBits,
                     VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                     &type))
        return false;
    VkMemoryAllocateInfo mai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                .allocationSize = req.size,
                                .memoryTypeIndex = type};
    VK_CHECK(r, vkAllocateMemory(r->device, &mai, NULL, &b->memory));
    VK_CHECK(r, vkBindBufferMemory(r->device, b->buffer, b->memory, 0));
    VK_CHECK(r, vkMapMemory(r->device, b->memory, 0, VK_WHOLE_SIZE, 0, &b->mapped));
    return true;
}

static void destroy_buffer(ref *r, buffer *b) {
    if (b->buffer) vkDestroyBuffer(r->device, b->buffer, NULL);
    if (b->memory) vkFreeMemory(r->device, b->memory, NULL);
    memset(b, 0, sizeof *b);
}

/* An image of `levels` mip levels and `samples` (1 or 4) samples a pixel. */
static bool create_image_full(ref *r, int w, int h, int levels, int samples, VkFormat format,
                              VkImageUsageFlags usage, VkImageAspectFlags aspect, texture *t) {
    VkImageCreateInfo ici = {.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO,
                             .imageType = VK_IMAGE_TYPE_2D,
                             .format = format,
                             .extent = {(uint32_t)w, (uint32_t)h, 1},
                             .mipLevels = (uint32_t)levels,
                             .arrayLayers = 1,
                             .samples =
                                 samples == 4 ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT,
                             .tiling = VK_IMAGE_TILING_OPTIMAL,
                             .usage = usage,
                             .initialLayout = VK_IMAGE_LAYOUT_UNDEFINED};
    VK_CHECK(r, vkCreateImage(r->device, &ici, NULL, &t->image));
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(r->device, t->image, &req);
    uint32_t type = 0;
    if (!find_memory(r, req.memoryTypeBits, 0, &type)) return false;
    VkMemoryAllocateInfo mai = {.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                .allocationSize = req.size,
                                .memoryTypeIndex = type};
    VK_CHECK(r, vkAllocateMemory(r->device, &mai, NULL, &t->memory));
    VK_CHECK(r, vkBindImageMemory(r->device, t->image, t->memory, 0));
    VkImageViewCreateInfo vci = {.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO,
                                 .image = t->image,
                                 .viewType = VK_IMAGE_VIEW_TYPE_2D,
                                 .format = format,
                                 .subresourceRange = {aspect, 0, (uint32_t)levels, 0, 1}};
    VK_CHECK(r, vkCreateImageView(r->device, &vci, NULL, &t->view));
    return true;
}

static bool create_image(ref *r, int w, int h, int levels, VkFormat format, VkImageUsageFlags usage,
                         VkImageAspectFlags aspect, texture *t) {
    return create_image_full(r, w, h, levels, 1, format, usage, aspect, t);
}

static bool create_image_ms(ref *r, int w, int h, int samples, VkFormat format,
                            VkImageUsageFlags usage, VkImageAspectFlags aspect, texture *t) {
    return create_image_full(r, w, h, 1, samples, format, usage, aspect, t);
}

static void destroy_image(ref *r, texture *t) {
    if (t->view) vkDestroyImageView(r->device, t->view, NULL);
    if (t->image) vkDestroyImage(r->device, t->image, NULL);
    if (t->memory) vkFreeMemory(r->device, t->memory, NULL);
    memset(t, 0, sizeof *t);
}

static bool begin_commands(ref *r) {
    VK_CHECK(r, vkResetCommandBuffer(r->cmd, 0));
    VkCommandBufferBeginInfo bi = {.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    VK_CHECK(r, vkBeginCommandBuffer(r->cmd, &bi));
    return true;
}

static bool submit_and_wait(ref *r) {
    VkSubmitInfo si = {.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO,
                       .commandBufferCount = 1,
                       .pCommandBuffers = &r->cmd};
    VK_CHECK(r, vkQueueSubmit(r->queue, 1, &si, r->fence));
    VK_CHECK(r, vkWaitForFences(r->device, 1, &r->fence, VK_TRUE, UINT64_MAX));
    VK_CHECK(r, vkResetFences(r->device, 1, &r->fence));
    return true;
}

static void barrier_levels(VkCommandBuffer cmd, VkImage image, uint32_t levels, VkImageLayout from,
                           VkImageLayout to, VkAccessFlags src_access, VkAccessFlags dst_access,
                           VkPipelineStageFlags src, VkPipelineStageFlags dst) {
    VkImageMemoryBarrier b = {.sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER,
                              .srcAccessMask = src_access,
                              .dstAccessMask = dst_access,
                              .oldLayout = from,
                              .newLayout = to,
                              .srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                              .dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED,
                              .image = image,
                              .subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, levels, 0, 1}};
    vkCmdPipelineBarrier(cmd, src, dst, 0, 0, NULL, 0, NULL, 1, &b);
}

/* Uploads an RGBA8 texture (top row first) with its rows reversed, so that image row 0 is the
 * bottom row as displayed and t = 0 samples it, as in OpenGL and sgapi; mipmapped, with its full
 * chain of levels as sgapi makes them (sgu_generate_mip_level), each reversed the same way, so
 * that both sample the same texels. */
static bool upload_texture(ref *r, const sc_image *img, bool mipmapped, texture *t) {
    const int levels = mipmapped ? sgu_mip_level_count(img->width, img->height) : 1;
    if (!create_image(r, img->width, img->height, levels, VK_FORMAT_R8G8B8A8_UNORM,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT, t))
        return false;
    /* Level k at offset[k] of the staging buffer, top row first in top, then reversed. */
    size_t offset[SG_MAX_MIP_LEVELS + 1], total = 0;
    int w = img->width, h = img->height;
    for (int k = 0; k < levels; k++) {
        offset[k] = total;
        total += (size_t)w * (size_t)h * 4;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
    }
    uint8_t *top = malloc(total);
    buffer staging = {0};
    if (!top) return fail(r, "out of memory for a texture's levels");
    if (!create_buffer(r, total, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, &staging)) {
        free(top);
        return false;
    }
    memcpy(top, img->pixels, (size_t)img->width * (size_t)img->height * 4);
    VkBufferImageCopy copies[SG_MAX_MIP_LEVELS];
    w = img->width;
    h = img->height;
    for (int k = 0; k < levels; k++) {
        if (k > 0) sgu_generate_mip_level(top + offset[k - 1], w, h, top + offset[k], &w, &h);
        size_t row = (size_t)w * 4;
        for (int y = 0; y < h; y++)
            memcpy((uint8_t *)staging.mapped + offset[k] + (size_t)y * row,
                   top + offset[k] + (size_t)(h - 1 - y) * row, row);
        copies[k] =
            (VkBufferImageCopy){.bufferOffset = offset[k],
                                .imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, (uint32_t)k, 0, 1},
                                .imageExtent = {(uint32_t)w, (uint32_t)h, 1}};
    }
    free(top);
    bool ok = begin_commands(r);
    if (ok) {
        barrier_levels(r->cmd, t->image, (uint32_t)levels, VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT);
        vkCmdCopyBufferToImage(r->cmd, staging.buffer, t->image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, (uint32_t)levels, copies);
        barrier_levels(r->cmd, t->image, (uint32_t)levels, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_ACCESS_TRANSFER_WRITE_BIT,
                       VK_ACCESS_SHADER_READ_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT);
        ok = vkEndCommandBuffer(r->cmd) == VK_SUCCESS && submit_and_wait(r);
    }
    destroy_buffer(r, &staging);
    return ok || fail(r, "texture upload failed: %s", sc_msg_text(&r->err));
}

/* Where each section of a mesh's vertex buffer starts, in bytes per vertex before it: the fixed
 * stages read the first four, twins all (the attributes: 16 bytes a vertex, the first for
 * attribute 0, the second, all zero, for attributes 1 to 3). */
enum {
    VERTEX_POSITIONS = 0,
    VERTEX_COLORS = 16,
    VERTEX_TEXCOORDS = 32,
    VERTEX_NORMALS = 40,
    VERTEX_ATTRIBUTE0 = 52,
    VERTEX_ZEROS = 68,
    VERTEX_BYTES = 84
};

/* GPU copies of one scene file's meshes and textures. */
typedef struct uploads {
    buffer *vertex;     /* per mesh: positions | colours | texcoords | normals | attributes, back to
                           back; see VERTEX_* */
    buffer *index;      /* per mesh: its triangles (no buffer when it has none) */
    buffer *line_index; /* per mesh: its line list (no buffer when it has none) */
    texture *textures;
    size_t mesh_count, texture_count;
} uploads;

static bool upload_file(ref *r, const sc_file *f, uploads *u) {
    u->vertex = calloc(f->mesh_count + 1, sizeof *u->vertex);
    u->index = calloc(f->mesh_count + 1, sizeof *u->index);
    u->line_index = calloc(f->mesh_count + 1, sizeof *u->line_index);
    u->textures = calloc(f->texture_count + 1, sizeof *u->textures);
    if (!u->vertex || !u->index || !u->line_index || !u->textures) return fail(r, "out of memory");
    for (size_t i = 0; i < f->mesh_count; i++) {
        const sc_mesh *m = &f->meshes[i];
        size_t n = m->vertex_count;
        size_t bytes = n * VERTEX_BYTES;
        if (!create_buffer(r, bytes, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT, &u->vertex[i]))
            return false;
        u->mesh_count = i + 1;
        uint8_t *p = u->vertex[i].mapped;
        memcpy(p, m->positions, n * 16);
        memcpy(p + n * 16, m->colors, n * 16);
        if (m->texcoords)
            memcpy(p + n * 32, m->texcoords, n * 8);
        else
            memset(p + n * 32, 0, n * 8);
        /* The loader gives every mesh normals; zeros would light only with the ambient. */
        if (m->normals)
            memcpy(p + n * 40, m->normals, n * 12);
        else
            memset(p + n * 40, 0, n * 12);
        /* Attribute 0 of a shader draw: the mesh's tangents where it has normals and texture
         * coordinates (as sgapi-render gives them, sgu_compute_tangents), else zero; 1 to 3 are
         * zero. */
        memset(p + n * VERTEX_ATTRIBUTE0, 0, n * (VERTEX_BYTES - VERTEX_ATTRIBUTE0));
        if (m->normals && m->texcoords && m->index_count > 0 &&
            sgu_compute_tangents(m->positions, m->normals, m->texcoords, (int)n, m->indices,
                                 (int)m->index_count, 0,
                                 (float *)(void *)(p + n * VERTEX_ATTRIBUTE0)) != 0) {
            fprintf(stderr, "sgapi-ref: mesh %zu: out of memory for its tangents\n", i);
            return false;
        }
        if (m->index_count > 0) {
            if (!create_buffer(r, (VkDeviceSize)m->index_count * 4,
                               VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &u->index[i]))
                return false;
            memcpy(u->index[i].mapped, m->indices, (size_t)m->index_count * 4);
        }
        if (m->line_index_count > 0) {
            if (!create_buffer(r, (VkDeviceSize)m->line_index_count * 4,
                               VK_BUFFER_USAGE_INDEX_BUFFER_BIT, &u->line_index[i]))
                return false;
            memcpy(u->line_index[i].mapped, m->line_indices, (size_t)m->line_index_count * 4);
        }
    }
    for (size_t i = 0; i < f->texture_count; i++) {
        if (!upload_texture(r, &f->textures[i], sc_texture_mipmapped(f, i), &u->textures[i]))
            return false;
        u->texture_count = i + 1;
    }
    return true;
}

static void destroy_uploads(ref *r, uploads *u) {
    for (size_t i = 0; i < u->mesh_count; i++) {
        destroy_buffer(r, &u->vertex[i]);
        destroy_buffer(r, &u->index[i]);
        destroy_buffer(r, &u->line_index[i]);
    }
    for (size_t i = 0; i < u->texture_count; i++) destroy_image(r, &u->textures[i]);
    free(u->vertex);
    free(u->index);
    free(u->line_index);
    free(u->textures);
    memset(u, 0, sizeof *u);
}

static double now_ms(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A scene's shadow on lavapipe (all zero without one): its map, the framebuffer of the map's
 * pass, the set the receivers read the map through, and the matrices of the casters. */
typedef struct shadow_pass {
    texture map;             /* D32, size x size, cleared to 1.0 by its pass */
    VkFramebuffer fb;        /* of r->depth_pass */
    VkDescriptorSet set;     /* set 2 of the receivers */
    float (*world_view)[16]; /* per draw: the light's view x worldView (casters) */
    float proj[16];          /* the light's projection */
    float matrix[16];        /* view space -> the light's clip space, for the receivers */
} shadow_pass;

/* Records the shadow's depth-only pass: every caster into the map, with the light's matrices. */
static bool record_shadow(ref *r, const sc_file *f, const sc_scene *s, const uploads *u,
                          const shadow_pass *sh, VkDescriptorSet color_set) {
    uint32_t size = (uint32_t)s->shadow.size;
    VkClearValue clear = {.depthStencil = {1.0f, 0}};
    VkRenderPassBeginInfo rbi = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                 .renderPass = r->depth_pass,
                                 .framebuffer = sh->fb,
                                 .renderArea = {{0, 0}, {size, size}},
                                 .clearValueCount = 1,
                                 .pClearValues = &clear};
    vkCmdBeginRenderPass(r->cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport vp = {0, 0, (float)size, (float)size, 0.0f, 1.0f};
    VkRect2D sc = {{0, 0}, {size, size}};
    vkCmdSetViewport(r->cmd, 0, 1, &vp);
    vkCmdSetScissor(r->cmd, 0, 1, &sc);
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        if (!d->casts_shadow) continue;
        const sc_mesh *m = &f->meshes[d->mesh];
        /* The mesh's triangles, then its lines, each with its own pipeline. */
        for (int lines = 0; lines < 2; lines++) {
            uint32_t count = lines ? m->line_index_count : m->index_count;
            if (count == 0) continue;
            VkPipeline pipe;
            if (!get_pipeline(r, d, false, DRAW_CASTER, lines, -1, &pipe)) return false;
            vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            float pc[32];
            memcpy(pc, sh->world_view[i], 64);
            memcpy(pc + 16, sh->proj, 64);
            vkCmdPushConstants(r->cmd, r->layout_color, VK_SHADER_STAGE_VERTEX_BIT, 0, 128, pc);
            /* Any draw's block holds the scene's bias; this draw's will do. */
            uint32_t offset = (uint32_t)(i * r->draw_stride);
            vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->layout_color, 0, 1,
                                    &color_set, 1, &offset);
            VkDeviceSize zero = 0;
            vkCmdBindVertexBuffers(r->cmd, 0, 1, &u->vertex[d->mesh].buffer, &zero);
            /* The nearest depth wins whatever the order: the mesh's own indices, even when
             * sorted. */
            VkBuffer ib = lines ? u->line_index[d->mesh].buffer : u->index[d->mesh].buffer;
            vkCmdBindIndexBuffer(r->cmd, ib, 0, VK_INDEX_TYPE_UINT32);
            vkCmdDrawIndexed(r->cmd, count, 1, 0, 0, 0);
        }
    }
    vkCmdEndRenderPass(r->cmd);
    return true;
}

/* Records one shader draw of the scene's pass with its twin: its triangles or its lines (count
 * indices), instances times. */
static bool record_twin_draw(ref *r, const sc_file *f, const sc_scene *s, const uploads *u,
                             size_t i, bool lines, uint32_t count, VkDescriptorSet set,
                             const buffer *sorted) {
    const sc_draw *d = &s->draws[i];
    int t;
    VkPipeline pipe;
    if (!get_twin(r, d->shader, &t) || !get_pipeline(r, d, false, DRAW_PLAIN, lines, t, &pipe))
        return false;
    vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    /* Transposed: a twin declares plain (column-major) mat4s, so that proj * world_view * p in
     * GLSL is the product of the scene's row-major matrices. */
    float pc[32];
    for (int row = 0; row < 4; row++)
        for (int col = 0; col < 4; col++) {
            pc[col * 4 + row] = d->world_view[row * 4 + col];
            pc[16 + col * 4 + row] = d->proj[row * 4 + col];
        }
    vkCmdPushConstants(r->cmd, r->layout_twin,
                       VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, 128, pc);
    vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, r->layout_twin, 0, 1, &set, 0,
                            NULL);
    VkDeviceSize n = f->meshes[d->mesh].vertex_count;
    VkBuffer vb[8];
    for (int k = 0; k < 8; k++) vb[k] = u->vertex[d->mesh].buffer;
    VkDeviceSize off[8] = {n * VERTEX_POSITIONS, n * VERTEX_COLORS,     n * VERTEX_NORMALS,
                           n * VERTEX_TEXCOORDS, n * VERTEX_ATTRIBUTE0, n * VERTEX_ZEROS,
                           n * VERTEX_ZEROS,     n * VERTEX_ZEROS};
    vkCmdBindVertexBuffers(r->cmd, 0, 8, vb, off);
    VkBuffer ib = lines              ? u->line_index[d->mesh].buffer
                  : sorted[i].buffer ? sorted[i].buffer
                                     : u->index[d->mesh].buffer;
    vkCmdBindIndexBuffer(r->cmd, ib, 0, VK_INDEX_TYPE_UINT32);
    /* The loader gives every draw instances >= 1; 0 means 1, as sgDrawParams.instance_count. */
    vkCmdDrawIndexed(r->cmd, count, d->instances > 0 ? (uint32_t)d->instances : 1u, 0, 0, 0);
    return true;
}

/* Records one draw of the scene's pass: its mesh's triangles, or its mesh's lines (count indices).
 */
static bool record_draw(ref *r, const sc_file *f, const sc_scene *s, const uploads *u, size_t i,
                        bool lines, uint32_t count, VkDescriptorSet color_set,
                        const VkDescriptorSet *sets, const buffer *sorted, const shadow_pass *sh) {
    const sc_draw *d = &s->draws[i];
    if (d->shader) return record_twin_draw(r, f, s, u, i, lines, count, sets[i], sorted);
    /* As in sgapi-render: a texture draw without a texture is drawn with vertex colour. */
    bool textured = d->mode == SC_MODE_TEXTURE && d->texture >= 0;
    draw_kind kind = s->has_shadow && d->receives_shadow ? DRAW_RECEIVER : DRAW_PLAIN;
    VkPipeline pipe;
    if (!get_pipeline(r, d, textured, kind, lines, -1, &pipe)) return false;
    vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
    VkPipelineLayout layout = layout_of(r, textured, kind);
    float pc[32];
    memcpy(pc, d->world_view, 64);
    memcpy(pc + 16, d->proj, 64);
    vkCmdPushConstants(r->cmd, layout, VK_SHADER_STAGE_VERTEX_BIT, 0, 128, pc);
    uint32_t color_offset = (uint32_t)(i * r->draw_stride);
    vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 0, 1, &color_set, 1,
                            &color_offset);
    if (textured)
        vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 1, 1, &sets[i], 0,
                                NULL);
    if (kind == DRAW_RECEIVER)
        vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout, 2, 1, &sh->set, 0,
                                NULL);
    VkDeviceSize n = f->meshes[d->mesh].vertex_count;
    VkBuffer vb[4] = {u->vertex[d->mesh].buffer, u->vertex[d->mesh].buffer,
                      u->vertex[d->mesh].buffer, u->vertex[d->mesh].buffer};
    VkDeviceSize off[4] = {0, n * 16, n * 32, n * 40};
    uint32_t inputs = d->lighting != SC_LIGHTING_NONE ? 4 : textured ? 3 : 2;
    vkCmdBindVertexBuffers(r->cmd, 0, inputs, vb, off);
    /* A sorted draw has its own index buffer: the mesh's is shared with other draws. The loader
     * sorts no mesh with lines. */
    VkBuffer ib = lines              ? u->line_index[d->mesh].buffer
                  : sorted[i].buffer ? sorted[i].buffer
                                     : u->index[d->mesh].buffer;
    vkCmdBindIndexBuffer(r->cmd, ib, 0, VK_INDEX_TYPE_UINT32);
    vkCmdDrawIndexed(r->cmd, count, 1, 0, 0, 0);
    return true;
}

/* Records one scene: the shadow's pass when it has one, then clear, every draw, copy of the colour
 * image to `readback`. */
static bool record_scene(ref *r, const sc_file *f, const sc_scene *s, const uploads *u,
                         VkFramebuffer fb, VkImage color, const buffer *readback,
                         VkDescriptorSet color_set, const VkDescriptorSet *sets,
                         const buffer *sorted, const shadow_pass *sh, VkDescriptorSet resolve_set) {
    if (!begin_commands(r)) return false;
    if (s->has_shadow && !record_shadow(r, f, s, u, sh, color_set)) return false;
    VkClearValue clear[2];
    memcpy(clear[0].color.float32, s->clear_color, sizeof s->clear_color);
    clear[1].depthStencil.depth = 1.0f;
    clear[1].depthStencil.stencil = 0;
    VkRenderPassBeginInfo rbi = {.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO,
                                 .renderPass = r->samples == 4 ? r->render_pass_ms : r->render_pass,
                                 .framebuffer = fb,
                                 .renderArea = {{0, 0}, {(uint32_t)s->width, (uint32_t)s->height}},
                                 .clearValueCount = 2,
                                 .pClearValues = clear};
    vkCmdBeginRenderPass(r->cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
    VkViewport vp = {0, 0, (float)s->width, (float)s->height, 0.0f, 1.0f};
    VkRect2D sc = {{0, 0}, {(uint32_t)s->width, (uint32_t)s->height}};
    vkCmdSetViewport(r->cmd, 0, 1, &vp);
    vkCmdSetScissor(r->cmd, 0, 1, &sc);
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        const sc_mesh *m = &f->meshes[d->mesh];
        /* The mesh's triangles, then its lines (as sgapi-render draws them), each with its own
         * pipeline and the same bindings. */
        for (int lines = 0; lines < 2; lines++) {
            uint32_t count = lines ? m->line_index_count : m->index_count;
            if (count > 0 && !record_draw(r, f, s, u, i, lines, count, color_set, sets, sorted, sh))
                return false;
        }
    }
    vkCmdEndRenderPass(r->cmd);
    if (resolve_set) { /* 4 samples: the compute pass writes the readback buffer */
        vkCmdBindPipeline(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->resolve);
        vkCmdBindDescriptorSets(r->cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r->layout_resolve, 0, 1,
                                &resolve_set, 0, NULL);
        int32_t size[2] = {s->width, s->height};
        vkCmdPushConstants(r->cmd, r->layout_resolve, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof size,
                           size);
        vkCmdDispatch(r->cmd, (uint32_t)(s->width + 7) / 8, (uint32_t)(s->height + 7) / 8, 1);
        VkMemoryBarrier host = {.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER,
                                .srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT,
                                .dstAccessMask = VK_ACCESS_HOST_READ_BIT};
        vkCmdPipelineBarrier(r->cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                             VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, NULL, 0, NULL);
        VK_CHECK(r, vkEndCommandBuffer(r->cmd));
        return true;
    }
    VkBufferImageCopy copy = {.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1},
                              .imageExtent = {(uint32_t)s->width, (uint32_t)s->height, 1}};
    vkCmdCopyImageToBuffer(r->cmd, color, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback->buffer, 1,
                           &copy);
    VK_CHECK(r, vkEndCommandBuffer(r->cmd));
    return true;
}

/* The normal matrix of a row-major worldView: the inverse transpose of its upper-left 3x3, in
 * double, rows out. A singular (or non-finite) matrix gives zero, so every normal is (0, 0, 0). */
static void normal_matrix(const float *wv, float out[3][4]) {
    double m[3][3], c[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) m[i][j] = wv[i * 4 + j];
    /* inverse(M)^T = cofactor(M) / det(M). */
    c[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    c[0][1] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    c[0][2] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    c[1][0] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    c[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    c[1][2] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    c[2][0] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    c[2][1] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    c[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    double det = m[0][0] * c[0][0] + m[0][1] * c[0][1] + m[0][2] * c[0][2];
    bool ok = det != 0.0 && isfinite(det);
    for (int i = 0; i < 3; i++) {
        for (int j = 0; j < 3; j++) {
            out[i][j] = ok ? (float)(c[i][j] / det) : 0.0f;
            ok = ok && isfinite(out[i][j]);
        }
        out[i][3] = 0.0f;
    }
    if (!ok) memset(out, 0, 3 * sizeof out[0]);
}

/* What the shaders of a draw read: its colour, the scene's shadow when it has one (the casters'
 * bias, the receivers' matrix and map) and, when lit, the material, the normal matrix and the
 * scene's ambient and lights. */
static void fill_draw_block(const sc_scene *s, const sc_draw *d, const shadow_pass *sh,
                            draw_block *b) {
    memset(b, 0, sizeof *b);
    memcpy(b->color, d->color, sizeof d->color);
    if (s->has_shadow) {
        memcpy(b->shadow_matrix, sh->matrix, sizeof b->shadow_matrix);
        b->shadow[0] = (float)s->shadow.size;
        b->shadow[1] = s->shadow.bias;
        b->shadow[2] = s->shadow.slope_bias;
        b->shadow_flags[0] = s->shadow.light;
        b->shadow_flags[1] = s->shadow.pcf;
    }
    if (d->lighting == SC_LIGHTING_NONE) return;
    memcpy(b->ambient, s->ambient, sizeof s->ambient);
    memcpy(b->specular, d->specular, sizeof d->specular);
    b->specular[3] = d->shininess;
    normal_matrix(d->world_view, b->nm);
    b->light_count = s->light_count;
    for (int i = 0; i < s->light_count; i++) {
        const sc_light *l = &s->lights[i];
        if (l->type == SC_LIGHT_DIRECTIONAL) {
            /* L = -normalize(direction), once per draw and in double; the loader refuses a zero
             * direction. */
            double x = l->direction[0], y = l->direction[1], z = l->direction[2];
            double len = sqrt(x * x + y * y + z * z);
            b->lights[i].vec[0] = (float)(-x / len);
            b->lights[i].vec[1] = (float)(-y / len);
            b->lights[i].vec[2] = (float)(-z / len);
            b->lights[i].vec[3] = 0.0f;
        } else {
            memcpy(b->lights[i].vec, l->position, sizeof l->position);
            b->lights[i].vec[3] = 1.0f;
        }
        memcpy(b->lights[i].color, l->color, sizeof l->color);
        memcpy(b->lights[i].attenuation, l->attenuation, sizeof l->attenuation);
    }
}

/* The per-draw data of a scene: each draw's uniform block, at draw_stride bytes apart, and for
 * each draw sorted back to front its own index buffer, in that order. */
static bool prepare_draws(ref *r, const sc_file *f, const sc_scene *s, const shadow_pass *sh,
                          buffer *blocks, buffer *sorted) {
    if (s->draw_count > UINT32_MAX / r->draw_stride)
        return fail(r, "too many draws (%zu)", s->draw_count);
    VkDeviceSize stride = r->draw_stride;
    if (!create_buffer(r, (VkDeviceSize)s->draw_count * stride, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                       blocks))
        return false;
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        draw_block block;
        fill_draw_block(s, d, sh, &block);
        memcpy((uint8_t *)blocks->mapped + i * stride, &block, sizeof block);
        if (d->sort != SC_SORT_BACK_TO_FRONT) continue;
        const sc_mesh *m = &f->meshes[d->mesh];
        if (!create_buffer(r, (VkDeviceSize)m->index_count * 4, VK_BUFFER_USAGE_INDEX_BUFFER_BIT,
                           &sorted[i]))
            return false;
        if (!sc_sort_back_to_front(m->positions, m->indices, m->index_count, d->world_view,
                                   sorted[i].mapped))
            return fail(r, "out of memory sorting draw %zu", i);
    }
    return true;
}

/* The scene's shadow, when it has one: the light's matrices (apps/common/shadow.h, as sgapi-render
 * takes them), the map and the framebuffer of its pass. */
static bool create_shadow(ref *r, const sc_file *f, const sc_scene *s, shadow_pass *sh) {
    if (!s->has_shadow) return true;
    double view[16], proj[16];
    /* The loader has fitted this scene's light already; failing here is a bug. */
    if (!sc_shadow_light(f, s, view, proj)) return fail(r, "the shadow light cannot be fitted");
    sh->world_view = calloc(s->draw_count, sizeof *sh->world_view);
    if (!sh->world_view) return fail(r, "out of memory");
    for (size_t i = 0; i < s->draw_count; i++)
        if (s->draws[i].casts_shadow)
            sc_shadow_caster_world_view(view, s->draws[i].world_view, sh->world_view[i]);
    for (int i = 0; i < 16; i++) sh->proj[i] = (float)proj[i];
    sc_mat4_mul_to_float(proj, view, sh->matrix);
    int size = s->shadow.size;
    if (!create_image(r, size, size, 1, VK_FORMAT_D32_SFLOAT,
                      VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                      VK_IMAGE_ASPECT_DEPTH_BIT, &sh->map))
        return false;
    VkFramebufferCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                   .renderPass = r->depth_pass,
                                   .attachmentCount = 1,
                                   .pAttachments = &sh->map.view,
                                   .width = (uint32_t)size,
                                   .height = (uint32_t)size,
                                   .layers = 1};
    VK_CHECK(r, vkCreateFramebuffer(r->device, &fci, NULL, &sh->fb));
    return true;
}

static void destroy_shadow(ref *r, shadow_pass *sh) {
    if (sh->fb) vkDestroyFramebuffer(r->device, sh->fb, NULL);
    destroy_image(r, &sh->map);
    free(sh->world_view);
    memset(sh, 0, sizeof *sh);
}

/* The sets of a scene's shader draws (sets[i] for draw i): each draw's uniforms, at their own
 * aligned offset in one storage buffer (one float of zero for a draw without uniforms), and its
 * textures with its filter and wrap, the slots it leaves unbound the blank image. */
static bool prepare_twin_sets(ref *r, const sc_scene *s, const uploads *u, VkDescriptorPool pool,
                              buffer *uniforms, VkDescriptorSet *sets) {
    VkDeviceSize size = 0, align = r->storage_align;
    for (size_t i = 0; i < s->draw_count; i++)
        if (s->draws[i].shader) {
            int count = s->draws[i].uniform_count;
            size = (size + align - 1) / align * align + (VkDeviceSize)(count > 0 ? count : 1) * 4;
        }
    if (size == 0) return true;
    if (!create_buffer(r, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, uniforms)) return false;
    VkDeviceSize offset = 0;
    for (size_t i = 0; i < s->draw_count; i++) {
        const sc_draw *d = &s->draws[i];
        if (!d->shader) continue;
        offset = (offset + align - 1) / align * align;
        VkDeviceSize range = (VkDeviceSize)(d->uniform_count > 0 ? d->uniform_count : 1) * 4;
        if (d->uniform_count > 0)
            memcpy((uint8_t *)uniforms->mapped + offset, d->uniforms, (size_t)range);
        else
            memset((uint8_t *)uniforms->mapped + offset, 0, (size_t)range);
        VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                           .descriptorPool = pool,
                                           .descriptorSetCount = 1,
                                           .pSetLayouts = &r->twin_set_layout};
        if (vkAllocateDescriptorSets(r->device, &dai, &sets[i]) != VK_SUCCESS)
            return fail(r, "vkAllocateDescriptorSets failed");
        VkDescriptorBufferInfo bi = {.buffer = uniforms->buffer, .offset = offset, .range = range};
        VkSampler sampler =
            r->samplers[(int)d->mipmap * 4 + (d->filter == SC_FILTER_BILINEAR ? 2 : 0) +
                        (d->wrap == SC_WRAP_CLAMP ? 1 : 0)];
        VkDescriptorImageInfo ii[TWIN_TEXTURES];
        for (int k = 0; k < TWIN_TEXTURES; k++) {
            bool bound = k < d->shader_texture_count;
            ii[k] = (VkDescriptorImageInfo){
                .sampler = sampler,
                .imageView = bound ? u->textures[d->shader_textures[k]].view : r->blank.view,
                .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
        }
        VkWriteDescriptorSet w[2] = {{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                      .dstSet = sets[i],
                                      .dstBinding = 0,
                                      .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                      .pBufferInfo = &bi},
                                     {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                      .dstSet = sets[i],
                                      .dstBinding = 1,
                                      .descriptorCount = TWIN_TEXTURES,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                      .pImageInfo = ii}};
        vkUpdateDescriptorSets(r->device, 2, w, 0, NULL);
        offset += range;
    }
    return true;
}

/* The resolve's descriptor set for a scene of 4 samples: its colour image, its readback. */
static bool create_resolve(ref *r, const sc_scene *s, const texture *color_ms,
                           const buffer *readback, VkDescriptorPool *pool, VkDescriptorSet *set) {
    VkDescriptorPoolSize ps[2] = {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1}};
    VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                      .maxSets = 1,
                                      .poolSizeCount = 2,
                                      .pPoolSizes = ps};
    VK_CHECK(r, vkCreateDescriptorPool(r->device, &dpi, NULL, pool));
    VkDescriptorSetAllocateInfo dai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                       .descriptorPool = *pool,
                                       .descriptorSetCount = 1,
                                       .pSetLayouts = &r->resolve_set_layout};
    VK_CHECK(r, vkAllocateDescriptorSets(r->device, &dai, set));
    VkDescriptorImageInfo ii = {r->samplers[0], color_ms->view,
                                VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorBufferInfo bi = {readback->buffer, 0,
                                 (VkDeviceSize)s->width * (VkDeviceSize)s->height * 4};
    VkWriteDescriptorSet w[2] = {{.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .dstSet = *set,
                                  .dstBinding = 0,
                                  .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                  .pImageInfo = &ii},
                                 {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                  .dstSet = *set,
                                  .dstBinding = 1,
                                  .descriptorCount = 1,
                                  .descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  .pBufferInfo = &bi}};
    vkUpdateDescriptorSets(r->device, 2, w, 0, NULL);
    return true;
}

static bool render_scene(ref *r, const sc_file *f, const sc_scene *s, const uploads *u,
                         const char *out_dir, int frames) {
    shadow_pass sh = {0};
    texture color = {0}, depth = {0}, color_ms = {0};
    buffer readback = {0}, blocks = {0}, uniforms = {0};
    r->samples = s->samples == 4 ? 4 : 1;
    const bool ms = r->samples == 4;
    VkDescriptorPool resolve_pool = VK_NULL_HANDLE;
    VkDescriptorSet resolve_set = VK_NULL_HANDLE;
    VkFramebuffer fb = VK_NULL_HANDLE;
    VkDescriptorPool pool = VK_NULL_HANDLE;
    VkDescriptorSet color_set = VK_NULL_HANDLE;
    VkDescriptorSet *sets = calloc(s->draw_count + 1, sizeof *sets);
    buffer *sorted = calloc(s->draw_count + 1, sizeof *sorted);
    double *times = calloc((size_t)frames, sizeof *times);
    bool ok = sets && sorted && times;
    if (!ok) fail(r, "out of memory");
    ok = ok && create_shadow(r, f, s, &sh) && prepare_draws(r, f, s, &sh, &blocks, sorted);
    ok = ok &&
         create_image(r, s->width, s->height, 1, VK_FORMAT_R8G8B8A8_UNORM,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                      VK_IMAGE_ASPECT_COLOR_BIT, &color) &&
         (!ms || create_image_ms(r, s->width, s->height, 4, VK_FORMAT_R8G8B8A8_UNORM,
                                 VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                                 VK_IMAGE_ASPECT_COLOR_BIT, &color_ms)) &&
         create_image_ms(r, s->width, s->height, r->samples, VK_FORMAT_D32_SFLOAT,
                         VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, VK_IMAGE_ASPECT_DEPTH_BIT,
                         &depth) &&
         create_buffer(r, (VkDeviceSize)s->width * s->height * 4,
                       VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       &readback);
    if (ok) {
        VkImageView views[2] = {ms ? color_ms.view : color.view, depth.view};
        VkFramebufferCreateInfo fci = {.sType = VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO,
                                       .renderPass = ms ? r->render_pass_ms : r->render_pass,
                                       .attachmentCount = 2,
                                       .pAttachments = views,
                                       .width = (uint32_t)s->width,
                                       .height = (uint32_t)s->height,
                                       .layers = 1};
        ok = vkCreateFramebuffer(r->device, &fci, NULL, &fb) == VK_SUCCESS ||
             fail(r, "vkCreateFramebuffer failed");
    }
    if (ok && s->draw_count) {
        /* A set per textured draw and per shader draw, whose set has TWIN_TEXTURES images. */
        uint32_t shader_draws = 0;
        for (size_t i = 0; i < s->draw_count; i++) shader_draws += s->draws[i].shader != NULL;
        VkDescriptorPoolSize ps[4] = {
            {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
             (uint32_t)s->draw_count + shader_draws * TWIN_TEXTURES},
            {VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC, 1},
            {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 1},
            {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, shader_draws ? shader_draws : 1}};
        VkDescriptorPoolCreateInfo dpi = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO,
                                          .maxSets = (uint32_t)s->draw_count + 2,
                                          .poolSizeCount = 4,
                                          .pPoolSizes = ps};
        ok = vkCreateDescriptorPool(r->device, &dpi, NULL, &pool) == VK_SUCCESS ||
             fail(r, "vkCreateDescriptorPool failed");
        /* One set for every draw's block: each draw binds it at its own dynamic offset. */
        VkDescriptorSetAllocateInfo cai = {.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                           .descriptorPool = pool,
                                           .descriptorSetCount = 1,
                                           .pSetLayouts = &r->color_layout};
        ok = ok && (vkAllocateDescriptorSets(r->device, &cai, &color_set) == VK_SUCCESS ||
                    fail(r, "vkAllocateDescriptorSets failed"));
        if (ok) {
            VkDescriptorBufferInfo bi = {
                .buffer = blocks.buffer, .offset = 0, .range = sizeof(draw_block)};
            VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                      .dstSet = color_set,
                                      .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC,
                                      .pBufferInfo = &bi};
            vkUpdateDescriptorSets(r->device, 1, &w, 0, NULL);
        }
        /* One set for the map, which every receiver samples. */
        if (ok && s->has_shadow) {
            cai.pSetLayouts = &r->shadow_layout;
            ok = vkAllocateDescriptorSets(r->device, &cai, &sh.set) == VK_SUCCESS ||
                 fail(r, "vkAllocateDescriptorSets failed");
        }
        if (ok && s->has_shadow) {
            VkDescriptorImageInfo ii = {.imageView = sh.map.view,
                                        .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                      .dstSet = sh.set,
                                      .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
                                      .pImageInfo = &ii};
            vkUpdateDescriptorSets(r->device, 1, &w, 0, NULL);
        }
        for (size_t i = 0; ok && i < s->draw_count; i++) {
            const sc_draw *d = &s->draws[i];
            if (d->shader || d->mode != SC_MODE_TEXTURE || d->texture < 0) continue;
            VkDescriptorSetAllocateInfo dai = {.sType =
                                                   VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO,
                                               .descriptorPool = pool,
                                               .descriptorSetCount = 1,
                                               .pSetLayouts = &r->texture_layout};
            ok = vkAllocateDescriptorSets(r->device, &dai, &sets[i]) == VK_SUCCESS ||
                 fail(r, "vkAllocateDescriptorSets failed");
            if (!ok) break;
            VkDescriptorImageInfo ii = {
                .sampler =
                    r->samplers[(int)d->mipmap * 4 + (d->filter == SC_FILTER_BILINEAR ? 2 : 0) +
                                (d->wrap == SC_WRAP_CLAMP ? 1 : 0)],
                .imageView = u->textures[d->texture].view,
                .imageLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
            VkWriteDescriptorSet w = {.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET,
                                      .dstSet = sets[i],
                                      .descriptorCount = 1,
                                      .descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                      .pImageInfo = &ii};
            vkUpdateDescriptorSets(r->device, 1, &w, 0, NULL);
        }
    }
    ok = ok && prepare_twin_sets(r, s, u, pool, &uniforms, sets);
    ok = ok && (!ms || create_resolve(r, s, &color_ms, &readback, &resolve_pool, &resolve_set));
    ok = ok && record_scene(r, f, s, u, fb, color.image, &readback, color_set, sets, sorted, &sh,
                            resolve_set);
    for (int i = 0; ok && i < frames; i++) {
        double t0 = now_ms();
        ok = submit_and_wait(r);
        times[i] = now_ms() - t0;
    }
    if (ok) {
        qsort(times, (size_t)frames, sizeof *times, cmp_double);
        double median =
            frames % 2 ? times[frames / 2] : 0.5 * (times[frames / 2 - 1] + times[frames / 2]);
        char *path = sc_format("%s/%s.png", out_dir, s->name);
        if (!path) {
            ok = fail(r, "out of memory");
        } else {
            ok = sc_image_write_png(path, s->width, s->height, readback.mapped, &r->err);
            free(path);
        }
        if (ok) {
            if (frames > 1)
                printf("%-32s %10.3f ms/frame (median of %d)\n", s->name, median, frames);
            else
                printf("%-32s %10.3f ms/frame\n", s->name, median);
        }
    }
    if (pool) vkDestroyDescriptorPool(r->device, pool, NULL);
    if (resolve_pool) vkDestroyDescriptorPool(r->device, resolve_pool, NULL);
    if (fb) vkDestroyFramebuffer(r->device, fb, NULL);
    destroy_buffer(r, &readback);
    destroy_buffer(r, &blocks);
    destroy_buffer(r, &uniforms);
    for (size_t i = 0; sorted && i < s->draw_count; i++) destroy_buffer(r, &sorted[i]);
    destroy_image(r, &color);
    destroy_image(r, &color_ms);
    destroy_image(r, &depth);
    destroy_shadow(r, &sh);
    free(sets);
    free(sorted);
    free(times);
    return ok;
}

/* What a twin's texture slot that the draw leaves unbound samples: one (0, 0, 0, 1) texel. */
static bool create_blank(ref *r) {
    unsigned char black[4] = {0, 0, 0, 255};
    sc_image img = {.width = 1, .height = 1, .pixels = black};
    return upload_texture(r, &img, false, &r->blank);
}

static void destroy_ref(ref *r) {
    if (r->device) {
        vkDeviceWaitIdle(r->device);
        for (int i = 0; i < r->twin_count; i++) {
            vkDestroyShaderModule(r->device, r->twins[i].vert, NULL);
            vkDestroyShaderModule(r->device, r->twins[i].frag, NULL);
        }
        destroy_image(r, &r->blank);
        if (r->layout_twin) vkDestroyPipelineLayout(r->device, r->layout_twin, NULL);
        if (r->twin_set_layout) vkDestroyDescriptorSetLayout(r->device, r->twin_set_layout, NULL);
        for (int i = 0; i < r->pipeline_count; i++)
            vkDestroyPipeline(r->device, r->pipelines[i].pipeline, NULL);
        if (r->render_pass) vkDestroyRenderPass(r->device, r->render_pass, NULL);
        if (r->render_pass_ms) vkDestroyRenderPass(r->device, r->render_pass_ms, NULL);
        if (r->resolve) vkDestroyPipeline(r->device, r->resolve, NULL);
        if (r->layout_resolve) vkDestroyPipelineLayout(r->device, r->layout_resolve, NULL);
        if (r->resolve_set_layout)
            vkDestroyDescriptorSetLayout(r->device, r->resolve_set_layout, NULL);
        if (r->depth_pass) vkDestroyRenderPass(r->device, r->depth_pass, NULL);
        for (int i = 0; i < 12; i++)
            if (r->samplers[i]) vkDestroySampler(r->device, r->samplers[i], NULL);
        for (int i = 0; i < SH_COUNT; i++)
            if (r->modules[i]) vkDestroyShaderModule(r->device, r->modules[i], NULL);
        if (r->layout_color) vkDestroyPipelineLayout(r->device, r->layout_color, NULL);
        if (r->layout_texture) vkDestroyPipelineLayout(r->device, r->layout_texture, NULL);
        if (r->layout_shadow) vkDestroyPipelineLayout(r->device, r->layout_shadow, NULL);
        if (r->color_layout) vkDestroyDescriptorSetLayout(r->device, r->color_layout, NULL);
        if (r->texture_layout) vkDestroyDescriptorSetLayout(r->device, r->texture_layout, NULL);
        if (r->shadow_layout) vkDestroyDescriptorSetLayout(r->device, r->shadow_layout, NULL);
        if (r->fence) vkDestroyFence(r->device, r->fence, NULL);
        if (r->cmd_pool) vkDestroyCommandPool(r->device, r->cmd_pool, NULL);
        vkDestroyDevice(r->device, NULL);
    }
    if (r->instance) vkDestroyInstance(r->instance, NULL);
    free(r->twins);
    if (r->glslang_ready) glslang_finalize_process();
    sc_msg_free(&r->err);
}

static void usage(FILE *f) {
    fprintf(f, "usage: sgapi-ref [options] SCENE.json... -o DIR\n"
               "Renders every scene with Vulkan on lavapipe to DIR/<scene name>.png and prints\n"
               "each scene's time per frame (submit to completion).\n"
               "  -o DIR          output folder, created if missing (required)\n"
               "  --frames N      render each scene N times and print the median (default 1)\n"
               "  --scene NAME    render only scenes of that name (repeatable)\n"
               "  --threads T     lavapipe's raster threads (sets LP_NUM_THREADS)\n"
               "  --samples N     samples a pixel, 1 or 4, for every scene (default: each\n"
               "                  scene's \"samples\")\n"
               "  --mipmap MODE   every draw's \"mipmap\" (none, nearest, linear), whatever the\n"
               "                  scenes say\n"
               "  --shaders LIB.so\n"
               "                  load the shaders of a shader library (a shared object\n"
               "                  exporting sgapi_shader_library; repeatable): scene files\n"
               "                  name them with \"shader\", their GLSL twins render them\n"
               "  --strict        an unknown key in a scene file is an error (exit 1, nothing\n"
               "                  rendered), not a warning\n"
               "  -h, --help      show this help\n");
}

static bool make_dir(const char *path) {
    size_t n = strlen(path);
    char *buf = n ? sc_format("%s", path) : NULL;
    if (!buf) return false;
    bool ok = true;
    for (size_t i = 1; i <= n && ok; i++)
        if (buf[i] == '/' || buf[i] == '\0') {
            char c = buf[i];
            buf[i] = '\0';
            if (mkdir(buf, 0777) != 0 && errno != EEXIST) ok = false;
            buf[i] = c;
        }
    free(buf);
    struct stat st;
    return ok && stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* Loads a scene file and checks its shader draws against the known shaders; on failure prints
 * why and returns the exit status (1: the file, 2: a shader draw), else 0. */
static int load_file(const char *path, const sc_shaders *shaders, int mipmap, sc_file *f) {
    sc_msg err = {0};
    int status = 0;
    if (!sc_load(path, f, &err)) {
        status = 1;
    } else if (!sc_shaders_check(shaders, f, &err)) {
        sc_free(f);
        status = 2;
    } else if (mipmap >= 0) {
        sc_override_mipmap(f, (sc_mipmap)mipmap); /* --mipmap: every draw's, whatever it says */
    }
    if (status) fprintf(stderr, "sgapi-ref: %s\n", sc_msg_text(&err));
    sc_msg_free(&err);
    return status;
}

int main(int argc, char **argv) {
    const char *out_dir = NULL;
    const char **files = calloc((size_t)argc, sizeof *files);
    const char **only = calloc((size_t)argc, sizeof *only);
    const char **libs = calloc((size_t)argc, sizeof *libs);
    int nfiles = 0, nonly = 0, nlibs = 0, frames = 1, mipmap = -1;
    bool strict = false;
    int samples = 0; /* --samples: every scene's (0: as the scenes say) */
    if (!files || !only || !libs) return 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        bool more = i + 1 < argc;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 0;
        } else if (!strcmp(a, "-o") && more) {
            out_dir = argv[++i];
        } else if (!strcmp(a, "--frames") && more) {
            if (!sc_parse_int(argv[++i], 1, 100000, &frames)) {
                fprintf(stderr, "sgapi-ref: --frames wants 1..100000, got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--samples") && more) {
            if (!sc_parse_samples(argv[++i], &samples)) {
                fprintf(stderr, "sgapi-ref: --samples wants 1 or 4, got '%s'\n", argv[i]);
                return 2;
            }
        } else if (!strcmp(a, "--strict")) {
            strict = true;
        } else if (!strcmp(a, "--scene") && more) {
            only[nonly++] = argv[++i];
        } else if (!strcmp(a, "--shaders") && more) {
            libs[nlibs++] = argv[++i];
        } else if (!strcmp(a, "--mipmap") && more) {
            sc_mipmap m;
            if (!sc_mipmap_from_name(argv[++i], &m)) {
                fprintf(stderr, "sgapi-ref: --mipmap wants none, nearest or linear, got '%s'\n",
                        argv[i]);
                return 2;
            }
            mipmap = (int)m;
        } else if (!strcmp(a, "--threads") && more) {
            int threads;
            if (!sc_parse_int(argv[++i], 0, 1024, &threads)) {
                fprintf(stderr, "sgapi-ref: --threads wants 0..1024, got '%s'\n", argv[i]);
                return 2;
            }
            /* lavapipe reads it when its device is created. */
            setenv("LP_NUM_THREADS", argv[i], 1);
        } else if (a[0] == '-') {
            fprintf(stderr, "sgapi-ref: unknown option or missing value: %s\n", a);
            usage(stderr);
            return 2;
        } else {
            files[nfiles++] = a;
        }
    }
    if (!out_dir || nfiles == 0) {
        usage(stderr);
        return 2;
    }
    /* The shaders scene files may name: the built-in ones and the libraries given. */
    sc_shaders *shaders = NULL;
    sc_msg err = {0};
    if (!sc_shaders_prepare(&shaders, SG_SIMD_DEFAULT, libs, nlibs, NULL, 0, &err)) {
        fprintf(stderr, "sgapi-ref: %s\n", sc_msg_text(&err));
        sc_msg_free(&err);
        return 2;
    }
    /* Files are rendered one after the other; every file is checked first, so that a shader
     * draw that does not fit its shader (exit 2), or with --strict an unknown key, in the last
     * stops the run before the first is rendered. */
    for (int fi = 0; fi < nfiles; fi++) {
        sc_file f;
        int bad = load_file(files[fi], shaders, mipmap, &f);
        if (bad) {
            sc_shaders_close(shaders);
            return bad;
        }
        bool clean = !strict || sc_report_warnings(&f, "sgapi-ref", true);
        sc_free(&f);
        if (!clean) {
            sc_shaders_close(shaders);
            return 1;
        }
    }
    if (!make_dir(out_dir)) {
        fprintf(stderr, "sgapi-ref: cannot create output folder %s: %s\n", out_dir,
                strerror(errno));
        sc_shaders_close(shaders);
        return 1;
    }
    ref *r = calloc(1, sizeof *r);
    if (!r) return 1;
    r->shaders = shaders;
    int status = 0;
    if (!create_instance(r) || !create_device(r) || !create_shaders_and_layouts(r) ||
        !create_blank(r)) {
        fprintf(stderr, "sgapi-ref: %s\n", sc_msg_text(&r->err));
        destroy_ref(r);
        free(r);
        sc_shaders_close(shaders);
        return 1;
    }
    for (int fi = 0; fi < nfiles && !status; fi++) {
        sc_file f;
        status = load_file(files[fi], shaders, mipmap, &f);
        if (status) break;
        if (samples) sc_set_samples(&f, samples);
        if (!strict) sc_report_warnings(&f, "sgapi-ref", false);
        uploads u = {0};
        if (!upload_file(r, &f, &u)) {
            fprintf(stderr, "sgapi-ref: %s: %s\n", files[fi], sc_msg_text(&r->err));
            status = 1;
        }
        /* Every twin the file's draws run, compiled before its first scene renders. */
        for (size_t si = 0; !status && si < f.scene_count; si++)
            for (size_t di = 0; !status && di < f.scenes[si].draw_count; di++) {
                const sc_draw *d = &f.scenes[si].draws[di];
                int t;
                if (d->shader && !get_twin(r, d->shader, &t)) {
                    fprintf(stderr, "sgapi-ref: %s: scene %s, draw %zu: %s\n", files[fi],
                            f.scenes[si].name, di, sc_msg_text(&r->err));
                    status = 1;
                }
            }
        for (size_t si = 0; !status && si < f.scene_count; si++) {
            const sc_scene *s = &f.scenes[si];
            bool want = nonly == 0;
            for (int k = 0; k < nonly; k++) want |= strcmp(only[k], s->name) == 0;
            if (!want) continue;
            if (!render_scene(r, &f, s, &u, out_dir, frames)) {
                fprintf(stderr, "sgapi-ref: %s: scene %s: %s\n", files[fi], s->name,
                        sc_msg_text(&r->err));
                status = 1;
            }
        }
        destroy_uploads(r, &u);
        sc_free(&f);
    }
    destroy_ref(r);
    free(r);
    sc_shaders_close(shaders);
    free(files);
    free(only);
    free(libs);
    return status;
}
