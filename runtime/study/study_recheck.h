/* study_recheck.h — the recheck of a study's best designs at dt/2
 * (study_recheck.c), for study.c. */
#ifndef SINEW_STUDY_RECHECK_H
#define SINEW_STUDY_RECHECK_H
#include "study.h"
#include "study_file.h"
#include "study_pool.h"

typedef struct swRecheck swRecheck;

/* The recheck of o->recheck designs; NULL when o->recheck is 0 or memory
 * is short (the study then goes on without it). */
swRecheck *sw_recheck_new(const swStudyOptions *o);

/* A design that ran (status ok), as the study takes its result: its index,
 * every param (SI), its score and objective as the file stores them (in
 * the objective's unit).  Keeps the best o->recheck distinct designs and
 * the size of every objective. */
void sw_recheck_offer(swRecheck *k, long index, const double *P, double score, double objective);

/* The /recheck rows of a resumed file: those of designs still among the
 * best are taken rather than evaluated again. */
void sw_recheck_stored(swRecheck *k, const swStudyRecheck *rows, long n);

/* Once the study is complete: evaluates its best designs at dt/2 on the
 * pool's workers (but those the file holds, and all of them with
 * o->no_recheck), writes /recheck and prints the report on stderr (with
 * o->quiet, a warning when a design is sensitive to the step).  SW_OK;
 * SW_EINTERRUPT (the rechecks that arrived are written, --resume does the
 * rest); SW_EIO. */
int sw_recheck_run(swRecheck *k, swPool *pool, swStudyFile *f);

void sw_recheck_free(swRecheck *k);

#endif
