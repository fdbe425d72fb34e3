/* vk_run.c - runs the GLSL form of every public evaluator on a Vulkan driver (lavapipe in
   `make portability`) and compares it, element by element, with the C float and double builds.

   usage: vk_run DOMAINS SPV_DIR [RESULTS_MD]
     DOMAINS   tests/gpu/domains.txt (input domain of every slot, per-function options)
     SPV_DIR   one SPIR-V module per header, pf_x.spv (tests/gpu/run.sh compiles them from the
               shaders tests/gpu/gen.awk writes)
     RESULTS_MD  optional: the per-function table (markdown) for docs/gpu.md
   Environment: PFG_N (domain samples per function, default 4096), PFG_EDGE (edge samples,
   default 1024), PFG_SEED (default 20), PFG_ONLY (run the functions whose name contains it), PFG_DUMP
   (list every domain sample of the functions whose name contains it on stderr: inputs, then
   per output GPU, double, C float).

   Per function: PFG_N inputs drawn from the domain table, and PFG_EDGE inputs where each slot
   is, with probability 1/2, one of 0, -0, +-1e-40 (subnormal), +-FLT_MIN, +-1e30, +-FLT_MAX,
   +-inf or NaN. The same float inputs go to the GPU, to the C float build, to the C double build
   (the reference) and to the emulated driver (pfg_fns.h): the C float build whose every libm
   call is perturbed by the most the GLSL 4.50 / Vulkan precision rules allow, run three times
   (all errors up, all down, a seeded random sign per call) with subnormals flushed (FTZ/DAZ),
   and, where the CPU has FMA, compiled with -mfma -ffp-contract=fast (a*b+c fused where the
   compiler likes, as a shader compiler may: SPIR-V without NoContraction).
   On domain inputs, with err(v) = |v - ref| / max(|ref|, floor) (floor: 1e-30 for `rel`
   functions, else 1e-6 x the output's rms), and the GPU's error taken after subtracting 4 x
   what a one-ulp move of the inputs changes the double result (the rounding scale of a
   backward-stable rearrangement, which matters only where the result cancels), a function
   passes when its GPU error is within
     bound = err(C float) + 2 x max|emulated - C float| / max(|ref|, floor) + 4 x 2^-23
   (the C float build's own error, twice what the allowed libm errors, flushing and contraction
   move it, and
   4 ulp of slack), and within the table's cap= target.
   On edge inputs the class of each result (NaN, +inf, -inf, finite) is compared with the C
   float build's and the emulated driver's: where every input is finite and at most 1e30 in
   magnitude and C's result is finite, the GPU's must be finite too; for `strict` functions (the docs promise an answer
   for NaN and inf inputs) every class must match; other mismatches are counted and listed.
   Each line shows the output with the largest GPU error / bound (and for several outputs the
   maxima over them); RESULTS_MD lists the maxima over outputs and that worst ratio.
   Prints one line per function, "RESULT <passed> <failed>", exits 1 on any failure. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "vk_common.h"
#if defined(__SSE__) || defined(__x86_64__)
#  include <xmmintrin.h>
#  define PFG_HAVE_FTZ 1
#endif
#include "pfg_fns.h"
#include "pyr_domains.h"

/* ------------------------------------------------------------------ emulated driver */
static int emu_mode;            /* +1, -1, 0: random sign per call */
static uint32_t emu_state = 1u;
#define ULP (1.0 / 8388608.0)   /* 2^-23: one ulp relative to a float, at most */

static double emu_sign(void)
{
    if (emu_mode) return emu_mode;
    emu_state = emu_state * 1664525u + 1013904223u;
    return (emu_state >> 31) ? 1.0 : -1.0;
}
/* exp, exp2: (3 + 2|x|) ULP */
float pfg_emu_exp(float x)
{
    double r = exp((double)x);
    return (float)(r * (1.0 + emu_sign() * (3.0 + 2.0 * fabs((double)x)) * ULP));
}
/* log: 3 ULP outside [0.5, 2], absolute 2^-21 inside */
float pfg_emu_log(float x)
{
    double r = log((double)x);
    if (x >= 0.5f && x <= 2.0f) return (float)(r + emu_sign() * ldexp(1.0, -21));
    return (float)(r * (1.0 + emu_sign() * 3.0 * ULP));
}
/* pow: inherited from exp2(y log2(x)): log2's error times |y|, the product's rounding, exp2's
   (3 + 2|t|) ULP */
float pfg_emu_pow(float x, float y)
{
    double r = pow((double)x, (double)y), l2 = log2((double)x), t = (double)y * l2;
    double dl = (x >= 0.5f && x <= 2.0f) ? ldexp(1.0, -21) : 3.0 * ULP * fabs(l2);
    double rel = (fabs((double)y) * dl + fabs(t) * ULP / 2.0) * 0.6931471805599453 + (3.0 + 2.0 * fabs(t)) * ULP;
    if (!(fabs(t) < 1e30)) return (float)r;
    return (float)(r * (1.0 + emu_sign() * rel));
}
/* sqrt: inherited from 1 / inversesqrt(x): 2 ULP + 2.5 ULP */
float pfg_emu_sqrt(float x) { return (float)(sqrt((double)x) * (1.0 + emu_sign() * 4.5 * ULP)); }
/* sin, cos: absolute 2^-11 (Vulkan, inside [-pi, pi]; taken everywhere) */
float pfg_emu_sin(float x) { return (float)(sin((double)x) + emu_sign() * ldexp(1.0, -11)); }
float pfg_emu_cos(float x) { return (float)(cos((double)x) + emu_sign() * ldexp(1.0, -11)); }

/* ------------------------------------------------------------------ domains */
typedef struct { char kind[4]; double a, b; } domain;
typedef struct { char name[64]; domain d; } param;
typedef struct {
    char name[64];
    int rel, strict, tight;
    double cap;
    int nslot;
    param slot[24];
} fnopt;

static param params[256];
static int nparams;
/* `unit NAME` lines: vectors (slots NAME.x, NAME.y, NAME.z) drawn as unit directions */
static char units[32][48];
static int nunits;
static fnopt fnopts[256];
static int nfnopts;
/* `at` lines: one input (unnamed slots 0), one output's documented value (see domains.txt) */
typedef struct {
    char name[64];
    int out, nslot;
    double expect, tol;
    char slot[12][64];
    float val[12];
} atcheck;
static atcheck ats[64];
static int nats;
static int need_hz, need_vm; /* a domain names hz(k) / vm(k): build the pyramids */
static int cur_pyr;           /* the current function draws from them: a record per sample */

static int parse_domain(const char *s, domain *d)
{
    char k[8];
    double a = 0.0, b = 0.0;
    int n;
    if (sscanf(s, "%7[a-z](%lf,%lf)", k, &a, &b) == 3) n = 3;
    else if (sscanf(s, "%7[a-z](%lf)", k, &a) == 2) n = 2;
    else return 0;
    if (strlen(k) > 3) return 0;
    strcpy(d->kind, k);
    d->a = a;
    d->b = n == 3 ? b : a;
    if (!strcmp(k, "n")) { d->b = a; d->a = 0.0; }
    if (!strcmp(k, "hz")) { need_hz = 1; return a >= 0.0 && a < HZ_COUNT; }
    if (!strcmp(k, "vm")) { need_vm = 1; return a >= 0.0 && a < VM_COUNT; }
    return !strcmp(k, "mom") || !strcmp(k, "qm") || !strcmp(k, "u") || !strcmp(k, "lu") || !strcmp(k, "slu") || !strcmp(k, "n") || !strcmp(k, "i") ||
           !strcmp(k, "c");
}

static int read_domains(const char *path)
{
    char line[1024];
    int ln = 0;
    FILE *f = fopen(path, "r");
    if (!f) { fprintf(stderr, "vk_run: cannot open %s\n", path); return 0; }
    while (fgets(line, sizeof line, f)) {
        char *tok, *save = NULL;
        ln++;
        tok = strtok_r(line, " \t\r\n", &save);
        if (!tok || tok[0] == '#') continue;
        if (!strcmp(tok, "unit")) {
            char *nm = strtok_r(NULL, " \t\r\n", &save);
            if (!nm || nunits >= 32) goto bad;
            snprintf(units[nunits++], sizeof units[0], "%s", nm);
        } else if (!strcmp(tok, "param")) {
            char *nm = strtok_r(NULL, " \t\r\n", &save), *dm = strtok_r(NULL, " \t\r\n", &save);
            if (!nm || !dm || nparams >= 256 || !parse_domain(dm, &params[nparams].d)) goto bad;
            snprintf(params[nparams].name, sizeof params[0].name, "%s", nm);
            nparams++;
        } else if (!strcmp(tok, "at")) {
            atcheck *a = &ats[nats];
            char *nm = strtok_r(NULL, " \t\r\n", &save), *ou = strtok_r(NULL, " \t\r\n", &save);
            char *ex = strtok_r(NULL, " \t\r\n", &save), *tl = strtok_r(NULL, " \t\r\n", &save);
            if (!nm || !ou || !ex || !tl || nats >= 64) goto bad;
            memset(a, 0, sizeof *a);
            snprintf(a->name, sizeof a->name, "%s", nm);
            a->out = atoi(ou);
            a->expect = strtod(ex, NULL);
            a->tol = strtod(tl, NULL);
            while ((tok = strtok_r(NULL, " \t\r\n", &save)) != NULL) {
                char *eq = strchr(tok, '=');
                if (!eq || a->nslot >= 12) goto bad;
                *eq = '\0';
                snprintf(a->slot[a->nslot], sizeof a->slot[0], "%s", tok);
                a->val[a->nslot++] = strtof(eq + 1, NULL);
            }
            nats++;
        } else if (!strcmp(tok, "fn")) {
            fnopt *o = &fnopts[nfnopts];
            char *nm = strtok_r(NULL, " \t\r\n", &save);
            if (!nm || nfnopts >= 256) goto bad;
            memset(o, 0, sizeof *o);
            snprintf(o->name, sizeof o->name, "%s", nm);
            while ((tok = strtok_r(NULL, " \t\r\n", &save)) != NULL) {
                char *eq = strchr(tok, '=');
                if (!strcmp(tok, "rel")) o->rel = 1;
                else if (!strcmp(tok, "strict")) o->strict = 1;
                else if (!strcmp(tok, "tight")) o->tight = 1;
                else if (!strncmp(tok, "cap=", 4)) o->cap = atof(tok + 4);
                else if (eq && o->nslot < 24) {
                    *eq = '\0';
                    snprintf(o->slot[o->nslot].name, sizeof o->slot[0].name, "%s", tok);
                    if (!parse_domain(eq + 1, &o->slot[o->nslot].d)) goto bad;
                    o->nslot++;
                } else goto bad;
            }
            nfnopts++;
        } else goto bad;
    }
    fclose(f);
    return 1;
bad:
    fprintf(stderr, "vk_run: %s:%d: cannot read this line\n", path, ln);
    fclose(f);
    return 0;
}

static const fnopt *find_opt(const char *fn)
{
    int i;
    for (i = 0; i < nfnopts; i++) if (!strcmp(fnopts[i].name, fn)) return &fnopts[i];
    return NULL;
}

/* the domain of a slot: its path with array indices removed (m.mu[3].z -> m.mu.z), then each
   shorter suffix (mu.z, z), first in the function's own entries, then in the params */
static domain slot_domain(const fnopt *o, const char *path)
{
    domain d = { "u", 0.0, 1.0 };
    char norm[128];
    const char *suf;
    size_t n = 0;
    int i;
    for (; *path && n + 1 < sizeof norm; path++) {
        if (*path == '[') { while (*path && *path != ']') path++; if (!*path) break; continue; }
        norm[n++] = *path;
    }
    norm[n] = '\0';
    for (suf = norm; suf; suf = strchr(suf, '.') ? strchr(suf, '.') + 1 : NULL) {
        if (o) for (i = 0; i < o->nslot; i++) if (!strcmp(o->slot[i].name, suf)) return o->slot[i].d;
        for (i = 0; i < nparams; i++) if (!strcmp(params[i].name, suf)) return params[i].d;
    }
    return d;
}

/* ------------------------------------------------------------------ seeded random numbers */
static uint64_t rng_state;
static double rnd(void) /* [0, 1) */
{
    rng_state = rng_state * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}
static double rnd_normal(void)
{
    double u = rnd(), v = rnd();
    return sqrt(-2.0 * log(1.0 - u)) * cos(6.283185307179586 * v);
}
/* mom(k): the k-th raw moment of the sample's depth mixture, sum_i w_i z_i^k over three depths
   with weights drawn once per sample (new_sample), so the slots of one texel form valid moments
   whose Hankel matrix (4 moments, 3 atoms) is not singular */
static double mix_z[3], mix_w[3];
static void new_sample(void)
{
    double t = 0.0;
    int i;
    for (i = 0; i < 3; i++) { mix_z[i] = rnd(); mix_w[i] = 0.05 + rnd(); t += mix_w[i]; }
    for (i = 0; i < 3; i++) mix_w[i] /= t;
    if (cur_pyr) pyr_draw(rnd);
}
/* qm(k): component k of the same moments as a 64-bit MSM texel stores them, Theta b + o
   (Peters & Klein 2015's optimized quantization, pf_msm_quantize_moments), unrounded */
static double mix_mom(int k)
{
    return mix_w[0] * pow(mix_z[0], k) + mix_w[1] * pow(mix_z[1], k) + mix_w[2] * pow(mix_z[2], k);
}
static float draw(domain d)
{
    if (!strcmp(d.kind, "mom"))
        return (float)(mix_w[0] * pow(mix_z[0], d.a) + mix_w[1] * pow(mix_z[1], d.a) + mix_w[2] * pow(mix_z[2], d.a));
    if (!strcmp(d.kind, "qm")) {
        static const double theta[4][4] = { { -2.07224649, 32.23703778, -68.571074599, 39.3703274134 },
                                            { 13.7948857237, -59.4683975703, 82.0359750338, -35.364903257 },
                                            { 0.105877704, -1.9077466311, 9.3496555107, -6.6543490743 },
                                            { 9.7924062118, -33.7652110555, 47.9456096605, -23.9728048165 } };
        int r = (int)d.a - 1, j;
        double q = r == 0 ? 0.035955884801 : 0.0;
        if (r < 0 || r > 3) return 0.0f;
        for (j = 0; j < 4; j++) q += theta[r][j] * mix_mom(j + 1);
        return (float)q;
    }
    if (!strcmp(d.kind, "hz")) return (float)pyr_hz_rec[(int)d.a];
    if (!strcmp(d.kind, "vm")) return (float)pyr_vm_rec[(int)d.a];
    if (!strcmp(d.kind, "u")) return (float)(d.a + (d.b - d.a) * rnd());
    if (!strcmp(d.kind, "lu")) return (float)exp(log(d.a) + (log(d.b) - log(d.a)) * rnd());
    if (!strcmp(d.kind, "slu")) return (float)((rnd() < 0.5 ? -1.0 : 1.0) * exp(log(d.a) + (log(d.b) - log(d.a)) * rnd()));
    if (!strcmp(d.kind, "n")) return (float)(d.b * rnd_normal());
    if (!strcmp(d.kind, "i")) return (float)floor(d.a + (d.b - d.a + 1.0) * rnd());
    return (float)d.a;
}
static float draw_edge(void)
{
    static const float e[] = { 0.0f, -0.0f, 1e-40f, -1e-40f, FLT_MIN, -FLT_MIN, 1e30f, -1e30f, FLT_MAX,
                               -FLT_MAX, 0.0f, 0.0f, 0.0f };
    int k = (int)(rnd() * 13.0);
    if (k == 10) return INFINITY;
    if (k == 11) return -INFINITY;
    if (k == 12) return NAN;
    return e[k];
}

/* ------------------------------------------------------------------ Vulkan */

static pfvk_ctx vk;            /* instance, device, queue (vk_common.h) */
static VkDevice dev;
static VkQueue queue;
static uint32_t qfam;
static VkDescriptorSetLayout dsl;
static VkPipelineLayout playout;
static VkDescriptorPool dpool;
static VkDescriptorSet dset;
static VkCommandPool cpool;
static VkCommandBuffer cmd;
static VkFence fence;
static VkBuffer buf_in, buf_out;
static VkDeviceMemory mem_in, mem_out;
static float *map_in, *map_out;
static const char *device_name = vk.name;

static void make_buffer(VkDeviceSize size, VkBuffer *b, VkDeviceMemory *m, float **map)
{
    void *p;
    pfvk_host_buffer(&vk, size, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, b, m, &p);
    *map = (float *)p;
}

static void vk_init(size_t in_floats, size_t out_floats)
{
    uint32_t i;
    VkDescriptorSetLayoutBinding bind[2];
    VkDescriptorSetLayoutCreateInfo dlci;
    VkPushConstantRange pcr;
    VkPipelineLayoutCreateInfo plci;
    VkDescriptorPoolSize ps;
    VkDescriptorPoolCreateInfo dpci;
    VkDescriptorSetAllocateInfo dsai;
    VkDescriptorBufferInfo dbi[2];
    VkWriteDescriptorSet wr[2];
    VkCommandPoolCreateInfo cpci;
    VkCommandBufferAllocateInfo cbai;
    VkFenceCreateInfo fci;

    pfvk_probe(&vk, "prefilter vk_run");
    pfvk_open_device(&vk, NULL, VK_QUEUE_COMPUTE_BIT);
    dev = vk.dev;
    queue = vk.queue;
    qfam = vk.qfam;

    memset(bind, 0, sizeof bind);
    for (i = 0; i < 2; i++) {
        bind[i].binding = i;
        bind[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        bind[i].descriptorCount = 1;
        bind[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    }
    memset(&dlci, 0, sizeof dlci);
    dlci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO;
    dlci.bindingCount = 2;
    dlci.pBindings = bind;
    VKC(vkCreateDescriptorSetLayout(dev, &dlci, NULL, &dsl));
    pcr.stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
    pcr.offset = 0;
    pcr.size = 8;
    memset(&plci, 0, sizeof plci);
    plci.sType = VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO;
    plci.setLayoutCount = 1;
    plci.pSetLayouts = &dsl;
    plci.pushConstantRangeCount = 1;
    plci.pPushConstantRanges = &pcr;
    VKC(vkCreatePipelineLayout(dev, &plci, NULL, &playout));

    make_buffer((VkDeviceSize)in_floats * 4u, &buf_in, &mem_in, &map_in);
    make_buffer((VkDeviceSize)out_floats * 4u, &buf_out, &mem_out, &map_out);

    ps.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    ps.descriptorCount = 2;
    memset(&dpci, 0, sizeof dpci);
    dpci.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO;
    dpci.maxSets = 1;
    dpci.poolSizeCount = 1;
    dpci.pPoolSizes = &ps;
    VKC(vkCreateDescriptorPool(dev, &dpci, NULL, &dpool));
    memset(&dsai, 0, sizeof dsai);
    dsai.sType = VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO;
    dsai.descriptorPool = dpool;
    dsai.descriptorSetCount = 1;
    dsai.pSetLayouts = &dsl;
    VKC(vkAllocateDescriptorSets(dev, &dsai, &dset));
    dbi[0].buffer = buf_in; dbi[0].offset = 0; dbi[0].range = VK_WHOLE_SIZE;
    dbi[1].buffer = buf_out; dbi[1].offset = 0; dbi[1].range = VK_WHOLE_SIZE;
    memset(wr, 0, sizeof wr);
    for (i = 0; i < 2; i++) {
        wr[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
        wr[i].dstSet = dset;
        wr[i].dstBinding = i;
        wr[i].descriptorCount = 1;
        wr[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        wr[i].pBufferInfo = &dbi[i];
    }
    vkUpdateDescriptorSets(dev, 2, wr, 0, NULL);

    memset(&cpci, 0, sizeof cpci);
    cpci.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
    cpci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cpci.queueFamilyIndex = qfam;
    VKC(vkCreateCommandPool(dev, &cpci, NULL, &cpool));
    memset(&cbai, 0, sizeof cbai);
    cbai.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
    cbai.commandPool = cpool;
    cbai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cbai.commandBufferCount = 1;
    VKC(vkAllocateCommandBuffers(dev, &cbai, &cmd));
    memset(&fci, 0, sizeof fci);
    fci.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
    VKC(vkCreateFence(dev, &fci, NULL, &fence));
}

/* one pipeline per header shader, made when first needed */
typedef struct { char header[64]; VkPipeline pipe; } hpipe;
static hpipe pipes[64];
static int npipes;

static VkPipeline pipeline_for(const char *spv_dir, const char *header)
{
    char path[1024];
    VkShaderModule sm;
    VkComputePipelineCreateInfo cpi;
    VkPipeline p;
    int i;
    for (i = 0; i < npipes; i++) if (!strcmp(pipes[i].header, header)) return pipes[i].pipe;
    snprintf(path, sizeof path, "%s/%.*s.spv", spv_dir, (int)(strlen(header) - 2), header);
    sm = pfvk_shader_module(&vk, path);
    memset(&cpi, 0, sizeof cpi);
    cpi.sType = VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO;
    cpi.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    cpi.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    cpi.stage.module = sm;
    cpi.stage.pName = "main";
    cpi.layout = playout;
    VKC(vkCreateComputePipelines(dev, VK_NULL_HANDLE, 1, &cpi, NULL, &p));
    vkDestroyShaderModule(dev, sm, NULL);
    if (npipes < 64) {
        snprintf(pipes[npipes].header, sizeof pipes[0].header, "%s", header);
        pipes[npipes++].pipe = p;
    }
    return p;
}

static void gpu_run(VkPipeline p, uint32_t index, uint32_t n)
{
    VkCommandBufferBeginInfo bi;
    VkSubmitInfo si;
    uint32_t pc[2];
    pc[0] = index;
    pc[1] = n;
    memset(&bi, 0, sizeof bi);
    bi.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
    bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VKC(vkResetCommandBuffer(cmd, 0));
    VKC(vkBeginCommandBuffer(cmd, &bi));
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, playout, 0, 1, &dset, 0, NULL);
    vkCmdPushConstants(cmd, playout, VK_SHADER_STAGE_COMPUTE_BIT, 0, 8, pc);
    vkCmdDispatch(cmd, (n + 63u) / 64u, 1, 1);
    VKC(vkEndCommandBuffer(cmd));
    memset(&si, 0, sizeof si);
    si.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd;
    VKC(vkResetFences(dev, 1, &fence));
    VKC(vkQueueSubmit(queue, 1, &si, fence));
    VKC(vkWaitForFences(dev, 1, &fence, VK_TRUE, UINT64_MAX));
}

/* ------------------------------------------------------------------ comparison */
static int cls(double v) { return v != v ? 3 : (v == INFINITY ? 1 : (v == -INFINITY ? 2 : 0)); }
static const char *cls_name(int c) { static const char *n[] = { "finite", "+inf", "-inf", "NaN" }; return n[c]; }

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
static double t_compile, t_gpu, t_cpu;

static double env_int(const char *name, double def)
{
    const char *s = getenv(name);
    return s && *s ? atof(s) : def;
}

#define MAXIO 64

int main(int argc, char **argv)
{
    int n_dom = (int)env_int("PFG_N", 4096), n_edge = (int)env_int("PFG_EDGE", 1024);
    uint64_t seed = (uint64_t)env_int("PFG_SEED", 20);
    const char *only = getenv("PFG_ONLY");
    int ntot = n_dom + n_edge, k, s, j, m, maxin = 0, maxout = 0, passed = 0, failed = 0, nfn = 0;
    FILE *md = NULL;
    float *in;
    double *rf, *rd, *re[3], *rg, *rp;
    float *inp;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (argc < 3) { fprintf(stderr, "usage: vk_run DOMAINS SPV_DIR [RESULTS_MD]\n"); return 2; }
    if (!read_domains(argv[1])) return 2;
    for (k = 0; pfg_table_f[k].name; k++) {
        if (pfg_table_f[k].nin > maxin) maxin = pfg_table_f[k].nin;
        if (pfg_table_f[k].nout > maxout) maxout = pfg_table_f[k].nout;
        if (pfg_table_d[k].name == NULL || strcmp(pfg_table_f[k].name, pfg_table_d[k].name) ||
            pfg_table_emu[k].name == NULL || strcmp(pfg_table_f[k].name, pfg_table_emu[k].name)) {
            fprintf(stderr, "vk_run: the three builds list different functions\n");
            return 2;
        }
    }
    if (maxout > MAXIO) { fprintf(stderr, "vk_run: a function has more than %d outputs\n", MAXIO); return 2; }
    for (k = 0; k < nfnopts; k++) {
        for (j = 0; pfg_table_f[j].name; j++) if (!strcmp(pfg_table_f[j].name, fnopts[k].name)) break;
        if (!pfg_table_f[j].name && !getenv("PFG_HEADERS")) { fprintf(stderr, "vk_run: %s: fn %s is not a GLSL-callable public function\n", argv[1], fnopts[k].name); return 2; }
    }
    if ((need_hz || need_vm) && !pyr_build(need_hz, need_vm)) { fprintf(stderr, "vk_run: building the real pyramids failed\n"); return 2; }
    vk_init((size_t)ntot * (size_t)(maxin > 0 ? maxin : 1), (size_t)ntot * (size_t)maxout);
    printf("device: %s\n", device_name);
    printf("samples: %d domain + %d edge per function, seed %llu\n", n_dom, n_edge, (unsigned long long)seed);
    if (pfg_skipped_f[0]) printf("not covered (struct with an array member; not synthesised): %s\n", pfg_skipped_f);
    in = (float *)malloc(sizeof(float) * (size_t)ntot * (size_t)(maxin > 0 ? maxin : 1));
    rf = (double *)malloc(sizeof(double) * (size_t)ntot * (size_t)maxout);
    rd = (double *)malloc(sizeof(double) * (size_t)ntot * (size_t)maxout);
    rg = (double *)malloc(sizeof(double) * (size_t)ntot * (size_t)maxout);
    rp = (double *)malloc(sizeof(double) * (size_t)ntot * (size_t)maxout);
    inp = (float *)malloc(sizeof(float) * (size_t)(maxin > 0 ? maxin : 1));
    if (!rp || !inp) { fprintf(stderr, "vk_run: out of memory\n"); return 2; }
    for (m = 0; m < 3; m++) re[m] = (double *)malloc(sizeof(double) * (size_t)ntot * (size_t)maxout);
    if (!in || !rf || !rd || !rg || !re[0] || !re[1] || !re[2]) { fprintf(stderr, "vk_run: out of memory\n"); return 2; }
    if (argc > 3) {
        md = fopen(argv[3], "w");
        if (md) fprintf(md, "| function | header | GPU error | C float error | allowed libm errors + flushing move C float by | GPU error / bound (worst output) | target | edge-class differences (finite / NaN-inf inputs) | verdict |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
    }

    for (k = 0; pfg_table_f[k].name; k++) {
        const pfg_fn *ff = &pfg_table_f[k];
        const fnopt *o = find_opt(ff->name);
        int nin = ff->nin, nout = ff->nout, rel = o ? o->rel : 0;
        double cap = o ? o->cap : 0.0, tight_lim = 0.0, eg = 0.0, ec = 0.0, ee = 0.0, bound = 0.0, worst_ratio = 0.0;
        double at_in[8] = { 0 }, at_g = 0, at_r = 0, eg_max = 0.0, ec_max = 0.0, ee_max = 0.0;
        int at_out = 0, edge_fin = 0, edge_nonfin = 0, edge_fail = 0, ok, ex_s = -1, domain_bad = 0;
        char slots[1024], *sp, *save = NULL;
        domain dom[64];
        char slot_name[64][128];
        int unit_at[64];
        VkPipeline pipe;
        if (only && !strstr(ff->name, only)) continue;
        nfn++;
        /* domains of the slots */
        snprintf(slots, sizeof slots, "%s", ff->slots);
        for (j = 0, sp = strtok_r(slots, " ", &save); sp && j < 64; sp = strtok_r(NULL, " ", &save), j++) {
            size_t L = strlen(sp);
            int u;
            dom[j] = slot_domain(o, sp);
            snprintf(slot_name[j], sizeof slot_name[0], "%s", sp);
            unit_at[j] = 0;
            /* the .x slot of a `unit` vector whose .y and .z follow: the last path component
               before ".x" names it (wo in g.wo.x) */
            if (j >= 2 && L > 2 && !strcmp(sp + L - 2, ".z")) {
                size_t q = L - 2, b = q;
                while (b > 0 && sp[b - 1] != '.') b--;
                for (u = 0; u < nunits; u++)
                    if (strlen(units[u]) == q - b && !strncmp(sp + b, units[u], q - b) &&
                        !strncmp(slot_name[j - 2], sp, q) && !strcmp(slot_name[j - 2] + q, ".x") &&
                        !strncmp(slot_name[j - 1], sp, q) && !strcmp(slot_name[j - 1] + q, ".y"))
                        unit_at[j - 2] = 1;
            }
        }
        for (cur_pyr = 0, j = 0; j < nin && j < 64; j++)
            if (!strcmp(dom[j].kind, "hz") || !strcmp(dom[j].kind, "vm")) cur_pyr = 1;
        {   /* seeded by the function's name (FNV-1a): its inputs do not move when other
               functions are added */
            uint64_t hsh = 1469598103934665603ull;
            const char *c;
            for (c = ff->name; *c; c++) hsh = (hsh ^ (uint64_t)(unsigned char)*c) * 1099511628211ull;
            rng_state = seed * 0x9E3779B97F4A7C15ull + hsh;
        }
        for (s = 0; s < ntot; s++) {
            for (new_sample(), j = 0; j < nin; j++) {
                float v = draw(dom[j]);
                if (s >= n_dom && rnd() < 0.5) v = draw_edge();
                in[(size_t)s * nin + j] = v;
            }
            /* unit directions: each slot triple NAME.x, NAME.y, NAME.z of a `unit` line,
               drawn from its domains, is normalized (domain samples; edge samples keep their
               special values) */
            for (j = 0; s < n_dom && j + 2 < nin; j++)
                if (unit_at[j]) {
                    float *v = in + (size_t)s * nin + j;
                    double l = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
                    if (l > 0.0) { v[0] = (float)(v[0] / l); v[1] = (float)(v[1] / l); v[2] = (float)(v[2] / l); }
                }
        }
        /* GPU */
        if (nin > 0) memcpy(map_in, in, sizeof(float) * (size_t)ntot * (size_t)nin);
        else map_in[0] = 0.0f;
        memset(map_out, 0, sizeof(float) * (size_t)ntot * (size_t)nout);
        {
            double ta = now(), tb;
            pipe = pipeline_for(argv[2], ff->header);
            tb = now();
            gpu_run(pipe, (uint32_t)ff->index, (uint32_t)ntot);
            t_compile += tb - ta;
            t_gpu += now() - tb;
            ta = now();
            for (s = 0; s < ntot; s++) {
                pfg_table_f[k].fn(in + (size_t)s * nin, rf + (size_t)s * nout);
                pfg_table_d[k].fn(in + (size_t)s * nin, rd + (size_t)s * nout);
                /* conditioning: the double build at the inputs moved by one ulp each (seeded
                   random direction; integer slots kept) */
                for (j = 0; j < nin; j++) {
                    float v = in[(size_t)s * nin + j];
                    inp[j] = (!strcmp(dom[j].kind, "i") || !(fabsf(v) <= FLT_MAX)) ? v
                             : nextafterf(v, rnd() < 0.5 ? -INFINITY : INFINITY);
                }
                pfg_table_d[k].fn(inp, rp + (size_t)s * nout);
            }
            t_cpu += now() - ta;
        }
        for (s = 0; s < ntot * nout; s++) rg[s] = (double)map_out[s];
        /* emulated driver (FTZ/DAZ on) */
#ifdef PFG_HAVE_FTZ
        {
            unsigned csr = _mm_getcsr();
            _mm_setcsr(csr | 0x8040u);
#endif
            for (m = 0; m < 3; m++) {
                emu_mode = m == 0 ? 1 : (m == 1 ? -1 : 0);
                for (s = 0; s < ntot; s++) {
                    emu_state = (uint32_t)(s * 2654435761u) ^ 0x5bd1e995u;
                    pfg_table_emu[k].fn(in + (size_t)s * nin, re[m] + (size_t)s * nout);
                }
            }
#ifdef PFG_HAVE_FTZ
            _mm_setcsr(csr);
        }
#endif
        if (getenv("PFG_DUMP") && strstr(ff->name, getenv("PFG_DUMP"))) { /* per-sample listing */
            for (s = 0; s < n_dom; s++) {
                for (j = 0; j < nin; j++) fprintf(stderr, "%.9g ", (double)in[(size_t)s * nin + j]);
                for (j = 0; j < nout; j++)
                    fprintf(stderr, "| %.9g %.17g %.9g ", rg[(size_t)s * nout + j], rd[(size_t)s * nout + j], rf[(size_t)s * nout + j]);
                fprintf(stderr, "\n");
            }
        }
        /* domain inputs: errors against the double build */
        for (j = 0; j < nout; j++) {
            double rms = 0.0, fl, ecj = 0.0, eej = 0.0, egj = 0.0, exj = 0.0, bj;
            int cnt = 0, sg = -1;
            for (s = 0; s < n_dom; s++) {
                double r = rd[(size_t)s * nout + j];
                if (fabs(r) < 1e300) { rms += r * r; cnt++; }
            }
            rms = cnt ? sqrt(rms / cnt) : 0.0;
            fl = rel ? 1e-30 : (rms > 0.0 ? 1e-6 * rms : 1e-30);
            if (fl < 1e-30) fl = 1e-30;
            for (s = 0; s < n_dom; s++) {
                size_t q = (size_t)s * nout + j;
                double r = rd[q], den = fabs(r) > fl ? fabs(r) : fl, e, cond;
                if (r != r) {                    /* the reference itself is NaN: classes only */
                    if (cls(rg[q]) != cls(rf[q]) && cls(rg[q]) != 3) egj = exj = INFINITY, sg = s;
                    continue;
                }
                if (fabs(r) == INFINITY) {
                    e = (rg[q] == r) ? 0.0 : INFINITY;
                    if (e > egj) { egj = exj = e; sg = s; }
                    continue;
                }
                e = fabs(rf[q] - r) / den;
                if (e > ecj) ecj = e;
                for (m = 0; m < 3; m++) {
                    double d = fabs(re[m][q] - rf[q]) / den;
                    if (d != d) d = INFINITY;
                    if (d > eej) eej = d;
                }
                /* what a one-ulp change of the inputs moves the exact result, 4 times: a
                   rearrangement of the formula (contraction, the order of a sum, division by
                   reciprocal) is backward stable within a few ulp of its operands, and where
                   the result cancels that is the honest scale of its rounding error */
                cond = fabs(rp[q] - r);
                if (!(cond < 1e300)) cond = 0.0;
                e = fabs(rg[q] - r) / den;
                if (e != e) e = INFINITY;
                if (e > egj) egj = e;
                e = fabs(rg[q] - r) - 4.0 * cond;
                e = (e > 0.0 ? e : 0.0) / den;
                if (e != e) e = INFINITY;
                if (e > exj) { exj = e; sg = s; }
            }
            bj = 2.0 * ecj + 2.0 * eej + 4.0 * ULP;
            /* a bound that is not finite would pass anything: the domain gave inputs the C
               builds cannot agree on (an invalid struct, an overflow): fix domains.txt */
            if (!(bj < 1e300)) domain_bad = 1;
            if (egj > eg_max) eg_max = egj;
            if (ecj > ec_max) ec_max = ecj;
            if (eej > ee_max) ee_max = eej;
            if (exj > 0.0 && exj / bj > worst_ratio) {
                worst_ratio = exj / bj;
                eg = egj; ec = ecj; ee = eej; bound = bj; at_out = j; ex_s = sg;
            }
            if (worst_ratio == 0.0 && egj >= eg) { eg = egj; ec = ecj; ee = eej; bound = bj; }
        }
        if (ex_s >= 0) {
            for (j = 0; j < nin && j < 8; j++) at_in[j] = in[(size_t)ex_s * nin + j];
            at_g = rg[(size_t)ex_s * nout + at_out];
            at_r = rd[(size_t)ex_s * nout + at_out];
        }
        /* edge inputs: classes */
        {
            char ex[256] = "";
            for (s = n_dom; s < ntot; s++) {
                int finite_in = 1, moderate = 1;
                for (j = 0; j < nin; j++) {
                    if (!(fabsf(in[(size_t)s * nin + j]) <= FLT_MAX)) finite_in = 0;
                    if (!(fabsf(in[(size_t)s * nin + j]) <= 1e30f)) moderate = 0;
                }
                for (j = 0; j < nout; j++) {
                    size_t q = (size_t)s * nout + j;
                    int cg = cls(rg[q]);
                    if (cg == cls(rf[q]) || cg == cls(re[0][q]) || cg == cls(re[1][q]) || cg == cls(re[2][q])) continue;
                    if (finite_in) edge_fin++; else edge_nonfin++;
                    /* inputs of magnitude <= 1e30: the GPU may not turn C's finite answer into
                       NaN or inf (C's own overflow on huge inputs is no promise, and near
                       FLT_MAX a reassociated sum, which GLSL allows, may overflow) */
                    if ((moderate && cls(rf[q]) == 0) || (o && o->strict)) edge_fail++;
                    if (!ex[0] || (finite_in && !strstr(ex, "finite inputs"))) {
                        int p = snprintf(ex, sizeof ex, "%s%s: out %d C %s GPU %s at", finite_in ? "finite inputs" : "e.g.", "", j,
                                         cls_name(cls(rf[q])), cls_name(cg));
                        int t;
                        for (t = 0; t < nin && t < 6 && p < 200; t++) p += snprintf(ex + p, sizeof ex - (size_t)p, " %g", (double)in[(size_t)s * nin + t]);
                    }
                    break;
                }
            }
            /* tight: the target on real-pyramid domains, the GPU within 4 x the C
               float error or 1e-4, whichever is larger */
            tight_lim = o && o->tight ? (4.0 * ec_max > 1e-4 ? 4.0 * ec_max : 1e-4) : 0.0;
            ok = worst_ratio <= 1.0 && !(cap > 0.0 && eg_max > cap) && !(tight_lim > 0.0 && eg_max > tight_lim) && edge_fail == 0 &&
                 !domain_bad;
            if (ok) passed++; else failed++;
            printf("%s %-32s gpu %-9.3g bound %-9.3g (2 x C float %.3g + 2 x driver %.3g, + 4 x conditioning) ratio %.2f edge %d/%d",
                   ok ? "ok  " : "FAIL", ff->name, eg, bound, ec, ee, worst_ratio, edge_fin, edge_nonfin);
            if (nout > 1) printf(" (max over outputs: gpu %.3g, C float %.3g, driver %.3g)", eg_max, ec_max, ee_max);
            if (cap > 0.0) printf(" [cap %g]", cap);
            if (tight_lim > 0.0) printf(" [target %.3g: 4 x C float or 1e-4; gpu / C float %.2f]", tight_lim, ec_max > 0.0 ? eg_max / ec_max : 0.0);
            printf("\n");
            if (domain_bad) printf("       FAIL: the bound is not finite: the domain's inputs give C float and double results that do not agree (tests/gpu/domains.txt)\n");
            if (!ok || eg > 0.0) {
                if (ex_s >= 0 && worst_ratio > 0.0) {
                    printf("       worst: output %d, GPU %.9g, double %.9g, inputs", at_out, at_g, at_r);
                    for (j = 0; j < nin && j < 8; j++) printf(" %.9g", at_in[j]);
                    printf("\n");
                }
            }
            if (edge_fin + edge_nonfin > 0) printf("       edge class differs (%s): %s\n", edge_fail ? "FAIL" : "not promised", ex);
            if (md) {
                char caps[32] = "";
                if (cap > 0.0) snprintf(caps, sizeof caps, "%g", cap);
                else if (tight_lim > 1e-4) snprintf(caps, sizeof caps, "4x C = %.2g", tight_lim);
                else if (tight_lim > 0.0) snprintf(caps, sizeof caps, "1e-4");
                fprintf(md, "| `%s` | %s | %.2g | %.2g | %.2g | %.2g | %s | %d / %d | %s |\n", ff->name, ff->header, eg_max, ec_max,
                        ee_max, worst_ratio, caps, edge_fin, edge_nonfin, ok ? "ok" : "FAIL");
            }
        }
    }
    /* point checks: the documented value at one input, on the GPU and in the C float build */
    for (m = 0; m < nats; m++) {
        const atcheck *a = &ats[m];
        const pfg_fn *ff = NULL;
        char slots[1024], *sp, *save = NULL;
        double cf[MAXIO], g;
        int used = 0, ok;
        if (only && !strstr(a->name, only)) continue;
        for (k = 0; pfg_table_f[k].name; k++) if (!strcmp(pfg_table_f[k].name, a->name)) { ff = &pfg_table_f[k]; break; }
        if (!ff) { if (!getenv("PFG_HEADERS")) { printf("FAIL at %s: not a GLSL-callable public function\n", a->name); failed++; } continue; }
        memset(inp, 0, sizeof(float) * (size_t)(maxin > 0 ? maxin : 1));
        snprintf(slots, sizeof slots, "%s", ff->slots);
        for (j = 0, sp = strtok_r(slots, " ", &save); sp && j < ff->nin; sp = strtok_r(NULL, " ", &save), j++)
            for (s = 0; s < a->nslot; s++) if (!strcmp(a->slot[s], sp)) { inp[j] = a->val[s]; used++; }
        if (used != a->nslot || a->out < 0 || a->out >= ff->nout) { printf("FAIL at %s: unknown slot or output\n", a->name); failed++; continue; }
        if (ff->nin > 0) memcpy(map_in, inp, sizeof(float) * (size_t)ff->nin);
        memset(map_out, 0, sizeof(float) * (size_t)ff->nout);
        gpu_run(pipeline_for(argv[2], ff->header), (uint32_t)ff->index, 1u);
        g = (double)map_out[a->out];
        ff->fn(inp, cf);
        ok = fabs(g - a->expect) <= a->tol && fabs(cf[a->out] - a->expect) <= a->tol;
        if (ok) passed++; else failed++;
        printf("%s at %s(", ok ? "ok  " : "FAIL", a->name);
        for (s = 0; s < a->nslot; s++) printf("%s%s=%g", s ? " " : "", a->slot[s], (double)a->val[s]);
        printf(") out %d: GPU %.9g, C float %.9g, documented %.9g +- %g\n", a->out, g, cf[a->out], a->expect, a->tol);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("time: shader compiles %.1f s, GPU runs %.1f s, C float and double %.1f s\n", t_compile, t_gpu, t_cpu);
    printf("%d functions on %s, %.1f s\n", nfn, device_name, (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec));
    printf("RESULT %d %d\n", passed, failed);
    if (md) fclose(md);
    return failed ? 1 : 0;
}
