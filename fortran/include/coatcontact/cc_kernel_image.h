/*
 * coatcontact: a kernel table (cc_kernel.h) as an array of doubles, its image, and the same
 * table made again from one, for the solve cache (cpp/solver/table_cache.cpp): a process that
 * finds a table's image skips building it. Implemented by fortran/cc_kernel_table_image.f90.
 * A table made from an image evaluates bit for bit as the table the image was taken from; an
 * image is only for the build that wrote it (the cache keys its entries by the build id).
 */
#ifndef COATCONTACT_CC_KERNEL_IMAGE_H
#define COATCONTACT_CC_KERNEL_IMAGE_H

#include "coatcontact/cc_kernel.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Number of doubles of the table's image. */
int cc_kernel_table_image_size(const cc_kernel_table *table, int *n_doubles);

/* The image into image[0 .. n_doubles - 1]; n_doubles must be cc_kernel_table_image_size's. */
int cc_kernel_table_image(const cc_kernel_table *table, int n_doubles, double *image);

/* A new table (*table; destroy with cc_kernel_table_destroy) from an image. CC_ERR_ARGUMENT
 * and *table = NULL for an image that is not one (a wrong length or format, sizes that do not
 * fit this build's tables, a value that is not finite). */
int cc_kernel_table_from_image(int n_doubles, const double *image, cc_kernel_table **table);

#ifdef __cplusplus
}
#endif

#endif
