/* internal.h — declarations shared between runtime files but not part of the
 * public interface (generated code never sees them). */
#ifndef SW_INTERNAL_H
#define SW_INTERNAL_H
#include "sinew.h"

void sw_bc_kick(const swModel *m, swData *d, double h, double t);     /* boundary.c  */
void sw_bc_loads(const swModel *m, swData *d);                        /* boundary.c  */
double sw_bc_energy(const swModel *m, const swData *d);               /* boundary.c  */
/* Largest h * omega for which the integrator is stable on the damped
 * oscillator x'' = -omega^2 x - c x', as a function of zeta = c / omega. */
double sw_integrator_stability_limit(swIntegrator integ, double zeta); /* stability.c */
#endif
