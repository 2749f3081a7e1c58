/* sinew_io.h — part of sinew.h (include that): what touches files, and the
 * run loop that writes them.
 *
 * Design.  Output files (HDF5, the XDMF beside them), the checkpoint that
 * lets a run continue (SIM --restart), the comparison with a golden file, the
 * run loop that steps a model and writes its frames, and the units' table and
 * parser that the command line and the compiler share.  Implemented in
 * runtime/io/, whose files are, with a study's file (study/study_file.c),
 * the only ones that include hdf5.h; the header itself does not, so the
 * generated C never sees it. */
#ifndef SINEW_IO_H
#define SINEW_IO_H

#include <stdio.h>
#include "sinew_model.h"

/* ---- output (io/output.c, output_datasets.c, output_attrs.c) ---- */
typedef struct swOutput swOutput;
typedef struct {
  const char *model_source;   /* full text, imports inlined (may be NULL)   */
  const char *model_sha256;   /* hex digest (may be NULL)                   */
  const char *params;         /* "name=value;..." (may be NULL)             */
  double duration;            /* s                                           */
  int velocity;               /* also write /rods/NAME/velocity             */
  int directors;              /* also write /rods/NAME/directors            */
  /* Per-item selection (SW_OUT_* bits), each array NULL for the default:
   * rods write their position (and velocity, directors as above), joints and
   * muscles every quantity they have. */
  const unsigned *rod_out;    /* (nrod)                                     */
  const unsigned *joint_out;  /* (njoint)                                   */
  const unsigned *muscle_out; /* (nmuscle)                                  */
  /* The params as a table /params of nparam rows (name, value, unit,
   * default): value and default in unit ("" if none); nparam may be 0. */
  int nparam;
  const char *const *param_name;
  const double *param_value, *param_default;
  const char *const *param_unit;
  double every;               /* s between frames (0: every step), recorded
                                 so that a continued run keeps it          */
} swOutputOptions;

/* What the output writes of each rod, joint and muscle (bits). */
enum {
  /* rods */
  SW_OUT_POSITION = 1u << 0,         /* /rods/NAME/position          [F, n+1, 3] m   */
  SW_OUT_VELOCITY = 1u << 1,         /* velocity                     [F, n+1, 3] m/s */
  SW_OUT_DIRECTORS = 1u << 2,        /* directors                    [F, n, 3, 3]    */
  SW_OUT_ANGULAR_VELOCITY = 1u << 3, /* angular_velocity (material)  [F, n, 3] rad/s */
  SW_OUT_STRAIN = 1u << 4,           /* strain sigma (material)      [F, n, 3]       */
  SW_OUT_CURVATURE = 1u << 5,        /* curvature kappa (material)   [F, n-1, 3] rad/m */
  SW_OUT_INTERNAL_FORCE = 1u << 6,   /* internal_force n (material)  [F, n, 3] N     */
  SW_OUT_INTERNAL_COUPLE = 1u << 7,  /* internal_couple (material)   [F, n-1, 3] N m */
  /* joints */
  SW_OUT_ANGLE = 1u << 8,            /* /joints/NAME/angle (hinges)  [F] rad         */
  SW_OUT_JOINT_FORCE = 1u << 9,      /* force                        [F, 3] N        */
  SW_OUT_LIMIT_TORQUE = 1u << 14,    /* limit_torque (limited joints) [F, 3] N m     */
  /* muscles */
  SW_OUT_MUSCLE_FORCE = 1u << 10,    /* /muscles/NAME/force          [F] N           */
  SW_OUT_STRETCH = 1u << 11,         /* stretch                      [F]             */
  SW_OUT_ACTIVATION = 1u << 12,      /* activation                   [F]             */
  SW_OUT_FILAMENT_FORCE = 1u << 13   /* filament_force               [F, filaments] N */
};

swOutput *sw_output_open(const char *path, const swModel *m, const swOutputOptions *o,
                         char *err, size_t errlen);
int sw_output_frame(swOutput *o, const swModel *m, swData *d);
/* SIM --restart (restart.c): reopens a file a run of the same model (same
 * model_sha256, params and `every`) wrote, puts the state of its checkpoint
 * into d (and the expectations' into x, may be NULL), cuts its datasets back
 * to the frames it held then, and appends from there. */
swOutput *sw_output_resume(const char *path, const swModel *m, const swOutputOptions *o,
                           swData *d, swExpectRun *x, char *err, size_t errlen);
/* The model's hash (sha256[65]), the params ("name=value;...", SI), the
 * time step and the frame interval (s; -1 if not recorded) and the
 * integrator (integrator[16]: "position-verlet", "pefrl" or "imex"; "" if
 * not recorded) a file's run had, for SIM --restart.  SW_OK or SW_EIO. */
int sw_output_read_run(const char *path, char *sha256, char *params, size_t len, double *dt,
                       double *every, char *integrator);
/* The run loop's checkpoint at a scheduled frame, just written: taken
 * into memory at the run's last frame (`last`) and otherwise at most every
 * quarter second of wall time, written to /restart every 10 s and at
 * close. */
int sw_output_checkpoint(swOutput *o, const swModel *m, const swData *d, const swExpectRun *x,
                         int last);
int sw_output_close(swOutput *o, const char *status);
/* The run's objective as root attributes objective, penalty, score (SI;
 * NaN when not reached) with their units (objective_units, penalty_units,
 * score_units: `units`) and objective_text ("maximize EXPR"); written
 * again if given again. */
int sw_output_objective(swOutput *o, const char *text, double objective, double penalty,
                        double score, const char *units);
long sw_output_frames(const swOutput *o);
/* SIM --accuracy (accuracy.c): two runs of one model at steps dt and dt/2,
 * observable by observable, frame by frame.  The observables are the probes
 * (/probes/NAME, the largest difference of the vector) and the hinge angles
 * (/joints/NAME/angle); each is held to its scale, its range over the finer
 * run (its largest magnitude if it barely moves), and parts where the
 * difference first exceeds tol times that scale.  The objective, when the
 * files have one, is compared by value. */
#define SW_ACCURACY_MAX 64
typedef struct {
  char name[96];             /* "probe toe", "joint right.knee_joint"      */
  char units[32];            /* the dataset's, SI                           */
  double worst;              /* largest difference over the frames          */
  double scale;              /* the observable's scale (see above)          */
  double part_time;          /* s, first frame past tol * scale; NAN: never */
} swAccuracyItem;
typedef struct {
  int n, more;               /* items kept, and those past SW_ACCURACY_MAX  */
  swAccuracyItem item[SW_ACCURACY_MAX];
  long frames;               /* frames compared (the shorter file's)        */
  long frames_coarse, frames_fine;
  int has_objective;
  double objective[2];       /* SI, coarse and fine (NaN: not reached)      */
} swAccuracy;
/* Fills a from the two files; SW_OK, or SW_EIO with the reason in err. */
int sw_accuracy_compare(const char *coarse, const char *fine, double tol, swAccuracy *a,
                        char *err, size_t errlen);

/* SIM --compare (compare.c): every numeric dataset of the golden file against
 * the run's, within rtol of the dataset's largest magnitude; the report to
 * f.  Returns how many datasets differ or are missing, -1 when a file cannot
 * be opened. */
int sw_compare_files(const char *run_path, const char *golden_path, double rtol, FILE *f,
                     const char *prog);
/* Message of the most recent failed sw_output_* call in this thread (names the
 * file and the object; "" if none failed).  Added because sw_output_frame()
 * and sw_output_close() have no err argument. */
const char *sw_output_error(void);

/* ---- the run loop (run.c): steps, frames, SIGINT, progress ---- */
typedef struct {
  double duration;       /* s */
  double every;          /* s between frames; 0 = every step            */
  int quiet;             /* no progress line                             */
  FILE *log;             /* messages (stderr when NULL)                  */
  swExpectRun *expect;   /* expectations to sample (NULL: none)          */
  int resumed;           /* the state is the output's last frame, already
                            written and sampled (sw_output_resume)      */
  int silent;            /* no message at all, not even an instability's
                            (it stays in d->error): sw_evaluate         */
} swRunOptions;

int sw_run(const swModel *m, swData *d, swOutput *out, const swRunOptions *ro);

/* Seconds of a monotonic clock, for wall times (progress, a study's
 * evaluations, benchmarks). */
double sw_wall_seconds(void);

/* The number of steps of dt that span `duration` (rounded to the nearest),
 * into *nsteps.  SW_EUSAGE, with the reason in err, when the run is absurd:
 * dt or duration not finite or not positive (a duration of 0 is 0 steps),
 * a positive duration shorter than half a step (no step would be taken),
 * or more than SW_MAX_STEPS steps (10^13: at a microsecond a step, four
 * months of wall time; beyond what any run here is for). */
#define SW_MAX_STEPS 1e13
int sw_step_count(double duration, double dt, long *nsteps, char *err, size_t errlen);

/* Parse a duration with optional unit ("50ns", "0.5 s", "2ms", "1e-3").
 * Returns 0 on success. */
int sw_parse_time(const char *text, double *seconds);

/* ---- units (units.c): the one table of unit names, shared with the
 * compiler, and the parser of quantities on the command line ---- */
enum { SW_DIM_MASS = 0, SW_DIM_LENGTH, SW_DIM_TIME, SW_DIM_ANGLE, SW_NDIM };
typedef struct {
  const char *name;            /* "kPa", "g", "deg"                         */
  double scale;                /* value of 1 name in SI (rad for angles)    */
  signed char dim[SW_NDIM];    /* exponents of kg, m, s, rad                */
} swUnit;
const swUnit *sw_unit_find(const char *name, size_t len);   /* NULL: unknown */
const swUnit *sw_unit_table(int *count);
/* Parse "0.3 m", "1.75 g/cm^3", "50ns", "-2", "10 N/m" into SI value and
 * dimension.  Returns 0, or nonzero with a message in err. */
int sw_parse_quantity(const char *text, double *si, signed char dim[SW_NDIM], char *err,
                      size_t errlen);
/* "length (m)", "pressure (Pa)", "kg m^-1 s^-2", "dimensionless" */
const char *sw_dim_describe(char *buf, size_t len, const signed char dim[SW_NDIM]);

#endif
