/* study_pool.c — the workers that evaluate a study's designs.
 *
 * Design.  Rank 0's main thread is the dispatcher: it keeps the study's file
 * and hands designs to workers, one at a time, to whichever is idle (dynamic
 * scheduling: a snake that goes unstable in 0.1 s and one that runs its 5 s
 * cost very different times).  One worker is a thread of rank 0 itself, so
 * `mpirun -np 1`, a simulator without MPI and one run by hand all evaluate
 * in the same way; under `mpirun -np N` ranks 1..N-1 are workers too, served
 * through study_mpi.c.  Only the main thread calls MPI (MPI_THREAD_FUNNELED).
 * Results can arrive in any order; the study writes each at its index, and
 * since an evaluation's result depends only on its design, the study's
 * results do not depend on N or on which worker ran what.  A batch of tasks
 * carries the factor of their time step (1; 0.5 for the recheck of the
 * study's best designs at dt/2), which each worker hands the evaluation.
 *
 * Waiting is polling with 1 ms sleeps, on both sides: OpenMPI's blocking
 * receives spin, and with more ranks than cores (`--oversubscribe`) an idle
 * rank spinning would take the core an evaluation needs.
 *
 * Faults.  A remote evaluation that runs longer than the timeout (by default
 * 20 times the slowest evaluation so far and at least 60 s) is given to
 * another worker and its rank is not used again; an evaluation that fails
 * for a reason not of the design's (SW_EVAL_FAILED: out of memory on that
 * node, ...) is tried once more on another worker.  A rank that dies ends
 * the job under OpenMPI without ULFM; the study file keeps every result so
 * far and `--resume` continues it (docs/optimisation.md).  For the tests,
 * SINEW_STUDY_FAULT=MODE:RANK:K makes rank RANK hang (MODE hang) or exit
 * (MODE exit) on its K-th task (K from 1).
 *
 * Ctrl-C and SIGTERM set a flag the dispatcher looks at between results; an
 * evaluation on rank 0's thread sees Ctrl-C through sw_run's own handler. */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "sinew.h"
#include "study_pool.h"

#define POLL_SLEEP_NS 1000000L      /* 1 ms between polls                   */
#define TIMEOUT_FACTOR 20.0         /* automatic timeout: x slowest so far    */
#define TIMEOUT_FLOOR 60.0          /* ... and at least this, s               */

extern const swStudyTransport *sw_study_mpi_transport(void) __attribute__((weak));

static volatile sig_atomic_t stop_requested;
static void on_stop_signal(int sig) {
  (void)sig;
  stop_requested = 1;
}
int sw_pool_interrupted(void) { return stop_requested != 0; }

static void nap(void) {
  struct timespec ts = {0, POLL_SLEEP_NS};
  nanosleep(&ts, NULL);
}

/* One evaluation, timed, with the rank recorded. */
static void evaluate(const swStudyOptions *o, int rank, const double *P, double dt_scale,
                     swStudyEval *r) {
  memset(r, 0, sizeof *r);
  double t0 = sw_wall_seconds();
  o->eval(o->ctx, P, dt_scale, r);
  r->wall = sw_wall_seconds() - t0;
  r->rank = rank;
}

/* ---- the worker thread of rank 0 ---- */

typedef struct {
  pthread_t thread;
  pthread_mutex_t mu;
  pthread_cond_t cv;
  int started;
  int has_task, has_result, quit;
  long index;
  double dt_scale;
  double *P;
  swStudyEval result;
} swLocal;

struct swPool {
  const swStudyOptions *o;
  int rank, size;
  const swStudyTransport *mpi;   /* NULL: this process only                 */
  swLocal local;
  /* per rank (index 0 is the local thread): the task it runs, or -1 */
  long *task;          /* position in the batch                               */
  double *started;
  char *lost;
  int nlost;
  double slowest;
  struct sigaction old_int, old_term;
  int handlers;
};

static void *local_main(void *arg) {
  swPool *p = arg;
  swLocal *l = &p->local;
  pthread_mutex_lock(&l->mu);
  for (;;) {
    while (!l->has_task && !l->quit) pthread_cond_wait(&l->cv, &l->mu);
    if (l->quit) break;
    pthread_mutex_unlock(&l->mu);
    swStudyEval r;
    evaluate(p->o, 0, l->P, l->dt_scale, &r);
    pthread_mutex_lock(&l->mu);
    l->result = r;
    l->has_task = 0;
    l->has_result = 1;
  }
  pthread_mutex_unlock(&l->mu);
  return NULL;
}

static void local_give(swPool *p, long index, double dt_scale, const double *P) {
  swLocal *l = &p->local;
  pthread_mutex_lock(&l->mu);
  memcpy(l->P, P, (size_t)p->o->nparam * sizeof *P);
  l->index = index;
  l->dt_scale = dt_scale;
  l->has_task = 1;
  pthread_cond_signal(&l->cv);
  pthread_mutex_unlock(&l->mu);
}

static int local_take(swPool *p, long *index, swStudyEval *r) {
  swLocal *l = &p->local;
  int got = 0;
  pthread_mutex_lock(&l->mu);
  if (l->has_result) {
    *index = l->index;
    *r = l->result;
    l->has_result = 0;
    got = 1;
  }
  pthread_mutex_unlock(&l->mu);
  return got;
}

/* ---- launch detection ---- */

static int env_int(const char *name, int *v) {
  const char *s = getenv(name);
  if (!s || !*s) return 0;
  char *end;
  long x = strtol(s, &end, 10);
  if (*end || x < 0 || x > 1 << 24) return 0;
  *v = (int)x;
  return 1;
}

int sw_study_launched(int *rank, int *size) {
  int r = 0, n = 1;
  /* OpenMPI's mpirun, then PMI/PMIx launchers (MPICH's hydra, Slurm's srun) */
  int ok = (env_int("OMPI_COMM_WORLD_SIZE", &n) && env_int("OMPI_COMM_WORLD_RANK", &r)) ||
           (env_int("PMIX_SIZE", &n) && env_int("PMIX_RANK", &r)) ||
           (env_int("PMI_SIZE", &n) && env_int("PMI_RANK", &r));
  if (rank) *rank = ok ? r : 0;
  if (size) *size = ok ? n : 1;
  return ok && n > 1;
}

int sw_study_have_mpi(void) { return sw_study_mpi_transport != NULL; }

/* ---- open and close ---- */

swPool *sw_pool_open(const swStudyOptions *o, int *rank, char *err, size_t errlen) {
  swPool *p = calloc(1, sizeof *p);
  if (!p) {
    snprintf(err, errlen, "out of memory");
    return NULL;
  }
  p->o = o;
  p->size = 1;
  int lrank = 0, lsize = 1;
  int launched = sw_study_launched(&lrank, &lsize);
  if (launched || (sw_study_have_mpi() && getenv("OMPI_COMM_WORLD_SIZE"))) {
    if (!sw_study_have_mpi()) {
      snprintf(err, errlen, "started by mpirun with %d ranks, but this simulator was built "
               "without MPI: every rank would run the whole study. Rebuild sinew where "
               "mpicc is installed (Debian: libopenmpi-dev), or run without mpirun", lsize);
      free(p);
      return NULL;
    }
    p->mpi = sw_study_mpi_transport();
    if (p->mpi->init(&p->rank, &p->size, err, errlen) != SW_OK) {
      free(p);
      return NULL;
    }
  }
  *rank = p->rank;
  int n = p->size;
  p->task = malloc((size_t)n * sizeof *p->task);
  p->started = calloc((size_t)n, sizeof *p->started);
  p->lost = calloc((size_t)n, 1);
  p->local.P = malloc(((size_t)o->nparam + 1) * sizeof *p->local.P);
  if (!p->task || !p->started || !p->lost || !p->local.P) {
    snprintf(err, errlen, "out of memory");
    sw_pool_close(p, 0);
    return NULL;
  }
  for (int i = 0; i < n; i++) p->task[i] = -1;
  if (p->rank == 0) {
    pthread_mutex_init(&p->local.mu, NULL);
    pthread_cond_init(&p->local.cv, NULL);
    if (pthread_create(&p->local.thread, NULL, local_main, p) != 0) {
      snprintf(err, errlen, "cannot start the evaluation thread: %s", strerror(errno));
      sw_pool_close(p, 0);
      return NULL;
    }
    p->local.started = 1;
    struct sigaction a;
    memset(&a, 0, sizeof a);
    a.sa_handler = on_stop_signal;
    sigemptyset(&a.sa_mask);
    stop_requested = 0;
    p->handlers = sigaction(SIGINT, &a, &p->old_int) == 0 &&
                  sigaction(SIGTERM, &a, &p->old_term) == 0;
  }
  return p;
}

int sw_pool_size(const swPool *p) { return p->size; }
int sw_pool_lost(const swPool *p) { return p->nlost; }

void sw_pool_close(swPool *p, int code) {
  if (!p) return;
  int detached = 0;
  if (p->local.started) {
    pthread_mutex_lock(&p->local.mu);
    p->local.quit = 1;
    pthread_cond_signal(&p->local.cv);
    pthread_mutex_unlock(&p->local.mu);
    /* an evaluation still running (the study was interrupted) is left to
     * the process's exit rather than waited for; it still uses p, which is
     * therefore not freed */
    if (p->local.has_task) {
      pthread_detach(p->local.thread);
      detached = 1;
    } else {
      pthread_join(p->local.thread, NULL);
    }
  }
  if (p->handlers) {
    sigaction(SIGINT, &p->old_int, NULL);
    sigaction(SIGTERM, &p->old_term, NULL);
  }
  if (p->mpi) {
    if (p->rank == 0)
      for (int r = 1; r < p->size; r++)
        if (!p->lost[r]) p->mpi->send_stop(r);
    /* MPI_Abort takes down ranks that may be mid-evaluation; a lone
     * process (the simulator run by hand, or `mpirun -np 1`) has none, so
     * it finalizes and exits with the code.  (Through MPI_Abort, a Ctrl-C
     * test under CI's load once ended by SIGKILL, 137 instead of 130.) */
    if (p->nlost > 0 || (p->rank == 0 && stop_requested && p->size > 1)) p->mpi->abort(code);
    else p->mpi->finalize();
  }
  if (detached) return;
  free(p->task);
  free(p->started);
  free(p->lost);
  free(p->local.P);
  free(p);
}

/* ---- a worker rank ---- */

/* SINEW_STUDY_FAULT=MODE:RANK:K, for the tests of re-queueing. */
static void maybe_fault(int rank, long served) {
  const char *f = getenv("SINEW_STUDY_FAULT");
  if (!f) return;
  char mode[8];
  int r;
  long k;
  if (sscanf(f, "%7[a-z]:%d:%ld", mode, &r, &k) != 3 || r != rank || k != served) return;
  if (!strcmp(mode, "exit")) _exit(9);
  if (!strcmp(mode, "hang"))
    for (;;) pause();
}

int sw_pool_serve(swPool *p) {
  const int np = p->o->nparam;
  double *P = malloc(((size_t)np + 1) * sizeof *P);
  if (!P) return SW_EIO;
  long served = 0;
  for (;;) {
    long index;
    double dt_scale = 1;
    int got = p->mpi->poll_task(&index, &dt_scale, P, np);
    if (got < 0) break;
    if (got == 0) {
      nap();
      continue;
    }
    maybe_fault(p->rank, ++served);
    swStudyEval r;
    evaluate(p->o, p->rank, P, dt_scale, &r);
    p->mpi->send_result(index, &r);
  }
  free(P);
  return SW_OK;
}

/* ---- the dispatcher ---- */

static double timeout_of(const swPool *p) {
  if (p->o->eval_timeout > 0) return p->o->eval_timeout;
  double t = TIMEOUT_FACTOR * p->slowest;
  return t > TIMEOUT_FLOOR ? t : TIMEOUT_FLOOR;
}

int sw_pool_run(swPool *p, long ntask, const long *index, const double *P, double dt_scale,
                swPoolResultFn cb, void *ctx) {
  const int np = p->o->nparam;
  /* the queue: positions in the batch, in order; a re-queued one goes to
   * the front, so that results keep arriving close to the order asked */
  long *queue = malloc(((size_t)ntask + 1) * sizeof *queue);
  char *tried = calloc((size_t)ntask + 1, 1);     /* failed once already */
  int *failed_on = malloc(((size_t)ntask + 1) * sizeof *failed_on);
  if (!queue || !tried || !failed_on) {
    free(queue);
    free(tried);
    free(failed_on);
    return SW_EIO;
  }
  long head = 0, tail = 0;
  for (long i = 0; i < ntask; i++) queue[tail++] = i;
  for (long i = 0; i < ntask; i++) failed_on[i] = -1;
  long remaining = ntask;
  int rc = SW_OK;
  /* the queue has room: a position is in it, running, or done */
  while (remaining > 0 && rc == SW_OK) {
    if (stop_requested) {
      rc = SW_EINTERRUPT;
      break;
    }
    /* hand out work to idle workers */
    for (int w = 0; w < p->size && head < tail; w++) {
      if (p->lost[w] || p->task[w] >= 0) continue;
      long pos = queue[head];
      if (failed_on[pos] == w && p->size - p->nlost > 1) continue;   /* elsewhere */
      head++;
      p->task[w] = pos;
      p->started[w] = sw_wall_seconds();
      if (w == 0) local_give(p, index[pos], dt_scale, P + pos * np);
      else p->mpi->send_task(w, index[pos], dt_scale, P + pos * np, np);
    }
    /* collect what has finished */
    int any = 0;
    long got_index;
    swStudyEval r;
    int w = -1;
    if (p->task[0] >= 0 && local_take(p, &got_index, &r)) w = 0;
    else if (p->mpi && p->mpi->poll_result(&w, &got_index, &r)) {
      if (w <= 0 || w >= p->size || p->lost[w] || p->task[w] < 0 ||
          index[p->task[w]] != got_index)
        w = -2;   /* a late answer of a rank given up on: ignored */
    }
    if (w >= 0) {
      any = 1;
      long pos = p->task[w];
      p->task[w] = -1;
      if (r.interrupted) {
        stop_requested = 1;
        rc = SW_EINTERRUPT;
        break;
      }
      if (r.wall > p->slowest) p->slowest = r.wall;
      if (r.status == SW_EVAL_FAILED && !tried[pos] && p->size - p->nlost > 1) {
        tried[pos] = 1;
        failed_on[pos] = w;
        queue[--head] = pos;   /* head > 0: pos was taken from the queue */
        if (!p->o->quiet)
          fprintf(stderr, "%s: evaluation %ld failed on rank %d (%s); trying it on another\n",
                  p->o->prog, got_index, w, r.message);
        continue;
      }
      remaining--;
      int cbrc = cb(ctx, got_index, P + pos * np, &r);
      if (cbrc != SW_OK) rc = cbrc;
    }
    /* remote evaluations that outlived the timeout: re-queued, rank lost */
    double t = sw_wall_seconds(), limit = timeout_of(p);
    for (int v = 1; v < p->size; v++) {
      if (p->lost[v] || p->task[v] < 0 || t - p->started[v] <= limit) continue;
      long pos = p->task[v];
      p->lost[v] = 1;
      p->nlost++;
      p->task[v] = -1;
      queue[--head] = pos;
      fprintf(stderr, "%s: rank %d has not answered evaluation %ld in %.0f s; it is given to "
              "another worker and rank %d is not used again\n", p->o->prog, v, index[pos],
              t - p->started[v], v);
    }
    if (!any) nap();
  }
  free(queue);
  free(tried);
  free(failed_on);
  return rc;
}
