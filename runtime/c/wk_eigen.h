/* wristkin: dense real eigenvalues, the quadratic eigenproblem and null vectors (C99, libm only; do not edit).
 * @generated-by@
 *
 * Written for the general-6R elimination (issue 23): per pose a 12x12 matrix polynomial
 * M(x) = A x^2 + B x + C in x = tan(theta/2) whose real eigenvalues are the joint's solutions and whose null
 * vectors back-substitute the others. No allocation, no VLAs: fixed-size stack arrays bounded by the
 * WK_*_MAX constants below; every size is checked before anything is read.
 *
 * Return codes (all three entry points): WK_EIG_OK, or a negative WK_EIG_ERR_* (outputs then hold no result).
 *
 * Accuracy contract.
 *   wk_eig_real is backward stable: the computed eigenvalues are the exact eigenvalues of A + E with
 *   ||E||_F <= c n eps ||A||_F (c a modest constant, eps = 2^-52; balancing and the power-of-two scalings are
 *   exact). A simple eigenvalue lambda is therefore within about c n eps ||A|| / s(lambda) of the true one,
 *   where s(lambda) = |y^H x| for unit left/right eigenvectors (the Wilkinson condition); an eigenvalue of
 *   multiplicity k in a Jordan block is only determined to about (c n eps ||A||)^(1/k) times a condition
 *   factor, so such clusters come back spread out (possibly as complex pairs) by that much. Eigenvalues in
 *   the subnormal range are, in addition, rounded to a multiple of 2^-1074.
 *   wk_generalized_quadratic_eig is backward stable for the *linearisation* it chooses (see wk_eigen.c), which
 *   carries over to the polynomial up to the growth of the companion matrix: with the parameter scaling
 *   x = g mu (g^2 ~ ||C|| / ||A||) and n_max = max(||A|| g^2, ||B|| g, ||C||), each eigenvalue x is exact for
 *   (A + dA) x^2 + (B + dB) x + (C + dC) with ||dA|| g^2, ||dB|| g, ||dC|| <= c m eps growth n_max, where
 *   growth = max(1, ||L^-1 [C' B']||_1) (L the leading coefficient used, C' B' the other two, all scaled;
 *   returned in the result, with L's reciprocal condition rcond). growth is a few units for a balanced,
 *   well-conditioned problem; it grows like 1 / rcond when L is near singular, and like
 *   ||B|| / sqrt(||A|| ||C||) for a heavily damped problem, whose small roots then carry an absolute error
 *   ~ eps growth g (Higham, Li & Tisseur 2007: inherent to companion forms). The caller's polish on the true
 *   chain recovers full accuracy where it matters.
 *   wk_null_vector (one-sided Jacobi SVD): the returned v has |M v| <= (sigma_min + c m eps sigma_max), and its
 *   angle to the true right singular vector is <= c m eps sigma_max / (sigma_2 - sigma_min) (sigma_2 the
 *   second smallest singular value), which the caller reads off the two returned ratios.
 */
#ifndef WK_EIGEN_H
#define WK_EIGEN_H

#ifdef __cplusplus
extern "C" {
#endif

#define WK_EIG_OK 0
#define WK_EIG_ERR_NOCONV (-1)   /* an iteration cap was hit (QR: 30 iterations for one eigenvalue) */
#define WK_EIG_ERR_INPUT (-2)    /* NULL pointer, size out of range, a NaN/inf entry, or an eigenvalue > DBL_MAX */
#define WK_EIG_ERR_SINGULAR (-3) /* quadratic: det(A x^2 + B x + C) vanishes identically (numerically) */

#define WK_EIG_MAXN 32  /* wk_eig_real: n <= 32 */
#define WK_QEP_MAXM 12  /* wk_generalized_quadratic_eig: m <= 12 (a 24 x 24 linearisation) */
#define WK_NULL_MAXM 24 /* wk_null_vector: m <= 24 */

/* Workspace doubles wk_eig_real needs for an n x n matrix. */
#define WK_EIG_WORK(n) (2 * (n))

/* All eigenvalues of the real n x n row-major matrix a (overwritten: on return it holds an upper Hessenberg
 * matrix similar to a scaled, balanced copy of the input). Eigenvalue k is wr[k] + i wi[k]; a complex pair
 * comes as two consecutive entries, +wi first. work: WK_EIG_WORK(n) doubles. Steps: an exact power-of-two
 * scaling to max|a| ~ 1, Parlett-Reinsch balancing (powers of 2), Householder reduction to Hessenberg form,
 * Francis implicit double-shift QR with deflation and exceptional shifts at iterations 10 and 20; 30
 * iterations without a deflation -> WK_EIG_ERR_NOCONV. */
int wk_eig_real(int n, double *a, double *wr, double *wi, double *work);

/* The quadratic eigenproblem det(A x^2 + B x + C) = 0, m x m row-major coefficients, m <= WK_QEP_MAXM. */
#define WK_QEP_FLAG_DOUBLE 1u /* a conjugate pair within tol of the real axis, reported once at its real part */

/* Default for tol (see wk_eigen.c): 2^-20 ~ 9.5e-7 in angle theta = 2 atan(x). */
#define WK_QEP_TOL_DEFAULT 9.5367431640625e-07

typedef struct {
    int n_real;                             /* finite real eigenvalues, ascending */
    double real[2 * WK_QEP_MAXM];
    unsigned real_flags[2 * WK_QEP_MAXM];   /* WK_QEP_FLAG_DOUBLE: counts twice */
    int n_complex;                          /* conjugate pairs, one entry each (im > 0) */
    double complex_re[WK_QEP_MAXM];
    double complex_im[WK_QEP_MAXM];
    int n_infinite;                         /* eigenvalues at x = infinity (theta = pi), or beyond 2 / tol */
    double rcond;                           /* 1-norm reciprocal condition of the leading coefficient used */
    double growth;                          /* max(1, ||L^-1 [C' B']||_1): the backward error factor */
    double angle;                           /* Moebius rotation used: x = g (cos a y + sin a) / (cos a - sin a y) */
} wk_qep_result;

/* n_real (doubles counted twice) + 2 n_complex + n_infinite = 2 m on success. tol <= 0 means
 * WK_QEP_TOL_DEFAULT; tol is a distance in theta = 2 atan(x): a pair with 2 |Im x| / (1 + |x|^2) <= tol is
 * one real double root, and |x| >= 2 / tol is infinite. */
int wk_generalized_quadratic_eig(int m, const double *A, const double *B, const double *C, double tol,
                                 wk_qep_result *out);

/* A unit vector v (m entries) minimising |M v| for the m x m row-major M (one-sided Jacobi SVD).
 * rel (may be NULL): rel[0] = sigma_min / sigma_max (how nearly M v = 0), rel[1] = sigma_2 / sigma_max with
 * sigma_2 the second smallest singular value (v is determined to about m eps / (rel[1] - rel[0]) radians);
 * m = 1 gives v = (1) and rel[1] = 1; M = 0 (m >= 2) gives v = e_1 and rel = {0, 0}. */
int wk_null_vector(int m, const double *M, double *v, double *rel);

/* The k right singular vectors of the m x m row-major M for its k smallest singular values, in v (k rows of m, the
 * smallest first), and all m singular values over the largest, ascending, in rel (the same one-sided Jacobi SVD
 * as wk_null_vector: ~4x an LU at m = 12). M = 0 gives rel = 0 and the unit vectors. */
int wk_small_singular_vectors(int m, const double *M, int k, double *v, double *rel);

/* The same for an M known to have a one-dimensional (numerical) null space, e.g. M(x) at a simple eigenvalue
 * x of the quadratic: LU with complete pivoting + two steps of inverse iteration on M^T M, ~4x cheaper than
 * the Jacobi SVD at m = 12; |M v| within a small multiple of sigma_min + c m eps ||M||. It does not tell how
 * well v is determined: resid (may be NULL) = |M v| / ||M||_F, computed, is the only output
 * about quality; where the null space may be two-dimensional (a double root) use wk_null_vector. M = 0 gives
 * v = e_1, resid 0. WK_EIG_ERR_NOCONV only if a solve overflowed, which finite M cannot make happen: the
 * pivots are floored at eps |u_11| and complete pivoting bounds each triangular solve's growth by 2^m. */
int wk_null_vector_lu(int m, const double *M, double *v, double *resid);

#ifdef __cplusplus
}
#endif

#endif /* WK_EIGEN_H */
