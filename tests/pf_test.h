/* pf_test.h - the tiny test harness shared by every tests/test_*.c.

   The same test bodies compile as C99 float, C99 double (-DPF_DOUBLE), C++11 and under
   sanitizers; they use pf_real and compare against long double references, so one source
   checks every build. No assert(): checks are counted and reported, and they survive NDEBUG.

   A test file:
     #include "pf_test.h"
     static void test_erfc_grid(void) { ... PF_CHECK(err <= bound, "max %g ulp", err); }
     int main(int argc, char **argv) { PF_TEST_BEGIN(argc, argv);
                                       PF_TEST_RUN(test_erfc_grid); return PF_TEST_END(); }

   Running `test_x edge` runs only the tests whose name starts with "edge_" (the -ffast-math
   build runs those: finiteness and range, no tight accuracy bounds). Each test prints one line,
   "ok" or "FAIL", with the notes it recorded (measured errors). The last line is
   "RESULT <passed> <failed>", which tests/run.sh sums. */
#ifndef PF_TEST_H
#define PF_TEST_H

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* pf_real's machine epsilon in long double, the unit of the tests' error bounds, and pi. */
#ifdef PF_DOUBLE
#  define PF_TEST_EPS 2.220446049250313e-16L
#else
#  define PF_TEST_EPS 1.1920928955078125e-7L
#endif
#define PF_TEST_PI 3.14159265358979323846264338327950288L

/* Harness functions are static and not all files use all of them. */
#if defined(__GNUC__) || defined(__clang__)
#  define PF_TEST_FN static __attribute__((unused))
#else
#  define PF_TEST_FN static
#endif

#ifndef PF_TEST_CONFIG
#  define PF_TEST_CONFIG "unknown"
#endif

static int pf_test_cases_passed = 0;
static int pf_test_cases_failed = 0;
static int pf_test_current_failures = 0;
static int pf_test_edge_only = 0;
static char pf_test_notes[2048];

/* Record a note (a measured number) for the current test's result line. */
PF_TEST_FN void pf_test_note(const char *fmt, ...)
{
    size_t used = strlen(pf_test_notes);
    va_list ap;
    if (used + 4 >= sizeof pf_test_notes) return;
    if (used > 0) {
        strcat(pf_test_notes, "; ");
        used += 2;
    }
    va_start(ap, fmt);
    vsnprintf(pf_test_notes + used, sizeof pf_test_notes - used, fmt, ap);
    va_end(ap);
}

PF_TEST_FN void pf_test_fail_at(const char *file, int line, const char *cond, const char *fmt, ...)
{
    va_list ap;
    pf_test_current_failures++;
    if (pf_test_current_failures > 8) return; /* keep the log readable */
    printf("    %s:%d: check failed: %s\n      ", file, line, cond);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
}

/* PF_CHECK(condition, printf-style explanation with the measured values). */
#define PF_CHECK(cond, ...) \
    do { \
        if (!(cond)) pf_test_fail_at(__FILE__, __LINE__, #cond, __VA_ARGS__); \
    } while (0)

#define PF_TEST_BEGIN(argc, argv) \
    do { \
        if ((argc) > 1 && strcmp((argv)[1], "edge") == 0) pf_test_edge_only = 1; \
    } while (0)

PF_TEST_FN void pf_test_run(void (*fn)(void), const char *name)
{
    if (pf_test_edge_only && strncmp(name, "edge_", 5) != 0) return;
    pf_test_current_failures = 0;
    pf_test_notes[0] = '\0';
    fn();
    if (pf_test_current_failures == 0) pf_test_cases_passed++;
    else pf_test_cases_failed++;
    printf("%s %-40s [%s] %s\n", pf_test_current_failures ? "FAIL" : "ok  ", name, PF_TEST_CONFIG,
           pf_test_notes);
    fflush(stdout);
}

#define PF_TEST_RUN(fn) pf_test_run(fn, #fn)

/* 1 when PF_TEST_REDUCED is set (not "0") in the environment: tests/portability/cell.sh sets it
   for the cells run under an emulator (arm-float under qemu-arm, about ten times slower than
   native), where the heaviest quadrature tests check fewer configurations with the same bounds
   (each says how many in its note); every native build runs the full grids. */
PF_TEST_FN int pf_test_reduced(void)
{
    const char *e = getenv("PF_TEST_REDUCED");
    return e && *e && strcmp(e, "0") != 0;
}

PF_TEST_FN int pf_test_end(void)
{
    printf("RESULT %d %d\n", pf_test_cases_passed, pf_test_cases_failed);
    return pf_test_cases_failed ? 1 : 0;
}
#define PF_TEST_END() pf_test_end()

/* ------------------------------------------------------------------ error measures */

/* Size of one unit in the last place of pf_real at the value ref (ref rounded to pf_real),
   with subnormal spacing below the smallest normal. */
PF_TEST_FN long double pf_test_ulp_of(long double ref)
{
#ifdef PF_DOUBLE
    const int mant = 53, emin = -1021;
#else
    const int mant = 24, emin = -125;
#endif
    int e;
    long double a = fabsl(ref);
    if (a == 0.0L) return ldexpl(1.0L, emin - mant);
    frexpl(a, &e); /* a = f * 2^e, f in [0.5, 1) */
    if (e < emin) e = emin;
    return ldexpl(1.0L, e - mant);
}

/* Error of got against the long double reference, in ulps of pf_real at ref. */
PF_TEST_FN long double pf_test_ulp_error(pf_real got, long double ref)
{
    if (isnan((double)got) || isinf((double)got)) return (long double)INFINITY;
    return fabsl((long double)got - ref) / pf_test_ulp_of(ref);
}

/* Relative error |got - ref| / |ref|; absolute when ref is 0. */
PF_TEST_FN long double pf_test_rel_error(long double got, long double ref)
{
    if (isnan((double)got) || isinf((double)got)) return (long double)INFINITY;
    if (ref == 0.0L) return fabsl(got);
    return fabsl(got - ref) / fabsl(ref);
}

PF_TEST_FN int pf_test_finite(pf_real x) { return !(isnan((double)x) || isinf((double)x)); }

/* Finite, tested on the bits (exponent not all ones): -ffast-math lets the compiler fold
   isnan/isinf, and so pf_test_finite, to constants; the edge_ tests that run under it use this. */
PF_TEST_FN int pf_test_bits_finite(pf_real x)
{
#ifdef PF_DOUBLE
    unsigned long long u;
    memcpy(&u, &x, sizeof u);
    return (u & 0x7FF0000000000000ULL) != 0x7FF0000000000000ULL;
#else
    unsigned int u;
    memcpy(&u, &x, sizeof u);
    return (u & 0x7F800000u) != 0x7F800000u;
#endif
}

/* Running maximum of an error with the input where it happened. */
typedef struct pf_test_max {
    long double err;
    long double at;
} pf_test_max;

PF_TEST_FN pf_test_max pf_test_max_init(void)
{
    pf_test_max m;
    m.err = 0.0L;
    m.at = 0.0L;
    return m;
}

PF_TEST_FN void pf_test_max_update(pf_test_max *m, long double err, long double at)
{
    if (!(err <= m->err)) { /* NaN errors count as worse than anything */
        m->err = err;
        m->at = at;
    }
}

/* ------------------------------------------------------------------ seeded random numbers */

/* splitmix64: fixed seeds, identical sequence on every platform and build. */
typedef struct pf_test_rng {
    unsigned long long state;
} pf_test_rng;

PF_TEST_FN pf_test_rng pf_test_rng_seed(unsigned long long seed)
{
    pf_test_rng r;
    r.state = seed;
    return r;
}

PF_TEST_FN unsigned long long pf_test_rng_next(pf_test_rng *r)
{
    unsigned long long z = (r->state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
}

/* Uniform in [a, b). */
PF_TEST_FN double pf_test_uniform(pf_test_rng *r, double a, double b)
{
    double u = (double)(pf_test_rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
    return a + (b - a) * u;
}

/* Uniform in (0, 1), never 0 or 1: the top 53 bits plus one half, over 2^53. */
PF_TEST_FN double pf_test_uniform_open(pf_test_rng *r)
{
    return ((double)(pf_test_rng_next(r) >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* Log-uniform in [a, b), a > 0: equal density per decade. */
PF_TEST_FN double pf_test_log_uniform(pf_test_rng *r, double a, double b)
{
    return exp(pf_test_uniform(r, log(a), log(b)));
}

/* The unit direction at polar angle theta and azimuth phi (degrees; phi from +x toward +y). */
PF_TEST_FN void pf_test_dir_deg(double theta, double phi, double w[3])
{
    theta *= (double)PF_TEST_PI / 180.0;
    phi *= (double)PF_TEST_PI / 180.0;
    w[0] = sin(theta) * cos(phi);
    w[1] = sin(theta) * sin(phi);
    w[2] = cos(theta);
}
PF_TEST_FN pf_vec3 pf_test_vec3(const double w[3]) { return pf_vec3_make((pf_real)w[0], (pf_real)w[1], (pf_real)w[2]); }

/* ------------------------------------------------------------------ guarded mappings
   pf_test_guarded_alloc(bytes): `bytes` of zeroed, readable and writable memory that ends
   exactly where a PROT_NONE guard page begins (and with a guard page before its first page),
   so a read or write past either end faults at once, in every build (not only under ASan).
   The mapping is MAP_NORESERVE: untouched pages cost no memory, so a test can map the
   documented size of a huge buffer (a 17 GB table) and touch a few entries. The pointer is
   aligned as bytes is (a multiple of 8 bytes gives 8-byte alignment). Returns NULL where this
   is unsupported (not __unix__, or <sys/mman.h> without MAP_ANONYMOUS and MAP_NORESERVE:
   define _DEFAULT_SOURCE before the first #include under -std=c99) or when the mapping fails;
   the caller then skips (and says so in a note). Free with pf_test_guarded_free(p, bytes). */
#if defined(__unix__)
#  include <sys/mman.h>
#  include <unistd.h>
#endif

PF_TEST_FN void *pf_test_guarded_alloc(size_t bytes)
{
#if defined(__unix__) && defined(MAP_ANONYMOUS) && defined(MAP_NORESERVE)
    long ps = sysconf(_SC_PAGESIZE);
    size_t page = ps > 0 ? (size_t)ps : 4096u, body, total;
    unsigned char *base;
    void *m;
    if (bytes == 0 || bytes > ((size_t)-1) / 2 - 2 * page) return NULL;
    body = (bytes + page - 1) / page * page;
    total = body + 2 * page;
    m = mmap(NULL, total, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (m == MAP_FAILED) return NULL;
    base = (unsigned char *)m;
    if (mprotect(base, page, PROT_NONE) != 0 || mprotect(base + page + body, page, PROT_NONE) != 0) {
        munmap(m, total);
        return NULL;
    }
    return base + page + (body - bytes);
#else
    (void)bytes;
    return NULL;
#endif
}

PF_TEST_FN void pf_test_guarded_free(void *p, size_t bytes)
{
#if defined(__unix__) && defined(MAP_ANONYMOUS) && defined(MAP_NORESERVE)
    long ps = sysconf(_SC_PAGESIZE);
    size_t page = ps > 0 ? (size_t)ps : 4096u, body;
    if (!p) return;
    body = (bytes + page - 1) / page * page;
    munmap((unsigned char *)p - (body - bytes) - page, body + 2 * page);
#else
    (void)p;
    (void)bytes;
#endif
}

#endif /* PF_TEST_H */
