/*
 * coatcontact: the one status vocabulary of the C interfaces (cc_kernel.h, coatcontact.h).
 *
 * Every function of both headers returns one of these codes. The three classes are the
 * command line's exit statuses: CC_INPUT_ERROR (2) a value outside its allowed range or a
 * bad argument, CC_NUMERICAL_ERROR (3) an accuracy target that could not be met,
 * CC_INTERNAL_ERROR (4) out of memory or an unexpected failure; CC_INTERRUPTED (5) a call stopped
 * on request by the calling thread's progress hook (cc_set_progress_hook in coatcontact.h). The kernel functions of
 * cc_kernel.h report a detail code (101 and up) that says which argument was refused;
 * cc_status_class() maps it to its class, cc_status_message() describes any code.
 * The Fortran constants are in kernels/cc_elastic_constants.f90 and must match.
 */
#ifndef COATCONTACT_CC_STATUS_H
#define COATCONTACT_CC_STATUS_H

#ifdef __cplusplus
extern "C" {
#endif

enum cc_status {
  CC_OK = 0,
  CC_INPUT_ERROR = 2,
  CC_NUMERICAL_ERROR = 3,
  CC_INTERNAL_ERROR = 4,
  CC_INTERRUPTED = 5,             /* stopped by the thread's progress hook (coatcontact.h) */
  /* details of the kernel functions; class in brackets */
  CC_ERR_FILM_MODULUS = 101,      /* [input] film Young's modulus not finite or <= 0 */
  CC_ERR_FILM_POISSON = 102,      /* [input] film Poisson ratio outside (-1, 0.5] or not finite */
  CC_ERR_SUBSTRATE_MODULUS = 103, /* [input] substrate Young's modulus not finite or <= 0 */
  CC_ERR_SUBSTRATE_POISSON = 104, /* [input] substrate Poisson ratio outside (-1, 0.5] */
  CC_ERR_ARGUMENT = 105,          /* [input] bad array length or order, negative or non-finite q or u, null handle */
  CC_ERR_FFT = 106,               /* [internal] FFTW could not plan the transform */
  CC_ERR_ALLOCATION = 107,        /* [internal] out of memory */
  CC_ERR_ACCURACY = 108,          /* [numerical] the table could not reach its accuracy target */
  CC_ERR_THICKNESS = 109,         /* [input] a stack layer's thickness not finite or <= 0 */
  CC_ERR_LAYER_COUNT = 110        /* [input] a stack with fewer than 1 or more than 1000 layers */
};

/* Short English description of any status code (static string, never NULL). */
const char *cc_status_message(int status);

/* The class of a status: CC_OK, CC_INPUT_ERROR, CC_NUMERICAL_ERROR, CC_INTERNAL_ERROR or
 * CC_INTERRUPTED (an unknown code is CC_INTERNAL_ERROR). */
int cc_status_class(int status);

#ifdef __cplusplus
}
#endif

#endif
