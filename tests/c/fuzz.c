/* Fuzz driver for one generated mechanism, run under ASan/UBSan (any report aborts).
 *
 * Compiled by tests/test_fuzz.py with:
 *   -DMECH=name -DMECH_H='"name.h"' -DUPPER=NAME -DKINDS='"RRP..."' -DPOSE_KIND=POSE_MATRIX12|POSE_EULER|
 *   POSE_RSR|POSE_HYBRID -DJOINT_SPAN=x (prismatic joints are drawn from [-x, x], revolute from [-pi, pi]).
 * Usage: fuzz N SEED  -> runs N cases (each several calls), prints "fuzz <mech>: <counts>" and exits 0; on the first violated
 * invariant it prints what and where, and exits 1.
 *
 * Invariants (the contract of docs/API.md):
 *  1. A negative return leaves count == 0 and no valid row; a non-finite input always gives a negative
 *     return.
 *  2. WK_OK: count equals the number of valid rows, every valid row (values and aux) is finite, and flags
 *     use only the documented bits.
 *  3. FK -> IK: for random (and special: 0, +-pi/2, pi, tiny) joints, every FK mode's IK contains the
 *     joints, or the set holding them is flagged (singular, double root, gimbal, indeterminate) and
 *     reproduces the pose instead. Joint tolerance JOINT_TOL: an unflagged row has sigma_min/sigma_max above
 *     the singular threshold 1e-6, so its error is below ~1e6 * eps * scale ~ 2e-10 * scale.
 *  4. IK -> FK: every valid IK row's FK has a mode that reproduces the pose to POSE_TOL (the solvers verify
 *     to 1e-9 * scale; 1e-8 leaves a decade for the comparison's own rounding), except a row flagged
 *     singular_direct: there FK amplifies rounding by 1 / cond_direct or finds no mode (the IK verified the
 *     row by its own equations).
 *  5. Hostile values (NaN, +-inf, +-0, denormals, +-1e308, +-DBL_MAX, ...) anywhere in joints, poses, designs
 *     and rates, and in poses also LENGTH_MAX = 1e6 and just inside it: never a crash or a sanitizer report, and
 *     (1) and (2) hold.
 *  6. IK returns only what FK accepts: FK of every valid IK row, of any pose (hostile ones too), returns WK_OK
 *     (a pose whose sets would need a joint outside FK's ranges is unreachable, docs/API.md "Ranges").
 */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include MECH_H

#define STR(x) #x
#define XSTR(x) STR(x)
#define CAT3(a, b, c) a##b##c
#define XCAT3(a, b, c) CAT3(a, b, c)
#define FN(verb) XCAT3(wk_, MECH, verb)
#define TYPE(suffix) XCAT3(wk_, MECH, suffix)
#define M(suffix) XCAT3(WK_, UPPER, suffix)

#define NJ M(_N_JOINTS)
#define NP M(_N_POSE)
#define NPAR M(_N_PARAMS)
#define MAXIK M(_MAX_IK)
#define MAXFK M(_MAX_FK)
#define NIKAUX M(_N_IK_AUX)
#define NFKAUX M(_N_FK_AUX)

#define POSE_MATRIX12 1
#define POSE_EULER 2
#define POSE_RSR 3
#define POSE_HYBRID 4

#define JOINT_TOL 1e-6
#define POSE_TOL 1e-8
#define KNOWN_FLAGS 63u
#define ANY_SPECIAL_FLAG (WK_FLAG_SINGULAR_INVERSE | WK_FLAG_SINGULAR_DIRECT | WK_FLAG_GIMBAL | WK_FLAG_DOUBLE_ROOT | WK_FLAG_INDETERMINATE)

static const char kinds[] = KINDS;
static unsigned long long state;
static long n_cases, n_rejected, n_solved, n_ik_rows, n_fk_rows, n_round_trips, n_flagged_trips;
static long case_no;
static const double *case_design; /* the design of the current case (printed with a failure) */

static unsigned long long next_u64(void)
{
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return state;
}

static double uniform(double lo, double hi)
{
    return lo + (hi - lo) * (double)(next_u64() >> 11) / 9007199254740992.0;
}

static const double hostile[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 5e-324, -5e-324, 2.2250738585072014e-308,
                                 1e308, -1e308, DBL_MAX, -DBL_MAX, 1e-300, 1e300, 1e16, -1e16, 1e-7, 3.141592653589793};
#define N_HOSTILE ((int)(sizeof hostile / sizeof hostile[0]))
/* Poses also get LENGTH_MAX and just inside it: a translation there can need a joint past FK's range (invariant 6).
   (Not designs: FK of a design near LENGTH_MAX can place the flange beyond LENGTH_MAX, where IK takes no pose.) */
#define N_HOSTILE_POSE (N_HOSTILE + 2)

static void fail(const char *what, const double *x, int n)
{
    int i;
    fprintf(stderr, "fuzz %s: case %ld: %s; input:", XSTR(MECH), case_no, what);
    for (i = 0; i < n; ++i) fprintf(stderr, " %.17g", x[i]);
    if (case_design) {
        fprintf(stderr, "; design:");
        for (i = 0; i < NPAR; ++i) fprintf(stderr, " %.17g", case_design[i]);
    }
    fprintf(stderr, "\n");
    exit(1);
}

static int finite_all(const double *x, int n)
{
    int i;
    for (i = 0; i < n; ++i)
        if (!isfinite(x[i])) return 0;
    return 1;
}

/* Invariants 1 and 2 on one result struct (the layout is the same for IK and FK). */
#define CHECK_RESULT(rc, s, maxn, width, naux, input, nin, nonfinite_input)                                  \
    do {                                                                                                     \
        int k_, cnt_ = 0;                                                                                    \
        if ((nonfinite_input) && (rc) >= 0) fail("non-finite input accepted", input, nin);                   \
        if ((rc) < 0) {                                                                                      \
            if ((s).count != 0) fail("error return with count != 0", input, nin);                            \
            for (k_ = 0; k_ < (maxn); ++k_)                                                                  \
                if ((s).valid[k_]) fail("error return with a valid row", input, nin);                        \
            ++n_rejected;                                                                                    \
        } else {                                                                                             \
            for (k_ = 0; k_ < (maxn); ++k_) {                                                                \
                if (!(s).valid[k_]) continue;                                                                \
                ++cnt_;                                                                                      \
                if (!finite_all((s).values[k_], width)) fail("valid row with non-finite values", input, nin); \
                if (!finite_all((s).aux[k_], naux)) fail("valid row with non-finite aux", input, nin);      \
                if ((s).flags[k_] & ~KNOWN_FLAGS) fail("undocumented flag bits", input, nin);                \
            }                                                                                                \
            if (cnt_ != (s).count) fail("count differs from the number of valid rows", input, nin);          \
            ++n_solved;                                                                                      \
        }                                                                                                    \
    } while (0)

static double joint_distance(const double *a, const double *b)
{
    double worst = 0.0;
    int j;
    for (j = 0; j < NJ; ++j) {
        double d = a[j] - b[j];
        if (kinds[j] == 'R') d = remainder(d, 2.0 * 3.141592653589793);
        d = fabs(d);
        if (!(d <= worst)) worst = d;
    }
    return worst;
}

#if POSE_KIND == POSE_EULER
static void euler_zxz(const double *e, double *r)
{
    double c1 = cos(e[0]), s1 = sin(e[0]), c2 = cos(e[1]), s2 = sin(e[1]), c3 = cos(e[2]), s3 = sin(e[2]);
    r[0] = c1 * c3 - s1 * c2 * s3;
    r[1] = -c1 * s3 - s1 * c2 * c3;
    r[2] = s1 * s2;
    r[3] = s1 * c3 + c1 * c2 * s3;
    r[4] = -s1 * s3 + c1 * c2 * c3;
    r[5] = -c1 * s2;
    r[6] = s2 * s3;
    r[7] = s2 * c3;
    r[8] = c2;
}
#endif

/* Distance between two FK rows as poses (frames, not their parameterisation) and the pose's scale. */
static double pose_distance(const double *v, const double *aux_v, const double *w, const double *aux_w, double *scale)
{
    double worst = 0.0, a[13], b[13];
    int i, n = 0;
#if POSE_KIND == POSE_MATRIX12 || POSE_KIND == POSE_HYBRID
    (void)aux_v;
    (void)aux_w;
    n = NP;
    memcpy(a, v, sizeof(double) * NP);
    memcpy(b, w, sizeof(double) * NP);
#elif POSE_KIND == POSE_EULER
    (void)aux_v;
    (void)aux_w;
    n = 9;
    euler_zxz(v, a);
    euler_zxz(w, b);
#else /* POSE_RSR: the platform frame [R_W | p_W] is aux[0..11] */
    (void)v;
    (void)w;
    n = 12;
    memcpy(a, aux_v, sizeof(double) * 12);
    memcpy(b, aux_w, sizeof(double) * 12);
#endif
    *scale = 1.0;
    for (i = 0; i < n; ++i) {
        double d = fabs(a[i] - b[i]);
        if (fabs(a[i]) > *scale) *scale = fabs(a[i]);
        if (!(d <= worst)) worst = d;
    }
    return worst;
}

static void random_joints(double *q, int special)
{
    static const double specials[] = {0.0, 1.5707963267948966, -1.5707963267948966, 3.141592653589793,
                                      -3.141592653589793, 1e-7, -1e-9, 1e-12};
    int j;
    for (j = 0; j < NJ; ++j) {
        if (kinds[j] == 'P')
            q[j] = uniform(-JOINT_SPAN, JOINT_SPAN);
        else if (special && (next_u64() & 1u))
            q[j] = specials[next_u64() % 8];
        else
            q[j] = uniform(-3.141592653589793, 3.141592653589793);
    }
}

static void hostile_fill_from(double *x, int n, int *nonfinite, int n_values)
{
    int k = (int)(next_u64() % (unsigned)n), m = 1 + (int)(next_u64() % 3u), i;
    *nonfinite = 0;
    for (i = 0; i < m; ++i) {
        const int pick = (int)(next_u64() % (unsigned)n_values);
        double h = pick < N_HOSTILE ? hostile[pick] : (pick == N_HOSTILE ? 1e6 : 999999.9);
        x[(k + 5 * i) % n] = (next_u64() & 1u) ? h : -h;
    }
    for (i = 0; i < n; ++i)
        if (!isfinite(x[i])) *nonfinite = 1;
}

static void hostile_fill(double *x, int n, int *nonfinite)
{
    hostile_fill_from(x, n, nonfinite, N_HOSTILE);
}

/* Invariant 6: FK accepts every valid IK row. */
static void ik_rows_accepted_by_fk(const TYPE(_ik_solutions) * ik, const TYPE(_design) * d)
{
    TYPE(_fk_solutions) fk;
    int k;
    for (k = 0; k < MAXIK; ++k)
        if (ik->valid[k] && FN(_fk)(ik->values[k], d, &fk) < 0) fail("FK rejects an IK row", ik->values[k], NJ);
}

/* Random joints -> FK -> IK of every mode and back (invariants 3 and 4), then hostile variants. */
static void round_trip_case(const TYPE(_design) * d, int special)
{
    TYPE(_fk_solutions) fk, fk2;
    TYPE(_ik_solutions) ik;
    double q[NJ], pose[NP];
    int rc, m, k, nonfinite;
    random_joints(q, special);
    rc = FN(_fk)(q, d, &fk);
    CHECK_RESULT(rc, fk, MAXFK, NP, NFKAUX, q, NJ, 0);
    if (rc < 0) fail("FK rejected finite joints", q, NJ);
    for (m = 0; m < MAXFK; ++m) {
        double best = INFINITY;
        int held_flagged = 0;
        if (!fk.valid[m]) continue;
        ++n_fk_rows;
        memcpy(pose, fk.values[m], sizeof pose);
        rc = FN(_ik)(pose, d, &ik);
        CHECK_RESULT(rc, ik, MAXIK, NJ, NIKAUX, pose, NP, 0);
        if (rc < 0) fail("IK rejected an FK pose", pose, NP);
        if (ik.count == 0) fail("IK of an FK pose is empty", q, NJ);
        for (k = 0; k < MAXIK; ++k) {
            double dist, scale;
            int i, ok = 0;
            if (!ik.valid[k]) continue;
            ++n_ik_rows;
            dist = joint_distance(ik.values[k], q);
            if (dist < best) best = dist;
            /* invariant 4: the row's FK reproduces the pose */
            rc = FN(_fk)(ik.values[k], d, &fk2);
            CHECK_RESULT(rc, fk2, MAXFK, NP, NFKAUX, ik.values[k], NJ, 0);
            for (i = 0; i < MAXFK; ++i)
                if (fk2.valid[i] &&
                    pose_distance(fk.values[m], fk.aux[m], fk2.values[i], fk2.aux[i], &scale) <= POSE_TOL * scale)
                    ok = 1;
            /* at (or next to) a direct singularity, flagged, the joints do not fix the pose stably: FK amplifies
               rounding by 1 / cond_direct or finds no mode; the IK verified such a row by its own equations */
            if (!ok && !(ik.flags[k] & WK_FLAG_SINGULAR_DIRECT))
                fail("an IK row does not reproduce the pose (joints that generated the pose follow)", q, NJ);
            if ((ik.flags[k] & ANY_SPECIAL_FLAG) || (fk.flags[m] & ANY_SPECIAL_FLAG)) held_flagged = 1;
        }
        ++n_round_trips;
        if (!(best <= JOINT_TOL)) {
            if (!held_flagged) fail("FK -> IK lost the generating joints (no flagged set stands in)", q, NJ);
            ++n_flagged_trips;
        }
        /* hostile variant of this pose */
        hostile_fill_from(pose, NP, &nonfinite, N_HOSTILE_POSE);
        rc = FN(_ik)(pose, d, &ik);
        CHECK_RESULT(rc, ik, MAXIK, NJ, NIKAUX, pose, NP, nonfinite);
        if (rc >= 0) ik_rows_accepted_by_fk(&ik, d);
    }
    /* hostile joints */
    hostile_fill(q, NJ, &nonfinite);
    rc = FN(_fk)(q, d, &fk);
    CHECK_RESULT(rc, fk, MAXFK, NP, NFKAUX, q, NJ, nonfinite);
}

/* Jacobians and rates: a non-finite input is an error; a finite result is finite. */
static void derivative_case(const TYPE(_design) * d)
{
    double q[NJ], out[6 * NJ + 9];
    int rc, bad_q = 0;
    random_joints(q, 1);
    if (next_u64() & 1u) hostile_fill(q, NJ, &bad_q);
#if POSE_KIND == POSE_MATRIX12 || POSE_KIND == POSE_HYBRID || POSE_KIND == POSE_RSR
    rc = FN(_jacobian)(q, d, out);
    if (bad_q && rc >= 0) fail("jacobian accepted non-finite joints", q, NJ);
    if (rc == WK_OK && !finite_all(out, 6 * NJ)) fail("jacobian returned WK_OK with non-finite entries", q, NJ);
#endif
#if POSE_KIND == POSE_MATRIX12 || POSE_KIND == POSE_HYBRID
    rc = FN(_fk_matrix)(q, d, out);
    if (bad_q && rc >= 0) fail("fk_matrix accepted non-finite joints", q, NJ);
    if (rc == WK_OK && !finite_all(out, 12)) fail("fk_matrix returned WK_OK with non-finite entries", q, NJ);
#endif
#if POSE_KIND == POSE_EULER || POSE_KIND == POSE_RSR
    {
        double pose[3], jq[3];
        int i, bad_pose = 0;
        for (i = 0; i < 3; ++i) pose[i] = uniform(-3.0, 3.0);
#if POSE_KIND == POSE_RSR
        pose[1] = uniform(0.0, 1.2);
        pose[2] = uniform(-0.12, 0.12);
#endif
        if (next_u64() & 1u) hostile_fill(pose, 3, &bad_pose);
        rc = FN(_jacobians)(q, pose, d, jq, out);
        if ((bad_q || bad_pose) && rc >= 0) fail("jacobians accepted non-finite input", pose, 3);
        if (rc == WK_OK && (!finite_all(jq, 3) || !finite_all(out, 9)))
            fail("jacobians returned WK_OK with non-finite entries", pose, 3);
#if POSE_KIND == POSE_EULER
        {
            double rates[3];
            int bad_rates = 0;
            for (i = 0; i < 3; ++i) rates[i] = uniform(-2.0, 2.0);
            if (next_u64() & 1u) hostile_fill(rates, 3, &bad_rates);
            rc = FN(_angular_velocity)(q, pose, rates, d, out);
            if ((bad_q || bad_pose || bad_rates) && rc >= 0) fail("angular_velocity accepted non-finite input", rates, 3);
            if (rc == WK_OK && !finite_all(out, 3))
                fail("angular_velocity returned WK_OK with non-finite entries", rates, 3);
            rc = FN(_angular_acceleration)(q, pose, rates, rates, d, out);
            if ((bad_q || bad_pose || bad_rates) && rc >= 0)
                fail("angular_acceleration accepted non-finite input", rates, 3);
            if (rc == WK_OK && !finite_all(out, 3))
                fail("angular_acceleration returned WK_OK with non-finite entries", rates, 3);
            rc = FN(_omega_from_euler_rates)(pose, rates, out);
            if ((bad_pose || bad_rates) && rc >= 0) fail("omega_from_euler_rates accepted non-finite input", rates, 3);
            if (rc == WK_OK && !finite_all(out, 3))
                fail("omega_from_euler_rates returned WK_OK with non-finite entries", rates, 3);
        }
#endif
    }
#endif
}

/* A design near the default (or hostile): rejected with WK_ERR_*, or usable with every invariant. */
static int design_case(const double *defaults, TYPE(_design) * d)
{
    double p[NPAR];
    int i, rc, nonfinite = 0;
    for (i = 0; i < NPAR; ++i) p[i] = defaults[i] * uniform(0.8, 1.25);
    if (next_u64() % 4u == 0u) hostile_fill(p, NPAR, &nonfinite);
    rc = FN(_design_init)(p, d);
    if (nonfinite && rc >= 0) fail("design_init accepted non-finite parameters", p, NPAR);
    if (rc < 0) ++n_rejected;
    return rc == WK_OK;
}

int main(int argc, char **argv)
{
    TYPE(_design) def, d;
    TYPE(_ik_solutions) ikb[2];
    TYPE(_fk_solutions) fkb[2];
    long n, i;
    double rows[2 * NP];
    if (argc != 3) {
        fprintf(stderr, "usage: fuzz N SEED\n");
        return 2;
    }
    n = atol(argv[1]);
    state = 0x9E3779B97F4A7C15ULL ^ (unsigned long long)atol(argv[2]) * 2654435761ULL;
    if (!state) state = 1;
    if (FN(_design_init)(NULL, &def) != WK_OK) fail("the default design is rejected", NULL, 0);
    for (i = 0; i < n; ++i) {
        case_no = i;
        if (i % 16 == 15) {
            case_design = d.params;
            if (design_case(def.params, &d)) round_trip_case(&d, 0);
        } else {
            case_design = def.params;
            round_trip_case(&def, (int)(i % 4 == 1));
        }
        if (i % 4 == 0) derivative_case(&def);
        ++n_cases;
    }
    /* NULL pointers and batch sizes are errors, not crashes */
    for (i = 0; i < 2 * NP; ++i) rows[i] = 0.0;
    if (FN(_ik)(NULL, &def, &ikb[0]) >= 0 || FN(_fk)(NULL, &def, &fkb[0]) >= 0 || FN(_ik)(rows, &def, NULL) >= 0)
        fail("a NULL pointer was accepted", NULL, 0);
    if (FN(_ik_batch)(2, NULL, &def, ikb) >= 0 || FN(_fk_batch)(2, rows, &def, NULL) >= 0)
        fail("a NULL batch pointer was accepted", NULL, 0);
    printf("fuzz %s: %ld cases, %ld rejected (negative return), %ld solved, %ld FK modes, %ld IK rows, "
           "%ld round trips (%ld through a flagged set)\n",
           XSTR(MECH), n_cases, n_rejected, n_solved, n_fk_rows, n_ik_rows, n_round_trips, n_flagged_trips);
    return 0;
}
