/* The types of the user-robot solver: a chain (axes, points, end frame) and its decomposition's ops.
 * (a wristkin runtime source, inlined whole into every user robot's generated C, after the robot's CK_*
 * constants; derive/runtime_files.py, tests/test_chain_runtime.py) */
/* The chain a call reads: axes, points on them and the end frame at q = 0 (free joint held, maybe reversed);
 * index[i] = the description's joint of the chain's joint i. */
typedef struct {
    int n;
    int prismatic[CK_N];
    double axis[CK_N][3];
    double point[CK_N][3];
    ck_rt home;
    int index[CK_N];
} ck_chain;
/* ------------------------------------------------------------------ the decomposition as data */
enum { CK_BEGIN, CK_FIRST_PLANE, CK_LAST_PLANE, CK_FIRST_DIST, CK_LAST_DIST, CK_PAIR, CK_SINGLE, CK_LINEAR,
       CK_ORIENT, CK_GROUP_REST, CK_SPATIAL3, CK_SP6, CK_GENERAL6R, CK_ARM_ANGLE };
/* a point x / s: where axes meet, a point on an axis, the end frame's origin; a direction n: an axis, or the
 * normal of two (slide) axes */
enum { CK_NONE, CK_MEET, CK_ON, CK_HOME, CK_DIR, CK_CROSS };

typedef struct {
    int op;
    int j, k;          /* the op's joint(s) in the solver's chain (pair: j then k; general6r: the loop's first
                        * joint and the hidden angle, lo: read backwards) */
    int prismatic;     /* joint j is a slide */
    int spec, n_spec;  /* the op's point or direction (begin: x, plane: n, dist / pair: s) and its joints */
    int spec_js[CK_N];
    int lo, hi;        /* begin / orient: the joints lo..hi left in the product */
    int n_units;       /* orient: its units (one joint, or a parallel group turning as one) */
    int unit_len[3];
    int units[3][CK_N];
    int n_js;          /* linear: its slides; group_rest: the group; arm_angle: the shoulder (j: the elbow) */
    int js[CK_N];
    int planar;        /* first/last_dist: the other joints keep the parts normal to j's axis (the target's distance
                        * there read as a sum of squares) */
} ck_op;
