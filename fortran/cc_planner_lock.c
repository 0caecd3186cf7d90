/* One process-wide lock around FFTW planning (plan creation and destruction are not
 * thread-safe in FFTW 3; fftw_execute is). Lives with the Fortran tables so that every
 * caller of the C interface, not only C++, is protected. */
#include <pthread.h>

static pthread_mutex_t planner_mutex = PTHREAD_MUTEX_INITIALIZER;

void cc_planner_lock(void) { pthread_mutex_lock(&planner_mutex); }
void cc_planner_unlock(void) { pthread_mutex_unlock(&planner_mutex); }
