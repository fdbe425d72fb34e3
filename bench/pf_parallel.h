/* pf_parallel.h - every core for the bench's independent work items, and progress on stderr.
   CPU-only bench infrastructure (POSIX threads), not part of the library.

   DETERMINISM. pfb_parallel_for(n, fn, ctx, label) calls fn(ctx, item) once for every item in
   [0, n), on PFB_THREADS threads (default: every online core). Items are handed out in order
   from a shared counter, so which thread runs an item varies from run to run: fn must write only
   its own item's output slots and draw any random numbers from a seed derived from the item
   (never from a per-thread or global generator). Reductions are then done by the caller, in
   item order, after the loop: the results are identical for any thread count (the bench's CSVs
   of a 1-thread and an N-thread run compare equal).

   TIMING stays single-threaded: never time inside pfb_parallel_for; time apart, after it.

   PROGRESS. With a label, a step that runs longer than PFB_PROGRESS_AFTER seconds (2 s) prints
   "label: 41% (123/300 items), 12 s left" on stderr, updated in place on a terminal (one line,
   carriage return) and as plain lines every 10 s otherwise (logs, CI). The estimate is the
   elapsed time scaled by the items left. A NULL label prints nothing.
   pfb_progress_* does the same for a serial loop.

   ENVIRONMENT
     PFB_THREADS=N   threads for every parallel step (1 = serial, the reference for the
                     determinism check); default: sysconf(_SC_NPROCESSORS_ONLN).
*/
#ifndef PF_PARALLEL_H
#define PF_PARALLEL_H

#if !defined(_POSIX_C_SOURCE) || _POSIX_C_SOURCE < 200809L
#error "define _POSIX_C_SOURCE 200809L before the first system header (pf_bench.h does)"
#endif

#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#ifndef PFB_PROGRESS_AFTER
#define PFB_PROGRESS_AFTER 2.0
#endif
#define PFB_MAX_THREADS 256

static double pfb_wall_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* Threads for the parallel steps: PFB_THREADS, else the online cores, in [1, PFB_MAX_THREADS]. */
static int pfb_thread_count(void)
{
    const char *e = getenv("PFB_THREADS");
    long n = 0;
    if (e && *e) n = strtol(e, NULL, 10);
    if (n <= 0) n = sysconf(_SC_NPROCESSORS_ONLN);
    if (n < 1) n = 1;
    if (n > PFB_MAX_THREADS) n = PFB_MAX_THREADS;
    return (int)n;
}

/* ---------------------------------------------------------------- progress */
typedef struct {
    const char *label;
    long long total;
    double t0, last_print;
    int printed, tty;
} pfb_progress;

static pfb_progress pfb_progress_start(const char *label, long long total)
{
    pfb_progress p;
    p.label = label;
    p.total = total;
    p.t0 = pfb_wall_s();
    p.last_print = p.t0;
    p.printed = 0;
    p.tty = isatty(2);
    return p;
}

/* done items of total; prints at most every 0.25 s on a terminal, every 10 s otherwise. */
static void pfb_progress_update(pfb_progress *p, long long done)
{
    double now, el, left;
    if (!p->label || p->total <= 0) return;
    now = pfb_wall_s();
    el = now - p->t0;
    if (el < PFB_PROGRESS_AFTER) return;
    if (now - p->last_print < (p->tty ? 0.25 : 10.0) && p->printed) return;
    left = done > 0 ? el * (double)(p->total - done) / (double)done : -1.0;
    if (left >= 0.0)
        fprintf(stderr, "%s%s: %3.0f%% (%lld/%lld), %.0f s elapsed, ~%.0f s left%s", p->tty ? "\r" : "",
                p->label, 100.0 * (double)done / (double)p->total, done, p->total, el, left,
                p->tty ? "\033[K" : "\n");
    else
        fprintf(stderr, "%s%s: 0/%lld, %.0f s elapsed%s", p->tty ? "\r" : "", p->label, p->total, el,
                p->tty ? "\033[K" : "\n");
    fflush(stderr);
    p->last_print = now;
    p->printed = 1;
}

/* Ends the in-place line on a terminal (only when something was printed). */
static void pfb_progress_end(pfb_progress *p)
{
    if (!p->label || !p->printed) return;
    fprintf(stderr, "%s%s: done, %lld items in %.1f s%s", p->tty ? "\r" : "", p->label, p->total,
            pfb_wall_s() - p->t0, p->tty ? "\033[K\n" : "\n");
    fflush(stderr);
}

/* ---------------------------------------------------------------- parallel for */
typedef void (*pfb_item_fn)(void *ctx, long long item);

typedef struct {
    pfb_item_fn fn;
    void *ctx;
    long long n, next, done;
    pthread_mutex_t lock;
    pfb_progress progress;
} pfb_pool_job;

static void *pfb_pool_worker(void *arg)
{
    pfb_pool_job *job = (pfb_pool_job *)arg;
    for (;;) {
        long long item;
        pthread_mutex_lock(&job->lock);
        item = job->next < job->n ? job->next++ : -1;
        pthread_mutex_unlock(&job->lock);
        if (item < 0) break;
        job->fn(job->ctx, item);
        pthread_mutex_lock(&job->lock);
        ++job->done;
        pfb_progress_update(&job->progress, job->done);
        pthread_mutex_unlock(&job->lock);
    }
    return NULL;
}

/* fn(ctx, i) for i in [0, n) on pfb_thread_count() threads (the calling thread is one of them).
   Returns the number of threads used. Exits with a message if a thread cannot be started. */
static int pfb_parallel_for(long long n, pfb_item_fn fn, void *ctx, const char *label)
{
    pthread_t tid[PFB_MAX_THREADS];
    pfb_pool_job job;
    int nt = pfb_thread_count(), i;
    if (n <= 0) return 0;
    if ((long long)nt > n) nt = (int)n;
    job.fn = fn;
    job.ctx = ctx;
    job.n = n;
    job.next = 0;
    job.done = 0;
    job.progress = pfb_progress_start(label, n);
    pthread_mutex_init(&job.lock, NULL);
    for (i = 1; i < nt; ++i)
        if (pthread_create(&tid[i], NULL, pfb_pool_worker, &job) != 0) {
            fprintf(stderr, "pf_parallel: cannot start thread %d of %d\n", i, nt);
            exit(1);
        }
    pfb_pool_worker(&job);
    for (i = 1; i < nt; ++i) pthread_join(tid[i], NULL);
    pthread_mutex_destroy(&job.lock);
    pfb_progress_end(&job.progress);
    return nt;
}

#endif /* PF_PARALLEL_H */
