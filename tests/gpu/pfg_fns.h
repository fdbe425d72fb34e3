/* pfg_fns.h - what tests/gpu/vk_run.c shares with the generated wrappers (tests/gpu/gen.awk),
   which are compiled three times:
     PFG_VARIANT 0  float (the C float build)           table pfg_table_f
     PFG_VARIANT 1  double (-DPF_DOUBLE, the reference) table pfg_table_d
     PFG_VARIANT 2  float with an emulated worst-case GPU driver: every libm call goes through
                    pfg_emu_* (vk_run.c), which perturbs the correctly rounded result by the
                    error the GLSL 4.50 / Vulkan precision rules allow (docs/gpu.md), and the
                    run sets x86 FTZ/DAZ (subnormals flushed, as GPUs may)   table pfg_table_emu
   The emulated build is what each function's bound comes from: the GPU may differ from the C
   float build by what the rules allow for the libm functions it calls and by flushing, and by
   nothing else. */
#ifndef PFG_FNS_H
#define PFG_FNS_H

typedef struct pfg_fn {
    const char *name;   /* public function */
    const char *header; /* pf_x.h */
    int index;          /* case of the header's shader switch */
    int nin, nout;      /* scalar inputs and outputs per evaluation */
    const char *slots;  /* space-separated names of the inputs (parameter paths) */
    void (*fn)(const float *in, double *out);
} pfg_fn;

extern const pfg_fn pfg_table_f[], pfg_table_d[], pfg_table_emu[];
extern const char pfg_skipped_f[], pfg_skipped_d[], pfg_skipped_emu[];

float pfg_emu_exp(float x);
float pfg_emu_log(float x);
float pfg_emu_pow(float x, float y);
float pfg_emu_sqrt(float x);
float pfg_emu_sin(float x);
float pfg_emu_cos(float x);

#if defined(PFG_VARIANT) && PFG_VARIANT == 2
#  define PF_EXP(x) pfg_emu_exp(x)
#  define PF_LOG(x) pfg_emu_log(x)
#  define PF_POW(x, y) pfg_emu_pow(x, y)
#  define PF_SQRT(x) pfg_emu_sqrt(x)
#  define PF_SIN(x) pfg_emu_sin(x)
#  define PF_COS(x) pfg_emu_cos(x)
/* GLSL's PF_ATAN2 is the library's pf_atan2 (pf_core.h), not the driver's atan: emulated as
   that float code under the run's FTZ/DAZ, contraction and reciprocal division */
#  define PF_ATAN2(y, x) pf_atan2(y, x)
#  define PFG_TABLE pfg_table_emu
#  define PFG_SKIPPED pfg_skipped_emu
#elif defined(PFG_VARIANT) && PFG_VARIANT == 1
#  define PFG_TABLE pfg_table_d
#  define PFG_SKIPPED pfg_skipped_d
#else
#  define PFG_TABLE pfg_table_f
#  define PFG_SKIPPED pfg_skipped_f
#endif

#endif /* PFG_FNS_H */
