/* sinew.h — the public interface of libsinewrt, the Cosserat rod runtime.
 *
 * Design.  A scene is described by a mutable swSpec (rods, loads, boundary
 * conditions, options), compiled once by sw_compile() into an immutable swModel
 * (flat arrays sized once, every derived constant precomputed), and simulated
 * in a mutable swData (positions, directors, velocities, time, scratch).  Every
 * kernel has the shape  f(const swModel *m, swData *d)  and nothing allocates
 * inside a step.
 *
 * Layout (docs/runtime.md, "Layout").  Nodes, elements and Voronoi domains of
 * all rods share one index space of slots, rods back to back (elastic rods
 * first, then rigid ones): rod r of n elements owns the n + 1 slots
 * [node_adr[r], node_adr[r] + n]; node i is slot node_adr[r] + i, element i is
 * slot elem_adr[r] + i and Voronoi domain j is slot vor_adr[r] + j, with
 * node_adr[r] == elem_adr[r] == vor_adr[r].  The last slot of a rod is a ghost
 * element and its last two slots ghost domains: they hold neutral values
 * (zero stiffness and load, unit lengths, identity frames) so that a kernel
 * can run one loop over all slots, as PyElastica's block layout does.  Arrays
 * are structure-of-arrays: a per-slot vector is three planes of m->stride
 * doubles and a frame nine, so component k of slot i is a[k * stride + i]
 * (SW_AT below) and entry (row a, column b) of a frame is plane 3a + b.
 * Vectors are 3-vectors, director frames are 3x3 matrices Q whose rows are
 * d1, d2, d3 in the lab frame (Gazzola et al. 2018, sec. 2), so Q maps lab
 * components to material ones; sw_get3/sw_getQ gather one slot's into a
 * plain double[3] or row-major double[9].
 *
 * The header is in parts, one per room of the runtime that implements them
 * (docs/runtime.md, "The rooms"): sinew_spec.h, the description of a scene
 * (engine/spec.c and the kernels' descriptors); sinew_model.h, the compiled
 * model, the state and the kernels (engine/); sinew_io.h, output files, the
 * run loop and units (io/); sinew_program.h, a compiled model as a program:
 * params, objective, one evaluation and the command line (study/, sim/).
 * Include this file, not the parts.  It and its parts are all that the
 * compiler's generated C may include.
 */
#ifndef SINEW_H
#define SINEW_H

#include <math.h>     /* generated code computes param-dependent values with sqrt, pow, sin */
#include <stddef.h>
#include <stdio.h>

#define SW_VERSION "0.1.0"

/* Status codes; they double as the process exit codes of
 * the simulators (docs/runtime.md, "Exit codes and status"). */
enum {
  SW_OK = 0,
  SW_EMODEL = 1,    /* the scene is invalid (bad sizes, materials, indices) */
  SW_EUSAGE = 2,    /* bad call or command-line argument */
  SW_EUNSTABLE = 3, /* the simulation became unstable */
  SW_EIO = 4,       /* file could not be written */
  SW_EEXPECT = 5,   /* an expect of the model (or --compare) failed */
  SW_EINTERRUPT = 130 /* stopped by SIGINT; output is valid up to the last frame */
};

#include "sinew_spec.h"     /* signals, swSpec and the descriptors of a scene      */
#include "sinew_model.h"    /* swModel, swData, sw_compile, the kernels            */
#include "sinew_io.h"       /* output, restart, compare, the run loop, units       */
#include "sinew_program.h"  /* params, objective, sw_evaluate, sw_main             */

#endif
