/* wristkin: the general 6R arm's inverse kinematics by elimination (C99, libm only; do not edit).
 * @generated-by@
 *
 * The C twin of runtime/python/general6r.py (read its docstring for the method): the arm and the pose close a
 * loop Rz(t1) K1 Rz(t2) K2 ... Rz(t6) K6 = I of six turns and constant links; read from joint `shift`
 * (backwards when `reverse`), the 14 equations of Raghavan and Roth are interpolated exactly from three angles
 * per joint, theta1 and theta2 eliminated by Q's left null space (Householder QR), and the six equations left
 * become the 12 x 12 matrix polynomial of the hidden angle, whose real eigenvalues (wk_eigen.c; for hidden t3 with
 * the determinant's extraneous (1 + x^2)^4 deflated: 16 x 16) and null vectors give the candidates, each refined
 * by Newton steps on the chain. The caller verifies each (candidates are not
 * solutions until then). Frames and poses are 4 x 4 row-major; no allocation, every size fixed below. */
#ifndef WK_GENERAL6R_H
#define WK_GENERAL6R_H

#ifdef __cplusplus
extern "C" {
#endif

#define WK_G6_MAX_CANDIDATES 120 /* 24 eigenvalues, each giving its null vector and a cluster's 4 at most */
#define WK_G6_NULL_TOL 1e-8     /* sigma / sigma_max of M(x) up to this spans its null space */
#define WK_G6_REFINE_STEPS 8    /* Newton steps per candidate at most (a simple root: 1-2 to rounding, then it stops;
                                   a double root converges linearly, halving the distance per step) */

/* A frame per joint with its z axis on the joint's line (axis i through point i; x any normal): frames holds
 * 6 x 16 doubles, frame i at frames + 16 i. */
void wk_g6_z_frames(const double *axes, const double *points, double *frames);

/* Candidate joint values (6 per row of q, max_out rows) of the chain  prod_i Z_i Rz(q_i) Z_i^-1 . home = pose, for the labelling
 * (shift 0..5, reverse 0/1, hidden 0..2). Returns the number written to q (<= max_out), or -1 when the
 * elimination fails for this pose (a numerical error of wk_eigen, or equations dependent at this pose). */
int wk_g6_solve(const double *frames, const double *home, const double *pose, int shift, int reverse, int hidden,
                double *q, int max_out);

/* wk_g6_solve with a choice. clusters = 0 (wk_g6_solve's): a root whose M(x) has a nearly shared null space (a
 * cluster of nearly equal roots, general6r.py's G6_CLUSTER_TOL) gives only its own null vector, and an eigenvalue
 * pair off the real axis by more than the rounding allows is not read. clusters = 1: such a root also gives the
 * cluster subspace's candidates (a Jacobi SVD each; approximate, refined but not polished, so for a caller that
 * polishes and merges them: the general 6R stage's second pass), and such a pair is read as a root. *near_pair (may
 * be NULL): such a pair was seen (a nearly defective cluster's members can all come out complex). */
int wk_g6_solve_clusters(const double *frames, const double *home, const double *pose, int shift, int reverse,
                         int hidden, int clusters, int *near_pair, double *q, int max_out);

#ifdef __cplusplus
}
#endif

#endif /* WK_GENERAL6R_H */
