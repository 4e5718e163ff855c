/* Compiled user torques for the tests of gyrostat.CustomTorque (tests/user_torques/__init__.py):
 * int f(double t, const double *omega, const double *quaternion, double *moment, void *user_data),
 * and vectorised over n members (the *_lanes functions), structure of arrays, member l = 0..n-1:
 * int f(int n, const double *t, const double *omega, const double *quaternion, double *moment, void *user_data)
 * with t[l], omega[i*n + l], quaternion[i*n + l] (or NULL), moment[i*n + l]. */
#include <math.h>
#include <stddef.h>

/* M = -c |omega| omega + (0, 0, a sin t), c = 0.05, a = 0.02 */
int quadratic_drag(double t, const double *w, const double *q, double *m, void *data) {
    (void)q, (void)data;
    const double norm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    m[0] = -0.05 * norm * w[0];
    m[1] = -0.05 * norm * w[1];
    m[2] = -0.05 * norm * w[2] + 0.02 * sin(t);
    return 0;
}

/* dM/domega = -c (|omega| I + omega omega^T / |omega|), row-major */
int quadratic_drag_jacobian(double t, const double *w, const double *q, double *d, void *data) {
    (void)t, (void)q, (void)data;
    const double norm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) d[3 * i + j] = -0.05 * ((i == j ? norm : 0.0) + w[i] * w[j] / norm);
    return 0;
}

/* M = -c omega, c = *(double *)data */
int linear_drag(double t, const double *w, const double *q, double *m, void *data) {
    (void)t, (void)q;
    const double c = *(const double *)data;
    for (int i = 0; i < 3; ++i) m[i] = -c * w[i];
    return 0;
}

/* fails (returns 3) after t = 1 */
int failing(double t, const double *w, const double *q, double *m, void *data) {
    (void)w, (void)q, (void)data;
    m[0] = m[1] = m[2] = 0.0;
    return t > 1.0 ? 3 : 0;
}

/* The largest n a vectorised function below was called with (the tests read it: the SIMD batches
 * call with n = their lanes, every other path with n = 1). */
static int widest;

static void note(int n) {
    int seen = __atomic_load_n(&widest, __ATOMIC_RELAXED);
    while (n > seen && !__atomic_compare_exchange_n(&widest, &seen, n, 0, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
}

int widest_call(void) { return __atomic_load_n(&widest, __ATOMIC_RELAXED); }
void reset_widest_call(void) { __atomic_store_n(&widest, 0, __ATOMIC_RELAXED); }

/* quadratic_drag for n members: the same operations, member by member */
int quadratic_drag_lanes(int n, const double *t, const double *w, const double *q, double *m, void *data) {
    (void)q, (void)data;
    note(n);
    for (int l = 0; l < n; ++l) {
        const double p = w[l], r = w[n + l], s = w[2 * n + l];
        const double norm = sqrt(p * p + r * r + s * s);
        m[l] = -0.05 * norm * p;
        m[n + l] = -0.05 * norm * r;
        m[2 * n + l] = -0.05 * norm * s + 0.02 * sin(t[l]);
    }
    return 0;
}

/* linear_drag for n members: M = -c omega, c = *(double *)data */
int linear_drag_lanes(int n, const double *t, const double *w, const double *q, double *m, void *data) {
    (void)t, (void)q;
    note(n);
    const double c = *(const double *)data;
    for (int k = 0; k < 3 * n; ++k) m[k] = -c * w[k];
    return 0;
}

/* R(q)^T M_I, M_I = (0.1, -0.2, 0.05) fixed in inertial space (q body -> inertial, normalised
 * here as the Python inertial_moment does) for n members */
int inertial_moment_lanes(int n, const double *t, const double *w, const double *quaternion, double *m, void *data) {
    (void)t, (void)w, (void)data;
    note(n);
    const double M[3] = {0.1, -0.2, 0.05};
    for (int l = 0; l < n; ++l) {
        const double norm = sqrt(quaternion[l] * quaternion[l] + quaternion[n + l] * quaternion[n + l] +
                                 quaternion[2 * n + l] * quaternion[2 * n + l] + quaternion[3 * n + l] * quaternion[3 * n + l]);
        const double a = quaternion[l] / norm, x = quaternion[n + l] / norm, y = quaternion[2 * n + l] / norm,
                     z = quaternion[3 * n + l] / norm;
        const double R[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - a * z), 2 * (x * z + a * y)},
                                {2 * (x * y + a * z), 1 - 2 * (x * x + z * z), 2 * (y * z - a * x)},
                                {2 * (x * z - a * y), 2 * (y * z + a * x), 1 - 2 * (x * x + y * y)}};
        for (int i = 0; i < 3; ++i) m[i * n + l] = R[0][i] * M[0] + R[1][i] * M[1] + R[2][i] * M[2];
    }
    return 0;
}

/* fails (returns 3) once a member passes t = 1 */
int failing_lanes(int n, const double *t, const double *w, const double *q, double *m, void *data) {
    (void)w, (void)q, (void)data;
    int status = 0;
    for (int l = 0; l < 3 * n; ++l) m[l] = 0.0;
    for (int l = 0; l < n; ++l)
        if (t[l] > 1.0) status = 3;
    return status;
}
