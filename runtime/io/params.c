/* params.c — the text record of a run's params: "name=value;...".
 *
 * Design.  One line of text, values in SI with 17 significant digits so that
 * reading it back gives the same doubles; it is what a run file's `params`
 * attribute holds (output.c), what SIM --restart compares (restart.c) and
 * what a study file records of its start (study/study.c).  It lives in io/
 * because files are where it goes; the simulator and the studies call it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "params.h"

/* "length=0.29999999999999999;strength=1", SI values, exact.  Caller frees. */
char *sw_params_text(int n, const char *const *name, const double *value) {
  size_t size = 1;
  for (int i = 0; i < n; i++) size += strlen(name[i]) + 32;
  char *text = malloc(size);
  if (!text) return NULL;
  size_t used = 0;
  text[0] = '\0';
  for (int i = 0; i < n; i++)
    used += (size_t)snprintf(text + used, size - used, "%s%s=%.17g", i ? ";" : "", name[i],
                             value[i]);
  return text;
}
