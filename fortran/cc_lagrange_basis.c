/* The 12-point Lagrange basis of evaluate_kernel_h_many (cc_kernel_tables.f90) for a chunk of
 * tabulated points: that loop's operations in its order (lagrange_basis_12's), built for SSE2
 * and for AVX2 and chosen when the library is loaded. Neither build contracts a multiply and
 * an add (FMA), so both give the elemental path's bits on every x86-64 host; AVX2 computes four
 * points per instruction instead of two (docs/speed.md, "Maugis-Dugdale 2-D table nodes").
 * ell is the Fortran array ell(chunk, 0:11), chunk = 64 there: ell[j * 64 + k] (a constant
 * stride, so that the twelve columns are known apart and the loop vectorizes). */
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define CC_BASIS_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define CC_BASIS_CLONES
#endif

enum { chunk = 64 };

CC_BASIS_CLONES void cc_lagrange_basis_12(int count, const double* restrict uu, double du,
                                          const double* restrict w, int* restrict index,
                                          double* restrict offset, double* restrict ell) {
  for (int k = 0; k < count; ++k) {
    double t = uu[k] / du;
    const int i = (int)t;
    index[k] = i;
    t = t - (double)i;
    offset[k] = t;
    const double d0 = t + 5.0, d1 = t + 4.0, d2 = t + 3.0, d3 = t + 2.0, d4 = t + 1.0, d5 = t;
    const double d6 = t - 1.0, d7 = t - 2.0, d8 = t - 3.0, d9 = t - 4.0, d10 = t - 5.0, d11 = t - 6.0;
    const double q0 = d5 * d6, q1 = d4 * d7, q2 = d3 * d8, q3 = d2 * d9, q4 = d1 * d10, q5 = d0 * d11;
    const double r01 = q0 * q1, r23 = q2 * q3, r45 = q4 * q5;
    const double o0 = q1 * (r23 * r45), o1 = q0 * (r23 * r45);
    const double o2 = q3 * (r01 * r45), o3 = q2 * (r01 * r45);
    const double o4 = q5 * (r01 * r23), o5 = q4 * (r01 * r23);
    ell[5 * chunk + k] = (w[5] * d6) * o0;
    ell[6 * chunk + k] = (w[6] * d5) * o0;
    ell[4 * chunk + k] = (w[4] * d7) * o1;
    ell[7 * chunk + k] = (w[7] * d4) * o1;
    ell[3 * chunk + k] = (w[3] * d8) * o2;
    ell[8 * chunk + k] = (w[8] * d3) * o2;
    ell[2 * chunk + k] = (w[2] * d9) * o3;
    ell[9 * chunk + k] = (w[9] * d2) * o3;
    ell[1 * chunk + k] = (w[1] * d10) * o4;
    ell[10 * chunk + k] = (w[10] * d1) * o4;
    ell[0 * chunk + k] = (w[0] * d11) * o5;
    ell[11 * chunk + k] = (w[11] * d0) * o5;
  }
}
