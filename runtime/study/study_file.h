/* study_file.h — the HDF5 file of a study (study_file.c), for study.c. */
#ifndef SINEW_STUDY_FILE_H
#define SINEW_STUDY_FILE_H
#include "study.h"

typedef struct swStudyFile swStudyFile;

/* What the file records beside the options. */
typedef struct {
  const swStudyOptions *o;
  const char *seed_text;        /* the seed, decimal (64 bits exact)          */
  const char *start_text;       /* "name=value;..." SI: every param's start    */
  const char *varied_text;      /* "name;name;..."                            */
  int nvar;                     /* the varied params: names, units, SI bounds */
  const char *const *design_name, *const *design_unit;
  const double *design_lo, *design_hi;
} swStudyFileInfo;

/* One of a study's best designs evaluated again at dt/2 (a row of
 * /recheck, best first; study_recheck.c): as /evaluations has it at dt, as
 * the recheck found it at dt/2, and how far apart the two are. */
typedef struct {
  long index;                   /* the design's row of /evaluations          */
  double dt;                    /* s: the step of its evaluation (the
                                   recheck's is dt/2); 0: unknown           */
  double objective, score;      /* at dt, in the objective's unit            */
  int status_half;              /* swEvalStatus at dt/2                      */
  double objective_half, score_half;   /* at dt/2 (NaN unless ok)           */
  double difference;            /* |objective_half - objective| / size, the
                                   size max(|objective|, the floor)          */
  int sensitive;                /* 1: difference over the tolerance, or the
                                   design failed at dt/2                     */
} swStudyRecheck;

/* The evaluations a file holds (for --resume): n rows, P in the units
 * shown, Psi in SI (NULL when the file predates /evaluations/params_si;
 * a row of NaN where it lacks that row), status swEvalStatus,
 * objective/penalty/score in the objective's unit; and the nrecheck rows
 * of its /recheck (index, dt and the results at dt/2; none when it has
 * none, or one that cannot be read, which the recheck then redoes). */
typedef struct {
  long n;
  double *P, *Psi;
  int *status;
  double *objective, *penalty, *score;
  long nrecheck;
  swStudyRecheck *recheck;
} swStudyRows;

swStudyFile *sw_study_file_create(const swStudyFileInfo *in, char *err, size_t errlen);
swStudyFile *sw_study_file_reopen(const swStudyFileInfo *in, swStudyRows *rows, char *err,
                                  size_t errlen);
void sw_study_rows_free(swStudyRows *rows);
/* Row `index`: the params as shown (units of the model) and in SI, r's
 * values divided by shown_scale (the objective's unit). */
int sw_study_file_write(swStudyFile *f, long index, int generation, const double *Pshown,
                        const double *Psi, const swStudyEval *r, double shown_scale);
/* Row `index` of /evaluations/params_si alone (SI): --resume of a file
 * that predates it fills it in for the rows it holds, from the designs
 * regenerated and checked against them. */
int sw_study_file_params_si(swStudyFile *f, long index, const double *Psi);
int sw_study_file_best(swStudyFile *f, long index, const double *Pshown, double score,
                       double objective, double penalty);
int sw_study_file_generation(swStudyFile *f, long g, double sigma, const double *mean, int nvar,
                             double best_score, long evaluations);
/* /recheck: n rows (0: none, and a /recheck the file has is removed), with
 * the tolerance (a fraction) and the floor of the sizes (the objective's
 * unit) the verdicts were made with. */
int sw_study_file_recheck(swStudyFile *f, const swStudyRecheck *rows, long n, double tolerance,
                          double floor);
int sw_study_file_attr(swStudyFile *f, const char *name, const char *value);
int sw_study_file_close(swStudyFile *f, const char *status);
#endif
