/* wristkin: status codes and flags shared by every generated mechanism (do not edit).
 * @generated-by@
 */
#ifndef WRISTKIN_COMMON_H
#define WRISTKIN_COMMON_H

#ifdef __cplusplus
extern "C" {
#endif

/* Return codes of every wk_* entry point (negative = error, out->count = 0). */
#define WK_OK 0
#define WK_ERR_NULL (-1)      /* a required pointer is NULL */
#define WK_ERR_NONFINITE (-2) /* NaN or inf in the input */
#define WK_ERR_DESIGN (-3)    /* design parameters out of range or not assemblable */
#define WK_ERR_RANGE (-4)     /* an argument is out of its range (e.g. batch size) */

/* Set-level status (out->status) when the call succeeded. */
#define WK_STATUS_OK 0
#define WK_STATUS_UNREACHABLE 1   /* IK: the pose cannot be reached; empty set */
#define WK_STATUS_NO_ASSEMBLY 2   /* FK: no real assembly mode; empty set */
#define WK_STATUS_INDETERMINATE 3 /* infinitely many solutions; representatives flagged */

/* Per-solution flag bits (out->flags[k]). */
#define WK_FLAG_SINGULAR_INVERSE 1u
#define WK_FLAG_SINGULAR_DIRECT 2u
#define WK_FLAG_GIMBAL 4u
#define WK_FLAG_DOUBLE_ROOT 8u
#define WK_FLAG_INDETERMINATE 16u
#define WK_FLAG_PROJECTED 32u /* the input rotation was projected onto SO(3) (max|R^T R - I| <= 1e-6) */
/* internal, never in a returned set: a two-root stage's half-gap within its upstream noise of a double root, or a
   several-candidate stage's candidate within WK_MERGE_SPAN of another (the pairs wk_merge_indistinct compares) */
#define WK_FLAG_MERGE_CANDIDATE 0x10000u
/* internal, never returned: a wrist within rounding of its family whose member the pose's own entries placed (a
 * serial arm's wrist stage); `previous` moves only a family's representative, not such a set */
#define WK_FLAG_READ_MEMBER 0x20000u

/* Input rotations: max|R^T R - I| <= WK_ROTATION_PROJECT_TOL is projected onto SO(3) (polar factor),
 * farther is WK_ERR_RANGE; below WK_ROTATION_EXACT_TOL the matrix is used as given. */
#define WK_ROTATION_PROJECT_TOL 1e-6
#define WK_ROTATION_EXACT_TOL 1e-13

/* Largest joint count / matrix dimension the shared numerics accept. */
#define WK_MAX_DIM 8

/* ------------------------------------------------------------------ the runtime (wristkin_runtime.c) */
/* The text of a return code. */
const char *wk_strerror(int code);

/* 1 if the n values are all finite. */
int wk_all_finite(const double *v, int n);

/* The angle a - 2 pi k in [-pi, pi] nearest a, for every finite double within an ulp of the exact value (reduced
 * against 2 pi itself, Payne-Hanek, not against the double 6.283185307179586: remainder(a, 6.283185307179586) is
 * |a| x 3.9e-17 off); NaN and inf give NaN. Revolute joint inputs of every mechanism go through it. */
double wk_wrap(double a);

/* The rotation block of a row-major 3x4 pose (entry (i, j) at p[4 * i + j]). Returns 0 when it is not within
 * WK_ROTATION_PROJECT_TOL of SO(3) (or det <= 0); else 1, with `r` (row-major 3x3) the polar factor of the block
 * (the nearest rotation) and *deviation = max|R^T R - I| of the input (0 when it was used as given). */
int wk_input_rotation(const double *p, double r[9], double *deviation);

/* A base or tool frame as given (the top 3x4 of a rigid 4x4, row-major): finite (else WK_ERR_NONFINITE), its
 * rotation within WK_ROTATION_PROJECT_TOL of SO(3) (else WK_ERR_DESIGN), written to `out` with the rotation
 * projected as wk_input_rotation does. */
int wk_input_frame(const double *in, double out[12]);

/* Eigenvalues of the symmetric n x n matrix g (row-major, n <= WK_MAX_DIM, overwritten) by cyclic Jacobi
 * rotations: returns sqrt of their product (the manipulability when g = J^T J) and sets *ratio =
 * sqrt(lambda_min / lambda_max) (sigma_min / sigma_max of J; 0 at a singular configuration, up to rounding). */
double wk_jacobi_spectrum(double *g, int n, double *ratio);
/* The smallest eigenvalue of the symmetric n x n g (row-major, overwritten; n <= WK_MAX_DIM) and its unit
 * eigenvector in v (cyclic Jacobi, as wk_jacobi_spectrum); -1 for a bad n. */
double wk_jacobi_smallest(double *g, int n, double *v);

/* Whether sigma_min / sigma_max of the 6 x n matrix jac (row-major, n <= WK_MAX_DIM) is above eps, proven from
 * Cholesky factorisations of its Gram matrix G (J^T J for n <= 6, J J^T above) at a fraction of a spectrum's cost
 * (eps >= 1e-7: the margins need eps^2 above G's rounding), a square J first by |det J| / ||J||_F^6 (cheaper
 * still): 1 proven above, with *man = sqrt(det G) = |det J| (the
 * manipulability, the product of the nonzero singular values; not computed when man is NULL); -1 proven at or
 * below; 0 undecided (near eps, or J = 0): the caller's spectrum decides. */
int wk_conditioning_bound(const double *jac, int n, double eps, double *man);

/* x = (J^T J + damping I)^-1 J^T e for a 6 x n J (row-major, n <= WK_MAX_DIM) by Gaussian elimination with
 * partial pivoting; returns 0 if singular. */
int wk_normal_solve(const double *jac, int n, const double *e, double damping, double *x);

/* x = a^-1 b for a square n x n a (row-major, n <= WK_MAX_DIM) by elimination with partial pivoting: a's
 * conditioning enters once, where the normal equations square it, at a fraction of their work or an SVD's. Returns
 * 1, or 0 with x untouched when a pivot is at or below rel_pivot of a's largest entry (near rank deficiency, a zeroed
 * column: the caller's least squares decide). Python's _runtime.solve_square step for step. */
int wk_square_solve(const double *a, int n, const double *b, double rel_pivot, double *x);

/* wk_square_solve in two parts, for several right-hand sides on one matrix (a chord iteration): a's LU with partial
 * pivoting into lu (n x n row-major, rows in the pivots' order perm: U on and above the diagonal, the multipliers
 * below), 0 when a pivot is at or below rel_pivot of a's largest entry; then x = a^-1 b from it. The same operations
 * in the same order as wk_square_solve's. */
int wk_lu_factor(const double *a, int n, double rel_pivot, double *lu, int *perm);
void wk_lu_solve(const double *lu, const int *perm, int n, const double *b, double *x);

/* The largest |x[j] - y[j]| of two sets of n joints, revolute differences (revolute[j] nonzero, every joint when
 * revolute is NULL) wrapped to [-pi, pi]; the scan stops at the first joint beyond `stop`, whose gap it returns
 * (Python's set_gap) */
double wk_set_gap(int n, const int *revolute, const double *x, const double *y, double stop);
/* two sets within this in every joint are one solution (a solution's identity): wk_same_set (Python's same_set) */
#define WK_SAME_SET 1e-9
int wk_same_set(int n, const int *revolute, const double *x, const double *y);

/* Merge two valid sets that differ only in the branch of one stage (k ^ k2 within one of masks[]: a two-root stage's
 * bit, a several-candidate stage's bits; mask by mask, k ascending, then k2 > k ascending) when the pose
 * cannot tell them apart: their midpoint, refitted by one Gauss-Newton step no longer than an eighth of their span,
 * fits the pose within WK_MERGE_ULPS eps max(1, scale) of their residuals (scale: the pose's size, max |p|;
 * wristkin_runtime.c says why). values: max_sets x n row-major; aux: the residual at aux[k * aux_stride].
 * Returns the number of sets removed. */
/* refit: the residual max |FK(q) - pose| after at most one damped Gauss-Newton step of at most max_step per joint
 * (q updated when the step helps), none when q's residual is already at most `accept`; ctx: the pose and the design */
typedef double (*wk_refit_fn)(double *q, double max_step, double accept, const void *ctx);
#define WK_MERGE_MAX_JOINTS 16
#define WK_MERGE_MAX_SETS 64
#define WK_MERGE_ULPS 16.0
/* sets farther apart in a joint are distinct at any curvature above 1e-7: not compared (Python's MERGE_SPAN) */
#define WK_MERGE_SPAN 1e-3
/* The FK's own rounding of a pose of size `scale` (max |p|): WK_MERGE_ULPS eps max(1, scale) */
double wk_fk_rounding(double scale);
/* Whether sets x and y of n joints (residuals rx, ry) are one solution the pose cannot tell apart, the merge's test:
 * within WK_MERGE_SPAN in every joint, and their midpoint (mid: n doubles), refitted by one step of at most an eighth
 * of their span, within floor_ of their residuals. Returns the refitted midpoint's residual (mid then holds it) when
 * they are, else -1 (Python's pair_indistinct). revolute as wk_set_gap's. */
double wk_pair_indistinct(int n, const int *revolute, const double *x, double rx, const double *y, double ry,
                          wk_refit_fn refit, const void *ctx, double floor_, double *mid);
/* candidates_only: only pairs both flagged WK_FLAG_MERGE_CANDIDATE are compared (a square chain, whose stages'
 * noise their amplification bounds; a chain of fewer than six joints over-determined by the pose carries the pose's
 * own inconsistency into its stages: every pair within the span). The flag is cleared from every set. */
int wk_merge_indistinct(int max_sets, int n, const int *revolute, const unsigned *masks, int n_masks,
                        double *values, int *valid, unsigned *flags, double *aux, int aux_stride, wk_refit_fn refit,
                        const void *ctx, double scale, int candidates_only);

/* A set its checks carried far from its stages' answer (the polish on a 5-joint arm's inconsistent candidate, a
 * calibrated arm's search along the near-null direction) may have reached another branch's solution: one flagged in
 * `carried` is dropped (values NaN, invalid, flags 0, its aux NaN) where it is one (wk_same_set) with another valid
 * set, an uncarried one or a carried one before it. Returns the count dropped. */
#define WK_CARRIED_MOVE 1e-6
int wk_drop_carried(int max_sets, int n, const int *revolute, double *values, int *valid, unsigned *flags,
                    double *aux, int aux_stride, const unsigned char *carried);

/* The selection rule of every mechanism (docs/API.md, `select`): among valid sets (values: max_sets x n,
 * row-major) within [lower, upper] (either may be NULL), with `previous` the nearest by weighted distance
 * (revolute differences wrapped; weights NULL = 1; ties by plain distance, then index), whatever the flags;
 * without it the first regular set, else the first one. Returns the index or -1. */
int wk_select(int max_sets, int n, const int *valid, const unsigned *flags, const double *values, const int *revolute,
              const double *previous, const double *lower, const double *upper, const double *weights);

/* The local conditioning index 1/kappa_F of the 3 x 3 J = diag(1/g) X (row i: x_i / g_i; x row-major), with
 * kappa_F = ||J||_F ||J^-1||_F / 3 the Frobenius condition number the design atlas averages into the global
 * conditioning index (Gosselin & Angeles 1991): in [0, 1], 1 where J is a multiple of a rotation, 0 at a singularity
 * (a g_i = 0: inverse; det X = 0: direct). Closed form, no division by g_i (wristkin_atlas/conditioning.py). */
double wk_inverse_kappa_f(const double x[9], const double g[3]);

/* The design atlas's per-block sums (docs/atlas.md), in this order in an int64 array: values in [0, 1] are summed
 * as round(v 2^32) (exact and order-independent whatever the chunking); the FK mode histogram follows. */
#define WK_ATLAS_N_REACH 0      /* sampled poses with an IK set within the limits */
#define WK_ATLAS_N_SETS 1       /* such IK sets */
#define WK_ATLAS_LI_SUM 2       /* their 1/kappa_F, fixed point */
#define WK_ATLAS_LI_BEST_SUM 3  /* per reachable pose, its best set's 1/kappa_F, fixed point */
#define WK_ATLAS_NEAR_INVERSE 4 /* sets with cond_inverse < threshold */
#define WK_ATLAS_NEAR_DIRECT 5  /* sets with cond_direct < threshold */
#define WK_ATLAS_FK_NEAR_DIRECT 6 /* joint samples with an assembly mode whose cond_direct < threshold */
#define WK_ATLAS_MODES 7        /* then MAX_FK + 1 counts: joint samples by their number of real assembly modes */
#define WK_ATLAS_FIXED 4294967296.0 /* 2^32 */

#ifdef __cplusplus
}
#endif

#endif /* WRISTKIN_COMMON_H */
