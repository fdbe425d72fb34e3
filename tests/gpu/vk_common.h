/* vk_common.h - the Vulkan setup shared by the project's Vulkan hosts: tests/gpu/vk_run.c (the
   GLSL evaluators on a compute queue) and bench/frame/frame.c (the scenes rendered through a
   graphics pipeline). Test and bench code, not part of the library; C99, static functions.

   What it does: creates the instance, picks the physical device, creates the logical device with
   one queue of the requested kind and the requested features, finds memory types, makes host-
   visible buffers and loads SPIR-V shader modules. Errors stop the program (exit 2) with a
   message naming the call, as a test host should.

   Device choice: PF_VK_DEVICE=N (the N-th device Vulkan enumerates, from 0) or PF_VK_DEVICE=text
   (the first whose name contains text, case-sensitive); default the first device. Under
   tests/gpu/run.sh and bench/frame the loader is pointed at lavapipe (VK_ICD_FILENAMES), which
   then is the only device; leave those unset to reach a real GPU. */
#ifndef PF_VK_COMMON_H
#define PF_VK_COMMON_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vulkan/vulkan.h>

#define VKC(x)                                                                                   \
    do {                                                                                         \
        VkResult r_ = (x);                                                                       \
        if (r_ != VK_SUCCESS) {                                                                  \
            fprintf(stderr, "vulkan: %s failed (%d) at %s:%d\n", #x, (int)r_, __FILE__, __LINE__); \
            exit(2);                                                                             \
        }                                                                                        \
    } while (0)

typedef struct {
    VkInstance inst;
    VkPhysicalDevice phys;
    VkDevice dev;
    VkQueue queue;
    uint32_t qfam;
    VkPhysicalDeviceProperties props;
    VkPhysicalDeviceFeatures features; /* what the device offers (not what was enabled) */
    int is_cpu;                        /* VK_PHYSICAL_DEVICE_TYPE_CPU (lavapipe): no GPU timing */
    char name[512];                    /* "name (Vulkan x.y.z, driver 0x...)" */
} pfvk_ctx;

/* Opens the device: a queue family with every bit of queue_flags, and the features of
   *enable (NULL: none; the caller checks ctx->features first, e.g. samplerAnisotropy, through
   pfvk_probe). */
static void pfvk_open_device(pfvk_ctx *c, const VkPhysicalDeviceFeatures *enable, VkQueueFlags queue_flags)
{
    VkQueueFamilyProperties qf[16];
    uint32_t n = 16, i;
    float prio = 1.0f;
    VkDeviceQueueCreateInfo qci;
    VkDeviceCreateInfo dci;
    vkGetPhysicalDeviceQueueFamilyProperties(c->phys, &n, NULL);
    if (n > 16) n = 16;
    vkGetPhysicalDeviceQueueFamilyProperties(c->phys, &n, qf);
    for (i = 0; i < n; i++) if ((qf[i].queueFlags & queue_flags) == queue_flags) break;
    if (i == n) { fprintf(stderr, "vulkan: %s has no queue family with flags 0x%x\n", c->name, (unsigned)queue_flags); exit(2); }
    c->qfam = i;
    memset(&qci, 0, sizeof qci);
    qci.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
    qci.queueFamilyIndex = c->qfam;
    qci.queueCount = 1;
    qci.pQueuePriorities = &prio;
    memset(&dci, 0, sizeof dci);
    dci.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
    dci.queueCreateInfoCount = 1;
    dci.pQueueCreateInfos = &qci;
    dci.pEnabledFeatures = enable;
    VKC(vkCreateDevice(c->phys, &dci, NULL, &c->dev));
    vkGetDeviceQueue(c->dev, c->qfam, 0, &c->queue);
}

/* Instance and physical device (PF_VK_DEVICE, above); fills props, features, is_cpu, name. */
static void pfvk_probe(pfvk_ctx *c, const char *app_name)
{
    VkApplicationInfo app;
    VkInstanceCreateInfo ici;
    VkPhysicalDevice devs[16];
    uint32_t n = 0, i, pick = 0;
    const char *want = getenv("PF_VK_DEVICE");
    memset(c, 0, sizeof *c);
    memset(&app, 0, sizeof app);
    app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
    app.pApplicationName = app_name;
    app.apiVersion = VK_API_VERSION_1_0;
    memset(&ici, 0, sizeof ici);
    ici.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
    ici.pApplicationInfo = &app;
    VKC(vkCreateInstance(&ici, NULL, &c->inst));
    VKC(vkEnumeratePhysicalDevices(c->inst, &n, NULL));
    if (n == 0) { fprintf(stderr, "vulkan: no Vulkan device (is VK_ICD_FILENAMES set to lvp_icd?)\n"); exit(2); }
    if (n > 16) n = 16;
    VKC(vkEnumeratePhysicalDevices(c->inst, &n, devs));
    if (want && *want) {
        char *end;
        long k = strtol(want, &end, 10);
        if (*end == '\0') {
            if (k < 0 || k >= (long)n) { fprintf(stderr, "vulkan: PF_VK_DEVICE=%s: only %u devices\n", want, n); exit(2); }
            pick = (uint32_t)k;
        } else {
            for (i = 0; i < n; i++) {
                VkPhysicalDeviceProperties p;
                vkGetPhysicalDeviceProperties(devs[i], &p);
                if (strstr(p.deviceName, want)) break;
            }
            if (i == n) { fprintf(stderr, "vulkan: PF_VK_DEVICE=%s: no device name contains it\n", want); exit(2); }
            pick = i;
        }
    }
    c->phys = devs[pick];
    vkGetPhysicalDeviceProperties(c->phys, &c->props);
    vkGetPhysicalDeviceFeatures(c->phys, &c->features);
    c->is_cpu = c->props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
    snprintf(c->name, sizeof c->name, "%.200s (Vulkan %u.%u.%u, driver 0x%x)", c->props.deviceName,
             VK_VERSION_MAJOR(c->props.apiVersion), VK_VERSION_MINOR(c->props.apiVersion),
             VK_VERSION_PATCH(c->props.apiVersion), c->props.driverVersion);
}

static uint32_t pfvk_find_memory(const pfvk_ctx *c, uint32_t bits, VkMemoryPropertyFlags want)
{
    VkPhysicalDeviceMemoryProperties mp;
    uint32_t i;
    vkGetPhysicalDeviceMemoryProperties(c->phys, &mp);
    for (i = 0; i < mp.memoryTypeCount; i++)
        if ((bits & (1u << i)) && (mp.memoryTypes[i].propertyFlags & want) == want) return i;
    fprintf(stderr, "vulkan: no memory type with properties 0x%x\n", (unsigned)want);
    exit(2);
}

/* Memory of the given properties bound to image or buffer (one of them VK_NULL_HANDLE). */
static VkDeviceMemory pfvk_bind_memory(const pfvk_ctx *c, VkBuffer b, VkImage im, VkMemoryPropertyFlags want)
{
    VkMemoryRequirements mr;
    VkMemoryAllocateInfo ai;
    VkDeviceMemory m;
    if (b != VK_NULL_HANDLE) vkGetBufferMemoryRequirements(c->dev, b, &mr);
    else vkGetImageMemoryRequirements(c->dev, im, &mr);
    memset(&ai, 0, sizeof ai);
    ai.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
    ai.allocationSize = mr.size;
    ai.memoryTypeIndex = pfvk_find_memory(c, mr.memoryTypeBits, want);
    VKC(vkAllocateMemory(c->dev, &ai, NULL, &m));
    if (b != VK_NULL_HANDLE) VKC(vkBindBufferMemory(c->dev, b, m, 0));
    else VKC(vkBindImageMemory(c->dev, im, m, 0));
    return m;
}

/* A host-visible, coherent buffer of `size` bytes, mapped at *map. */
static void pfvk_host_buffer(const pfvk_ctx *c, VkDeviceSize size, VkBufferUsageFlags usage, VkBuffer *b,
                             VkDeviceMemory *m, void **map)
{
    VkBufferCreateInfo bi;
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
    bi.size = size;
    bi.usage = usage;
    bi.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    VKC(vkCreateBuffer(c->dev, &bi, NULL, b));
    *m = pfvk_bind_memory(c, *b, VK_NULL_HANDLE, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    VKC(vkMapMemory(c->dev, *m, 0, VK_WHOLE_SIZE, 0, map));
}

/* A shader module from a SPIR-V file; stops with a message when it cannot be read. */
static VkShaderModule pfvk_shader_module(const pfvk_ctx *c, const char *path)
{
    FILE *f = fopen(path, "rb");
    long size;
    uint32_t *code;
    VkShaderModuleCreateInfo smci;
    VkShaderModule sm;
    if (!f) { fprintf(stderr, "vulkan: no SPIR-V %s\n", path); exit(2); }
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fseek(f, 0, SEEK_SET);
    code = (uint32_t *)malloc((size_t)size + 4u);
    if (!code || size <= 0 || fread(code, 1, (size_t)size, f) != (size_t)size) { fprintf(stderr, "vulkan: cannot read %s\n", path); exit(2); }
    fclose(f);
    memset(&smci, 0, sizeof smci);
    smci.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
    smci.codeSize = (size_t)size;
    smci.pCode = code;
    VKC(vkCreateShaderModule(c->dev, &smci, NULL, &sm));
    free(code);
    return sm;
}

#endif /* PF_VK_COMMON_H */
