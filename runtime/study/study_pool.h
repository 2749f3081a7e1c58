/* study_pool.h — the workers of a study (study_pool.c) and the MPI transport
 * they may use (study_mpi.c, linked only when sinew was built with MPI). */
#ifndef SINEW_STUDY_POOL_H
#define SINEW_STUDY_POOL_H
#include "study.h"

/* The MPI side, one message at a time.  A task is an index, the factor of
 * its time step (swStudyEvalFn's dt_scale) and the nparam values of a
 * design; a result is the index and its swStudyEval.  Every call
 * but init returns at once (the callers poll and sleep), so that a rank
 * waiting for work does not spin on a core an evaluation needs. */
typedef struct {
  /* MPI_Init_thread (FUNNELED) and the rank and size of MPI_COMM_WORLD;
   * SW_OK or SW_EIO with a message. */
  int (*init)(int *rank, int *size, char *err, size_t errlen);
  void (*send_task)(int rank, long index, double dt_scale, const double *P, int nparam);
  void (*send_stop)(int rank);
  /* a result from any rank, if one has arrived: 1 and its fields, else 0 */
  int (*poll_result)(int *rank, long *index, swStudyEval *r);
  /* worker side: 1 with a task, -1 when told to stop, 0 when nothing came */
  int (*poll_task)(long *index, double *dt_scale, double *P, int nparam);
  void (*send_result)(long index, const swStudyEval *r);
  void (*finalize)(void);
  void (*abort)(int code);    /* ends every rank (a rank was lost)            */
} swStudyTransport;

/* Defined by study_mpi.c; a weak reference elsewhere, so that a simulator
 * linked without it still sweeps on one machine. */
const swStudyTransport *sw_study_mpi_transport(void);

typedef struct swPool swPool;

/* Opens the workers: a thread of this process and, when launched by mpirun
 * with MPI linked, the other ranks (MPI is initialised here).  *rank is this
 * process's rank (0 without MPI).  NULL with a message in err. */
swPool *sw_pool_open(const swStudyOptions *o, int *rank, char *err, size_t errlen);
int sw_pool_size(const swPool *p);    /* workers: 1 + other ranks            */

/* On a rank other than 0: evaluate the tasks rank 0 sends until it says
 * stop.  Returns SW_OK. */
int sw_pool_serve(swPool *p);

/* Called by sw_pool_run for every result, as it arrives, in any order. Its
 * non-zero return stops the run with that code. */
typedef int (*swPoolResultFn)(void *ctx, long index, const double *P, const swStudyEval *r);

/* Evaluates ntask designs (P: ntask rows of nparam, index: their numbers in
 * the study, distinct) on the workers, each at the step its evaluation takes
 * times dt_scale (1: as the study runs them), and calls back with each
 * result.  A remote
 * evaluation that outlives the timeout is given to another worker and its
 * rank is not used again; one that fails for a reason not of the design's
 * (SW_EVAL_FAILED) is tried once more on another worker.  Returns SW_OK,
 * SW_EINTERRUPT (Ctrl-C or SIGTERM: the results not yet in are dropped), or
 * the callback's code. */
int sw_pool_run(swPool *p, long ntask, const long *index, const double *P, double dt_scale,
                swPoolResultFn cb, void *ctx);

/* How many ranks were lost (their evaluations re-queued). */
int sw_pool_lost(const swPool *p);

/* Stops the workers and ends MPI (MPI_Abort with `code` if a rank was lost,
 * since MPI_Finalize would wait for it); frees p. */
void sw_pool_close(swPool *p, int code);

/* 1 once Ctrl-C or SIGTERM arrived during the study. */
int sw_pool_interrupted(void);

#endif
