/* study_mpi.c — a study's messages over MPI (OpenMPI from Debian).
 *
 * Design.  Compiled only where mpicc exists, into its own object that sinewc
 * links beside libsinewrt.a (with mpicc's libraries), so that the runtime
 * and every simulator still build without MPI; study_pool.c finds this file
 * through a weak reference to sw_study_mpi_transport().  Rank 0 sends a
 * task as nparam + 2 doubles (the design's index first: exact below 2^53;
 * then the factor of its time step, 1 or 0.5 for a recheck at dt/2) with
 * TAG_TASK, or an empty TAG_STOP; a worker answers with its index and
 * swStudyEval as bytes (TAG_RESULT): the ranks of one study run one build of
 * one simulator, so the layout is the same everywhere.  Nothing here blocks
 * but MPI_Init: receives are MPI_Iprobe first, and sends are of a few
 * hundred bytes, which MPI buffers eagerly. */
#include <mpi.h>
#include <stdio.h>
#include <string.h>

#include "sinew.h"
#include "study_pool.h"

enum { TAG_TASK = 1, TAG_STOP = 2, TAG_RESULT = 3 };
#define MAX_PARAMS 4096

typedef struct {
  long index;
  swStudyEval r;
} swResultMsg;

static int mpi_init(int *rank, int *size, char *err, size_t errlen) {
  int provided = 0, argc = 0;
  char **argv = NULL;
  if (MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
    snprintf(err, errlen, "MPI_Init_thread failed");
    return SW_EIO;
  }
  if (provided < MPI_THREAD_FUNNELED) {
    snprintf(err, errlen, "this MPI does not allow a second thread beside MPI calls "
             "(MPI_THREAD_FUNNELED)");
    MPI_Finalize();
    return SW_EIO;
  }
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
  MPI_Comm_rank(MPI_COMM_WORLD, rank);
  MPI_Comm_size(MPI_COMM_WORLD, size);
  return SW_OK;
}

static void mpi_send_task(int rank, long index, double dt_scale, const double *P, int nparam) {
  double buf[MAX_PARAMS + 2];
  buf[0] = (double)index;
  buf[1] = dt_scale;
  memcpy(buf + 2, P, (size_t)nparam * sizeof *P);
  MPI_Send(buf, nparam + 2, MPI_DOUBLE, rank, TAG_TASK, MPI_COMM_WORLD);
}

static void mpi_send_stop(int rank) {
  MPI_Send(NULL, 0, MPI_DOUBLE, rank, TAG_STOP, MPI_COMM_WORLD);
}

static int mpi_poll_result(int *rank, long *index, swStudyEval *r) {
  int flag = 0;
  MPI_Status st;
  if (MPI_Iprobe(MPI_ANY_SOURCE, TAG_RESULT, MPI_COMM_WORLD, &flag, &st) != MPI_SUCCESS || !flag)
    return 0;
  swResultMsg m;
  if (MPI_Recv(&m, (int)sizeof m, MPI_BYTE, st.MPI_SOURCE, TAG_RESULT, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE) != MPI_SUCCESS)
    return 0;
  *rank = st.MPI_SOURCE;
  *index = m.index;
  *r = m.r;
  return 1;
}

static int mpi_poll_task(long *index, double *dt_scale, double *P, int nparam) {
  int flag = 0;
  MPI_Status st;
  if (MPI_Iprobe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st) != MPI_SUCCESS || !flag) return 0;
  if (st.MPI_TAG == TAG_STOP) {
    MPI_Recv(NULL, 0, MPI_DOUBLE, 0, TAG_STOP, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    return -1;
  }
  double buf[MAX_PARAMS + 2];
  MPI_Recv(buf, nparam + 2, MPI_DOUBLE, 0, TAG_TASK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  *index = (long)buf[0];
  *dt_scale = buf[1];
  memcpy(P, buf + 2, (size_t)nparam * sizeof *P);
  return 1;
}

static void mpi_send_result(long index, const swStudyEval *r) {
  swResultMsg m;
  memset(&m, 0, sizeof m);
  m.index = index;
  m.r = *r;
  MPI_Send(&m, (int)sizeof m, MPI_BYTE, 0, TAG_RESULT, MPI_COMM_WORLD);
}

static void mpi_finalize(void) { MPI_Finalize(); }
static void mpi_abort(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

static const swStudyTransport transport = {
  mpi_init, mpi_send_task, mpi_send_stop, mpi_poll_result, mpi_poll_task, mpi_send_result,
  mpi_finalize, mpi_abort,
};

const swStudyTransport *sw_study_mpi_transport(void) { return &transport; }
