/* params.h — the text record of params (params.c), for the rooms above io/
 * (the simulator's command line and the studies). */
#ifndef SINEW_PARAMS_H
#define SINEW_PARAMS_H

/* "name=value;..." of n params, values SI with 17 digits (exact); the
 * record of a run's and a study's params.  NULL when out of memory; the
 * caller frees. */
char *sw_params_text(int n, const char *const *name, const double *value);

#endif
